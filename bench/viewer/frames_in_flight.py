#!/usr/bin/env python3
"""The viewer's frame time with 1 and with 2 (or more) frames in flight.

  frames_in_flight.py VIEWER [--size WxH] [--frames N] [--rounds R] [--scene FILE]

Drives `VIEWER --control --frames-in-flight K` under xvfb-run, sending N 'frame'
commands. A reply comes once the frame is submitted (the frame before it may still run),
so the time between the replies of frame 3 and frame N over the frames in between is the
steady frame time, for either setting. The settings' runs are interleaved (1, 2, 1, 2, ...)
so both see the same machine load; prints each run and the median per setting.
"""
import argparse
import json
import os
import statistics
import subprocess
import time

WARM_UP = 3  # frames before the timed ones (pipelines, first uploads)


def frame_time_ms(viewer, frames_in_flight, size, frames, scene):
    command = ["xvfb-run", "-a", viewer, "--control", "--size", size, "--frames-in-flight", str(frames_in_flight)]
    if scene:
        command += ["--scene", scene]
    env = dict(os.environ, XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp"))
    process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                               text=True, env=env)
    replied = []
    for _ in range(frames):
        process.stdin.write("frame\n")
        process.stdin.flush()
        line = process.stdout.readline()
        if not line:
            raise SystemExit(f"the viewer exited (status {process.wait()}): run {' '.join(command)} to see why")
        if not json.loads(line).get("rendered"):
            raise SystemExit(f"no frame rendered: {line.strip()}")
        replied.append(time.monotonic())
    process.stdin.write("quit\n")
    process.stdin.flush()
    process.stdout.readline()
    if process.wait() != 0:
        raise SystemExit(f"the viewer failed (status {process.returncode}): run {' '.join(command)} to see why")
    return (replied[-1] - replied[WARM_UP - 1]) / (frames - WARM_UP) * 1000.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("viewer")
    parser.add_argument("--size", default="160x90")
    parser.add_argument("--frames", type=int, default=25)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--in-flight", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--scene", default="")
    args = parser.parse_args()
    if args.frames <= WARM_UP + 1:
        parser.error(f"--frames must be more than {WARM_UP + 1}")
    results = {k: [] for k in args.in_flight}
    print(f"{'round':>5}{'in flight':>11}{'ms per frame':>14}")
    for round_index in range(args.rounds):
        for k in args.in_flight:
            ms = frame_time_ms(args.viewer, k, args.size, args.frames, args.scene)
            results[k].append(ms)
            print(f"{round_index + 1:>5}{k:>11}{ms:>14.1f}", flush=True)
    print(f"median over {args.rounds} rounds, {args.size}, frames {WARM_UP + 1}..{args.frames}:")
    for k, values in results.items():
        print(f"{'':>5}{k:>11}{statistics.median(values):>14.1f}")


if __name__ == "__main__":
    main()

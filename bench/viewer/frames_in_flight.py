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
import statistics
import time

from viewer_control import ControlledViewer, steady_frame_ms

WARM_UP = 3  # frames before the timed ones (pipelines, first uploads)


def frame_time_ms(viewer, frames_in_flight, size, frames, scene):
    arguments = ["--size", size, "--frames-in-flight", str(frames_in_flight)] + (["--scene", scene] if scene else [])
    run = ControlledViewer(viewer, arguments)
    replied = []
    for _ in range(frames):
        run.frame()
        replied.append(time.monotonic())
    run.quit_or_exit()
    return steady_frame_ms(replied, WARM_UP)


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

#!/usr/bin/env python3
"""A VDB sequence played in a capture, against the same scene with one static frame
(issue 35's targets), on the generated content (plume_sequence.scene.json: 24 simulated
frames looping at 24 fps on the default stage):

1. Playback: avsm-capture --frame-range over three scenes, interleaved over --rounds rounds:
     static     the scene with its volume fixed at frame 12 (nothing moves);
     held       a sequence of 24 files that all hold frame 12: every frame is read, prepared,
                staged and uploaded as in any sequence, and renders what static renders, so
                the two differ only by what playing a sequence costs;
     sequence   the simulated sequence itself, whose smoke grows from frame to frame (its
                render cost follows the content: more smoke, more capture and march).
   Per run the mean and median wall ms per frame after the first (posing, reading a frame
   the worker had not, staging, rendering), and the ms waited for the reader. Target: the
   held sequence's frame rate >= 0.9x the static scene's (the ratio of the medians over the
   rounds). The per-frame chart is the sequence's report.html (--report): its path is printed.

2. Memory over a --loop-frames loop of the sequence (200 by default: the 24 frames 8 times
   over): the process's resident memory (VmRSS) and heap in use (glibc's mallinfo2) after
   every frame, from shot.json, printed at checkpoints. Target: flat, within --tolerance
   percent, from the second pass of the loop on (the first fills the reader's cache and
   grows the volume buffers to the largest frame).

usage: bench/media/sequence.py [--build DIR] [--width W] [--height H] [--frames N]
                               [--rounds R] [--loop-frames N] [--tolerance PERCENT]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def capture(args, scene, out, frames, extra=()):
    command = [os.path.join(args.build, "tools", "avsm-capture"), "--scene", scene, "--out", out,
               "--width", str(args.width), "--height", str(args.height), "--quiet",
               "--frame-range", f"0:{frames - 1}", "--fps", "24", *extra]
    result = subprocess.run(command, capture_output=True, text=True,
                            env=dict(os.environ, XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp")))
    if result.returncode != 0:
        sys.exit(f"sequence.py: {' '.join(command)} failed:\n{result.stderr}")
    with open(os.path.join(out, "shot.json")) as f:
        return json.load(f)


def variant_scene(sequence_scene, work, name, held):
    """The sequence's scene with its volume fixed at frame 12 (held None), or playing a
    sequence of `held` files in `work` that all are frame 12."""
    with open(sequence_scene) as f:
        scene = json.load(f)
    directory = os.path.dirname(os.path.abspath(sequence_scene))
    for volume in scene["volumes"]:
        frame_12 = os.path.join(directory, volume["file"].replace("####", "0012"))
        if held is None:
            volume["file"] = frame_12
            volume.pop("sequence", None)
        else:
            os.makedirs(os.path.join(work, "held"), exist_ok=True)
            for frame in range(1, held + 1):
                os.symlink(frame_12, os.path.join(work, "held", f"plume.{frame:04d}.vdb"))
            volume["file"] = os.path.join(work, "held", "plume.####.vdb")
            volume["sequence"] = {"frames": [1, held], "fps": 24, "mode": "loop"}
    for model in scene.get("models", []):
        model["file"] = os.path.join(directory, model["file"])
    path = os.path.join(work, f"{name}.scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=2)
    return path


def after_first(shot, key):
    return [frame[key] for frame in shot["frames"][1:]]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--loop-frames", type=int, default=200)
    parser.add_argument("--tolerance", type=float, default=2.0)
    args = parser.parse_args()
    sequence_scene = os.path.join(args.build, "content", "default", "plume_sequence.scene.json")
    work = tempfile.mkdtemp(prefix="avsm_sequence_bench_")
    scenes = (("static", variant_scene(sequence_scene, work, "static", None)),
              ("held", variant_scene(sequence_scene, work, "held", 24)),
              ("sequence", sequence_scene))

    print(f"playback: {args.frames} frames at 24 fps, {args.width}x{args.height}, {args.rounds} rounds interleaved")
    print(f"{'run':<22} {'mean ms':>9} {'median ms':>10} {'first ms':>9} {'waited ms':>10}")
    medians = {name: [] for name, _ in scenes}
    report = None
    for round_index in range(args.rounds):
        for name, scene in scenes:
            out = os.path.join(work, f"{name}_{round_index}")
            shot = capture(args, scene, out, args.frames, ["--report"] if name == "sequence" else [])
            walls = after_first(shot, "wall_ms")
            waited = sum(after_first(shot, "volume_wait_ms"))
            medians[name].append(statistics.median(walls))
            print(f"{name + ' ' + str(round_index + 1):<22} {statistics.mean(walls):9.1f} {statistics.median(walls):10.1f} "
                  f"{shot['frames'][0]['wall_ms']:9.1f} {waited:10.1f}")
            if name == "sequence":
                report = os.path.join(out, "report.html")
    static_median = statistics.median(medians["static"])
    ratio = static_median / statistics.median(medians["held"])
    print(f"\nheld sequence frame rate / static frame rate: {ratio:.3f} (target >= 0.9: {'met' if ratio >= 0.9 else 'MISSED'})")
    print(f"simulated sequence frame rate / static (frame 12) frame rate: "
          f"{static_median / statistics.median(medians['sequence']):.3f} (its smoke changes size: content, not playing)")
    print(f"per-frame chart: {report}")

    print(f"\nmemory over a {args.loop_frames}-frame loop, {args.width // 2}x{args.height // 2}")
    half = argparse.Namespace(**{**vars(args), "width": args.width // 2, "height": args.height // 2})
    shot = capture(half, sequence_scene, os.path.join(work, "loop"), args.loop_frames)
    frames = shot["frames"]
    print(f"{'frame':>6} {'resident MiB':>13} {'heap MiB':>9}")
    checkpoints = list(range(0, len(frames), 24)) + [len(frames) - 1]
    for i in checkpoints:
        print(f"{frames[i]['frame']:>6} {frames[i]['resident_mib']:13.1f} {frames[i]['heap_mib']:9.1f}")
    start = min(48, len(frames) - 1)  # from the second pass on
    for key, label in (("resident_mib", "resident"), ("heap_mib", "heap")):
        base = frames[start][key]
        peak = max(frame[key] for frame in frames[start:])
        growth = 100.0 * (peak - base) / base
        print(f"{label}: {base:.1f} MiB at frame {frames[start]['frame']}, at most {peak:.1f} after it "
              f"({growth:+.2f}%; target within {args.tolerance}%: {'met' if growth <= args.tolerance else 'MISSED'})")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The viewer's frame time while the camera orbits the default scene, with dense maps
(today's default: 256^2 per light, the Gaussian kernel on the sun) and with paged maps
(both lights paged, no kernel, fitted to the scene).

  orbit.py VIEWER [--size WxH] [--frames N] [--degrees D] [--rounds R] [--scene FILE]

Drives `VIEWER --control` under xvfb-run (viewer_control.py). Paged runs first switch
both lights to paged maps through the panel's fields ('light I layout paged', ...). The
camera stands still until no page request is pending (the viewer builds at most
page_builds_per_frame pages a frame, so a paged map converges over frames). Then each
frame is 'orbit D' and 'frame'. A 'frame' reply comes once the frame is submitted, so
the time between the replies of the frames after the first few, over their count, is the
steady frame time as a user orbiting the camera sees it. The layouts' runs are
interleaved (dense, paged, dense, paged, ...) so both see the same machine load.
"""
import argparse
import statistics
import time

from viewer_control import ControlledViewer, steady_frame_ms

WARM_UP = 4  # orbit frames before the timed ones (the pages the first turns ask for)
MAX_SETTLING_FRAMES = 80  # a still camera's frames until no page request is pending
LAYOUTS = {
    "dense": [],
    "paged": [f"light {i} {field} {value}" for i in (0, 1)
              for field, value in (("layout", "paged"), ("kernel", "none"), ("fit", "scene"))],
}


def orbit_frame_ms(viewer, layout, args):
    arguments = ["--size", args.size] + (["--scene", args.scene] if args.scene else [])
    run = ControlledViewer(viewer, arguments, reply_timeout=600)
    for command in LAYOUTS[layout]:
        run.send(command)
    settled = 0
    for _ in range(MAX_SETTLING_FRAMES):
        answer = run.frame()
        settled = settled + 1 if answer.get("pages_pending", 0) == 0 else 0
        if settled == 3:  # the requests lag a frame: pending 0 three times in a row
            break
    else:
        raise SystemExit(f"{layout} maps still had pages pending after {MAX_SETTLING_FRAMES} frames")
    replied = []
    for _ in range(args.frames):
        run.send(f"orbit {args.degrees}")
        answer = run.frame()
        if answer.get("error"):
            raise SystemExit(f"the viewer reported an error with {layout} maps: {answer['error']}")
        replied.append(time.monotonic())
    run.quit_or_exit()
    return steady_frame_ms(replied, WARM_UP)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("viewer")
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--frames", type=int, default=16)
    parser.add_argument("--degrees", type=float, default=2.0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--scene", default="")
    args = parser.parse_args()
    if args.frames <= WARM_UP + 1:
        parser.error(f"--frames must be more than {WARM_UP + 1}")
    results = {layout: [] for layout in LAYOUTS}
    print(f"{'round':>5}{'layout':>8}{'ms per frame':>14}")
    for round_index in range(args.rounds):
        for layout in LAYOUTS:
            ms = orbit_frame_ms(args.viewer, layout, args)
            results[layout].append(ms)
            print(f"{round_index + 1:>5}{layout:>8}{ms:>14.1f}", flush=True)
    dense = statistics.median(results["dense"])
    print(f"orbiting {args.degrees} degrees a frame, window {args.size}, frames {WARM_UP + 1}..{args.frames}, "
          f"medians over {args.rounds} rounds:")
    for layout, values in results.items():
        ms = statistics.median(values)
        print(f"{'':>5}{layout:>8}{ms:>14.1f}   x dense {ms / dense:.2f}")


if __name__ == "__main__":
    main()

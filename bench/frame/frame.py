#!/usr/bin/env python3
"""One scene's frame, fast against reference volume shading, in one avsm-capture run.

Prints per pass the median GPU ms of the fast path and of the reference path (their
frames interleaved in the same process), the camera-side totals and ratios, the
targets of the real-time camera side, and the smoke-pixel error of the fast path
against the reference (mean and 99th percentile of |dL| relative to the mean
luminance, on linear HDR).
"""
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402

# Camera-side passes of each path; everything else (shadow maps, tonemap, debug) is common.
FAST_VOLUME = ["volume cache layout", "volume lighting cache", "volume march", "volume composite"]
REFERENCE_VOLUME = ["volumes"]
HAIR = ["hair lighting", "hair"]


def run_capture(capture, scene, width, height, frames, extra):
    out = Path(tempfile.mkdtemp(prefix="avsm-frame-bench-"))
    command = [capture, "--scene", scene, "--width", str(width), "--height", str(height), "--frames", str(frames),
               "--out", str(out), "--quiet", "--compare-volume-shading"] + extra
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"frame.py: {' '.join(command)} failed:\n{result.stderr}")
    return capture_report.volume_quality(out)


def total(passes, names):
    return sum(passes.get(name, 0.0) for name in names)


def main():
    parser = capture_report.scene_arguments(__doc__, 1280, 720)
    parser.add_argument("--frames", type=int, default=3, help="frames per path; medians over all but the first")
    parser.add_argument("--capture-arg", action="append", default=[],
                        help="extra avsm-capture argument, e.g. --capture-arg=--volume-step=2 (split at '=')")
    args = parser.parse_args()
    extra = []
    for arg in args.capture_arg:
        extra += arg.split("=", 1) if arg.startswith("--") and "=" in arg else [arg]

    q = run_capture(args.capture, args.scene, args.width, args.height, args.frames, extra)
    fast, reference = q.fast_gpu_ms, q.reference_gpu_ms
    print(f"## {Path(args.scene).name} at {args.width}x{args.height} ({q.fast_settings})")
    print(f"{'pass':32} {'fast ms':>10} {'reference ms':>13} {'ref/fast':>9}")
    for name in sorted(set(fast) | set(reference), key=lambda n: -max(fast.get(n, 0.0), reference.get(n, 0.0))):
        f, r = fast.get(name), reference.get(name)
        ratio = f"{r / f:9.1f}" if f and r else f"{'-':>9}"
        fast_text = f"{f:10.1f}" if f is not None else f"{'-':>10}"
        reference_text = f"{r:13.1f}" if r is not None else f"{'-':>13}"
        print(f"{name:32} {fast_text} {reference_text} {ratio}")
    opaque = fast.get("opaque", 0.0)
    fast_volumes, reference_volumes = total(fast, FAST_VOLUME), total(reference, REFERENCE_VOLUME)
    fast_hair, reference_hair = total(fast, HAIR), total(reference, HAIR)
    fast_frame, reference_frame = sum(fast.values()), sum(reference.values())
    # The shadow build (per-light passes) is common to both paths and another issue's work.
    camera_fast = sum(ms for name, ms in fast.items() if not name.startswith("light "))
    camera_reference = sum(ms for name, ms in reference.items() if not name.startswith("light "))
    print()
    print(f"{'':32} {'fast ms':>10} {'reference ms':>13} {'ref/fast':>9}")
    for label, f, r in [("volumes (all volume passes)", fast_volumes, reference_volumes),
                        ("hair (lighting + draw)", fast_hair, reference_hair),
                        ("camera side (no shadow passes)", camera_fast, camera_reference),
                        ("frame (every pass)", fast_frame, reference_frame)]:
        print(f"{label:32} {f:10.1f} {r:13.1f} {r / f if f else float('nan'):9.1f}")
    print()
    if opaque > 0:
        checks = [("volumes <= 1.5 x opaque", fast_volumes / opaque, 1.5, "x opaque"),
                  ("hair <= 1.0 x opaque", fast_hair / opaque, 1.0, "x opaque")]
    else:
        checks = []
    checks.append(("frame >= 8x faster than reference", reference_frame / fast_frame if fast_frame else 0.0, 8.0, "x"))
    for label, value, bound, unit in checks:
        ok = value >= bound if label.startswith("frame") else value <= bound
        print(f"target {label:38} {value:6.2f} {unit:9} {'met' if ok else 'MISSED'}")
    print(f"quality over {q.smoke_pixels} smoke pixels: mean |dL| {100 * q.mean_relative:.2f}% (bound 2%), "
          f"p99 {100 * q.p99_relative:.2f}% (bound 10%) of mean luminance {q.mean_luminance:.4f}: "
          f"{'within' if q.within_bound else 'OUTSIDE'} the bound")


if __name__ == "__main__":
    main()

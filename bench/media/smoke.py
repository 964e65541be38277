#!/usr/bin/env python3
"""Smoke lit as a medium, against a CPU path tracer (issue "Light in media", target "Smoke").

Per scene, one avsm-capture run per shading (--compare-volume-shading --path-trace-volumes):
multiple scattering with the sky (the default), single scattering with the sky, and single
scattering from the lights alone (the shading before multiple scattering and sky light).
Prints the smoke pixels' mean luminance in the fast frame, the reference frame and the
path-traced frame (every order of scattering, the lights and the sky), and the fast frame's
difference from the path-traced one. The target: with multiple scattering on, the lit
real_assets plume within 25% of the path tracer's mean luminance.
"""
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402

SHADINGS = [  # (name, avsm-capture arguments)
    ("multiple scattering + sky (default)", []),
    ("single scattering + sky", ["--volume-octaves", "1"]),
    ("single scattering, lights only", ["--volume-octaves", "1", "--sky-light", "0"]),
]
TARGET = 0.25


def measure(capture, scene, width, height, paths, extra):
    out = Path(tempfile.mkdtemp(prefix="avsm-media-smoke-"))
    command = [capture, "--scene", scene, "--width", str(width), "--height", str(height), "--frames", "1",
               "--out", str(out), "--quiet", "--compare-volume-shading", "--path-trace-volumes", str(paths)] + extra
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"smoke.py: {' '.join(command)} failed:\n{result.stderr}")
    return capture_report.volume_quality(out).path_traced, out


def main():
    parser = capture_report.scene_arguments(__doc__, 320, 180)
    parser.add_argument("--paths", type=int, default=64, help="path-traced paths per pixel")
    args = parser.parse_args()
    print(f"{Path(args.scene).name} at {args.width}x{args.height}, {args.paths} paths a pixel")
    print("| shading | smoke pixels | fast | reference | path traced | fast vs path traced |")
    print("|---|---|---|---|---|---|")
    default = None
    for name, extra in SHADINGS:
        figures, out = measure(args.capture, args.scene, args.width, args.height, args.paths, extra)
        default = default or figures
        print(f"| {name} | {figures.smoke_pixels} | {figures.fast_mean_luminance:.4f} | "
              f"{figures.reference_mean_luminance:.4f} | {figures.path_traced_mean_luminance:.4f} | "
              f"{figures.fast_relative:+.1%} |  ({out})")
    met = abs(default.fast_relative) <= TARGET
    print(f"target: multiple scattering within {TARGET:.0%} of the path tracer: "
          f"{default.fast_relative:+.1%}, {'met' if met else 'MISSED'}")


if __name__ == "__main__":
    main()

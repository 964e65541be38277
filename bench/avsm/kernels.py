#!/usr/bin/env python3
"""Soft surface shadows (shadow.kernel): the opaque pass's GPU ms on the default scene
with no kernel (bilinear: 4 curve taps per lookup) and with box / Gaussian kernels of
radius 1 and 2 ((2r + 2)^2 taps), interleaved over rounds in one run, and the cost per
extra tap: (opaque ms - opaque ms without a kernel) / (pixels x shadowed lights x extra
taps), an upper bound on the pixels the opaque pass shades.

usage: bench/avsm/kernels.py [--build DIR] [--width W] [--height H] [--rounds R]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CONFIGS = [("none", 1), ("box", 1), ("box", 2), ("gaussian", 1), ("gaussian", 2)]


def opaque_ms(capture, scene, out, args, kernel, radius):
    subprocess.run([capture, "--scene", scene, "--out", out, "--width", str(args.width), "--height", str(args.height),
                    "--frames", "2", "--quiet", "--kernel", kernel, "--kernel-radius", str(radius)],
                   check=True, capture_output=True)
    timings = json.load(open(os.path.join(out, "timings.json")))
    return sum(p["gpu_ms"]["median"] for p in timings["passes"] if p["name"] == "opaque")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--width", type=int, default=1280)
    parser.add_argument("--height", type=int, default=720)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    capture = os.path.join(args.build, "tools", "avsm-capture")
    scene = os.path.join(args.build, "content", "default", "scene.json")
    if not os.path.exists(capture):
        sys.exit(f"{capture} not found: build first")
    os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")
    lights = len(json.load(open(scene))["lights"])
    times = {c: [] for c in CONFIGS}
    with tempfile.TemporaryDirectory() as work:
        for _ in range(args.rounds):
            for kernel, radius in CONFIGS:
                times[(kernel, radius)].append(opaque_ms(capture, scene, os.path.join(work, f"{kernel}{radius}"), args,
                                                         kernel, radius))
    base = statistics.median(times[("none", 1)])
    pixels = args.width * args.height
    print(f"default scene, {args.width}x{args.height}, {lights} lights (--kernel on all), opaque pass GPU ms, "
          f"medians of {args.rounds} interleaved rounds")
    print(f"   {'kernel':<14}{'taps':>6}{'opaque ms':>11}{'x none':>8}{'ns / extra tap':>16}")
    for kernel, radius in CONFIGS:
        taps = 4 if kernel == "none" else (2 * radius + 2) ** 2
        ms = statistics.median(times[(kernel, radius)])
        per_tap = "" if kernel == "none" else f"{(ms - base) * 1e6 / (pixels * lights * (taps - 4)):.2f}"
        label = "none (bilinear)" if kernel == "none" else f"{kernel} r{radius}"
        print(f"   {label:<14}{taps:>6}{ms:>11.1f}{ms / base:>8.2f}{per_tap:>16}")


if __name__ == "__main__":
    main()

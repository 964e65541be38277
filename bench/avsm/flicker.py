#!/usr/bin/env python3
"""Flicker under a moving camera (issue 35's temporal stability target), per layout and
technique, on the default scene: the camera orbits its target (avsm-capture --orbit, 2
degrees a frame by default) while lights and casters hold still, and avsm-capture --flicker
measures at the surfaces the first frame sees (a 64 x 36 grid of its pixels) how much each
light's transmittance changes from frame to frame (capture/flicker.h). The exact shadows do
not change at all, so every change is the maps' own: fitting to the view, paged levels and
pages, filtering, and anything else that differs from frame to frame.

  default                 the scene file's settings (dense 256 maps fitted to the view, the
                          sun's gaussian kernel)
  dense scene 1024        a whole-scene 1024^2 map per light, bilinear: the target's bound
  dense view 256          the default maps without the kernel
  paged 16384/64          paged virtual maps, no kernel, trilinear across levels
  uncompressed ...        the exact lists' own map (the uncompressed reference), dense and paged

Per configuration: mean dL (per point and frame pair, the sum over lights of |dT| weighed by
each light's share of the light), and per light the mean, 95th percentile and maximum |dT|
and the share of |dT| above 0.1 (pops: a point going from lit to shadowed, not shimmer).
Target: the default's mean dL <= the dense whole-scene 1024^2 map's.

usage: bench/avsm/flicker.py [--build DIR] [--width W] [--height H] [--frames N] [--orbit DEGREES]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PAGED = ["--shadow-layout", "paged", "--kernel", "none", "--fit", "scene", "--filter", "trilinear",
         "--virtual-res", "16384", "--page-size", "64"]
CONFIGS = [
    ("default", []),
    ("dense scene 1024", ["--fit", "scene", "--shadow-res", "1024", "--kernel", "none"]),
    ("dense view 256", ["--kernel", "none"]),
    ("paged 16384/64", PAGED),
    ("uncompressed dense", ["--technique", "uncompressed"]),
    ("uncompressed paged", ["--technique", "uncompressed", *PAGED]),
]


def flicker(args, name, extra, work):
    out = os.path.join(work, name.replace(" ", "_").replace("/", "_"))
    command = [os.path.join(args.build, "tools", "avsm-capture"), "--out", out, "--width", str(args.width),
               "--height", str(args.height), "--orbit", str(args.orbit), "--frames", str(args.frames),
               "--flicker", "--quiet", *extra]
    result = subprocess.run(command, capture_output=True, text=True,
                            env=dict(os.environ, XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp")))
    if result.returncode != 0:
        sys.exit(f"flicker.py: {' '.join(command)} failed:\n{result.stderr}")
    with open(os.path.join(out, "flicker.json")) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--orbit", type=float, default=2.0)
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="avsm_flicker_bench_")
    print(f"camera orbit {args.orbit} degrees a frame, {args.frames} frames, {args.width}x{args.height}, default scene")
    print(f"{'configuration':<20} {'mean dL':>9}  per light: mean / p95 / max |dT|, share of |dT| > 0.1")
    results = {}
    for name, extra in CONFIGS:
        figures = flicker(args, name, extra, work)
        results[name] = figures
        lights = "  ".join(f"{l['light']} {l['mean_abs_dt']:.5f} / {l['p95_abs_dt']:.4f} / {l['max_abs_dt']:.3f}, "
                           f"{100 * l['share_over_0_1']:.2f}%" for l in figures["lights"])
        print(f"{name:<20} {figures['mean_delta_l']:9.6f}  {lights}")
    default, bound = results["default"]["mean_delta_l"], results["dense scene 1024"]["mean_delta_l"]
    print(f"\n{results['default']['points']} points; frame pairs measured (unfinished frames left out): " +
          ", ".join(f"{name} {r['frame_pairs']} ({r['unfinished_frames_left_out']})" for name, r in results.items()))
    print(f"default {default:.6f} vs dense whole-scene 1024^2 {bound:.6f}: target (<=) {'met' if default <= bound else 'MISSED'}")


if __name__ == "__main__":
    main()

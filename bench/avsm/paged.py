#!/usr/bin/env python3
"""Paged maps (shadow.layout paged) against dense ones on the default scene, measured in
one run with the configurations interleaved over rounds:

  dense 256 gaussian r2   the default scene before it was paged (a 256^2 map per light,
                          soft kernel on the sun): "today's default" in the targets
  dense 256 bilinear      the same maps without the kernel
  dense 1024 bilinear     the finest dense map lavapipe holds: the quality reference
  paged (default scene)   the default scene as it is: a 16384^2 virtual map per light in
                          32^2 pages, pools of 66 and 46 MiB, no kernel

A static camera first. Per configuration: the converged frame's GPU ms (the fastest
measured frame: a paged capture's first frames build its pages), the opaque pass and the
shadow passes' ms in that frame, the first frame's cost, the pages asked for, resident
and built, and the frame's mean |difference| from the dense 1024 frame (avsm-compare,
in 1/255).

Then the viewer's case: the camera orbits the static scene (avsm-capture --orbit, the
default 2 degrees a frame). Per frame after the first ones have converged: GPU ms, the
shadow passes' ms, and the pages built against those resident.

Then a light that moves every frame (avsm-capture --light-orbit, 2 degrees a frame), so
every page is stale every frame: today's default, and paged maps under each per-frame
budget of page builds per light (--page-builds). Per configuration: the GPU ms of the frames
while the light moves, against today's default static frame; the frames it takes,
after the light stops, until no page request is pending; and the shadow passes' ms per
step (capture per caster kind, sort, resolve) in the moving frames, in all and per
page built.

Last, resolution matching at --match-width x --match-height (1280x720), measured by the
engine (avsm-capture --measure-resolution, capture/resolution.h): the share of lit
receiver pixels whose texel is at most 1.5 screen pixels wide at its widest, the median
and 95th percentile widths, and the resident texels against the lit receiver pixels
(summed over the lights), for today's default, the paged default pool and the largest
pools lavapipe's 128 MiB storage range holds for two lights. Then the same figures on a
large scene (content/examples/cascades.scene.json, a 150 m avenue) for its sun paged at
16384, 65536 and 262144 texels (clipmap windows around the camera beyond 4096), beside
its own dense cascades.

usage: bench/avsm/paged.py [--build DIR] [--width W] [--height H] [--rounds R]
                           [--page-size P] [--virtual-res V] [--orbit DEGREES]
                           [--orbit-frames K] [--moving-frames K] [--budgets B ...]
                           [--match-width W] [--match-height H] [--clipmap-pool MIB]
                           [--only resolution|clipmap]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


# The default scene's lights as they were before it was paged (the targets' "today").
DENSE_DEFAULT = [{"layout": "dense", "fit": "view", "filter": "bilinear", "kernel": "gaussian", "kernel_radius": 2,
                  "resolution": 256},
                 {"layout": "dense", "filter": "trilinear", "resolution": 256}]


def configs(args, dense_scene):
    """(name, flags, scene) per configuration; dense_scene: the default scene with DENSE_DEFAULT."""
    paged = ["--virtual-res", str(args.virtual_res)] + (["--page-size", str(args.page_size)] if args.page_size else [])
    return [("dense 256 gaussian r2", [], dense_scene),
            ("dense 256 bilinear", ["--kernel", "none"], dense_scene),
            ("dense 1024 bilinear", ["--kernel", "none", "--shadow-res", "1024"], dense_scene),
            ("paged (default scene)", paged, None)]


def capture(tool, scene, out, args, flags, frames=4, orbit=0.0, light_orbit=0.0):
    subprocess.run([tool, "--scene", scene, "--out", out, "--width", str(args.width), "--height", str(args.height),
                    "--frames", str(frames), "--frames-in-flight", "1", "--orbit", str(orbit),
                    "--light-orbit", str(light_orbit), "--quiet"] + flags, check=True, capture_output=True)
    timings = json.load(open(os.path.join(out, "timings.json")))
    memory = json.load(open(os.path.join(out, "memory.json")))
    # The frame a renderer draws: without the capture's light pictures (inspection passes).
    frames = [dict(f, gpu_ms=f["gpu_ms"] - f["inspection_gpu_ms"]) for f in timings["frames"]]
    fastest = min(frames, key=lambda f: f["gpu_ms"])
    passes = {p["name"]: p["gpu_ms"]["min"] for p in timings["passes"]}
    pages = [l["pages"] for l in memory["lights"] if "pages" in l]
    return {"frame": fastest["gpu_ms"], "first": frames[0]["gpu_ms"], "opaque": passes.get("opaque", 0.0),
            "shadow": fastest["shadow_gpu_ms"], "pages": pages, "frames": frames}


def orbit_figures(result, skip):
    """Medians over the orbit's frames after `skip` (the frames that build the first pages)."""
    frames = result["frames"][skip:]
    resident = sum(p["resident"] for p in result["pages"])
    return {"frame": statistics.median(f["gpu_ms"] for f in frames),
            "shadow": statistics.median(f["shadow_gpu_ms"] for f in frames),
            "built": statistics.median(f["pages_built"] for f in frames),
            "most built": max(f["pages_built"] for f in frames), "resident": resident}


STEPS = ["capture opaque", "capture hair", "capture smoke", "sort", "resolve / build"]


def moving_light_figures(result, frames):
    """The frames while the light moves (timings.json's measured frames 1 .. frames - 2: the
    first one after the warm-up still builds from the first requests) and after it stops."""
    moving = result["frames"][1:frames - 1]
    built = statistics.median(f["pages_built"] for f in moving)
    steps = {s: statistics.median(f["shadow_step_gpu_ms"].get(s, 0.0) for f in moving) for s in STEPS}
    return {"frame": statistics.median(f["gpu_ms"] for f in moving),
            "shadow": statistics.median(f["shadow_gpu_ms"] for f in moving), "built": built, "steps": steps,
            "converge": len(result["frames"]) - (frames - 1)}


def print_moving_light(moving, today, args):
    print(f"\na moving light: --light-orbit {args.light_orbit} degrees a frame, {args.moving_frames} frames; medians "
          f"over the moving frames after the first; converge: frames rendered after the light stopped until no "
          f"page request was pending; per step: ms in a moving frame (ms per page built)")
    print(f"   {'configuration':<24}{'frame ms':>10}{'x today':>9}{'shadow':>9}{'built':>7}{'converge':>10}   "
          + "  ".join(f"{s:>20}" for s in STEPS))
    for name, xs in moving.items():
        frame = statistics.median(x["frame"] for x in xs)
        built = statistics.median(x["built"] for x in xs)
        steps = "  ".join(
            f"{statistics.median(x['steps'][s] for x in xs):>11.1f}"
            + (f" ({statistics.median(x['steps'][s] for x in xs) / built:>5.2f})" if built else f"{'':>8}")
            for s in STEPS)
        converge = max(x["converge"] for x in xs)
        print(f"   {name:<24}{frame:>10.1f}{frame / today:>9.2f}{statistics.median(x['shadow'] for x in xs):>9.1f}"
              f"{built:>7.0f}{converge:>10}   {steps}")
    print("   target: frame <= 1.5x today's default (static) frame; today's default rebuilds every frame anyway")


def mean_abs_error(compare, base, new):
    run = subprocess.run([compare, base, new, "--allow-different-settings"], capture_output=True, text=True)
    found = re.search(r"image mean_abs_error\s+([0-9.e-]+)", run.stdout)
    return float(found.group(1)) * 255.0 if found else 0.0


def resolution_figures(tool, scene, out, width, height, flags):
    """One converged frame's resolution.json and page figures (avsm-capture --measure-resolution)."""
    subprocess.run([tool, "--scene", scene, "--out", out, "--width", str(width), "--height", str(height),
                    "--frames", "1", "--quiet", "--measure-resolution"] + flags, check=True, capture_output=True)
    resolution = json.load(open(os.path.join(out, "resolution.json")))
    memory = json.load(open(os.path.join(out, "memory.json")))
    settings = json.load(open(os.path.join(out, "settings.json")))
    # Each paged light's page figures, with its texels per page (settings.json's page size).
    pages = [dict(l["pages"], page_texels=light["page_size"] ** 2)
             for l, light in zip(memory["lights"], settings["lights"]) if "pages" in l]
    return resolution, pages


MATCH_HEADER = f"   {'configuration':<24}{'matched':>9}{'median':>8}{'p95':>7}"


def match_cells(name, fraction, median, p95):
    return f"   {name:<24}{100 * fraction:>8.1f}%{median:>8.2f}{p95:>7.2f}"


def measured_rows(tool, scene, work, args, rows, tag):
    """Per row (name, flags[, scene]): its name, resolution.json and page figures at --match-width x
    --match-height."""
    for i, (name, flags, *own_scene) in enumerate(rows):
        yield (name,) + resolution_figures(tool, own_scene[0] if own_scene and own_scene[0] else scene,
                                           os.path.join(work, f"{tag}_{i}"), args.match_width,
                                           args.match_height, flags)


def with_light_shadows(scene, shadows, tag):
    """A copy of `scene` beside it (its assets are relative) with these settings over its lights'
    shadow blocks (a dense layout ignores the paged-only ones left there)."""
    with open(scene) as f:
        data = json.load(f)
    for light, shadow in zip(data["lights"], shadows):
        light.setdefault("shadow", {}).update(shadow)
    path = os.path.join(os.path.dirname(scene), f"bench_paged_{tag}_{os.getpid()}.scene.json")
    with open(path, "w") as f:
        json.dump(data, f)
    return path


def print_resolution(tool, scene, dense_scene, work, args):
    # The default scene's sun asks for about 1.4x the spot's pages: its pools are sized per
    # light, 112 MiB in all (what the 128 MiB storage binding holds), each asked to about 80%.
    of_64 = ["--page-size", "64"]
    rows = [("dense 256 gaussian r2", [], dense_scene), ("paged, 32 MiB of 64^2", of_64 + ["--page-pool-mib", "32"]),
            ("paged, 56 MiB of 64^2", of_64 + ["--page-pool-mib", "56"]),
            ("paged, 56 MiB of 32^2", ["--page-pool-mib", "56"]),
            ("default: 66+46 of 32^2", [])]
    print(f"\nresolution matched: {args.match_width}x{args.match_height}, one converged frame each; texel width "
          f"= the widest a texel of the level read is on screen (pixels); texels over lit receiver pixels summed "
          f"over the lights: resident (the pool, with pages kept from earlier frames), asked for (the frame's "
          f"pages), and needed (the least any map of square texels spends meeting the target: each receiver "
          f"pixel's area in the map over a texel just 1.5 px wide at its widest there)")
    print(f"{MATCH_HEADER}{'resident':>10}{'asked':>7}{'needed':>8}   per light: matched, median px, LOD bias, "
          f"pages asked / resident of slots")
    for name, resolution, pages in measured_rows(tool, scene, work, args, rows, "resolution"):
        lights = resolution["lights"]
        receivers = resolution["receivers"]

        def per_lit(texels):
            return f"{texels / receivers:.2f}" if pages and receivers else "-"
        resident = per_lit(sum(p["resident"] * p["page_texels"] for p in pages))
        asked = per_lit(sum(p["requested"] * p["page_texels"] for p in pages))
        needed = f"{sum(l['needed_texels'] for l in lights) / receivers:.2f}" if receivers else "-"
        per_light = "  ".join(
            f"{l['light']} {100 * l['matched_fraction']:.0f}% {l['median_texel_pixels']:.2f}"
            + (f" b{p['lod_bias']:g} {p['requested']}/{p['resident']}/{p['pool_slots']}" if p else "")
            for l, p in zip(lights, pages or [None] * len(lights)))
        median = statistics.median(l['median_texel_pixels'] for l in lights)
        p95 = max(l['p95_texel_pixels'] for l in lights)
        print(f"{match_cells(name, resolution['matched_fraction'], median, p95)}{resident:>10}{asked:>7}{needed:>8}"
              f"   {per_light}")
    print("   target: >= 95% matched; resident texels <= 2x lit receiver pixels; 66+46: the sun's and the "
          "spot's pools")


def print_clipmap(tool, work, args):
    """A large scene (content/examples/cascades.scene.json, a 150 m avenue; its sun paged over the
    scene) where the virtual resolution, not the pool, bounds the texels near the camera."""
    scene = os.path.join(ROOT, "content", "examples", "cascades.scene.json")
    base = ["--shadow-layout", "paged", "--kernel", "none", "--fit", "scene", "--cascades", "1",
            "--filter", "trilinear", "--page-size", str(args.page_size or 64), "--page-pool-mib", str(args.clipmap_pool)]
    rows = [("dense 1024 cascades x3", ["--shadow-res", "1024"])] + \
           [(f"paged {v}", base + ["--virtual-res", str(v)]) for v in (16384, 65536, 262144)]
    print(f"\na large scene: content/examples/cascades.scene.json (150 m), {args.match_width}x{args.match_height}, "
          f"the sun paged over the scene with a {args.clipmap_pool} MiB pool; beyond 4096 texels a level keeps a "
          f"window around the camera (clipmap), beyond the device's viewports its pages are cropped projections")
    print(f"{MATCH_HEADER}{'finest level read':>19}{'pages asked/resident':>22}")
    for name, resolution, pages in measured_rows(tool, scene, work, args, rows, "clipmap"):
        light = resolution["lights"][0]
        finest = next((level for level, n in enumerate(light["receivers_per_level"]) if n), "-")
        asked = f"{pages[0]['requested']}/{pages[0]['resident']}" if pages else "-"
        print(f"{match_cells(name, light['matched_fraction'], light['median_texel_pixels'], light['p95_texel_pixels'])}"
              f"{finest:>19}{asked:>22}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--page-size", type=int, help="the paged row's page size (default: the scene's, 32; "
                        "the large scene's: 64)")
    parser.add_argument("--virtual-res", type=int, default=16384)
    parser.add_argument("--orbit", type=float, default=2.0)
    parser.add_argument("--orbit-frames", type=int, default=10)
    parser.add_argument("--light-orbit", type=float, default=2.0)
    parser.add_argument("--moving-frames", type=int, default=8)
    parser.add_argument("--budgets", type=int, nargs="+", default=[16, 32, 64],
                        help="page builds per frame per light, for the moving light")
    parser.add_argument("--match-width", type=int, default=1280)
    parser.add_argument("--match-height", type=int, default=720)
    parser.add_argument("--clipmap-pool", type=int, default=100, help="MiB: the large scene's sun pool")
    parser.add_argument("--only", choices=["resolution", "clipmap"], help="print this table alone")
    args = parser.parse_args()
    tool = os.path.join(args.build, "tools", "avsm-capture")
    compare = os.path.join(args.build, "tools", "avsm-compare")
    scene = os.path.join(args.build, "content", "default", "scene.json")
    if not os.path.exists(tool):
        sys.exit(f"{tool} not found: build first")
    os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")
    dense_scene = with_light_shadows(scene, DENSE_DEFAULT, "dense")
    try:
        with tempfile.TemporaryDirectory() as work:
            if args.only == "resolution":
                print_resolution(tool, scene, dense_scene, work, args)
            elif args.only == "clipmap":
                print_clipmap(tool, work, args)
            else:
                run_all(tool, compare, scene, dense_scene, work, args)
    finally:
        os.remove(dense_scene)


def run_all(tool, compare, scene, dense_scene, work, args):
    rows = configs(args, dense_scene)
    orbit_rows = [rows[0], rows[1], rows[3]]
    results = {name: [] for name, *_ in rows}
    errors = {name: [] for name, *_ in rows}
    orbits = {name: [] for name, *_ in orbit_rows}
    moving_rows = [rows[0]] + [(f"paged, {b} a frame", rows[3][1] + ["--page-builds", str(b)], None)
                               for b in args.budgets]
    moving = {name: [] for name, *_ in moving_rows}
    skip = 2  # measured frames left out of the orbit figures: the paged maps' first builds
    for r in range(args.rounds):
        for i, (name, flags, own) in enumerate(rows):
            results[name].append(capture(tool, own or scene, os.path.join(work, f"{r}_{i}"), args, flags))
        reference = os.path.join(work, f"{r}_2")
        for i, (name, *_) in enumerate(rows):
            errors[name].append(mean_abs_error(compare, reference, os.path.join(work, f"{r}_{i}")))
        for i, (name, flags, own) in enumerate(orbit_rows):
            result = capture(tool, own or scene, os.path.join(work, f"{r}_orbit_{i}"), args, flags,
                             frames=args.orbit_frames, orbit=args.orbit)
            orbits[name].append(orbit_figures(result, skip))
        for i, (name, flags, own) in enumerate(moving_rows):
            result = capture(tool, own or scene, os.path.join(work, f"{r}_moving_{i}"), args, flags,
                             frames=args.moving_frames, light_orbit=args.light_orbit)
            moving[name].append(moving_light_figures(result, args.moving_frames))
    today = statistics.median(x["frame"] for x in results[rows[0][0]])
    print(f"default scene, {args.width}x{args.height}, 2 lights, AVSM-8; GPU ms, medians of {args.rounds} "
          f"interleaved rounds; converged frame = the fastest of 4 (+ frames rendered again until converged); "
          f"frames without the capture's light pictures")
    print(f"   {'configuration':<24}{'frame ms':>10}{'x today':>9}{'opaque':>9}{'shadow':>9}{'1st frame':>11}"
          f"{'|d| /255':>10}   pages asked / resident / built (per light)")
    for name, *_ in rows:
        xs = results[name]
        frame = statistics.median(x["frame"] for x in xs)
        pages = "  ".join(f"{p['requested']}/{p['resident']}/{p['built']}" for p in xs[-1]["pages"])
        print(f"   {name:<24}{frame:>10.1f}{frame / today:>9.2f}{statistics.median(x['opaque'] for x in xs):>9.1f}"
              f"{statistics.median(x['shadow'] for x in xs):>9.1f}{statistics.median(x['first'] for x in xs):>11.1f}"
              f"{statistics.median(errors[name]):>10.2f}   {pages}")
    dense_rebuild = statistics.median(o["shadow"] for o in orbits[rows[1][0]])
    orbit_today = statistics.median(o["frame"] for o in orbits[rows[0][0]])
    print(f"\norbiting the static scene: --orbit {args.orbit} degrees a frame, {args.orbit_frames} frames, the "
          f"first {skip + 1} left out (warm-up and first builds); medians per frame")
    print(f"   {'configuration':<24}{'frame ms':>10}{'x today':>9}{'shadow':>9}{'x dense':>9}"
          f"{'built':>8}{'most':>6}{'resident':>10}{'built %':>9}")
    for name, *_ in orbit_rows:
        xs = orbits[name]
        frame = statistics.median(o["frame"] for o in xs)
        shadow = statistics.median(o["shadow"] for o in xs)
        built = statistics.median(o["built"] for o in xs)
        resident = xs[-1]["resident"]
        share = f"{100.0 * built / resident:>8.1f}%" if resident else f"{'-':>9}"
        print(f"   {name:<24}{frame:>10.1f}{frame / orbit_today:>9.2f}{shadow:>9.1f}{shadow / dense_rebuild:>9.2f}"
              f"{built:>8.0f}{max(o['most built'] for o in xs):>6}{resident:>10}{share}")
    print("   x dense: the shadow passes against the dense 256 bilinear full rebuild in the same run")
    print_moving_light(moving, today, args)
    print_resolution(tool, scene, dense_scene, work, args)
    print_clipmap(tool, work, args)


if __name__ == "__main__":
    main()

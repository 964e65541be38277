#!/usr/bin/env python3
"""AVSM-4/8/12/16, deep shadow maps at two error thresholds, opacity shadow maps
(32 planes) and Fourier opacity maps (16 terms) against the uncompressed reference,
measured in one run (a table in the manner of the AVSM paper's Table 1). AVSM-4/8/12/16,
OSM-32 and FOM-16 also as the fixed-memory build ("fixed" rows: straight from the
casters, no lists), with a line comparing fixed to lists.

Renders the default scene once per technique with avsm-capture, reads the
per-pass GPU timings (timings.json) and probes every light's transmittance at a
grid of points through the scene (probes.json), then prints per technique:
capture, sort, resolve, mips, camera (shading with lookups; the engine's stages of the
passes, engine/capture/pass_stages.h) and frame ms, the map memory, and the mean/max
transmittance error against the uncompressed lists at the receivers: a 20x12x16 grid
through the scene's bounds, counting the points whose reference transmittance is
strictly between 0 and 1 (partially shadowed: where a compressed curve can be wrong).
Then each row's frame time over AVSM-8's and the ns per segment put into the maps (the
build passes' time over the segments they took). "trans MiB": the transient bytes
besides the map (the lists, or the fixed build's depth image and hair bins).

--rows REGEX measures only the rows whose label matches (the uncompressed reference and
AVSM-8, which the errors and ratios are taken against, always run); the ratio lines then
leave out what was not measured. DSM over AVSM-8 is printed next to the AVSM paper's
Table 1 (Salvi et al. 2010, DSM 0.01 against AVSM 8: frame 251 / 12.1 ms, about 21x;
compress 193 / 0.7 ms, about 276x).

usage: bench/avsm/techniques.py [--build DIR] [--width W] [--height H] [--frames K]
                                [--shadow-res R] [--filter F] [--scene FILE] [--rows REGEX]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402


def grid_points(lo, hi, counts):
    points = []
    for i in range(counts[0]):
        for j in range(counts[1]):
            for k in range(counts[2]):
                points.append([lo[a] + (hi[a] - lo[a]) * (idx + 0.5) / counts[a]
                               for a, idx in enumerate((i, j, k))])
    return points


# The engine's stages of a frame (timings.json "stage", engine/capture/pass_stages.h) as this
# table's columns.
COLUMN_OF_STAGE = {"shadow capture": "capture", "sort": "sort", "resolve / build": "resolve", "mips": "mips",
                   "camera shading": "camera", "other": "other"}


def run(capture, scene, out, args, technique, nodes, probe_file, params=(), build="lists"):
    cmd = [capture, "--out", out, "--width", str(args.width), "--height", str(args.height),
           "--frames", str(args.frames), "--shadow-res", str(args.shadow_res), "--quiet",
           "--technique", technique, "--probe", probe_file, "--filter", args.filter, "--build", build]
    if scene:
        cmd += ["--scene", scene]
    if nodes:
        cmd += ["--nodes", str(nodes)]
    for param in params:
        cmd += ["--shadow-param", param]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    timings = capture_report.timings(out)
    memory = capture_report.memory(out)
    probes = capture_report.probes(out)
    ms = {}
    for p in timings.passes:
        column = COLUMN_OF_STAGE[p.stage]
        ms[column] = ms.get(column, 0.0) + p.gpu_ms.median
    ms["frame"] = timings.frame_gpu_ms.median
    map_bytes = sum(light.map_bytes for light in memory.lights)
    # Transient bytes besides the map: the lists, or the fixed build's depth image and bins.
    capture_bytes = sum(light.capture_bytes + (light.fixed_transient_bytes or 0) for light in memory.lights)
    values = [light.transmittance for light in probes.lights]
    # ns per segment put into curves: the resolve over the captured segments, or the
    # fixed build's kernel over what it inserted (the smoke march included).
    fixed = [light.inserted_segments for light in memory.lights if light.inserted_segments is not None]
    segments = sum(fixed) if fixed else sum(light.capture_requested for light in memory.lights)
    ms["ns_per_segment"] = ms.get("resolve", 0.0) * 1e6 / segments if segments else 0.0
    return ms, map_bytes, capture_bytes, values


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--scene", default="")
    parser.add_argument("--width", type=int, default=1280)
    parser.add_argument("--height", type=int, default=720)
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--shadow-res", type=int, default=256)
    # Bilinear everywhere by default, so the errors are those of compression alone
    # (trilinear reads AVSM mips, which the uncompressed reference does not have).
    parser.add_argument("--filter", default="bilinear", choices=["point", "bilinear", "trilinear"])
    parser.add_argument("--rows", default="", help="only rows whose label matches this regex (plus the references)")
    args = parser.parse_args()
    capture = os.path.join(args.build, "tools", "avsm-capture")
    if not os.path.exists(capture):
        sys.exit(f"{capture} not found: build first (cmake --build {args.build})")
    os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")

    work = tempfile.mkdtemp(prefix="avsm-bench-")
    # Receivers: a grid through the scene's bounds (read from a tiny first capture),
    # slightly inset so the points lie inside what the lights' maps cover.
    bounds_run = os.path.join(work, "bounds")
    subprocess.run([capture, "--out", bounds_run, "--width", "16", "--height", "16", "--frames", "1",
                    "--shadow-res", "16", "--quiet"] + (["--scene", args.scene] if args.scene else []),
                   check=True, stdout=subprocess.DEVNULL)
    bounds = capture_report.memory(bounds_run).scene_bounds
    lo = [a + 0.02 * (b - a) for a, b in zip(bounds.min, bounds.max)]
    hi = [b - 0.02 * (b - a) for a, b in zip(bounds.min, bounds.max)]
    points = grid_points(lo, hi, [20, 12, 16])
    probe_file = os.path.join(work, "probes.json")
    json.dump(points, open(probe_file, "w"))

    # (label, technique, AVSM nodes, technique parameters[, build])
    rows = ([("uncompressed", "uncompressed", None, ())] +
            [(f"AVSM-{n}", "avsm", n, ()) for n in (4, 8, 12, 16)] +
            [(f"AVSM-{n} fixed", "avsm", n, (), "fixed") for n in (4, 8, 12, 16)] +
            [(f"DSM e={e}", "dsm", None, (f"error={e}",)) for e in (0.01, 0.05)] +
            [("OSM-32", "osm", None, ("slices=32",)), ("FOM-16", "fom", None, ("terms=16",))] +
            # Built straight from the casters, as their papers build them (additive).
            [("OSM-32 fixed", "osm", None, ("slices=32",), "fixed"), ("FOM-16 fixed", "fom", None, ("terms=16",), "fixed")])
    # Every other registered technique at its defaults, so a new one is measured too.
    registered = subprocess.run([capture, "--list-techniques"], check=True, capture_output=True, text=True).stdout.split()
    rows += [(name, name, None, ()) for name in registered if name not in {row[1] for row in rows}]
    if args.rows:
        rows = [row for row in rows if row[0] in ("uncompressed", "AVSM-8") or re.search(args.rows, row[0])]
    print(f"{os.path.basename(args.scene) or 'default scene'}:", file=sys.stderr)
    results = {}
    for label, technique, nodes, params, *build in rows:
        print(f"rendering {label} ...", file=sys.stderr)
        results[label] = run(capture, args.scene, os.path.join(work, label.replace(" ", "_")), args, technique, nodes,
                             probe_file, params, *build)

    reference = results["uncompressed"][3]
    receivers = sum(1 for light in reference for r in light if 0.0 < r < 1.0)
    print(f"\nscene: {args.scene or 'default'}  {args.width}x{args.height}, shadow maps {args.shadow_res}^2, "
          f"{args.filter} lookups, GPU ms medians over {max(args.frames - 1, 1)} frames; receivers: {len(points)} grid points x "
          f"{len(reference)} lights, errors over partially shadowed ones")
    header = (f"{'technique':<13}{'capture':>9}{'sort':>8}{'build':>9}{'mips':>8}{'camera':>9}{'frame':>9}"
              f"{'map MiB':>9}{'trans MiB':>10}{'mean err':>10}{'max err':>9}{'frame/AVSM-8':>13}{'ns/seg':>8}")
    print(header)
    print("-" * len(header))
    avsm8_frame = results["AVSM-8"][0]["frame"]
    for label, (ms, map_bytes, capture_bytes, values) in results.items():
        errors = []
        for light_values, light_reference in zip(values, reference):
            for v, r in zip(light_values, light_reference):
                if 0.0 < r < 1.0:
                    errors.append(abs(v - r))
        mean = sum(errors) / len(errors) if errors else 0.0
        worst = max(errors) if errors else 0.0
        print(f"{label:<13}{ms.get('capture', 0):>9.1f}{ms.get('sort', 0):>8.1f}{ms.get('resolve', 0):>9.1f}"
              f"{ms.get('mips', 0):>8.1f}{ms.get('camera', 0):>9.1f}{ms['frame']:>9.1f}"
              f"{map_bytes / 2**20:>9.2f}{capture_bytes / 2**20:>10.2f}{mean:>10.4f}{worst:>9.4f}"
              f"{ms['frame'] / avsm8_frame:>13.2f}{ms['ns_per_segment']:>8.0f}")
    print(f"\nerror receivers: {receivers} (light, point) pairs with 0 < T_ref < 1; outputs in {work}")
    frame = {label: r[0]["frame"] for label, r in results.items()}

    def ratio(text, a, b, of):
        return f"{text} = {of[a] / of[b]:.2f}" if a in of and b in of else None

    def line(title, parts):
        parts = [p for p in parts if p]
        if parts:
            print(f"{title}: " + "; ".join(parts))

    line("ratios (frame ms, this run)", [
        ratio("AVSM-8 / OSM-32", "AVSM-8", "OSM-32", frame),
        ratio("AVSM-8 fixed / OSM-32 fixed", "AVSM-8 fixed", "OSM-32 fixed", frame),
        ratio("DSM e=0.01 / AVSM-8", "DSM e=0.01", "AVSM-8", frame),
        ratio("uncompressed / AVSM-8", "uncompressed", "AVSM-8", frame)])
    build_ms = {label: r[0].get("capture", 0) + r[0].get("sort", 0) + r[0].get("resolve", 0) for label, r in results.items()}
    resolve_ms = {label: r[0].get("resolve", 0) for label, r in results.items()}
    line("DSM against AVSM-8 (this run; the paper's Table 1: frame 251 / 12.1 = 21x, compress 193 / 0.7 = 276x)", [
        ratio(f"{label} frame ms {frame[label]:.1f} / {frame['AVSM-8']:.1f}", label, "AVSM-8", frame) + ", " +
        ratio(f"build ms {resolve_ms[label]:.1f} / {resolve_ms['AVSM-8']:.1f}", label, "AVSM-8", resolve_ms)
        for label in results if label.startswith("DSM")])
    bytes_of = {label: r[1] + r[2] for label, r in results.items()}
    line("fixed against lists (this run)", [
        f"AVSM-{n} build ms {build_ms[f'AVSM-{n} fixed']:.1f} / {build_ms[f'AVSM-{n}']:.1f} = "
        f"{build_ms[f'AVSM-{n} fixed'] / build_ms[f'AVSM-{n}']:.2f}x, map + transient bytes "
        f"{bytes_of[f'AVSM-{n} fixed'] / bytes_of[f'AVSM-{n}']:.2f}x" for n in (4, 8, 12, 16)
        if f"AVSM-{n} fixed" in results and f"AVSM-{n}" in results])

if __name__ == "__main__":
    main()

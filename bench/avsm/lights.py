#!/usr/bin/env python3
"""Shadowed lights at scale: three tables, each measured in one run, with the targets
next to the figures (MET / MISSED).

a. Clustered maps (seed 004) against one fitted map at equal map bytes, on
   bench_sparse (two plumes and the hair curtain 20-25 m apart over a 96 m ground):
   one 512^2 map against --clusters 4 at 256^2 each. Transmittance is probed at a grid
   through each caster group's box swept down its shadow to the ground, against the
   exact reference (uncompressed capture lists, clustered the same way at 4x the
   clustered maps' resolution, so finer than both). Mean and max |T - T_ref| over the
   partially shadowed points (0 < T_ref < 1, where a map can be wrong) and over all
   points; shadow build ms (passes named "light ..."), camera ms (the passes that look
   the maps up: opaque, hair, volumes), frame ms (GPU, without the capture's light debug
   images) and the error ratio clustered / single. Target: <= 0.5.
b. 1, 2, 4, 8 and 16 of bench_many_lights' lights (its every first 4k lights hold one
   directional, two spot and one point light each): frame ms and its slope (ms per
   light), and the CPU cost per light of recording the frame (trace.json's "record":
   the executor compiling the graph and recording every pass; timings.json's per-pass
   cpu_record_ms summed; and building the graph). Targets: frame ms linear in lights
   (the per-light cost of each doubling from 4 lights on, where the mix of types is
   the same, within 25% of the fitted slope), recording <= 0.1 ms per light.
c. A point light's cube (6 faces) against one spot light of the same face resolution,
   at the same place over the same casters (the default scene's): shadow build ms
   ratio. Target: <= 6.5x.

Times vary 10-30% from run to run, so configurations compared by time are run
interleaved (round after round, every configuration once per round) and the medians
over rounds are compared; error figures come from the first round (they do not vary).

usage: bench/avsm/lights.py [--build DIR] [--width W] [--height H] [--frames K]
                            [--rounds R] [--tables abc]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from typing import Dict, List, Sequence

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402

SHARED_PASSES = ("shadow parameters",)  # per frame, not per light


def verdict(met):
    return "MET" if met else "MISSED"


# ---- running captures ----

@dataclass
class Run:
    folder: str
    timings: capture_report.Timings
    memory: capture_report.Memory
    cpu: List[capture_report.FrameCpu]  # measured frames only

    def pass_ms(self, keep) -> float:
        return sum(p.gpu_ms.median for p in self.timings.passes if keep(p.name))

    def build_ms(self) -> float:
        return self.pass_ms(is_shadow_build)

    def camera_ms(self) -> float:
        return self.pass_ms(is_camera)

    def frame_ms(self) -> float:
        # Without the capture's own light debug images (a pass per light no renderer has).
        return self.timings.frame_gpu_ms.median - self.pass_ms(is_debug_image)

    def record_pass_ms(self) -> float:  # the passes' own recording callbacks
        return sum(p.cpu_record_ms.median for p in self.timings.passes)

    def record_ms(self) -> float:  # Executor::record as a whole
        return statistics.median(f.record_ms for f in self.cpu)

    def build_graph_ms(self) -> float:
        return statistics.median(f.build_graph_ms for f in self.cpu)

    def map_bytes(self) -> int:
        return sum(light.map_bytes for light in self.memory.lights)


def is_debug_image(name):
    # light<i>_transmittance.png: the capture's own picture of a light's map.
    return name.startswith("light ") and name.endswith("debug image")


def is_shadow_build(name):
    # A light's capture, sort, build and mips passes.
    return name.startswith("light ") and not is_debug_image(name)


def is_camera(name):
    # The passes that look the maps up: opaque, hair and volume shading.
    return not name.startswith("light ") and name not in SHARED_PASSES and name != "tonemap"


class Capture:
    def __init__(self, args, work):
        self.exe = os.path.join(args.build, "tools", "avsm-capture")
        if not os.path.exists(self.exe):
            sys.exit(f"{self.exe} not found: build first (cmake --build {args.build})")
        self.args = args
        self.work = work
        self.count = 0

    def run(self, label, scene, flags=(), probe_file=None, size=None, warnings=True) -> Run:
        self.count += 1
        out = os.path.join(self.work, f"{self.count:03d}_{label.replace(' ', '_').replace('/', '_')}")
        width, height, frames = size or (self.args.width, self.args.height, self.args.frames)
        cmd = [self.exe, "--scene", scene, "--out", out, "--width", str(width), "--height", str(height),
               "--frames", str(frames), "--quiet", *flags]
        if probe_file:
            cmd += ["--probe", probe_file]
        print(f"  {label}: {' '.join(cmd[1:])}", file=sys.stderr)
        result = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if result.returncode != 0:
            sys.exit(f"avsm-capture failed ({result.returncode}) for {label}:\n{result.stderr}")
        if warnings and "warning" in result.stderr:
            print(result.stderr.strip(), file=sys.stderr)
        cpu = capture_report.frame_cpu(out)
        measured = cpu[1:] if len(cpu) > 1 else cpu  # the first frame warms up when there are more
        return Run(out, capture_report.timings(out), capture_report.memory(out), measured)


def interleaved(capture, rounds, configs) -> Dict[str, List[Run]]:
    """configs: [(label, scene, flags)]. Every configuration once per round, in turn."""
    runs: Dict[str, List[Run]] = {label: [] for label, _, _ in configs}
    for r in range(rounds):
        print(f"round {r + 1}/{rounds}", file=sys.stderr)
        for label, scene, flags in configs:
            runs[label].append(capture.run(label, scene, flags))
    return runs


def median_of(runs: Sequence[Run], figure) -> float:
    return statistics.median(figure(run) for run in runs)


# ---- scenes written for a table ----

def absolute_files(scene, scene_dir):
    """The scene's asset paths made absolute, so that it can be written elsewhere."""
    for key in ("models", "volumes", "hair"):
        for entry in scene.get(key, []):
            entry["file"] = os.path.join(scene_dir, entry["file"])
    return scene


def read_scene(path):
    with open(path) as f:
        return absolute_files(json.load(f), os.path.dirname(os.path.abspath(path)))


def write_scene(scene, path):
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


# ---- a. clustered against single at equal bytes ----

def grid(lo, hi, counts):
    return [[lo[a] + (hi[a] - lo[a]) * (idx + 0.5) / counts[a] for a, idx in enumerate((i, j, k))]
            for i in range(counts[0]) for j in range(counts[1]) for k in range(counts[2])]


def shadow_region(box_min, box_max, direction, ground_y):
    """The box and where the light carries it down to the ground: an axis-aligned box
    around both (the caster, its inside, the air under it and its shadow)."""
    drop = (box_min[1] - ground_y) / -direction[1] if direction[1] < 0 else 0.0
    lo = [min(box_min[a], box_min[a] + direction[a] * drop) for a in range(3)]
    hi = [max(box_max[a], box_max[a] + direction[a] * drop) for a in range(3)]
    lo[1] = ground_y + 0.02  # just above the ground: its receivers, not its inside
    return lo, hi


def caster_group_bounds(capture, scene, work):
    """World bounds of each volume and hair entry of `scene`, from a tiny capture of a
    scene holding only that entry (memory.json's scene_bounds)."""
    bounds = []
    for key in ("volumes", "hair"):
        for entry in scene.get(key, []):
            alone = {"version": 1, key: [entry], "lights": scene["lights"], "cameras": scene["cameras"]}
            path = write_scene(alone, os.path.join(work, f"alone_{entry['name']}.scene.json"))
            # Only the bounds count: a capture overflow in its tiny maps does not matter.
            run = capture.run(f"bounds of {entry['name']}", path, ["--shadow-res", "64"], size=(16, 16, 1),
                              warnings=False)
            bounds.append((entry["name"], run.memory.scene_bounds))
    return bounds


def normalized(v):
    length = sum(c * c for c in v) ** 0.5
    return [c / length for c in v]


def probe_groups(capture, scene, work):
    """[(caster group name, probe points)]: a grid through each group's shadow region."""
    direction = normalized(scene["lights"][0]["direction"])
    groups = []
    for name, b in caster_group_bounds(capture, scene, work):
        lo, hi = shadow_region(b.min, b.max, direction, ground_y=0.0)
        groups.append((name, grid(lo, hi, [16, 10, 16])))
    return groups


@dataclass
class Errors:
    mean: float   # over the partially shadowed points (0 < T_ref < 1)
    max: float
    mean_all: float  # over every point
    max_all: float
    partial: int


def errors(values, reference) -> Errors:
    partial = [abs(v - r) for v, r in zip(values, reference) if 0.0 < r < 1.0]
    every = [abs(v - r) for v, r in zip(values, reference)]
    mean = lambda e: sum(e) / len(e) if e else 0.0  # noqa: E731
    return Errors(mean(partial), max(partial, default=0.0), mean(every), max(every, default=0.0), len(partial))


def transmittance(run: Run) -> List[float]:
    return capture_report.probes(run.folder).lights[0].transmittance


def table_clusters(capture, args, content, work):
    print("\n== a. clustered maps against one fitted map at equal map bytes (bench_sparse) ==", file=sys.stderr)
    scene_file = os.path.join(content, "bench_sparse.scene.json")
    groups = probe_groups(capture, read_scene(scene_file), work)
    points = [p for _, group in groups for p in group]
    probe_file = os.path.join(work, "sparse_probes.json")
    with open(probe_file, "w") as f:
        json.dump(points, f)
    single_res, clusters, cluster_res = 512, 4, 256
    common = ["--technique", "avsm", "--nodes", "8", "--filter", "bilinear", "--probe", probe_file]
    configs = [(f"single {single_res}^2", scene_file, common + ["--clusters", "1", "--shadow-res", str(single_res)]),
               (f"{clusters} clusters x {cluster_res}^2", scene_file,
                common + ["--clusters", str(clusters), "--shadow-res", str(cluster_res)])]
    # The exact lists, finer than either: clustered the same way at 4x the resolution,
    # and (a check that does not trust the clustering) one map at 2048^2.
    exact = ["--technique", "uncompressed", "--filter", "bilinear"]
    references = {label: capture.run(label, scene_file, exact + flags, probe_file, size=(args.width, args.height, 1))
                  for label, flags in
                  ((f"reference {clusters} clusters x {4 * cluster_res}^2",
                    ["--clusters", str(clusters), "--shadow-res", str(4 * cluster_res)]),
                   ("reference single 2048^2", ["--clusters", "1", "--shadow-res", "2048"]))}
    reference, check = (transmittance(r) for r in references.values())
    runs = interleaved(capture, args.rounds, configs)

    print(f"\na. bench_sparse, sun only, {args.width}x{args.height}, AVSM-8 bilinear; GPU ms medians over "
          f"{args.rounds} interleaved rounds x {max(args.frames - 1, 1)} measured frames")
    for label, r in references.items():
        light = r.memory.lights[0]
        print(f"   {label}: uncompressed lists, {light.maps} map(s) ({light.map_kind}) at "
              f"{light.resolution}^2{', CAPTURE OVERFLOWED' if light.capture_overflowed else ''}")
    print(f"   errors against the first; {len(points)} probe points through the shadow regions of "
          f"{', '.join(name for name, _ in groups)}, {sum(1 for r in reference if 0.0 < r < 1.0)} with 0 < T_ref < 1")
    header = (f"   {'configuration':<22}{'maps':>12}{'map bytes':>11}{'mean err':>10}{'max err':>9}"
              f"{'mean all':>10}{'max all':>9}{'build ms':>10}{'camera ms':>11}{'frame ms':>10}")
    print(header)
    print("   " + "-" * (len(header) - 3))
    for label, _, _ in configs:
        first = runs[label][0]
        light = first.memory.lights[0]
        e = errors(transmittance(first), reference)
        print(f"   {label:<22}{f'{light.maps} {light.map_kind}':>12}{first.map_bytes():>11}{e.mean:>10.4f}{e.max:>9.4f}"
              f"{e.mean_all:>10.4f}{e.max_all:>9.4f}{median_of(runs[label], Run.build_ms):>10.1f}"
              f"{median_of(runs[label], Run.camera_ms):>11.1f}{median_of(runs[label], Run.frame_ms):>10.1f}")
    single, clustered = (label for label, _, _ in configs)

    def ratio(against, within=slice(None)):
        means = [errors(transmittance(runs[label][0])[within], against[within]).mean for label in (single, clustered)]
        return means[1] / means[0] if means[0] > 0 else float("inf")

    bytes_single, bytes_clustered = runs[single][0].map_bytes(), runs[clustered][0].map_bytes()
    print(f"   map bytes {bytes_clustered} / {bytes_single}: {'equal' if bytes_single == bytes_clustered else 'NOT EQUAL'}")
    main_ratio = ratio(reference)
    print(f"   mean error clustered / single = {main_ratio:.2f}   target <= 0.5   {verdict(main_ratio <= 0.5)}")
    offsets = [0]
    for _, group in groups:
        offsets.append(offsets[-1] + len(group))
    print("   the same ratio per caster group: " + ", ".join(
        f"{name} {ratio(reference, slice(a, b)):.2f}" for (name, _), a, b in zip(groups, offsets, offsets[1:])) +
        f"; against the single 2048^2 reference: {ratio(check):.2f}")
    build_ratio = median_of(runs[clustered], Run.build_ms) / median_of(runs[single], Run.build_ms)
    camera_ratio = median_of(runs[clustered], Run.camera_ms) / median_of(runs[single], Run.camera_ms)
    print(f"   clustered / single: build ms {build_ratio:.2f}x, camera ms {camera_ratio:.2f}x (no target)")


# ---- b. cost per light ----

def fit_line(xs, ys):
    """Least squares y = a + b x; returns a, b and R^2."""
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    a = my - b * mx
    ss_tot = sum((y - my) ** 2 for y in ys)
    ss_res = sum((y - a - b * x) ** 2 for x, y in zip(xs, ys))
    return a, b, 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0


def table_many_lights(capture, args, content, work):
    print("\n== b. cost per shadowed light (bench_many_lights) ==", file=sys.stderr)
    scene = read_scene(os.path.join(content, "bench_many_lights.scene.json"))
    counts = [1, 2, 4, 8, 16]
    configs = []
    for n in counts:
        reduced = dict(scene, lights=scene["lights"][:n])
        configs.append((f"{n} lights", write_scene(reduced, os.path.join(work, f"many_lights_{n}.scene.json")), []))
    runs = interleaved(capture, args.rounds, configs)
    rows = []
    for n, (label, _, _) in zip(counts, configs):
        r = runs[label]
        kinds: Dict[str, int] = {}
        for light in r[0].memory.lights:
            kinds[light.map_kind] = kinds.get(light.map_kind, 0) + 1
        rows.append({"n": n, "maps": sum(light.maps for light in r[0].memory.lights),
                     "kinds": ", ".join(f"{v} {k}" for k, v in sorted(kinds.items())),
                     "frame": median_of(r, Run.frame_ms), "build": median_of(r, Run.build_ms),
                     "record": median_of(r, Run.record_ms), "record_passes": median_of(r, Run.record_pass_ms),
                     "build_graph": median_of(r, Run.build_graph_ms)})

    print(f"\nb. bench_many_lights, first N lights, 256^2 AVSM-8 each, {args.width}x{args.height}; medians over "
          f"{args.rounds} interleaved rounds x {max(args.frames - 1, 1)} measured frames")
    header = (f"   {'lights':>6}{'maps':>6}  {'map kinds':<26}{'frame ms':>10}{'shadow ms':>11}"
              f"{'record ms':>11}{'pass rec ms':>12}{'graph ms':>10}")
    print(header)
    print("   " + "-" * (len(header) - 3))
    for row in rows:
        print(f"   {row['n']:>6}{row['maps']:>6}  {row['kinds']:<26}{row['frame']:>10.1f}{row['build']:>11.1f}"
              f"{row['record']:>11.3f}{row['record_passes']:>12.3f}{row['build_graph']:>10.3f}")
    xs = [row["n"] for row in rows]
    base, slope, r2 = fit_line(xs, [row["frame"] for row in rows])
    print(f"   frame ms = {base:.1f} + {slope:.1f} x lights (R^2 {r2:.3f}); ms per light = {slope:.1f}")
    # From 4 lights on every doubling adds the same mix of types: its cost per light
    # should be the slope's, if the frame is linear in lights.
    doublings = [(a, b) for a, b in zip(rows, rows[1:]) if a["n"] >= 4]
    steps = [(b["frame"] - a["frame"]) / (b["n"] - a["n"]) for a, b in doublings]
    linear = all(abs(step - slope) <= 0.25 * slope for step in steps)
    print("   per light, each doubling: " + ", ".join(
        f"{a['n']}->{b['n']}: {step:.1f} ms" for (a, b), step in zip(doublings, steps)) +
        f"   target: within 25% of {slope:.1f}   {verdict(linear)}")
    for key, what in (("record", "recording (Executor::record)"), ("record_passes", "the passes' record callbacks"),
                      ("build_graph", "building the graph (no target)")):
        _, per_light, _ = fit_line(xs, [row[key] for row in rows])
        target = "" if key == "build_graph" else f"   target <= 0.1 ms   {verdict(per_light <= 0.1)}"
        print(f"   CPU {what}: {per_light:.4f} ms per light{target}")


# ---- c. cube against spot ----

def table_cube(capture, args, content, work):
    print("\n== c. point light cube against one spot light ==", file=sys.stderr)
    scene = read_scene(os.path.join(content, "scene.json"))
    position, target = [0.2, 3.2, 0.4], [0.0, 0.9, -0.3]
    shadow = {"technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": True}
    # A spot cone of 45 degrees from its axis spans what a cube face does.
    lights = {
        "point cube": {"name": "lamp", "type": "point", "position": position, "range": 8.0, "intensity": 20.0,
                       "shadow": shadow},
        "spot": {"name": "lamp", "type": "spot", "position": position, "target": target, "inner_cone_deg": 40.0,
                 "outer_cone_deg": 45.0, "intensity": 20.0, "shadow": shadow},
    }
    configs = [(label, write_scene(dict(scene, lights=[light]), os.path.join(work, f"lamp_{label.split()[0]}.scene.json")),
                []) for label, light in lights.items()]
    runs = interleaved(capture, args.rounds, configs)
    print(f"\nc. one light at {position} over the default scene's casters, 256^2 AVSM-8 per map, "
          f"{args.width}x{args.height}; medians over {args.rounds} interleaved rounds")
    header = f"   {'light':<12}{'maps':>6}{'build ms':>10}{'ms per map':>12}{'frame ms':>10}"
    print(header)
    print("   " + "-" * (len(header) - 3))
    build = {}
    for label, _, _ in configs:
        r = runs[label]
        maps = r[0].memory.lights[0].maps
        build[label] = median_of(r, Run.build_ms)
        print(f"   {label:<12}{maps:>6}{build[label]:>10.1f}{build[label] / maps:>12.1f}{median_of(r, Run.frame_ms):>10.1f}")
    ratio = build["point cube"] / build["spot"]
    print(f"   shadow build ms cube / spot = {ratio:.2f}x   target <= 6.5x   {verdict(ratio <= 6.5)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--frames", type=int, default=2, help="per capture; the first warms up")
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds of the timed configurations")
    parser.add_argument("--tables", default="abc", help="which tables: any of a, b, c")
    args = parser.parse_args()
    if args.rounds < 1 or args.frames < 1:
        sys.exit("--rounds and --frames must be at least 1")
    os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")
    content = os.path.join(args.build, "content", "default")
    work = tempfile.mkdtemp(prefix="avsm-lights-")
    capture = Capture(args, work)
    tables = {"a": table_clusters, "b": table_many_lights, "c": table_cube}
    for name in args.tables:
        if name not in tables:
            sys.exit(f"--tables: unknown table '{name}' (a, b or c)")
        tables[name](capture, args, content, work)
    print(f"\noutputs in {work}")


if __name__ == "__main__":
    main()

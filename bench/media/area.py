#!/usr/bin/env python3
"""Rect lights' cost against a hard spot light at their centre (issue "Light in media", target "Cost":
an area light with K = 256 virtual lights at most 4.0x one hard spot light, with K = 64 at most 2.5x,
counting its shadow build and its share of the shading).

The softbox example (content/examples/softbox.scene.json; ../shared/content needed) rendered with its
rect light at K virtual lights, with a spot light in its place instead (position and target the same,
an 80 degree cone: what one virtual light's map covers), and with no light, interleaved round by round
in one run. A light's cost is its frame's median GPU ms minus the frame without it.
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402

TARGETS = {64: 2.5, 256: 4.0}


def variant(scene, light):
    """The scene with `light` (a dict, or None for no light) in place of its rect light, asset paths absolute."""
    description = json.loads(Path(scene).read_text())
    folder = Path(scene).resolve().parent
    for key in ("models", "volumes", "hair"):
        for entry in description.get(key, []):
            entry["file"] = str((folder / entry["file"]).resolve())
    description["lights"] = [light] if light else []
    path = Path(tempfile.mkdtemp(prefix="avsm-media-area-")) / "scene.json"
    path.write_text(json.dumps(description, indent=1))
    return str(path)


def frame_ms(capture, scene, width, height, frames):
    out = Path(tempfile.mkdtemp(prefix="avsm-media-area-"))
    command = [capture, "--scene", scene, "--width", str(width), "--height", str(height), "--frames", str(frames),
               "--out", str(out), "--quiet"]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"area.py: {' '.join(command)} failed:\n{result.stderr}")
    return capture_report.timings(out).frame_gpu_ms.median


def main():
    parser = capture_report.scene_arguments(__doc__, 640, 360)
    parser.add_argument("--virtual-lights", default="1,16,64,256", help="K values, comma separated (1 to 256)")
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--frames", type=int, default=3)
    args = parser.parse_args()
    rect = json.loads(Path(args.scene).read_text())["lights"][0]
    spot = {"name": "spot", "type": "spot", "position": rect["position"], "target": rect["target"],
            "inner_cone_deg": 70.0, "outer_cone_deg": 80.0, "color": rect.get("color", [1, 1, 1]),
            "intensity": rect["intensity"], "shadow": rect.get("shadow", {})}
    counts = [int(k) for k in args.virtual_lights.split(",")]
    variants = {"no light": variant(args.scene, None), "spot": variant(args.scene, spot)}
    for k in counts:
        variants[f"rect, K = {k}"] = variant(args.scene, dict(rect, virtual_lights=k))
    times = {name: [] for name in variants}
    for _ in range(args.rounds):  # interleaved: every variant sees the same machine load
        for name, scene in variants.items():
            times[name].append(frame_ms(args.capture, scene, args.width, args.height, args.frames))
    median = {name: sorted(t)[len(t) // 2] for name, t in times.items()}
    base = median["no light"]
    spot_cost = median["spot"] - base
    print(f"{Path(args.scene).name} at {args.width}x{args.height}, {args.rounds} interleaved rounds")
    print("| light | frame GPU ms | its cost ms | x the hard spot's |")
    print("|---|---|---|---|")
    for name, ms in median.items():
        cost = ms - base
        ratio = f"{cost / spot_cost:.2f}" if name != "no light" else ""
        print(f"| {name} | {ms:.1f} | {cost:.1f} | {ratio} |")
    for k, bound in TARGETS.items():
        name = f"rect, K = {k}"
        if name in median:
            ratio = (median[name] - base) / spot_cost
            print(f"target: K = {k} within {bound}x the hard spot: {ratio:.2f}x, {'met' if ratio <= bound else 'MISSED'}")
        else:
            print(f"target: K = {k} within {bound}x the hard spot: not measured (not in --virtual-lights)")


if __name__ == "__main__":
    main()

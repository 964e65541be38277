#!/usr/bin/env python3
"""Fog through the froxel grid, against its per-pixel march (issue "Light in media", target "Quality": fog
in-scattering within 5% relative L1 over fogged pixels of the reference).

Per scene, one avsm-capture run with --compare-fog: the fast frames, then the last view with the fog
marched per pixel (256 steps, every light's map looked up at each) and without fog. Prints the relative
L1 of the fog's effect (sum |fast - reference| / sum |reference - no fog| over the channels the fog
changes by more than 1%) and the fog passes' median GPU ms beside the frame's. A scene without a "fog"
block gets a ground fog under a thin global one, written to a temporary file; --virtual-lights K gives
every area light K virtual lights the same way (the target is at K = 256: bench/media/run.sh measures the
window example at K = 16, 64 and 256, small, for the reference marches every virtual light per step).
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402

GROUND_FOG = {"scattering": 0.04, "absorption": 0.0, "phase_g": 0.6,
              "boxes": [{"min": [-6, 0, -4], "max": [6, 0.6, 4], "scattering": 0.3}]}
TARGET = 0.05
FOG_PASSES = ("fog scattering", "fog integration", "fog composite")


def scene_with_fog(scene, virtual_lights=None):
    """The scene file itself when it has fog (and no --virtual-lights), else a copy with GROUND_FOG and every
    area light's virtual lights set (asset paths made absolute)."""
    description = json.loads(Path(scene).read_text())
    if "fog" in description and virtual_lights is None:
        return scene
    for light in description.get("lights", []):
        if virtual_lights is not None and light.get("type") in ("rect", "disk", "sphere"):
            light["virtual_lights"] = virtual_lights
    folder = Path(scene).resolve().parent
    for key in ("models", "volumes", "hair"):
        for entry in description.get(key, []):
            entry["file"] = str(folder / entry["file"])
    description.setdefault("fog", GROUND_FOG)
    copy = Path(tempfile.mkdtemp(prefix="avsm-media-fog-")) / Path(scene).name
    copy.write_text(json.dumps(description, indent=1))
    return str(copy)


def main():
    parser = capture_report.scene_arguments(__doc__, 1280, 720)
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--virtual-lights", type=int, help="every area light's virtual lights (1 to 256)")
    args = parser.parse_args()
    scene = scene_with_fog(args.scene, args.virtual_lights)
    out = Path(tempfile.mkdtemp(prefix="avsm-media-fog-"))
    command = [args.capture, "--scene", scene, "--width", str(args.width), "--height", str(args.height),
               "--frames", str(args.frames), "--out", str(out), "--quiet", "--compare-fog"]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"fog.py: {' '.join(command)} failed:\n{result.stderr}")
    quality = capture_report.fog_quality(out)
    timings = capture_report.timings(out)
    fog_ms = {p.name: p.gpu_ms.median for p in timings.passes if p.name in FOG_PASSES}
    frame_ms = timings.frame_gpu_ms.median
    lights = f", K = {args.virtual_lights}" if args.virtual_lights else ""
    print(f"{Path(args.scene).name}{lights} at {args.width}x{args.height} ({out})")
    print("| fogged pixels | relative L1 vs per-pixel march | " + " | ".join(f"{name} ms" for name in FOG_PASSES) +
          " | fog share of the frame |")
    print("|---|---|" + "---|" * len(FOG_PASSES) + "---|")
    print(f"| {quality.fogged_pixels} | {quality.relative_l1:.2%} | " +
          " | ".join(f"{fog_ms.get(name, 0.0):.1f}" for name in FOG_PASSES) +
          f" | {sum(fog_ms.values()) / frame_ms:.0%} of {frame_ms:.0f} ms |")
    met = quality.relative_l1 <= TARGET
    print(f"target: within {TARGET:.0%} of the per-pixel march: {quality.relative_l1:.2%}, {'met' if met else 'MISSED'}")


if __name__ == "__main__":
    main()

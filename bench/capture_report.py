"""An avsm-capture output folder, read into typed records for the bench scripts.

The Python side of engine/capture/frame_report.h: timings.json, memory.json and
probes.json as the engine's FrameReport writes them, graph.json as the frame graph's
CompiledPlan::to_json writes it, and volume_quality.json (--compare-volume-shading).
The scripts read fields, not string keys: a key the engine renames breaks here, once.
"""
import argparse
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional


@dataclass
class Spread:  # of one figure over the measured frames
    min: float
    median: float
    max: float

    @staticmethod
    def from_json(j):
        return Spread(j["min"], j["median"], j["max"])


@dataclass
class PassTiming:
    name: str
    stage: str  # the engine's grouping of passes (engine/capture/pass_stages.h): "shadow capture", "sort", ...
    queue: str
    gpu_ms: Spread
    cpu_record_ms: Spread

    @staticmethod
    def from_json(j):
        return PassTiming(j["name"], j["stage"], j["queue"], Spread.from_json(j["gpu_ms"]),
                          Spread.from_json(j["cpu_record_ms"]))


@dataclass
class Timings:  # timings.json
    device: str
    passes: List[PassTiming]
    frame_gpu_ms: Spread
    frame_wall_ms: Optional[Spread] = None

    @staticmethod
    def from_json(j):
        return Timings(j["device"], [PassTiming.from_json(p) for p in j["passes"]], Spread.from_json(j["frame_gpu_ms"]),
                       Spread.from_json(j["frame_wall_ms"]))


@dataclass
class FrameCpu:  # one frame's CPU slices in trace.json
    build_graph_ms: float  # SceneRenderer::build_frame: the frame graph declared
    record_ms: float       # Executor::record: the graph compiled (or reused) and every pass recorded
    submit_wait_ms: float  # submit to completion


def frame_cpu(folder) -> List[FrameCpu]:
    """Every frame's CPU slices from trace.json (the warm-up frame first), in frame order."""
    trace = json.loads((Path(folder) / "trace.json").read_text())
    events = trace["traceEvents"]
    tracks = {e["tid"]: e["args"]["name"] for e in events if e.get("ph") == "M" and e["name"] == "thread_name"}
    frames: List[Dict[str, float]] = []
    for e in events:
        if e.get("ph") != "X" or tracks.get(e["tid"]) != "CPU":
            continue
        if e.get("cat") == "frame":
            frames.append({})
        elif frames:
            frames[-1][e["name"]] = e["dur"] / 1000.0  # trace durations are microseconds
    return [FrameCpu(f.get("build graph", 0.0), f.get("record", 0.0), f.get("submit + wait", 0.0)) for f in frames]


@dataclass
class LightShadowStats:
    light: str
    technique: str
    map_bytes: int
    capture_bytes: int
    capture_requested: int  # segments the lists asked for (0 in the fixed build)
    # The fixed-memory build's depth image + hair bins; None for the lists build.
    fixed_transient_bytes: Optional[int] = None
    inserted_segments: Optional[int] = None  # fixed build: segments that went into curves
    resolution: int = 0             # of each of its maps
    maps: int = 1                   # point lights: 6 faces; cascades; clusters
    map_kind: str = "single"        # single, cube, cascades or clusters
    lowered_from: int = 0           # the resolution asked for, when the map budget lowered it
    capture_overflowed: bool = False

    @staticmethod
    def from_json(j):
        fixed = j.get("fixed_build")
        # Files written before lights had several maps lack maps, map_kind and lowered_from.
        return LightShadowStats(j["light"], j["technique"], j["map_bytes"], j["capture_bytes"],
                                j["capture_requested_segments"],
                                fixed["transient_bytes"] if fixed else None,
                                fixed["inserted_segments"] if fixed else None,
                                resolution=j["resolution"], maps=j.get("maps", 1),
                                map_kind=j.get("map_kind", "single"), lowered_from=j.get("lowered_from", 0),
                                capture_overflowed=j["capture_overflowed"])


@dataclass
class Bounds:
    min: List[float]
    max: List[float]


@dataclass
class Memory:  # memory.json
    transient_bytes_aliased: int
    transient_bytes_unaliased: int
    lights: List[LightShadowStats]
    scene_bounds: Bounds

    @staticmethod
    def from_json(j):
        bounds = j["scene_bounds"]
        return Memory(j["transient_bytes_aliased"], j["transient_bytes_unaliased"],
                      [LightShadowStats.from_json(light) for light in j["lights"]],
                      Bounds(bounds["min"], bounds["max"]))


@dataclass
class ProbeLight:
    light: str
    transmittance: List[float]


@dataclass
class Probes:  # probes.json
    lights: List[ProbeLight]

    @staticmethod
    def from_json(j):
        return Probes([ProbeLight(light["light"], light["transmittance"]) for light in j["lights"]])


@dataclass
class PlanResource:
    name: str
    kind: str
    imported: bool
    used: bool
    size: int
    heap: Optional[int]
    offset: int
    first_pass: Optional[int]
    last_pass: Optional[int]

    @staticmethod
    def from_json(j):
        return PlanResource(j["name"], j["kind"], j["imported"], j["used"], j["size"], j["heap"], j["offset"],
                            j["first_pass"], j["last_pass"])


@dataclass
class Plan:  # graph.json
    pass_names: List[str]
    resources: List[PlanResource]

    @staticmethod
    def from_json(j):
        return Plan([p["name"] for p in j["passes"]], [PlanResource.from_json(r) for r in j["resources"]])


@dataclass
class PathTracedSmoke:  # volume_quality.json "path_traced" (--path-trace-volumes)
    paths_per_pixel: int
    smoke_pixels: int
    fast_mean_luminance: float
    reference_mean_luminance: float
    path_traced_mean_luminance: float
    fast_relative: float  # fast / path traced - 1

    @staticmethod
    def from_json(j):
        return PathTracedSmoke(j["paths_per_pixel"], j["smoke_pixels"], j["fast_mean_luminance"],
                               j["reference_mean_luminance"], j["path_traced_mean_luminance"], j["fast_relative"])


@dataclass
class VolumeQuality:  # volume_quality.json
    fast_settings: str
    smoke_pixels: int
    mean_luminance: float
    mean_relative: float
    p99_relative: float
    within_bound: bool
    fast_gpu_ms: Dict[str, float]
    reference_gpu_ms: Dict[str, float]
    path_traced: Optional[PathTracedSmoke]

    @staticmethod
    def from_json(j):
        traced = PathTracedSmoke.from_json(j["path_traced"]) if j.get("path_traced") else None
        return VolumeQuality(j["fast_settings"], j["smoke_pixels"], j["mean_luminance"], j["mean_relative"],
                             j["p99_relative"], j["within_bound"], j["fast_gpu_ms"], j["reference_gpu_ms"], traced)


@dataclass
class FogQuality:  # fog_quality.json (--compare-fog)
    fogged_pixels: int
    relative_l1: float
    within_bound: bool

    @staticmethod
    def from_json(j):
        return FogQuality(j["fogged_pixels"], j["relative_l1"], j["within_bound"])


def scene_arguments(description, width, height):
    """The arguments every one-scene bench script takes: the scene, the image size and avsm-capture."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--width", type=int, default=width)
    parser.add_argument("--height", type=int, default=height)
    parser.add_argument("--capture", default="build/tools/avsm-capture")
    return parser


def _read(folder, name, record):
    return record.from_json(json.loads((Path(folder) / name).read_text()))


def timings(folder) -> Timings:
    return _read(folder, "timings.json", Timings)


def memory(folder) -> Memory:
    return _read(folder, "memory.json", Memory)


def probes(folder) -> Probes:
    return _read(folder, "probes.json", Probes)


def plan(folder) -> Plan:
    return _read(folder, "graph.json", Plan)


def volume_quality(folder) -> VolumeQuality:
    return _read(folder, "volume_quality.json", VolumeQuality)


def fog_quality(folder) -> FogQuality:
    return _read(folder, "fog_quality.json", FogQuality)

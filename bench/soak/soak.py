#!/usr/bin/env python3
"""A soak of the viewer: many frames with every kind of edit, watching memory, validation and hangs.

  soak.py VIEWER SHADERS_DIR SCENE_DIR [--frames N] [--size WxH] [--shadow-res R]
          [--hair-every K] [--checkpoints F,F,...] [--flat-from F] [--tolerance PCT]
          [--watchdog S] [--progress F] [--work DIR]

Copies the shader sources (SHADERS_DIR, the repository's shaders/, with passes/shadows/techniques)
and the scene folder (SCENE_DIR, the generated default scene) into a work folder, sets
every light's shadow map to a dense one of --shadow-res (the default scene's are paged:
with them, rebuilding pages after every light move and technique switch, 350 frames took
590 s against 71) and keeps every --hair-every-th hair
strand in the copy (the hair passes dominate a CPU device's frame), and drives
`VIEWER --control --validation` (bench/viewer/viewer_control.py, under xvfb-run) on the
copies for --frames frames. The frames go round a cycle of CYCLE frames; each cycle
makes, between frames, every kind of edit and undoes it (steps() below): light moves,
technique, node-count, build-mode and filter changes through control commands; the
scene file edited, broken and restored; a shader broken, fixed differently and restored;
an asset edited (the stage's glTF) and broken (the hair file cut short) and restored.
Every edit's reply is checked (reloaded, or an error naming the broken file while it is
broken, and no error otherwise), so a soak whose reloads stopped working fails.

Each cycle's last frames show the scene as loaded, so memory is read there: at every
multiple of CYCLE among the checkpoints (and the last frame), both resident memory (the
viewer's VmRSS) and the heap in use (glibc's mallinfo2, in the frame reply): freed heap
pages stay resident, so a leak can hide in them for thousands of frames while VmRSS stays
flat. frames.csv in the work folder has the heap after every frame and the edit before it,
to tell which edit keeps memory. Prints that table, the validation message count, and the percentiles of the time a
'frame' command takes to come back (plain frames, and frames right after an edit, which
include the reload; the first frame, which compiles every shader, is left out). Fails,
saying why, when
  - memory (resident or heap in use) at a checkpoint after --flat-from differs from memory
    at --flat-from by more than --tolerance (--heap-tolerance) percent: growth or a leak
    (before --flat-from, by default the first cycle of each technique, is warm-up);
  - the viewer reported a validation message (it runs with validation and sync validation);
  - a frame does not come back within --watchdog seconds (a hang: the viewer is stopped);
  - an edit's reply is not what that edit must give;
  - the last frame (a screenshot, last_frame/) differs from the frame after the first cycle
    (first_cycle/): both show the scene as loaded, so edits must leave nothing behind.
SIGTERM or Ctrl-C ends the soak at the end of the current cycle, with the table of the
frames that ran (exit status 3).
"""
import argparse
import csv
import json
import math
import os
import shutil
import signal
import struct
import sys
import time
from pathlib import Path

REPOSITORY = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPOSITORY / "bench" / "viewer"))
sys.path.insert(0, str(REPOSITORY / "tests" / "viewer"))
from check_viewer_outputs import check_against_capture, check_image  # noqa: E402
from viewer_control import ControlledViewer, ViewerError  # noqa: E402

CYCLE = 50  # frames per cycle of edits; checkpoints must be multiples of it
TECHNIQUES = ["uncompressed", "osm", "fom", "dsm", "constant"]  # light 1 tries one per cycle, then avsm again
NODE_COUNTS = [4, 12, 16]                                       # light 0, then 8 again
FILTERS = ["point", "bilinear"]                                 # light 1, then trilinear again
# Warm-up: until every technique has had its cycle, each compiling its pipelines once into
# the context's pipeline cache (which keeps them); memory is judged from here on.
WARM_UP = CYCLE * len(TECHNIQUES)


def thin_hair(path, keep_every):
    """Rewrites a cyHair file (every array present, as avsm-make-content writes it) with every
    keep_every-th strand: the soak is about edits and memory over many frames, not the hair's cost."""
    data = path.read_bytes()
    strands, points, arrays = struct.unpack_from("<3I", data, 4)
    if data[:4] != b"HAIR" or arrays != 0x1F:
        raise SystemExit(f"{path}: expected a cyHair file with every array (flags 0x1f), as avsm-make-content writes")
    segments = struct.unpack_from(f"<{strands}H", data, 128)
    starts = [0]
    for count in segments:
        starts.append(starts[-1] + count + 1)
    # Per point: position (3 floats), thickness, transparency, colour (3 floats), in that order of arrays.
    arrays_at, floats_per_point = 128 + 2 * strands, (3, 1, 1, 3)
    kept = range(0, strands, keep_every)
    kept_points = sum(segments[s] + 1 for s in kept)
    out = bytearray(data[:128])
    struct.pack_into("<2I", out, 4, len(kept), kept_points)
    out += struct.pack(f"<{len(kept)}H", *(segments[s] for s in kept))
    for width in floats_per_point:
        for s in kept:
            out += data[arrays_at + 4 * width * starts[s]: arrays_at + 4 * width * starts[s + 1]]
        arrays_at += 4 * width * points
    path.write_bytes(bytes(out))


class Workspace:
    """The copies the soak edits, with their original content."""

    def __init__(self, work, shaders, scene_dir, shadow_res, hair_every):
        shutil.rmtree(work, ignore_errors=True)
        self.source_root = work / "src"
        shutil.copytree(shaders, self.source_root / "shaders")
        # The shadow techniques' lookups, which the shaders include (passes/shadows/techniques/<name>/<name>.glsl).
        shutil.copytree(shaders.parent / "passes" / "shadows" / "techniques", self.source_root / "passes" / "shadows" / "techniques")
        shutil.copytree(scene_dir, work / "scene")
        self.scene_file = work / "scene" / "scene.json"
        self.scene = json.loads(self.scene_file.read_text())
        for light in self.scene["lights"]:  # dense maps of that size, as avsm-capture --shadow-res gives
            light["shadow"].update(resolution=shadow_res, layout="dense")
        self.scene_file.write_text(json.dumps(self.scene, indent=1))
        self.tonemap = self.source_root / "shaders" / "passes" / "camera" / "tonemap.comp"
        self.gltf = work / "scene" / "stage.gltf"
        self.hair = work / "scene" / "curtain.hair"
        thin_hair(self.hair, hair_every)
        self.originals = {path: path.read_bytes() for path in (self.scene_file, self.tonemap, self.gltf, self.hair)}
        lines = self.originals[self.tonemap].decode().splitlines()
        # The line the broken shader breaks, which the error must name.
        self.tonemap_line = next(i for i, line in enumerate(lines) if "imageLoad(hdr" in line) + 1

    def restore(self, *paths):
        for path in paths:
            path.write_bytes(self.originals[path])

    def edit_scene_file(self):
        scene = json.loads(self.originals[self.scene_file])
        scene["lights"][1]["intensity"] *= 0.5
        self.scene_file.write_text(json.dumps(scene, indent=1))

    def break_file(self, path):
        path.write_bytes(self.originals[path][: len(self.originals[path]) // 2])

    def break_shader(self):
        lines = self.originals[self.tonemap].decode().splitlines()
        lines[self.tonemap_line - 1] += " this is not GLSL"
        self.tonemap.write_text("\n".join(lines) + "\n")

    def edit_shader(self):
        """A different good shader: the exposure halved."""
        source = self.originals[self.tonemap].decode()
        if "* pc.exposure;" not in source:
            raise SoakFailure(f"{self.tonemap}: no '* pc.exposure;' to edit (update Workspace.edit_shader)")
        self.tonemap.write_text(source.replace("* pc.exposure;", "* pc.exposure * 0.5;"))

    def edit_asset(self):
        gltf = json.loads(self.originals[self.gltf])
        sphere = next(node for node in gltf["nodes"] if node.get("name") == "sphere")
        sphere["translation"][1] += 0.3
        self.gltf.write_text(json.dumps(gltf, indent=1))


def light_moves(scene, step):
    """Commands that move the sun and the spot light a step along a small circle (step 0: home)."""
    sun, spot = scene["lights"][0], scene["lights"][1]
    angle = 2.0 * math.pi * step / 10.0
    direction = [sun["direction"][0] + 0.3 * math.sin(angle), sun["direction"][1], sun["direction"][2] + 0.3 * (1.0 - math.cos(angle))]
    position = [spot["position"][0] + 0.5 * math.sin(angle), spot["position"][1], spot["position"][2]]
    return [f"light 0 direction {','.join(f'{v:.4f}' for v in direction)}",
            f"light 1 position {','.join(f'{v:.4f}' for v in position)}"]


# What happens before the frame at each offset of a cycle. An edit is (commands to send,
# a function editing the files, the reply key that must be true, the file the error must
# name from this frame on, or None for none). Offsets not listed render with no edit.
def steps(workspace, cycle):
    w = workspace
    technique = TECHNIQUES[cycle % len(TECHNIQUES)]
    nodes = NODE_COUNTS[cycle % len(NODE_COUNTS)]
    filter_name = FILTERS[cycle % len(FILTERS)]
    moves = {offset: (light_moves(w.scene, offset), None, "scene_reloaded", None) for offset in range(1, 11)}
    moves[10] = (light_moves(w.scene, 0), None, "scene_reloaded", None)  # home again
    return moves | {
        12: ([f"light 1 technique {technique}"], None, "scene_reloaded", None),
        14: (["light 1 technique avsm"], None, "scene_reloaded", None),
        16: ([f"light 0 nodes {nodes}"], None, "scene_reloaded", None),
        18: (["light 0 nodes 8"], None, "scene_reloaded", None),
        20: (["light 0 build fixed"], None, "scene_reloaded", None),
        22: (["light 0 build lists"], None, "scene_reloaded", None),
        24: ([f"light 1 filter {filter_name}"], None, "scene_reloaded", None),
        26: (["light 1 filter trilinear"], None, "scene_reloaded", None),
        28: ([], w.edit_scene_file, "scene_reloaded", None),
        30: ([], lambda: w.break_file(w.scene_file), None, w.scene_file.name),
        32: ([], lambda: w.restore(w.scene_file), "scene_reloaded", None),
        34: ([], w.break_shader, None, f"{w.tonemap.name}:{w.tonemap_line}"),
        36: ([], w.edit_shader, "shaders_reloaded", None),
        38: ([], lambda: w.restore(w.tonemap), "shaders_reloaded", None),
        40: ([], w.edit_asset, "scene_reloaded", None),
        42: ([], lambda: w.break_file(w.hair), None, w.hair.name),
        44: ([], lambda: w.restore(w.gltf, w.hair), "scene_reloaded", None),
    }


def percentiles(values):
    ordered = sorted(values)
    pick = lambda p: ordered[min(len(ordered) - 1, int(p / 100.0 * len(ordered)))]  # noqa: E731
    return [pick(50), pick(90), pick(99), ordered[-1]]


class SoakFailure(Exception):
    pass


# Set by SIGTERM or Ctrl-C: the soak ends at the end of the current cycle, where memory is
# read, and reports the frames it ran (a long soak stopped early still has its table).
stop_requested = False


def request_stop(signum, frame):
    global stop_requested
    stop_requested = True


def soak(args):
    workspace = Workspace(args.work, args.shaders, args.scene_dir, args.shadow_res, args.hair_every)
    env = dict(os.environ, AVSM_SOURCE_DIR=str(workspace.source_root))
    log = open(args.work / "viewer.log", "w")
    validation = [] if args.no_validation else ["--validation"]
    viewer = ControlledViewer(args.viewer, validation + ["--size", args.size, "--scene", str(workspace.scene_file)],
                              env=env, stderr=log, reply_timeout=args.watchdog)
    memory, plain_ms, edited_ms = {}, [], []
    # Per frame: what came before it and the heap after it, to tell which edit holds on to memory.
    frames_log = csv.writer(open(args.work / "frames.csv", "w", buffering=1))  # line by line: readable while it runs
    frames_log.writerow(["frame", "offset", "edit", "heap_in_use_bytes", "resident_kib"])
    expected_error, frame, messages = None, 0, 0
    started = time.monotonic()
    schedule = {}
    try:
        for frame in range(1, args.frames + 1):
            cycle, offset = divmod(frame - 1, CYCLE)
            if offset == 0 and stop_requested:
                print(f"soak: stopped after frame {frame - 1} of {args.frames}, as asked (SIGTERM or Ctrl-C)", flush=True)
                # Still the scene as loaded: no edit came since the last frame.
                memory.setdefault(frame - 1, (viewer.rss_kib(), answer["heap_in_use_bytes"] / 1024))
                break
            if offset == 0:
                schedule = steps(workspace, cycle)
            commands, edit_files, must_be_true, error_from_now = schedule.get(offset, ([], None, None, expected_error))
            edited = offset in schedule
            for command in commands:
                viewer.send(command)
            if edit_files:
                edit_files()
            expected_error = error_from_now
            sent = time.monotonic()
            answer = viewer.frame()
            # The first frame compiles every shader from source: startup, not a frame time.
            if frame > 1:
                (edited_ms if edited else plain_ms).append((time.monotonic() - sent) * 1000.0)
            check_reply(frame, answer, must_be_true, expected_error)
            edit_name = "; ".join(commands) or (edit_files.__qualname__ if edit_files else "")
            frames_log.writerow([frame, offset, edit_name, answer["heap_in_use_bytes"], viewer.rss_kib()])
            messages = answer["validation_messages"]
            if messages:
                raise SoakFailure(f"frame {frame}: {messages} validation message(s) (they are in {args.work / 'viewer.log'})")
            if frame in args.checkpoints or frame == args.frames or (offset == CYCLE - 1 and stop_requested):
                memory[frame] = (viewer.rss_kib(), answer["heap_in_use_bytes"] / 1024)
            if frame == CYCLE:  # the first cycle's edits undone: what the last frame must show again
                viewer.send(f"screenshot {args.work / 'first_cycle'}")
            if frame in memory or frame % args.progress == 0:
                print(f"frame {frame:>6}: {viewer.rss_kib() / 1024:8.1f} MiB resident, "
                      f"{answer['heap_in_use_bytes'] / 2**20:8.1f} MiB heap in use, {messages} validation messages, "
                      f"{time.monotonic() - started:7.0f} s", flush=True)
        viewer.send(f"screenshot {args.work / 'last_frame'}")  # after the last memory reading: it allocates
        status = viewer.quit()
        if status != 0:
            raise SoakFailure(f"the viewer exited with status {status} (validation messages at exit? see {args.work / 'viewer.log'})")
    except ViewerError as error:
        raise SoakFailure(f"frame {frame}: {error}")
    finally:
        if viewer.process.poll() is None:
            viewer.kill()
    return memory, plain_ms, edited_ms, messages


def check_reply(frame, answer, must_be_true, expected_error):
    error = answer["error"]
    if expected_error is None and error is not None:
        raise SoakFailure(f"frame {frame}: unexpected reload error: {error}")
    if expected_error is not None and (error is None or expected_error not in error):
        raise SoakFailure(f"frame {frame}: expected an error naming '{expected_error}', got {error!r}")
    if must_be_true and not answer[must_be_true]:
        raise SoakFailure(f"frame {frame}: expected {must_be_true} after this frame's edit: {answer}")


def report(args, memory, plain_ms, edited_ms, messages):
    """Prints the tables; returns the reasons the goals were missed."""
    failures = []
    print(f"\nmemory (flat within {args.tolerance}% of frame {args.flat_from} after it): resident (VmRSS), and the heap in")
    print("use (glibc mallinfo2), which resident memory hides while freed heap pages take the growth")
    print(f"{'frame':>8}{'resident MiB':>14}{'vs base':>10}{'heap MiB':>10}{'vs base':>10}")
    baseline = memory.get(args.flat_from)
    for frame, kib in sorted(memory.items()):
        row = f"{frame:>8}"
        for what, value, base, tolerance in (("resident memory", kib[0], baseline and baseline[0], args.tolerance),
                                             ("heap in use", kib[1], baseline and baseline[1], args.heap_tolerance)):
            change = None if base is None or frame < args.flat_from else (value / base - 1.0) * 100.0
            row += f"{value / 1024:>{14 if what == 'resident memory' else 10}.1f}" + (f"{change:>+9.2f}%" if change is not None else f"{'':>10}")
            if change is not None and tolerance >= 0 and abs(change) > tolerance:
                failures.append(f"{what} at frame {frame} is {change:+.2f}% against frame {args.flat_from} "
                                f"(more than {tolerance}%): it grows")
        print(row)
    print(f"\nvalidation messages: {'not looked for (--no-validation)' if args.no_validation else messages}")
    print(f"\ntime for a 'frame' command to come back (ms):\n{'':>22}{'frames':>8}{'p50':>8}{'p90':>8}{'p99':>8}{'max':>8}")
    for name, values in (("plain frames", plain_ms), ("after an edit", edited_ms), ("all", plain_ms + edited_ms)):
        if values:
            print(f"{name:>22}{len(values):>8}" + "".join(f"{v:>8.0f}" for v in percentiles(values)))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("viewer", type=Path)
    parser.add_argument("shaders", type=Path, help="the repository's shaders/ folder")
    parser.add_argument("scene_dir", type=Path, help="the default scene's folder (build/content/default)")
    parser.add_argument("--frames", type=int, default=10000)
    parser.add_argument("--size", default="96x54")
    parser.add_argument("--shadow-res", type=int, default=64)
    parser.add_argument("--hair-every", type=int, default=20, help="keep every Nth hair strand in the copy")
    parser.add_argument("--checkpoints", default=f"100,{WARM_UP},1000,5000,10000",
                        help=f"frames whose memory is read (multiples of {CYCLE}); the last frame is read too")
    parser.add_argument("--flat-from", type=int, default=WARM_UP, help="the checkpoint that ends the warm-up")
    parser.add_argument("--tolerance", type=float, default=2.0, help="percent")
    parser.add_argument("--heap-tolerance", type=float, help="percent for the heap in use (default: --tolerance; "
                        "negative: printed, not judged)")
    parser.add_argument("--no-validation", action="store_true",
                        help="memory of the engine alone, without the validation layer's")
    parser.add_argument("--watchdog", type=float, default=120.0, help="seconds a frame may take to come back")
    parser.add_argument("--progress", type=int, default=250, help="print memory every this many frames")
    parser.add_argument("--work", type=Path, default=Path("out/soak"))
    args = parser.parse_args()
    args.checkpoints = [int(f) for f in args.checkpoints.split(",")]
    if args.heap_tolerance is None:
        args.heap_tolerance = args.tolerance
    for frame in args.checkpoints + [args.frames, args.flat_from]:
        if frame % CYCLE:
            parser.error(f"frame {frame}: checkpoints, --flat-from and --frames must be multiples of {CYCLE} "
                         "(memory is read where the scene is as loaded)")
    if args.frames < args.flat_from:
        parser.error(f"--frames {args.frames}: the soak needs more than its warm-up (--flat-from {args.flat_from})")
    if args.flat_from not in args.checkpoints + [args.frames]:
        parser.error(f"--flat-from {args.flat_from} must be one of the checkpoints")
    args.checkpoints = [f for f in args.checkpoints if f <= args.frames]
    print(f"soak: {args.frames} frames of {args.viewer.name} --control{'' if args.no_validation else ' --validation'} at {args.size}, "
          f"shadow maps {args.shadow_res}^2, every {args.hair_every}th hair strand, an edit cycle every {CYCLE} frames; work folder {args.work}", flush=True)
    signal.signal(signal.SIGTERM, request_stop)
    signal.signal(signal.SIGINT, request_stop)
    try:
        results = soak(args)
    except SoakFailure as failure:
        print(f"soak: FAIL: {failure}")
        sys.exit(1)
    failures = report(args, *results)
    # Thousands of edits later, the scene as loaded looks as it did after the first cycle.
    # frame.png is the view's size: the window's less the panel's column (engine/viewer/view_layout.h).
    layout = json.loads((args.work / "first_cycle" / "layout.json").read_text())
    width, height = layout["view"]["width"], layout["view"]["height"]
    last = check_image(args.work / "last_frame" / "frame.png", width, height)
    check_against_capture(last, args.work / "first_cycle" / "frame.png", width, height, name=f"frame {CYCLE}")
    for failure in failures:
        print(f"soak: FAIL: {failure}")
    if failures:
        sys.exit(1)
    if stop_requested:
        print("soak: STOPPED early: the goals held for the frames above, the rest did not run")
        sys.exit(3)
    print("soak: OK")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The viewer follows edits while it runs, and survives broken ones.

  check_live_reload.py XVFB_RUN VIEWER SHADERS_DIR SCENE_DIR WORK_DIR

Copies the shader sources (SHADERS_DIR, the repository's shaders/) and the default
scene (SCENE_DIR) into WORK_DIR, starts `VIEWER --control --validation` on the copies
(AVSM_SOURCE_DIR points the live shader compiler at them) and, between frames,
edits the copies as a user would in an editor (the copy's lights start dense; the
default scene's are paged):
  1. a syntax error in tonemap.comp: the reply names tonemap.comp and its line, and
     the frame still renders with the last good pipelines;
  2. the fix, with the exposure scaled by 0.25: shaders reloaded, the error gone,
     and the frame is darker than before the edit;
  3. scene.json made invalid: the error names scene.json; the frame still renders;
  4. scene.json valid again with the key light's intensity changed: scene reloaded;
  5. an asset (the hair file) cut short: the error names it; then restored: reloaded;
  6. a panel edit the renderer rejects (light 0 nodes 5), then a valid one (nodes 4);
  7. a click on the smoke, whose curves must be evaluated (inspect.json);
  8. the shadow level overlay of light 0 (the sun, a dense map: every receiver reads
     level 0, red): the sky, no receiver, is dimmed and the floor turns red; then off;
  9. the sun switched to paged maps and the smoke clicked again: the sun's curve is its
     finest resident page's (a level, stored nodes) with no exact curve, the spot's
     still has one;
and finally quits: the exit status is 0 only without validation messages.
The viewer runs under XVFB_RUN (xvfb-run).
"""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_viewer_outputs import check_inspection, read_png  # noqa: E402

WIDTH, HEIGHT = 160, 90


def fail(message):
    print(f"check_live_reload: FAIL: {message}")
    sys.exit(1)


class Viewer:
    def __init__(self, command, env):
        print("starting:", " ".join(command))
        self.process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)

    def send(self, line):
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()
        reply = self.process.stdout.readline()
        if not reply:
            fail(f"the viewer exited (status {self.process.wait()}) after '{line}'")
        answer = json.loads(reply)
        print(f"> {line}\n< {reply.strip()}")
        if "rejected" in answer:
            fail(f"'{line}' was rejected: {answer['rejected']}")
        return answer

    def frame(self, expect_error=None, expect=()):
        answer = self.send("frame")
        if not answer["rendered"]:
            fail("no frame was rendered")
        error = answer["error"]
        if expect_error is None and error is not None:
            fail(f"unexpected error: {error}")
        if expect_error is not None and (error is None or expect_error not in error):
            fail(f"expected an error naming '{expect_error}', got {error!r}")
        for key in expect:
            if not answer[key]:
                fail(f"expected {key} after this edit: {answer}")
        return answer


def plume_pixel(view_width, view_height):
    """A view pixel on the default scene's smoke plume: the one the 320x180 test clicks
    (46,66 of its 192x180 view), moved with the view's size (the vertical field of view
    is fixed, the image centred)."""
    scale = view_height / 180
    return f"{round(view_width / 2 - 50 * scale)},{round(66 * scale)}"


def mean_brightness(png):
    _, _, rows = read_png(png)
    return sum(sum(row) for row in rows) / (len(rows) * len(rows[0]))


def pixel(png, x, y):
    """The RGB of pixel (x, y), y down."""
    width, _, rows = read_png(png)
    channels = len(rows[0]) // width
    return tuple(rows[y][x * channels:x * channels + 3])


def main():
    xvfb_run = sys.argv[1]
    viewer_exe, shaders, scene_dir, work = (Path(a) for a in sys.argv[2:6])
    shutil.rmtree(work, ignore_errors=True)
    source_root = work / "src"
    shutil.copytree(shaders, source_root / "shaders")
    # The shadow techniques' lookups, which the shaders include (passes/shadows/techniques/<name>/<name>.glsl).
    shutil.copytree(shaders.parent / "passes" / "shadows" / "techniques", source_root / "passes" / "shadows" / "techniques")
    shutil.copytree(scene_dir, work / "scene")
    scene_file = work / "scene" / "scene.json"
    # Dense maps, the sun's fitted to the view, as steps 6 to 8 need; step 9 pages the sun.
    dense = json.loads(scene_file.read_text())
    for light in dense["lights"]:
        light["shadow"].update(layout="dense", fit="view")
    scene_file.write_text(json.dumps(dense, indent=1))
    tonemap = source_root / "shaders" / "passes" / "camera" / "tonemap.comp"
    hair_file = work / "scene" / "curtain.hair"
    good_tonemap, good_scene, good_hair = tonemap.read_text(), scene_file.read_text(), hair_file.read_bytes()

    env = dict(os.environ, AVSM_SOURCE_DIR=str(source_root), XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp"))
    viewer = Viewer([xvfb_run, "-a", str(viewer_exe), "--control", "--validation", "--size", f"{WIDTH}x{HEIGHT}",
                     "--scene", str(scene_file)], env)
    view_width, view_height = viewer.frame()["view"]  # the view beside the panel: the frame's size
    viewer.send(f"screenshot {work / 'before'}")

    # 1-2: shaders.
    lines = good_tonemap.splitlines()
    broken_line = next(i for i, line in enumerate(lines) if "imageLoad(hdr" in line) + 1
    lines[broken_line - 1] += " this is not GLSL"
    tonemap.write_text("\n".join(lines) + "\n")
    viewer.frame(expect_error=f"tonemap.comp:{broken_line}")
    tonemap.write_text(good_tonemap.replace("* pc.exposure;", "* pc.exposure * 0.25;"))
    viewer.frame(expect=["shaders_reloaded"])
    viewer.send(f"screenshot {work / 'darker'}")
    before, darker = mean_brightness(work / "before" / "frame.png"), mean_brightness(work / "darker" / "frame.png")
    print(f"mean brightness before {before:.1f}, after the shader edit {darker:.1f}")
    if not darker < before * 0.9:
        fail("the edited tonemapper (exposure x 0.25) did not darken the frame")

    # 3-4: the scene file.
    scene_file.write_text(good_scene[: len(good_scene) // 2])
    viewer.frame(expect_error="scene.json")
    scene = json.loads(good_scene)
    scene["lights"][1]["intensity"] *= 0.5
    scene_file.write_text(json.dumps(scene, indent=1))
    viewer.frame(expect=["scene_reloaded"])

    # 5: an asset.
    hair_file.write_bytes(good_hair[:100])
    viewer.frame(expect_error="curtain.hair")
    hair_file.write_bytes(good_hair)
    viewer.frame(expect=["scene_reloaded"])

    # 6: panel edits.
    viewer.send("light 0 nodes 5")
    viewer.frame(expect_error="5")
    viewer.send("light 0 nodes 4")
    viewer.frame(expect=["scene_reloaded"])

    # 7: texel inspection.
    answer = viewer.send(f"inspect {plume_pixel(view_width, view_height)}")
    if answer["inspect"] is None:
        fail("nothing under the smoke pixel")
    viewer.frame()
    viewer.send(f"screenshot {work / 'inspected'}")
    check_inspection(work / "inspected" / "inspect.json")

    # 8: the shadow level overlay.
    viewer.send("levels 0")
    viewer.frame()
    viewer.send(f"screenshot {work / 'levels'}")
    sky, floor = (2, 2), (view_width // 2, view_height - 3)
    plain_sky, tinted_sky = pixel(work / "inspected" / "frame.png", *sky), pixel(work / "levels" / "frame.png", *sky)
    tinted_floor = pixel(work / "levels" / "frame.png", *floor)
    print(f"overlay: sky {plain_sky} -> {tinted_sky}, floor {tinted_floor}")
    if not sum(tinted_sky) < 0.5 * sum(plain_sky):
        fail("the level overlay did not dim the sky (no receiver)")
    if not tinted_floor[0] > tinted_floor[1] + 40 and tinted_floor[0] > tinted_floor[2] + 40:
        fail("the level overlay did not tint the floor red (level 0 of the sun's dense map)")
    viewer.send("levels off")
    viewer.frame()

    # 9: a paged sun, inspected: its curve is its finest resident page's, without an exact one.
    for field, value in (("layout", "paged"), ("kernel", "none"), ("fit", "scene")):
        viewer.send(f"light 0 {field} {value}")
    viewer.frame(expect=["scene_reloaded"])
    for _ in range(3):  # the pages the receivers ask for arrive a frame later
        viewer.frame()
    answer = viewer.send(f"inspect {plume_pixel(view_width, view_height)}")
    if answer["inspect"] is None:
        fail("nothing under the smoke pixel with the sun paged")
    viewer.frame()
    viewer.send(f"screenshot {work / 'paged_inspected'}")
    curves = check_inspection(work / "paged_inspected" / "inspect.json")
    sun = next((c for c in curves if c["light"] == 0), None)
    if sun is None or sun["exact"] or sun["reference_values"] or sun["level"] is None or not sun["nodes"]:
        fail(f"the paged sun's curve should come from a resident page (a level, nodes) without an exact curve: {sun}")
    if any(c["light"] != 0 and not c["exact"] for c in curves):
        fail("a dense light lost its exact curve when the sun became paged")

    viewer.send("quit")
    status = viewer.process.wait(timeout=60)
    if status != 0:
        fail(f"the viewer exited with status {status} (validation messages?)")
    print("check_live_reload: OK")


if __name__ == "__main__":
    main()

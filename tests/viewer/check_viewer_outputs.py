#!/usr/bin/env python3
"""Checks a scripted avsm-viewer run (tests/viewer/CMakeLists.txt).

  check_viewer_outputs.py SHOT_DIR WIDTH HEIGHT [--view VW VH] [--capture CAPTURE_DIR] [--inspect]

SHOT_DIR is the viewer's --screenshot folder, WIDTH x HEIGHT the window's size. The
panel is docked in a column at the left and the 3D view takes the rest of the window
(engine/viewer/view_layout.h). Checks:
  - window.png is WIDTHxHEIGHT, frame.png (the scene, rendered at the view's size) is
    not uniform, and every file avsm-capture writes for a frame is there;
  - the view does not lie under the panel: frame.png fits beside the panel (narrower
    than the window, as tall), and window.png's rectangle at the right edge of that
    size equals frame.png exactly, pixel for pixel (the blit copies display values,
    unscaled, and nothing is drawn over them); the column left of it shows the panel;
  - layout.json (the viewer's layout) says the same: panel and view do not overlap and
    cover the window, and the view is frame.png's rectangle; with --view, the view is
    VW x VH (the size the capture below was made at);
  - with --capture: frame.png matches avsm-capture's frame.png of the same camera
    and size (per channel |difference| <= 2 of 255 on 99.9% of pixels: both render
    the same scene with the same passes; only float reordering may differ);
  - with --inspect: inspect.json holds a curve per light; each curve's technique and
    exact values start at 1, never increase (AVSM and the exact product of segments
    are monotone), end lower than they start for at least one light, and the
    technique stays close to the exact curve (mean |difference| <= 0.05).
Only the Python standard library is used (PNG decoding through zlib).
"""
import json
import struct
import sys
import zlib
from pathlib import Path

FRAME_FILES = ["frame.png", "frame.exr", "timings.json", "trace.json", "graph.json", "graph.dot",
               "memory.json", "light0_transmittance.png"]


def fail(message):
    print(f"check_viewer_outputs: FAIL: {message}")
    sys.exit(1)


def read_png(path):
    """8-bit RGB/RGBA, non-interlaced PNG -> (width, height, rows of RGBA tuples' flat bytes)."""
    data = Path(path).read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    channels = {2: 3, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        fail(f"{path}: expected 8-bit RGB(A) non-interlaced, got depth {depth} colour type {colour}")
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if channels == 3 else bytes(v for j, v in enumerate(line) if j % 4 != 3))
        previous = line
    return width, height, rows  # rows hold RGB only


def read_image(path):
    """(width, height, rows) of an 8-bit PNG; fails when it is (nearly) uniform."""
    w, h, rows = read_png(path)
    if len(set(rows[y][x * 3:x * 3 + 3] for y in range(0, h, 3) for x in range(0, w, 3))) < 16:
        fail(f"{path}: (nearly) uniform: fewer than 16 distinct colours")
    return w, h, rows


def check_image(path, width, height):
    w, h, rows = read_image(path)
    if (w, h) != (width, height):
        fail(f"{path}: {w}x{h}, expected {width}x{height}")
    return rows


def check_window(frame_size, frame, window, width, height):
    """The view, frame.png's size at the window's right edge, shows the frame unobstructed;
    the panel's column is left of it. Returns the view rectangle (x, y, w, h)."""
    fw, fh = frame_size
    if fw > width or fh != height:
        fail(f"frame.png is {fw}x{fh} in a {width}x{height} window: the view must be as tall as the window")
    view = (width - fw, 0, fw, fh)
    covered = [(x, y) for y in range(fh) for x in range(fw)
               if window[y][(view[0] + x) * 3:(view[0] + x) * 3 + 3] != frame[y][x * 3:x * 3 + 3]]
    if covered:
        x, y = covered[0]
        fail(f"window.png differs from frame.png at {len(covered)} of {fw * fh} pixels of the view "
             f"({view[2]}x{view[3]} at x {view[0]}), first at view pixel ({x}, {y}): something covers the scene "
             "or the blit scaled it")
    if fw == width:
        fail(f"frame.png is as wide as the window ({width}): no column is left beside the view for the panel")
    panel_colours = set(window[y][x * 3:x * 3 + 3] for y in range(height) for x in range(view[0]))
    if len(panel_colours) < 8:
        fail(f"window.png: the column left of the view (x < {view[0]}) shows no panel ({len(panel_colours)} colours)")
    print(f"window.png: the view ({fw}x{fh} at x {view[0]}) equals frame.png exactly; "
          f"the panel's column ({view[0]} px) beside it")
    return view


def check_layout(path, view, width, height, expected_view=None):
    """layout.json: the viewer's own account of the panel and the view."""
    if not Path(path).is_file():
        fail(f"missing {path}: the viewer did not write its layout")
    layout = json.loads(Path(path).read_text())
    rect = lambda r: (r["x"], r["y"], r["width"], r["height"])  # noqa: E731
    panel, reported = rect(layout["panel"]), rect(layout["view"])
    if tuple(layout["window"]) != (width, height):
        fail(f"{path}: window {layout['window']}, expected {width}x{height}")
    if reported != view:
        fail(f"{path}: view {reported}, but frame.png sits at {view} in window.png")
    px, py, pw, ph = panel
    vx, vy, vw, vh = reported
    if px + pw > vx and vx + vw > px and py + ph > vy and vy + vh > py:
        fail(f"{path}: panel {panel} and view {reported} overlap")
    if (px, py, ph, vy, vh) != (0, 0, height, 0, height) or pw != vx or vx + vw != width:
        fail(f"{path}: panel {panel} and view {reported} do not cover the {width}x{height} window side by side")
    if expected_view and (vw, vh) != expected_view:
        fail(f"{path}: the view is {vw}x{vh}, expected {expected_view[0]}x{expected_view[1]} "
             "(the layout rule changed? see engine/viewer/view_layout.h and tests/viewer/CMakeLists.txt)")
    print(f"layout.json: panel {pw}x{ph} at the left, view {vw}x{vh} beside it")


def check_against_capture(frame, capture_png, width, height, name="avsm-capture"):
    """frame.png (rows) against another frame of the same view, `name` (avsm-capture's by default)."""
    reference = check_image(capture_png, width, height)
    off = worst = 0
    for y in range(height):
        for a, b in zip(frame[y], reference[y]):
            d = abs(a - b)
            worst = max(worst, d)
            off += d > 2
    channels = width * height * 3
    print(f"frame.png vs {name}: {off} of {channels} channels differ by more than 2, worst {worst}")
    if off > channels * 0.001:
        fail(f"frame.png differs from {name}'s frame: {off} channels off by more than 2 (worst {worst})")


def check_inspection(path):
    if not Path(path).is_file():
        fail(f"missing {path}: the inspected texel's curves were not written")
    inspection = json.loads(Path(path).read_text())
    curves = inspection.get("curves", [])
    if not curves:
        fail(f"{path}: no curves")
    falls = False
    for curve in curves:
        name = f"light {curve['light']} texel {curve['texel']}"
        technique, exact = curve["technique_values"], curve["reference_values"]
        if not curve.get("exact", True):  # a paged light: its pages keep no exact curve
            if len(technique) < 64 or len(technique) != len(curve["depths"]) or exact:
                fail(f"{name}: {len(technique)} technique values for {len(curve['depths'])} depths, {len(exact)} exact")
            if abs(technique[0] - 1.0) > 1e-3 or any(b > a + 1e-4 for a, b in zip(technique, technique[1:])):
                fail(f"{name}: the paged curve does not start at 1 and fall: {technique[:3]} ... {technique[-3:]}")
            falls = falls or technique[-1] < technique[0] - 0.1
            print(f"{name} ({curve['technique']}, paged level {curve['level']}): {technique[0]:.3f} -> "
                  f"{technique[-1]:.3f}, {len(curve['nodes'])} nodes, no exact curve")
            continue
        if len(technique) < 64 or len(technique) != len(exact) or len(exact) != len(curve["depths"]):
            fail(f"{name}: {len(technique)} technique / {len(exact)} exact values for {len(curve['depths'])} depths")
        for label, values in (("technique", technique), ("exact", exact)):
            if abs(values[0] - 1.0) > 1e-3:
                fail(f"{name}: the {label} curve starts at {values[0]}, not 1 (nothing lies before the near depth)")
            rises = [i for i in range(1, len(values)) if values[i] > values[i - 1] + 1e-4]
            if rises:
                fail(f"{name}: the {label} curve rises at sample {rises[0]}: {values[rises[0] - 1]} -> {values[rises[0]]}")
        falls = falls or exact[-1] < exact[0] - 0.1
        mean = sum(abs(a - b) for a, b in zip(technique, exact)) / len(exact)
        print(f"{name} ({curve['technique']}): {exact[0]:.3f} -> {exact[-1]:.3f}, mean |T - T_exact| {mean:.4f}, "
              f"max {curve['max_abs_difference']:.4f}, {len(curve['nodes'])} nodes")
        if mean > 0.05:
            fail(f"{name}: technique curve too far from the exact one (mean |difference| {mean:.4f} > 0.05)")
    if not falls:
        fail(f"{path}: no light's curve falls: the inspected ray crosses nothing")
    return curves


def main():
    args = sys.argv[1:]
    if len(args) < 3:
        fail(__doc__)
    shot, width, height = Path(args[0]), int(args[1]), int(args[2])
    for name in FRAME_FILES + ["window.png"]:
        if not (shot / name).is_file() or (shot / name).stat().st_size == 0:
            fail(f"missing or empty {shot / name}")
    fw, fh, frame = read_image(shot / "frame.png")
    window = check_image(shot / "window.png", width, height)
    view = check_window((fw, fh), frame, window, width, height)
    expected_view = None
    if "--view" in args:
        at = args.index("--view")
        expected_view = (int(args[at + 1]), int(args[at + 2]))
    check_layout(shot / "layout.json", view, width, height, expected_view)
    if "--capture" in args:
        check_against_capture(frame, Path(args[args.index("--capture") + 1]) / "frame.png", fw, fh)
    if "--inspect" in args:
        check_inspection(shot / "inspect.json")
    print("check_viewer_outputs: OK")


if __name__ == "__main__":
    main()

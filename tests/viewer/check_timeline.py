#!/usr/bin/env python3
"""The viewer's timeline on an animated scene, driven by --control under validation:

  check_timeline.py XVFB_RUN VIEWER SCENE WORK_DIR

`time 0.5` moves the playhead and the next frame shows that instant; `play` then advances one
timeline frame (1 / 24 s) per rendered frame and `pause` holds it; screenshots at 0 s and at
0.5 s differ (the example's ball bounces); the viewer quits with status 0 (no validation
messages)."""
import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path


def fail(message):
    print(f"check_timeline: FAIL: {message}")
    sys.exit(1)


def main():
    xvfb_run, viewer_exe, scene, work = sys.argv[1], sys.argv[2], sys.argv[3], Path(sys.argv[4])
    work.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", "/tmp"))
    process = subprocess.Popen([xvfb_run, "-a", viewer_exe, "--control", "--validation", "--size", "320x180", "--scene", scene],
                               stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)

    def send(line):
        process.stdin.write(line + "\n")
        process.stdin.flush()
        reply = process.stdout.readline()
        if not reply:
            fail(f"the viewer exited (status {process.wait()}) after '{line}'")
        print(f"> {line}\n< {reply.strip()}")
        answer = json.loads(reply)
        if "rejected" in answer:
            fail(f"'{line}' was rejected: {answer['rejected']}")
        return answer

    if abs(send("frame")["time"]) > 1e-6:
        fail("the first frame is not at time 0")
    send(f"screenshot {work / 'start'}")
    scrubbed = send("time 0.5")
    if abs(scrubbed["time"] - 0.5) > 1e-4 or scrubbed["duration"] <= 0.5:
        fail(f"'time 0.5' gave {scrubbed}")
    if abs(send("frame")["time"] - 0.5) > 1e-4:
        fail("the frame after 'time 0.5' does not show 0.5 s")
    send(f"screenshot {work / 'half'}")
    if not send("play")["playing"]:
        fail("'play' did not start playing")
    times = [send("frame")["time"] for _ in range(3)]
    expected = [0.5 + k / 24.0 for k in (1, 2, 3)]
    if any(abs(t - e) > 1e-3 for t, e in zip(times, expected)):
        fail(f"playing frames show {times}, expected {expected} (one 1/24 s step per frame)")
    send("pause")
    if abs(send("frame")["time"] - times[-1]) > 1e-6:
        fail("the playhead moved while paused")

    digest = lambda p: hashlib.sha256(p.read_bytes()).hexdigest()
    if digest(work / "start" / "frame.png") == digest(work / "half" / "frame.png"):
        fail("the frames at 0 s and 0.5 s are the same image: nothing moved")
    send("quit")
    status = process.wait(timeout=60)
    if status != 0:
        fail(f"the viewer exited with status {status} (validation messages?)")
    print("check_timeline: OK")


if __name__ == "__main__":
    main()

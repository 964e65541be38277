"""Drives `avsm-viewer --control` (engine/viewer/control_commands.h) under xvfb-run.

  viewer = ControlledViewer(VIEWER, ["--size", "160x90"], reply_timeout=60)
  answer = viewer.frame()          # one JSON reply per command, as a dict
  viewer.rss_kib()                 # the viewer's resident memory (not xvfb-run's)
  status = viewer.quit()

A command whose reply does not come back within `reply_timeout` seconds raises
ViewerError saying so (the viewer hangs), after stopping the viewer and its display.
"""
import json
import os
import queue
import signal
import subprocess
import threading
from pathlib import Path


def steady_frame_ms(replied, warm_up):
    """A frame's ms from the times of successive 'frame' replies: a reply comes once its frame
    is submitted, so the time from the reply of frame `warm_up` to the last over the frames
    in between is the steady frame time, whatever the frames in flight."""
    return (replied[-1] - replied[warm_up - 1]) / (len(replied) - warm_up) * 1000.0


class ViewerError(Exception):
    """The viewer exited, hung, or answered what a script did not expect."""


class ControlledViewer:
    def __init__(self, viewer, arguments=(), env=None, stderr=subprocess.DEVNULL, reply_timeout=None):
        self.viewer = Path(viewer)
        self.command = ["xvfb-run", "-a", str(viewer), "--control", *arguments]
        self.reply_timeout = reply_timeout
        env = dict(env if env is not None else os.environ)
        env.setdefault("XDG_RUNTIME_DIR", "/tmp")
        # A session of its own: a hang is ended by stopping xvfb-run, Xvfb and the viewer together.
        self.process = subprocess.Popen(self.command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=stderr,
                                        text=True, env=env, start_new_session=True)
        # Replies are read on a thread so that waiting for one can time out.
        self.replies = queue.Queue()
        threading.Thread(target=self._read_replies, daemon=True).start()
        self._viewer_pid = None

    def _read_replies(self):
        for line in self.process.stdout:
            self.replies.put(line)
        self.replies.put(None)  # the viewer closed its output: it exited

    def send(self, line):
        """Sends one command and returns its reply; a rejected command raises ViewerError."""
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()
        try:
            reply = self.replies.get(timeout=self.reply_timeout)
        except queue.Empty:
            self.kill()
            raise ViewerError(f"no reply to '{line}' within {self.reply_timeout} s: the viewer hangs (stopped it)")
        if reply is None:
            raise ViewerError(f"the viewer exited (status {self.process.wait()}) after '{line}': "
                              f"run {' '.join(self.command)} to see why")
        answer = json.loads(reply)
        if "rejected" in answer:
            raise ViewerError(f"'{line}' was rejected: {answer['rejected']}")
        return answer

    def frame(self):
        """Renders one frame; raises ViewerError when none was rendered."""
        answer = self.send("frame")
        if not answer.get("rendered"):
            raise ViewerError(f"no frame rendered: {answer}")
        return answer

    def quit(self, timeout=60):
        """Stops the viewer; returns its exit status (1 after validation messages)."""
        self.process.stdin.write("quit\n")
        self.process.stdin.flush()
        try:
            return self.process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.kill()
            raise ViewerError(f"the viewer did not exit within {timeout} s of 'quit' (stopped it)")

    def quit_or_exit(self):
        """Stops the viewer; ends the script, saying how to see why, when it failed."""
        if self.quit() != 0:
            raise SystemExit(f"the viewer failed (status {self.process.returncode}): "
                             f"run {' '.join(self.command)} to see why")

    def kill(self):
        try:
            os.killpg(self.process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self.process.wait()

    def viewer_pid(self):
        """The viewer's process id: the child of xvfb-run running the viewer executable."""
        if self._viewer_pid is None:
            for stat in Path("/proc").glob("[0-9]*/stat"):
                try:
                    # pid (comm) state ppid ...: comm may hold spaces, so split after its ')'.
                    fields = stat.read_text().rsplit(")", 1)[1].split()
                    if int(fields[1]) == self.process.pid and \
                            Path(f"/proc/{stat.parent.name}/exe").resolve() == self.viewer.resolve():
                        self._viewer_pid = int(stat.parent.name)
                        break
                except (OSError, IndexError, ValueError):
                    continue  # a process that ended meanwhile
            else:
                raise ViewerError(f"no viewer process under xvfb-run (pid {self.process.pid})")
        return self._viewer_pid

    def rss_kib(self):
        """The viewer's resident memory (VmRSS), in KiB."""
        for line in Path(f"/proc/{self.viewer_pid()}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
        raise ViewerError("no VmRSS in /proc/PID/status")

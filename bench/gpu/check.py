#!/usr/bin/env python3
"""One unattended check of the engine on a GPU, within a time budget (bench/gpu/check.sh runs this).

Steps, in order; each gets a share of the budget, and what one leaves unused goes to the
steps after it:
  device       the device as the engine sees it: bench/gpu/avsm_gpu_device_info (name,
               driver, API version, the limits engine/gpu/device_limits.h checks, the
               features DeviceRequirements enables, memory heaps, the timestamp mode)
  tests        the GPU tests under validation + synchronization validation: ctest -L gpu
               (smoke: a few quick GPU tests, run straight from the gtest binary)
  capture      the default scene with per-pass GPU timings (avsm-capture, --report)
  capture-real the real-asset scene, content/real_assets.scene.json (../shared/content;
               reported as missing, not failed, when the content is not there)
  techniques   the technique table (bench/avsm/techniques.py) at 256^2 maps, a bounded row set
Then summary.txt / summary.json at the top of the output folder: every step ok / FAILED /
cut by the budget, the device, the test counts, the frame time and stages of both
captures and the technique rows. A step that fails does not stop the others; the exit
status is 1 when any step failed (the message names them), 2 on a bad command line.

Outputs (--out, default out/gpu-check):
  summary.txt summary.json   the table, as text and JSON (everything below in one file)
  device.txt device.json     avsm_gpu_device_info's output
  tests.log                  the test run's output
  capture_default/ capture_real/   avsm-capture's files (timings.json, frame.png, report.html, ...)
  techniques/                table.txt and the bench's own outputs
  logs/                      every step's full output
With --fetch DIR, the files that matter are also copied into DIR (at most 8, flat):
summary.txt, summary.json, device.txt, tests.log, default_frame.png, real_frame.png and
gpu-check.tar.gz (the whole output folder but the HDR images, for the rest).
"""
import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tarfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))  # bench/: capture_report
import capture_report  # noqa: E402

STEPS = ["device", "tests", "capture", "capture-real", "techniques"]
TITLES = {"build": "build (--build)", "device": "device info", "tests": "GPU tests (validation)",
          "capture": "capture default scene", "capture-real": "capture real assets", "techniques": "techniques bench"}
# Shares of the budget: seconds of the default budgets (300 s full, 110 s smoke) less the
# summary's reserve; scaled to another --budget.
SHARES_FULL = {"device": 20, "tests": 125, "capture": 35, "capture-real": 45, "techniques": 70}
SHARES_SMOKE = {"device": 10, "tests": 15, "capture": 20, "capture-real": 20, "techniques": 40}
RESERVE_S = 5  # kept for the summary
MIN_STEP_S = 3  # a step left less than this is not started

# Smoke: GPU tests that cover device creation, a compute dispatch, a draw, and that
# validation and synchronization validation are on and catch what they should.
SMOKE_GTESTS = [("avsm_gpu_tests", ["GpuTest.CreatesDeviceWithQueueAndTimestamps",
                                    "GpuTest.ComputeDispatchWritesExpectedValues",
                                    "GpuTest.OffscreenDrawProducesExpectedPixels",
                                    "GpuTest.MissingBarrierIsCaughtBySyncValidation",
                                    "GpuTest.SameWorkWithTheBarrierIsClean"])]
# The GPU test executables (ctest label gpu), for when ctest cannot run them (below).
GPU_GTEST_BINARIES = ["tests/avsm_gpu_tests", "tests/passes/avsm_pass_tests", "tests/api/avsm_api_tests",
                      "tests/live/avsm_live_tests"]
# They compare measured times: alone, after the rest (RUN_SERIAL in tests/CMakeLists.txt).
SERIAL_GTESTS = ["GpuTest.CalibrationDetectsLateComputeTimestamps", "GpuTest.PassesOfKnownCostAreTimedInRatio"]
# Full mode's technique rows (the references uncompressed and AVSM-8 always run).
FULL_TECHNIQUE_ROWS = r"^(AVSM-4|AVSM-16|AVSM-8 fixed|DSM e=0\.01|OSM-32|FOM-16)$"

# The camera's shading split as the engine names its passes (engine/capture/pass_stages.cpp).
STAGE_COLUMNS = [("shadow capture", "capture"), ("sort", "sort"), ("resolve / build", "build"), ("mips", "mips"),
                 ("opaque", "opaque"), ("hair", "hair"), ("volumes", "volumes"), ("camera other", "cam other"),
                 ("other", "other")]


def camera_part(name):
    if name == "opaque":
        return "opaque"
    if name == "hair" or name.startswith("hair "):
        return "hair"
    if name == "volumes" or name.startswith("volume "):
        return "volumes"
    return "camera other"


def say(text=""):
    print(text, flush=True)


def fmt_s(seconds):
    return f"{seconds:.0f} s" if seconds >= 10 else f"{seconds:.1f} s"


class Step:
    def __init__(self, name):
        self.name = name
        self.status = "not run"
        self.seconds = 0.0
        self.cap = 0.0
        self.note = ""
        self.failed = False

    def as_json(self):
        return {"step": self.name, "title": TITLES.get(self.name, self.name), "status": self.status,
                "seconds": round(self.seconds, 2), "cap_seconds": round(self.cap, 1), "note": self.note}


def run_capped(cmd, cap, log_path, env, cwd, stdout_path=None):
    """Runs cmd in its own process group, its output into log_path (stdout into stdout_path
    when given), for at most cap seconds: then the whole group is stopped.
    Returns (exit status or None when it could not start, seconds, timed out)."""
    os.makedirs(os.path.dirname(log_path), exist_ok=True)
    start = time.monotonic()
    with open(log_path, "ab") as log:
        log.write(("$ " + " ".join(cmd) + "\n").encode())
        log.flush()
        out = open(stdout_path, "wb") if stdout_path else log
        try:
            proc = subprocess.Popen(cmd, stdout=out, stderr=log, cwd=cwd, env=env, start_new_session=True)
        except OSError as e:
            log.write(f"cannot start: {e}\n".encode())
            if stdout_path:
                out.close()
            return None, time.monotonic() - start, False
        timed_out = False
        try:
            proc.wait(timeout=max(cap, 0.1))
        except subprocess.TimeoutExpired:
            timed_out = True
            for sig in (signal.SIGTERM, signal.SIGKILL):
                try:
                    os.killpg(proc.pid, sig)
                except ProcessLookupError:
                    break
                try:
                    proc.wait(timeout=5)
                    break
                except subprocess.TimeoutExpired:
                    continue
            proc.wait()
        if stdout_path:
            out.close()
        elapsed = time.monotonic() - start
        log.write(f"\n[exit {proc.returncode}{', cut at the cap of %.0f s' % cap if timed_out else ''}, "
                  f"{elapsed:.1f} s]\n".encode())
    return proc.returncode, elapsed, timed_out


def tail(path, lines=15):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return ""


class Check:
    def __init__(self, args):
        self.args = args
        self.smoke = args.smoke
        self.build = os.path.abspath(args.build_dir)
        self.out = os.path.abspath(args.out)
        self.logs = os.path.join(self.out, "logs")
        self.steps = {name: Step(name) for name in STEPS}
        self.build_step = Step("build") if args.build else None
        self.shares = dict(SHARES_SMOKE if self.smoke else SHARES_FULL)
        self.budget = float(args.budget if args.budget else (110 if self.smoke else 300))
        self.results = {}
        self.env = dict(os.environ)
        self.env.setdefault("XDG_RUNTIME_DIR", "/tmp")
        self.env["PYTHONUNBUFFERED"] = "1"
        if args.device:
            self.env["AVSM_DEVICE"] = args.device
        self.relocated = None  # (source, build) the tree was configured at, when not here

    # ---- set-up -------------------------------------------------------------------------
    def nominal_caps(self):
        active = [s for s in STEPS if s not in self.args.skip]
        total = sum(self.shares[s] for s in active) or 1
        usable = max(self.budget - RESERVE_S, 0)
        return {s: usable * self.shares[s] / total for s in active}

    def cap_now(self, name):
        """What is left of the budget, shared among this step and the ones after it."""
        left = self.budget - RESERVE_S - (time.monotonic() - self.t0)
        rest = [s for s in STEPS[STEPS.index(name):] if s not in self.args.skip]
        total = sum(self.shares[s] for s in rest) or 1
        return max(left, 0) * self.shares[name] / total

    def check_relocation(self):
        """A tree configured elsewhere (copied to a GPU machine) has absolute paths in its
        test files and binaries: the shader folders are redirected (AVSM_SOURCE_DIR,
        AVSM_SPIRV_DIR), ctest is replaced by the gtest binaries, or --link-original links
        the original paths here."""
        cache = os.path.join(self.build, "CMakeCache.txt")
        if not os.path.exists(cache):
            return
        values = {}
        for line in open(cache, errors="replace"):
            m = re.match(r"(CMAKE_HOME_DIRECTORY|CMAKE_CACHEFILE_DIR):INTERNAL=(.*)", line.strip())
            if m:
                values[m.group(1)] = m.group(2)
        source, build = values.get("CMAKE_HOME_DIRECTORY"), values.get("CMAKE_CACHEFILE_DIR")
        if not source or not build:
            return
        same = (os.path.realpath(source) == os.path.realpath(ROOT) and
                os.path.realpath(build) == os.path.realpath(self.build))
        if same:
            return
        self.relocated = (source, build)
        if self.args.link_original:
            for original, here in ((source, ROOT), (build, self.build)):
                if not os.path.exists(original):
                    os.makedirs(os.path.dirname(original), exist_ok=True)
                    os.symlink(here, original)
                    say(f"linked {original} -> {here} (--link-original)")
            self.relocated = None if all(os.path.exists(p) for p in (source, build)) else self.relocated
        if self.relocated:
            self.env["AVSM_SOURCE_DIR"] = ROOT
            self.env["AVSM_SPIRV_DIR"] = os.path.join(self.build, "spirv")
            say(f"note: {self.build} was configured as {build} (sources {source}); shaders are read from here "
                f"(AVSM_SOURCE_DIR, AVSM_SPIRV_DIR), the tests run from the gtest binaries; --link-original "
                f"links the original paths here instead")

    def run_build(self):
        """--build: configure (Release, Ninja when there is one and the folder is new) and build everything."""
        step = self.build_step
        step.cap = self.args.build_timeout
        cmake = shutil.which("cmake")
        if not cmake:
            return self.fail(step, "cmake not found")
        configure = [cmake, "-S", ROOT, "-B", self.build, "-DCMAKE_BUILD_TYPE=Release"]
        if not os.path.exists(os.path.join(self.build, "CMakeCache.txt")) and shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        log = os.path.join(self.logs, "build.log")
        start = time.monotonic()
        say(f"[build] {' '.join(configure[1:])}; cmake --build -j {self.args.jobs} "
            f"(allowed {fmt_s(self.args.build_timeout)}, besides the budget)")
        rc, _, cut = run_capped(configure, self.args.build_timeout, log, self.env, ROOT)
        if rc == 0:
            left = self.args.build_timeout - (time.monotonic() - start)
            rc, _, cut = run_capped([cmake, "--build", self.build, "-j", str(self.args.jobs)], left, log, self.env,
                                    ROOT)
        step.seconds = time.monotonic() - start
        if rc != 0:
            say(tail(log, 25))
            return self.fail(step, ("cut by its time cap" if cut else f"exit {rc}") +
                             "; the steps run on what there is; see logs/build.log", cut=cut)
        step.status, step.note = "ok", "configured and built"
        say(f"      ok in {fmt_s(step.seconds)}")
        return True

    # ---- steps --------------------------------------------------------------------------
    def step_device(self, step, cap):
        exe = os.path.join(self.build, "bench", "gpu", "avsm_gpu_device_info")
        if not os.path.exists(exe):
            return self.fail(step, f"{exe} is not built (target avsm_gpu_device_info)")
        json_path = os.path.join(self.out, "device.json")
        text_path = os.path.join(self.out, "device.txt")
        rc, _, cut = run_capped([exe, "--json", json_path], cap, os.path.join(self.logs, "device.log"), self.env,
                                self.out, stdout_path=text_path)
        if os.path.exists(text_path):
            say("".join("      " + line for line in open(text_path, errors="replace").readlines()))
        info = None
        try:
            info = json.load(open(json_path))
        except (OSError, ValueError):
            pass
        if info:
            self.results["device"] = info
        if cut:
            return self.fail(step, "cut by its time cap", cut=True)
        if rc != 0 or not info or "device" not in info:
            reason = info.get("error") if info and "error" in info else f"exit {rc}"
            return self.fail(step, f"no device info: {reason}; see logs/device.log")
        d = info["device"]
        step.note = f"{d['name']} ({d['type']}), {d['driver_name']} {d['driver_version']}, Vulkan {d['api_version']}"
        problems = []
        if not info.get("validation_layer", {}).get("available"):
            problems.append("validation layer missing")
        if "error" in info.get("timestamps", {}):
            problems.append("timestamp calibration failed")
        if problems:
            return self.fail(step, step.note + "; " + ", ".join(problems))
        return True

    def ctest_usable(self):
        if self.relocated:
            return False, "the tree was configured elsewhere"
        if not shutil.which("ctest"):
            return False, "ctest not found"
        if not os.path.exists(os.path.join(self.build, "CTestTestfile.cmake")):
            return False, "no CTestTestfile.cmake in the build folder"
        return True, ""

    def step_tests(self, step, cap):
        log = os.path.join(self.out, "tests.log")
        if os.path.exists(log):
            os.remove(log)
        if not self.smoke:
            usable, why = self.ctest_usable()
            if usable:
                return self.run_ctest(step, cap, log)
            say(f"      ({why}: running the GPU test binaries directly)")
            return self.run_gtests(step, cap, log, [(b, None) for b in GPU_GTEST_BINARIES], self.args.jobs)
        return self.run_gtests(step, cap, log, [("tests/" + b, f) for b, f in SMOKE_GTESTS], self.args.jobs)

    def run_ctest(self, step, cap, log):
        per_test = int(max(min(90, cap - 5), 5))
        # Not this check's own smoke test (label gpu too): it would run a second check.
        exclude = r"^bench\.GpuCheck" + ("|" + self.args.tests_exclude if self.args.tests_exclude else "")
        cmd = ["ctest", "--test-dir", self.build, "-L", "gpu", "-E", exclude, "-j", str(self.args.jobs),
               "--timeout", str(per_test), "--output-on-failure", "--no-tests=error"]
        say(f"      {' '.join(cmd)}")
        rc, seconds, cut = run_capped(cmd, cap, log, self.env, self.out)
        text = open(log, errors="replace").read()
        results = {}
        # "  3/40 Test  #3: name ........***Failed    1.52 sec" (no dots after a long name)
        line = r"^\s*\d+/\d+ Test\s+#\d+: (\S+?)(?:\s+\.*\s*|(?=\*\*\*))\**([A-Za-z][^*]*?)\s+[\d.]+ sec\s*$"
        for m in re.finditer(line, text, re.M):
            status = m.group(2).strip()
            results[m.group(1)] = ("passed" if status == "Passed" else
                                   "skipped" if status.startswith("Skipped") else status.lower())
        totals = [int(t) for t in re.findall(r"^\s*\d+/(\d+) Test", text, re.M)]
        total = max(totals) if totals else len(results)
        passed = sum(1 for r in results.values() if r == "passed")
        failed = sorted(n for n, r in results.items() if r not in ("passed", "skipped"))
        skipped = sum(1 for r in results.values() if r == "skipped")
        not_finished = max(total - len(results), 0)
        m = re.search(r"Total Test time \(real\) =\s*([\d.]+) sec", text)
        self.results["tests"] = {"runner": "ctest -L gpu", "total": total, "passed": passed, "failed": len(failed),
                                 "skipped": skipped, "not_finished": not_finished, "failed_tests": failed,
                                 "seconds": float(m.group(1)) if m else round(seconds, 1), "per_test_timeout": per_test}
        return self.tests_verdict(step, rc, cut, log)

    def list_gtests(self, exe):
        """The tests of a gtest binary (--gtest_list_tests), DISABLED_ ones left out."""
        listing = subprocess.run([exe, "--gtest_list_tests"], capture_output=True, text=True, timeout=60,
                                 env=self.env, cwd=self.out)
        tests, suite = [], ""
        for line in listing.stdout.splitlines():
            if not line.strip() or line.startswith(("Running main", "Note:")):
                continue
            if not line.startswith(" "):
                suite = line.split("#")[0].strip()
            else:
                name = line.split("#")[0].strip()
                if not name.startswith("DISABLED_") and not suite.startswith("DISABLED_"):
                    tests.append(suite + name)
        return tests

    def run_gtests(self, step, cap, log, jobs, workers):
        """Each test in its own process (ctest runs one per suite; one per test isolates
        more), `workers` at a time; the timing tests alone at the end
        (RUN_SERIAL in tests/CMakeLists.txt). jobs: (binary, tests or None for all of them)."""
        work = os.path.join(self.logs, "gtest")
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        start = time.monotonic()
        queue, missing = [], []  # (exe, test)
        for binary, tests in jobs:
            exe = os.path.join(self.build, binary)
            if not os.path.exists(exe):
                missing.append(binary)
                continue
            try:
                queue += [(exe, t) for t in (tests if tests is not None else self.list_gtests(exe))]
            except (OSError, subprocess.SubprocessError) as e:
                missing.append(f"{binary} (cannot list its tests: {e})")
        queue.sort(key=lambda job: job[1] in SERIAL_GTESTS)  # stable: the timing tests last
        per_test = max(min(90.0, cap - 5), 5.0)
        found = len(jobs) - len(missing)
        say(f"      {len(queue)} test(s) from {found} gtest binar{'y' if found == 1 else 'ies'}, "
            f"one process each, {workers} at a time, {per_test:.0f} s per test at most")
        results = {}  # test -> (status, log file)
        running = []  # (proc, test, log file, started, handle)
        cut = False
        index = 0
        while index < len(queue) or running:
            now = time.monotonic()
            if now - start > cap:
                cut = True
                break
            serial_next = index < len(queue) and queue[index][1] in SERIAL_GTESTS
            while index < len(queue) and len(running) < (1 if serial_next else workers) and not (
                    serial_next and running):
                exe, test = queue[index]
                index += 1
                out_json = os.path.join(work, f"{index:04d}.json")
                out_log = os.path.join(work, f"{index:04d}.log")
                handle = open(out_log, "wb")
                proc = subprocess.Popen([exe, "--gtest_filter=" + test, "--gtest_output=json:" + out_json],
                                        stdout=handle, stderr=subprocess.STDOUT, cwd=self.out, env=self.env,
                                        start_new_session=True)
                running.append((proc, test, out_log, time.monotonic(), handle, out_json))
                serial_next = index < len(queue) and queue[index][1] in SERIAL_GTESTS
            still = []
            for proc, test, out_log, started, handle, out_json in running:
                if proc.poll() is None:
                    if time.monotonic() - started > per_test:
                        os.killpg(proc.pid, signal.SIGKILL)
                        proc.wait()
                        handle.close()
                        results[test] = ("timeout", out_log)
                    else:
                        still.append((proc, test, out_log, started, handle, out_json))
                    continue
                handle.close()
                status = "passed" if proc.returncode == 0 else "failed"
                try:
                    for suite in json.load(open(out_json)).get("testsuites", []):
                        for t in suite.get("testsuite", []):
                            if t.get("result") == "SKIPPED":
                                status = "skipped"
                except (OSError, ValueError):
                    pass
                results[test] = (status, out_log)
            running = still
            time.sleep(0.05)
        for proc, test, out_log, started, handle, out_json in running:  # cut by the cap
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            handle.close()
        seconds = time.monotonic() - start
        failed = sorted(t for t, (status, _) in results.items() if status not in ("passed", "skipped"))
        with open(log, "w") as out:
            for test in failed:
                out.write(f"==== {test}: {results[test][0]}\n")
                out.write(tail(results[test][1], 60))
            out.write("==== all tests\n")
            for exe, test in queue:
                out.write(f"{test:<90} {results.get(test, ('not finished', ''))[0]}\n")
        self.results["tests"] = {
            "runner": ("gtest smoke subset" if self.smoke else "gtest binaries") + ", one process per test",
            "total": len(queue), "passed": sum(1 for s, _ in results.values() if s == "passed"), "failed": len(failed),
            "skipped": sum(1 for s, _ in results.values() if s == "skipped"),
            "not_finished": len(queue) - len(results), "failed_tests": failed, "missing_binaries": missing,
            "seconds": round(seconds, 1), "per_test_timeout": round(per_test)}
        rc = 0 if queue and not missing and not failed and len(results) == len(queue) else 1
        return self.tests_verdict(step, rc, cut, log, head=True)

    def tests_verdict(self, step, rc, cut, log, head=False):
        t = self.results["tests"]
        step.note = (f"{t['passed']} passed, {t['failed']} failed" +
                     (f", {t['skipped']} skipped" if t['skipped'] else "")
                     + (f", {t['not_finished']} not finished" if t['not_finished'] else "") + f" ({t['runner']})")
        if t.get("missing_binaries"):
            step.note += "; not built: " + ", ".join(t["missing_binaries"])
        if cut:
            return self.fail(step, "cut by its time cap: " + step.note, cut=True)
        if rc != 0 or t["failed"] or t["total"] == 0:
            if t["failed_tests"]:
                step.note += "; failed: " + ", ".join(t["failed_tests"][:8]) + (
                    " ..." if len(t["failed_tests"]) > 8 else "")
            if head:  # the failures come first
                say("".join(open(log, errors="replace").readlines()[:30]))
            else:
                say(tail(log, 20))
            return self.fail(step, step.note)
        return True

    def capture_args(self):
        if self.smoke:
            return ["--width", "160", "--height", "90", "--frames", "1", "--shadow-res", "32"]
        return ["--width", "1920", "--height", "1080", "--frames", str(self.args.frames)]

    def step_capture(self, step, cap):
        scene = os.path.join(self.build, "content", "default", "scene.json")
        if not os.path.exists(scene):
            return self.fail(step, f"{scene} is missing (target avsm_default_content)")
        return self.capture(step, cap, "default", scene)

    def step_capture_real(self, step, cap):
        scene = os.path.join(ROOT, "content", "real_assets.scene.json")
        if not os.path.exists(scene):
            return self.fail(step, f"{scene} is missing")
        scene, missing = self.real_scene(scene)
        if missing:
            step.status = "missing"
            step.note = (f"real content missing, looked in {' and '.join(self.content_dirs())} (--content DIR): " +
                         ", ".join(missing))
            self.results["captures"] = self.results.get("captures", {})
            self.results["captures"]["real"] = {"missing_content": missing}
            return True
        return self.capture(step, cap, "real", scene)

    def content_dirs(self):
        if self.args.content:
            return [os.path.abspath(self.args.content)]
        return [os.path.join(os.path.dirname(ROOT), "shared", "content"), os.path.join(ROOT, "shared", "content")]

    def real_scene(self, scene):
        """The scene with its files resolved: relative to the scene file, or under --content
        (or ROOT/shared/content, where a copied checkout keeps it) for those under shared/content.
        Returns (scene path to render, missing files)."""
        content_dirs = self.content_dirs()
        data = json.load(open(scene))
        scene_dir = os.path.dirname(scene)
        missing, rewritten = [], False

        def resolve(path):
            nonlocal rewritten
            here = os.path.normpath(os.path.join(scene_dir, path))
            if os.path.exists(here) and not self.args.content:
                return here
            m = re.search(r"shared/content/(.*)$", path.replace("\\", "/"))
            if m:
                for d in content_dirs:
                    candidate = os.path.join(os.path.abspath(d), m.group(1))
                    if os.path.exists(candidate):
                        rewritten = True
                        return candidate
            missing.append(path)
            return here

        def walk(node):
            if isinstance(node, dict):
                for key, value in node.items():
                    if key == "file" and isinstance(value, str):
                        node[key] = resolve(value)
                    else:
                        walk(value)
            elif isinstance(node, list):
                for item in node:
                    walk(item)

        walk(data)
        if missing:
            return scene, missing
        path = os.path.join(self.out, "capture_real", "real_assets.scene.json")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        json.dump(data, open(path, "w"), indent=1)  # every file resolved: renders from anywhere
        return path, []

    def capture(self, step, cap, key, scene):
        exe = os.path.join(self.build, "tools", "avsm-capture")
        if not os.path.exists(exe):
            return self.fail(step, f"{exe} is not built")
        folder = os.path.join(self.out, "capture_" + key)
        for name in os.listdir(folder) if os.path.isdir(folder) else []:
            if not name.endswith(".scene.json"):
                path = os.path.join(folder, name)
                shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
        cmd = [exe, "--scene", scene, "--out", folder, "--report"] + self.capture_args()
        if self.args.device:
            cmd += ["--device", self.args.device]
        log = os.path.join(self.logs, f"capture_{key}.log")
        say(f"      avsm-capture {' '.join(cmd[1:])}")
        rc, seconds, cut = run_capped(cmd, cap, log, self.env, self.out)
        if cut:
            return self.fail(step, "cut by its time cap", cut=True)
        if rc != 0:
            say(tail(log))
            return self.fail(step, f"avsm-capture exit {rc}: " + (tail(log, 3).strip().splitlines() or [""])[0])
        try:
            figures = self.capture_figures(folder, log)
        except (OSError, ValueError, KeyError) as e:
            return self.fail(step, f"unreadable outputs in {folder}: {e}")
        figures["seconds"] = round(seconds, 1)
        self.results.setdefault("captures", {})[key] = figures
        step.note = (f"{figures['width']}x{figures['height']}, frame {figures['frame_gpu_ms']:.2f} ms GPU "
                     f"(median of {figures['frames_measured']}), {figures['passes']} passes")
        return True

    def capture_figures(self, folder, log):
        raw = json.load(open(os.path.join(folder, "timings.json")))
        timings = capture_report.timings(folder)
        stages = {column: 0.0 for column, _ in STAGE_COLUMNS}
        passes = []
        for p in timings.passes:
            column = camera_part(p.name) if p.stage == "camera shading" else p.stage
            stages[column if column in stages else "other"] += p.gpu_ms.median
            passes.append({"name": p.name, "stage": p.stage, "gpu_ms_median": round(p.gpu_ms.median, 4),
                           "gpu_ms_max": round(p.gpu_ms.max, 4)})
        figures = {"device": timings.device, "driver": raw.get("driver", ""),
                   "timestamp_mode": raw.get("timestamp_mode", ""), "width": raw["width"], "height": raw["height"],
                   "frames_measured": raw.get("frames_measured", 0), "frame_gpu_ms": timings.frame_gpu_ms.median,
                   "frame_gpu_ms_min": timings.frame_gpu_ms.min, "frame_gpu_ms_max": timings.frame_gpu_ms.max,
                   "frame_wall_ms": timings.frame_wall_ms.median if timings.frame_wall_ms else None,
                   "stage_gpu_ms": {k: round(v, 4) for k, v in stages.items()}, "passes": len(passes),
                   "pass_gpu_ms": passes}
        m = re.search(r"(\d+) frames in [\d.]+ ms \((\d+) in flight\): ([\d.]+) ms per frame", open(log).read())
        if m:
            figures["throughput_ms_per_frame"] = float(m.group(3))
            figures["frames_in_flight"] = int(m.group(2))
        try:
            mem = capture_report.memory(folder)
            figures["map_mib"] = round(sum(light.map_bytes for light in mem.lights) / 2**20, 2)
            figures["capture_mib"] = round(sum(light.capture_bytes for light in mem.lights) / 2**20, 2)
            figures["transient_mib"] = round(mem.transient_bytes_aliased / 2**20, 2)
            figures["lights"] = len(mem.lights)
        except (OSError, ValueError, KeyError):
            pass
        return figures

    def step_techniques(self, step, cap):
        script = os.path.join(ROOT, "bench", "avsm", "techniques.py")
        folder = os.path.join(self.out, "techniques")
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(os.path.join(folder, "work"))
        if self.smoke:
            size, rows, res = ["--width", "96", "--height", "54", "--frames", "1"], r"^$", 32  # the two references only
        else:
            size, rows, res = ["--width", "1280", "--height", "720", "--frames", "3"], self.args.technique_rows, 256
        res = self.args.shadow_res or res
        cmd = [sys.executable, script, "--build", self.build, "--shadow-res", str(res), "--rows", rows] + size
        say(f"      {os.path.relpath(script, ROOT)} {' '.join(cmd[2:])}")
        env = dict(self.env, TMPDIR=os.path.join(folder, "work"))  # its captures land here, not in /tmp
        table = os.path.join(folder, "table.txt")
        log = os.path.join(self.logs, "techniques.log")
        rc, seconds, cut = run_capped(cmd, cap, log, env, self.out, stdout_path=table)
        for folder_, _, files in os.walk(os.path.join(folder, "work")):  # its captures' HDR images: large, unread
            for name in files:
                if name.endswith(".exr"):
                    os.remove(os.path.join(folder_, name))
        rows_out = parse_technique_table(open(table, errors="replace").read() if os.path.exists(table) else "")
        self.results["techniques"] = {"shadow_res": res, "args": cmd[2:], "rows": rows_out,
                                      "seconds": round(seconds, 1)}
        if cut:
            done = len(re.findall(r"^rendering ", open(log, errors="replace").read(), re.M))
            return self.fail(step, f"cut by its time cap after {done} renders", cut=True)
        if rc != 0 or not rows_out:
            say(tail(log))
            return self.fail(step, f"techniques.py exit {rc}, {len(rows_out)} rows; see logs/techniques.log")
        step.note = f"{len(rows_out)} rows at {res}^2 maps: " + ", ".join(
            f"{r['technique']} {r['frame']:.1f} ms" for r in rows_out[:4]) + (" ..." if len(rows_out) > 4 else "")
        return True

    def all_steps(self):
        return ([self.build_step] if self.build_step else []) + [self.steps[s] for s in STEPS]

    def fail(self, step, note, cut=False):
        step.note = note
        step.status = "CUT" if cut else "FAILED"
        step.failed = True
        return False

    # ---- the run ------------------------------------------------------------------------
    def run(self):
        shutil.rmtree(self.logs, ignore_errors=True)  # this run's logs only (they are appended to)
        os.makedirs(self.logs)
        for name in ("summary.txt", "summary.json", "device.txt", "device.json", "tests.log"):
            if os.path.exists(os.path.join(self.out, name)):
                os.remove(os.path.join(self.out, name))
        mode = "smoke" if self.smoke else "full"
        say(f"bench/gpu/check.sh ({mode}): build {self.build}, out {self.out}, budget {fmt_s(self.budget)}, "
            f"{self.args.jobs} jobs")
        if self.args.build:
            self.run_build()
        self.check_relocation()
        caps = self.nominal_caps()
        say("time allowed per step (what a step leaves unused goes to the next ones): " +
            ", ".join(f"{TITLES[s]} {fmt_s(c)}" for s, c in caps.items()) + f"; summary {RESERVE_S} s")
        self.t0 = time.monotonic()
        for i, name in enumerate(STEPS, 1):
            step = self.steps[name]
            if name in self.args.skip:
                step.status, step.note = "skipped", "--skip"
                continue
            cap = self.cap_now(name)
            step.cap = cap
            if cap < MIN_STEP_S:
                self.fail(step, f"not started: {cap:.1f} s of the budget left", cut=True)
                say(f"[{i}/{len(STEPS)}] {TITLES[name]}: CUT ({step.note})")
                continue
            say(f"[{i}/{len(STEPS)}] {TITLES[name]} (allowed {fmt_s(cap)})")
            start = time.monotonic()
            try:
                ok = getattr(self, "step_" + name.replace("-", "_"))(step, cap)
            except Exception as e:  # a bug here must not cost the other steps
                ok = self.fail(step, f"{type(e).__name__}: {e}")
            step.seconds = time.monotonic() - start
            if ok and step.status == "not run":
                step.status = "ok"
            say(f"      {step.status} in {fmt_s(step.seconds)}: {step.note}")
        self.total_seconds = time.monotonic() - self.t0
        try:
            self.write_summary()
        except Exception as e:  # the steps' statuses at least, whatever the figures held
            text = "".join(f"{TITLES[s.name]:<25}{s.status:<9}{s.note}\n" for s in self.all_steps())
            text += f"(the full summary failed: {type(e).__name__}: {e})\n"
            say(text)
            with open(os.path.join(self.out, "summary.txt"), "w") as f:
                f.write(text)
            with open(os.path.join(self.out, "summary.json"), "w") as f:
                json.dump({"ok": False, "error": str(e), "steps": [s.as_json() for s in self.all_steps()]}, f)
            summary_error = f"the summary: {type(e).__name__}: {e}"
        else:
            summary_error = ""
        failed = [s for s in self.all_steps() if s.failed]
        if self.args.fetch:
            self.fetch(self.args.fetch)
        if failed or summary_error:
            print("bench/gpu/check.sh: FAILED: " + "; ".join(
                [f"{TITLES[s.name]}: {s.note}" for s in failed] + ([summary_error] if summary_error else [])),
                file=sys.stderr, flush=True)
            return 1
        say(f"bench/gpu/check.sh: all steps ok in {fmt_s(self.total_seconds)}")
        return 0

    # ---- summary ------------------------------------------------------------------------
    def write_summary(self):
        lines = []
        mode = "smoke" if self.smoke else "full"
        dev = self.results.get("device", {}).get("device")
        caps = self.results.get("captures", {})
        if dev:
            device_line = (f"{dev['name']} ({dev['type']}); driver {dev['driver_name']} {dev['driver_version']} "
                           f"({dev['driver_info']}); Vulkan {dev['api_version']}")
        else:  # from a capture's timings.json
            any_capture = next((c for c in caps.values() if "device" in c), None)
            device_line = (f"{any_capture['device']}; driver {any_capture['driver']} (from timings.json)"
                           if any_capture else "unknown")
        lines.append(f"GPU check ({mode}), {time.strftime('%Y-%m-%d %H:%M:%S')}: {fmt_s(self.total_seconds)} "
                     f"of a {fmt_s(self.budget)} budget")
        lines.append(f"device: {device_line}")
        info = self.results.get("device", {})
        if info.get("limits"):
            lim, feat = info["limits"], info.get("features", {})
            mem = info.get("memory", {}).get("heaps", [])
            local = sum(h["size_bytes"] for h in mem if "DEVICE_LOCAL" in h["flags"])
            lines.append(f"limits: maxStorageBufferRange {lim['maxStorageBufferRange'] / 2**20:.0f} MiB, "
                         f"maxImageDimension2D {lim['maxImageDimension2D']}, timestamps "
                         f"{lim['timestampPeriod_ns']:g} ns x {lim['timestampValidBits']} bits "
                         f"({info.get('timestamps', {}).get('mode', '?')}), subgroup {lim['subgroupSize']}, "
                         f"device-local memory {local / 2**30:.1f} GiB")
            off = [k for k, v in feat.items() if not v]
            lines.append("features: " + ("all the engine asks for" if not off else "missing " + ", ".join(off)))
        lines.append("")
        header = f"{'step':<25}{'status':<9}{'time':>8}{'allowed':>9}  notes"
        lines += [header, "-" * len(header)]
        for s in self.all_steps():
            name = s.name
            lines.append(f"{TITLES[name]:<25}{s.status:<9}{fmt_s(s.seconds) if s.seconds else '-':>8}"
                         f"{fmt_s(s.cap) if s.cap else '-':>9}  {s.note}")
        rendered = {k: c for k, c in caps.items() if "frame_gpu_ms" in c}
        if rendered:
            lines.append("")
            lines.append("frame GPU ms (medians over the measured frames) by stage:")
            head = f"{'scene':<9}{'size':>10}{'frames':>7}{'frame':>9}{'wall/fr':>9}" + "".join(
                f"{label:>10}" for _, label in STAGE_COLUMNS) + f"{'maps MiB':>10}"
            lines += [head, "-" * len(head)]
            for key, c in rendered.items():
                wall = c.get("throughput_ms_per_frame", c.get("frame_wall_ms"))
                lines.append(f"{key:<9}{c['width']:>5}x{c['height']:<4}{c['frames_measured']:>7}"
                             f"{c['frame_gpu_ms']:>9.2f}{wall if wall is not None else float('nan'):>9.2f}" +
                             "".join(f"{c['stage_gpu_ms'][stage]:>10.2f}" for stage, _ in STAGE_COLUMNS) +
                             f"{c.get('map_mib', float('nan')):>10.2f}")
            lines.append("(wall/fr: wall ms per frame with frames in flight, after the first; timestamps "
                         f"{next(iter(rendered.values()))['timestamp_mode']})")
        tech = self.results.get("techniques", {}).get("rows")
        if tech:
            lines.append("")
            lines.append(f"techniques at {self.results['techniques']['shadow_res']}^2 maps "
                         f"({' '.join(self.results['techniques']['args'][4:])}), GPU ms:")
            head = f"{'technique':<14}{'capture':>9}{'sort':>8}{'build':>9}{'mips':>8}{'camera':>9}{'frame':>9}" \
                   f"{'map MiB':>9}{'mean err':>10}{'max err':>9}{'x AVSM-8':>9}"
            lines += [head, "-" * len(head)]
            for r in tech:
                lines.append(f"{r['technique']:<14}{r['capture']:>9.2f}{r['sort']:>8.2f}{r['build']:>9.2f}"
                             f"{r['mips']:>8.2f}{r['camera']:>9.2f}{r['frame']:>9.2f}{r['map_mib']:>9.2f}"
                             f"{r['mean_err']:>10.4f}{r['max_err']:>9.4f}{r['frame_over_avsm8']:>9.2f}")
        failed = [s for s in self.all_steps() if s.failed]
        lines.append("")
        missing = " (the real content is missing)" if self.steps["capture-real"].status == "missing" else ""
        lines.append("result: " + ("all steps ok" + missing if not failed else
                                   "FAILED: " + ", ".join(TITLES[s.name] for s in failed)))
        text = "\n".join(lines) + "\n"
        say("")
        say(text)
        with open(os.path.join(self.out, "summary.txt"), "w") as f:
            f.write(text)
        summary = {"mode": mode, "ok": not failed, "budget_seconds": self.budget,
                   "seconds": round(self.total_seconds, 1), "build_dir": self.build, "jobs": self.args.jobs,
                   "relocated_from": self.relocated, "steps": [s.as_json() for s in self.all_steps()]}
        summary.update(self.results)
        with open(os.path.join(self.out, "summary.json"), "w") as f:
            json.dump(summary, f, indent=1)

    def fetch(self, dest):
        """The few files that matter, flat in dest (at most 8), with the rest in one archive."""
        os.makedirs(dest, exist_ok=True)
        picks = [("summary.txt", "summary.txt"), ("summary.json", "summary.json"), ("device.txt", "device.txt"),
                 ("tests.log", "tests.log"), ("capture_default/frame.png", "default_frame.png"),
                 ("capture_real/frame.png", "real_frame.png")]
        copied = []
        for src, name in picks:
            path = os.path.join(self.out, src)
            if os.path.exists(path):
                shutil.copyfile(path, os.path.join(dest, name))
                copied.append(name)
        archive = os.path.join(dest, "gpu-check.tar.gz")
        # A fetched file may hold 16 MiB: leave out the biggest kinds of file until it fits.
        for leave_out in ((".exr",), (".exr", "report.html", "trace.json"),
                          (".exr", "report.html", "trace.json", ".png")):
            with tarfile.open(archive, "w:gz") as tar:
                for folder, dirs, files in os.walk(self.out):
                    dirs[:] = sorted(d for d in dirs if d != "work")  # the technique bench's scratch captures
                    for name in sorted(files):
                        path = os.path.join(folder, name)
                        if name.endswith(leave_out) or os.path.abspath(path) == os.path.abspath(archive):
                            continue
                        tar.add(path, arcname=os.path.join("gpu-check", os.path.relpath(path, self.out)))
            if os.path.getsize(archive) < 15 * 2**20:
                break
        copied.append("gpu-check.tar.gz")
        say(f"fetch: {', '.join(copied)} in {dest}")


def parse_technique_table(text):
    """techniques.py's table rows: a label (may hold spaces), then 12 numbers."""
    keys = ["capture", "sort", "build", "mips", "camera", "frame", "map_mib", "trans_mib", "mean_err", "max_err",
            "frame_over_avsm8", "ns_per_segment"]
    rows = []
    for line in text.splitlines():
        parts = line.split()
        if len(parts) < 13:
            continue
        try:
            numbers = [float(p) for p in parts[-12:]]
        except ValueError:
            continue
        row = {"technique": " ".join(parts[:-12])}
        row.update(zip(keys, numbers))
        rows.append(row)
    return rows


def main():
    cores = os.cpu_count() or 1
    parser = argparse.ArgumentParser(
        prog="bench/gpu/check.sh", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__.split("\n\n")[0],
        epilog="\n\n".join(__doc__.split("\n\n")[1:]) + "\n\nexamples:\n"
        "  bench/gpu/check.sh                          # full check of build/, 5 minutes at most\n"
        "  bench/gpu/check.sh --build --out /tmp/gc --fetch $OUT   # build first; copy the results to $OUT\n"
        "  bench/gpu/check.sh --smoke                  # every step, tiny (CI, lavapipe): about a minute\n"
        "  bench/gpu/check.sh --budget 120 --skip techniques\n"
        "time allowed per step at the default budgets (scaled to --budget; what a step leaves unused goes\n"
        "to the steps after it; a step is stopped, with its whole process group, at its time):\n"
        "  full, 300 s:  " + ", ".join(f"{s} {SHARES_FULL[s]} s" for s in STEPS) + f", summary {RESERVE_S} s\n"
        "  smoke, 110 s: " + ", ".join(f"{s} {SHARES_SMOKE[s]} s" for s in STEPS) + f", summary {RESERVE_S} s\n"
        "environment: VK_DRIVER_FILES / VK_ICD_FILENAMES / VK_LAYER_PATH as the machine needs; AVSM_DEVICE\n"
        "picks the device (or --device); XDG_RUNTIME_DIR defaults to /tmp.")
    parser.add_argument("--smoke", action="store_true",
                        help="every step at a tiny size (a few GPU tests, 160x90 captures, 32^2 maps): for CI")
    parser.add_argument("--build-dir", default=os.path.join(ROOT, "build"), help="the build tree (default build/)")
    parser.add_argument("--build", action="store_true",
                        help="configure (Release; Ninja when present) and build the build tree first, with --jobs "
                             "cores; its time is not part of --budget")
    parser.add_argument("--build-timeout", type=float, default=600, metavar="SECONDS",
                        help="cap of --build (default 600)")
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "gpu-check"),
                        help="output folder (default out/gpu-check)")
    parser.add_argument("--budget", type=float, default=0, metavar="SECONDS",
                        help="time for all the steps (default 300; smoke 110)")
    parser.add_argument("--jobs", type=int, default=cores, help=f"parallel tests and build jobs (default {cores})")
    parser.add_argument("--device", default="", help="Vulkan device: index or part of its name (else AVSM_DEVICE)")
    parser.add_argument("--content", default="", metavar="DIR",
                        help="the real content folder (default ../shared/content, else shared/content)")
    parser.add_argument("--frames", type=int, default=30, help="frames per capture in the full mode (default 30)")
    parser.add_argument("--shadow-res", type=int, default=0,
                        help="the techniques bench's map size (default 256; smoke 32)")
    parser.add_argument("--technique-rows", default=FULL_TECHNIQUE_ROWS, metavar="REGEX",
                        help="the techniques bench's rows in the full mode, besides uncompressed and AVSM-8 "
                             "(default %(default)s; '.' for all)")
    parser.add_argument("--tests-exclude", default="", metavar="REGEX",
                        help="full mode: also leave these tests out of ctest -L gpu (e.g. '^embed\\.', whose fixture "
                             "installs the engine and builds the host examples: it needs a compiler and -dev packages)")
    parser.add_argument("--skip", action="append", default=[], choices=STEPS, help="leave a step out (repeatable)")
    parser.add_argument("--fetch", default="", metavar="DIR",
                        help="also copy the files that matter into DIR (at most 8; see above)")
    parser.add_argument("--link-original", action="store_true",
                        help="for a build tree copied from another path: link the original paths to here so "
                             "ctest and the binaries' built-in paths work")
    args = parser.parse_args()
    if args.budget < 0 or args.jobs < 1 or args.frames < 1:
        parser.error("--budget, --jobs and --frames must be positive")
    return Check(args).run()


if __name__ == "__main__":
    sys.exit(main())

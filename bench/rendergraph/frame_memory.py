#!/usr/bin/env python3
"""Transient memory of the engine's real frame, with and without aliasing.

Renders one frame of a scene with avsm-capture (default: the default scene at
1280x720 with its two shadowed lights) and prints every transient resource the
frame graph placed (size, heap offset, first and last pass) and the totals the
plan reports: bytes with aliasing, bytes if every transient had its own memory,
and the share aliasing saves.

usage: bench/rendergraph/frame_memory.py [--build DIR] [--scene FILE] [extra avsm-capture flags...]
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bench/
import capture_report  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--scene", default="")
    args, extra = parser.parse_known_args()
    capture = os.path.join(args.build, "tools", "avsm-capture")
    if not os.path.exists(capture):
        sys.exit(f"{capture} not found: build first")
    os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")
    out = tempfile.mkdtemp(prefix="avsm-frame-memory-")
    cmd = [capture, "--out", out, "--frames", "1", "--quiet"] + (["--scene", args.scene] if args.scene else []) + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    plan = capture_report.plan(out)
    memory = capture_report.memory(out)
    passes = plan.pass_names

    print(f"transient resources of the frame ({' '.join(cmd[1:])}):")
    header = f"{'resource':<24}{'kind':>8}{'MiB':>9}{'heap':>6}{'offset MiB':>12}  lifetime (passes)"
    print(header)
    print("-" * (len(header) + 30))
    for r in plan.resources:
        if r.imported or not r.used:
            continue
        first, last = passes[r.first_pass], passes[r.last_pass]
        print(f"{r.name:<24}{r.kind:>8}{r.size / 2**20:>9.2f}{r.heap:>6}{r.offset / 2**20:>12.2f}"
              f"  {first} .. {last}")
    aliased = memory.transient_bytes_aliased
    unaliased = memory.transient_bytes_unaliased
    saved = 1.0 - aliased / unaliased if unaliased else 0.0
    print()
    print(f"{'transient bytes without aliasing':<36}{unaliased / 2**20:>10.2f} MiB")
    print(f"{'transient bytes with aliasing':<36}{aliased / 2**20:>10.2f} MiB")
    print(f"{'saved by aliasing':<36}{100.0 * saved:>10.1f} %")


if __name__ == "__main__":
    main()

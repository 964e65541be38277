#!/usr/bin/env python3
"""run_if_content.py CONTENT_DIR COMMAND...: runs COMMAND when CONTENT_DIR (the real
third-party assets, ../shared/content) exists; otherwise says so and exits 77, which
CTest reports as a skipped test (SKIP_RETURN_CODE), not as a pass."""
import subprocess
import sys
from pathlib import Path

content, command = Path(sys.argv[1]), sys.argv[2:]
if not content.is_dir():
    print(f"skipped: {content} is missing (see content/real_assets.scene.json)")
    sys.exit(77)
sys.exit(subprocess.call(command))

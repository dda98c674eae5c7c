"""Start JupyterLab on 127.0.0.1 with a fresh random token, and print the URL.

The token is never empty; ``--allow-root`` is added only when running as root.
"""

from __future__ import annotations

import os
import secrets
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def build_command(token: str, port: str, as_root: bool) -> list[str]:
    """The JupyterLab command line: loopback only, a non-empty token, root only if needed."""
    if not token:
        raise ValueError("token must not be empty: JupyterLab would accept anyone")
    cmd = [
        sys.executable,
        "-m",
        "jupyterlab",
        "--ServerApp.ip=127.0.0.1",
        f"--ServerApp.port={port}",
        f"--IdentityProvider.token={token}",
        "--ServerApp.open_browser=False",
        f"--ServerApp.root_dir={ROOT}",
        "--LabApp.default_url=/lab/tree/lessons/00_start_here.ipynb",
    ]
    if as_root:
        cmd.append("--allow-root")
    return cmd


def main() -> int:
    token = secrets.token_hex(24)
    port = os.environ.get("PORT", "8888")
    cmd = build_command(token, port, as_root=hasattr(os, "geteuid") and os.geteuid() == 0)
    print("JupyterLab for the shapelab course, on this machine only (127.0.0.1).")
    print(f"Open: http://127.0.0.1:{port}/lab/tree/lessons/00_start_here.ipynb?token={token}")
    print("(If the port is taken, JupyterLab picks the next one and prints its own URL below.)")
    sys.stdout.flush()
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.call(cmd, cwd=ROOT, env=env)


if __name__ == "__main__":
    sys.exit(main())

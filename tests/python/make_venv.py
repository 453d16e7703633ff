#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Create the Python tests' virtual environment in the build folder.

usage: make_venv.py VENV REQUIREMENTS STAMP

Run by the build with the interpreter the module `cleave` is built for (so the venv's python is the
same Python, and loads the module). Creates VENV with `python -m venv`, installs the pinned
REQUIREMENTS with pip (bounded timeouts and retries) and writes STAMP when every package imports.
When venv or the package index is not available it prints a warning, writes the reason to
VENV/.unavailable (the test runner prints it when it skips) and exits 0: the build goes on and the
Python tests skip with the reason. Nothing is installed outside VENV.
"""
import os
import subprocess
import sys


def run(command):
    """Run a command quietly; return None on success, else a one-line reason."""
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    except (OSError, subprocess.TimeoutExpired) as error:
        return str(error)
    if done.returncode == 0:
        return None
    lines = [line for line in done.stdout.splitlines() if line.strip()]
    return lines[-1] if lines else f"exit status {done.returncode}"


def unavailable(venv, reason):
    """Record why the environment is missing and tell the person building."""
    os.makedirs(venv, exist_ok=True)
    with open(os.path.join(venv, ".unavailable"), "w", encoding="utf-8") as f:
        f.write(reason + "\n")
    print(f"cleave: warning: no Python test environment in {venv}: {reason} (the Python tests will skip)",
          file=sys.stderr)
    return 0


def main(argv):
    """Create or update the venv; always exit 0 so that the build goes on."""
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    venv, requirements, stamp = argv[1:]
    python = os.path.join(venv, "bin", "python")
    if not os.path.exists(python):
        reason = run([sys.executable, "-m", "venv", venv])
        if reason:
            return unavailable(venv, f"python3 -m venv failed ({reason}; Debian: python3-venv)")
    reason = run([python, "-m", "pip", "install", "--disable-pip-version-check", "--no-input", "-q",
                  "--timeout", "20", "--retries", "1", "-r", requirements])
    if reason:
        return unavailable(venv, f"pip could not install {os.path.basename(requirements)} ({reason})")
    reason = run([python, "-c", "import pytest, numpy, trimesh"])
    if reason:
        return unavailable(venv, f"the installed packages do not import ({reason})")
    marker = os.path.join(venv, ".unavailable")
    if os.path.exists(marker):
        os.remove(marker)
    with open(stamp, "w", encoding="utf-8") as f:
        f.write(f"{sys.version.split()[0]} {sys.executable}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

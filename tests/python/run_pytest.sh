#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the Python tests (pytest, in the build folder's venv) on the module in MODULE_DIR.
# usage: run_pytest.sh VENV MODULE_DIR TESTS_DIR SOURCE_DIR [SKIP_REASON]
# Exit 77 (ctest's SKIP_RETURN_CODE) with the reason when the module was not built or the venv is
# not there (no python3-venv, no package index); otherwise pytest's own status.
set -uo pipefail
venv="$1" module="$2" tests="$3" root="$4" skip="${5:-}"
if [ -n "$skip" ]; then
  echo "skipped: the Python module was not built: $skip"
  exit 77
fi
python="$venv/bin/python"
if [ ! -x "$python" ] || ! "$python" -c "import pytest, numpy, trimesh" 2>/dev/null; then
  reason="$(cat "$venv/.unavailable" 2>/dev/null || echo "it was not created")"
  echo "skipped: no Python test environment in $venv: $reason"
  exit 77
fi
if ! ls "$module"/cleave*.so >/dev/null 2>&1; then
  echo "error: the module cleave is missing from $module (build the target cleave_python)"
  exit 1
fi
export PYTHONPATH="$module" CLEAVE_SOURCE_DIR="$root" PYTHONDONTWRITEBYTECODE=1
exec "$python" -m pytest -q -p no:cacheprovider --rootdir "$tests" "$tests"

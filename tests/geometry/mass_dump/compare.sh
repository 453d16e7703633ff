#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs mass_dump with one vector kernel (sse2, avx2 or avx512) and the scalar build, and compares
# their output byte for byte. Exits 77 (ctest's skip code, SKIP_RETURN_CODE) when this CPU lacks
# the kernel: a kernel that was not compared is never reported as passed.
# compare.sh DUMP SCALAR_DUMP KERNEL, or compare.sh DUMP --one-digit-changed (must fail).
set -euo pipefail
if [ "$2" = "--one-digit-changed" ]; then  # the positive control: a copy with one digit changed
  b=$("$1" sse2 | sed '1s/volume 0x1\./volume 0x1.1/')
  kernel=sse2
else
  b=$("$2")
  kernel="$3"
fi
status=0
a=$("$1" "$kernel") || status=$?
if [ "$status" -eq 77 ]; then
  echo "this CPU has no $kernel: not compared (skipped)"
  exit 77
fi
[ "$status" -eq 0 ] || { echo "mass_dump $kernel failed ($status)"; exit 1; }
if [ "$a" != "$b" ]; then
  echo "the $kernel and the scalar mass integration differ:"
  diff <(echo "$a") <(echo "$b") || true
  exit 1
fi
echo "$kernel and scalar mass integration agree bit for bit on $(echo "$b" | wc -l) cases"

#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs mass_dump with each vector kernel this CPU has (SSE2, AVX2, AVX-512) and the scalar build,
# and compares their output byte for byte.
# compare.sh DUMP SCALAR_DUMP, or compare.sh DUMP --one-digit-changed (must fail).
set -euo pipefail
scalar_output() {
  if [ "$2" = "--one-digit-changed" ]; then  # the positive control: a copy with one digit changed
    "$1" sse2 | sed '1s/volume 0x1\./volume 0x1.1/'
  else
    "$2"
  fi
}
b=$(scalar_output "$1" "$2")
compared=()
for kernel in sse2 avx2 avx512; do
  status=0
  a=$("$1" "$kernel") || status=$?
  if [ "$status" -eq 77 ]; then
    echo "this CPU has no $kernel: not compared"
    continue
  fi
  [ "$status" -eq 0 ] || { echo "mass_dump $kernel failed ($status)"; exit 1; }
  if [ "$a" != "$b" ]; then
    echo "the $kernel and the scalar mass integration differ:"
    diff <(echo "$a") <(echo "$b") || true
    exit 1
  fi
  compared+=("$kernel")
done
echo "${compared[*]} and scalar mass integration agree bit for bit on $(echo "$b" | wc -l) cases"

#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the two builds of mass_dump and compares their output byte for byte.
# compare.sh DUMP SCALAR_DUMP, or compare.sh DUMP --one-digit-changed (must fail).
set -euo pipefail
a=$("$1")
if [ "$2" = "--one-digit-changed" ]; then  # the positive control: a copy with one digit changed
  b=$(echo "$a" | sed '1s/volume 0x1\./volume 0x1.1/')
else
  b=$("$2")
fi
if [ "$a" != "$b" ]; then
  echo "the SSE2 and the scalar mass integration differ:"
  diff <(echo "$a") <(echo "$b") || true
  exit 1
fi
echo "SSE2 and scalar mass integration agree bit for bit on $(echo "$a" | wc -l) cases"

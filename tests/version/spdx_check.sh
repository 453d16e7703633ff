#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every C++ source and header, CMake file and script of the project names its license in its first
# two lines (an SPDX identifier; LICENSE holds the text). Prints the files that do not.
# usage: spdx_check.sh SOURCE_DIR
set -euo pipefail
cd "$1"
missing=0
while IFS= read -r -d '' f; do
  if ! head -n 2 "$f" | grep -q "SPDX-License-Identifier: MIT"; then
    echo "no SPDX line: $f"
    missing=$((missing + 1))
  fi
done < <(find engine components game tools tests examples cmake python -type f \
           \( -name '*.h' -o -name '*.cpp' -o -name '*.cmake' -o -name '*.py' -o -name '*.sh' -o -name 'CMakeLists.txt' \) \
           -not -path '*/data/*' -print0)
count=$(find engine components game tools tests examples cmake python -type f \( -name '*.h' -o -name '*.cpp' \) | wc -l)
echo "checked $count C++ files and the CMake files and scripts: $missing without an SPDX line"
[ "$missing" -eq 0 ]

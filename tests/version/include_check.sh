#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every include of an engine layer or of components/ uses the path it has when installed,
# <cleave/<layer>/<file>.h> (the build tree has the same paths), never the folder in the
# repository. Prints the lines that do not.
# usage: include_check.sh SOURCE_DIR
set -euo pipefail
cd "$1"
found=$(grep -rnE '#include [<"](engine|components)/' engine components game tools tests examples python \
          --include='*.h' --include='*.cpp' || true)
if [ -n "$found" ]; then
  echo "includes by repository folder instead of <cleave/...>:"
  echo "$found"
  exit 1
fi
count=$(grep -rhE '#include [<"]cleave/' engine components game tools tests examples python --include='*.h' --include='*.cpp' | wc -l)
echo "$count includes of <cleave/...>, none by repository folder"

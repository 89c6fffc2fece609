#!/usr/bin/env bash
# Fails, naming the files, when a C++ source differs from what clang-format writes with the
# repository's .clang-format (Debian 12's clang-format 14).
set -euo pipefail
fmt=${1:-clang-format}
cd "$(dirname "$0")/.."
mapfile -t files < <(find App bench tests -name '*.cpp' -o -name '*.hpp' | sort)
"$fmt" --dry-run --Werror "${files[@]}"
echo "check_format: ${#files[@]} files formatted"

#!/usr/bin/env bash
# Every C++ file of the repository follows .clang-format: clang-format would change nothing.
# On failure it names each file and shows the change clang-format wants.
#
#   tests/format/format_test.sh SOURCE_DIR     (ctest: format.clang_format)
set -euo pipefail
cd "$1"
command -v clang-format >/dev/null || { echo "FAIL: clang-format is missing: apt-get install clang-format" >&2; exit 1; }
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h')
else
  mapfile -t files < <(find . -path './build*' -prune -o \( -name '*.cpp' -o -name '*.h' \) -print)
fi
[ ${#files[@]} -gt 100 ] || { echo "FAIL: only ${#files[@]} C++ files found in $1" >&2; exit 1; }
bad=0
for f in "${files[@]}"; do
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "not formatted: $f (clang-format -i $f)"
    diff -u "$f" <(clang-format "$f") | head -n 20 || true
    bad=$((bad + 1))
  fi
done
echo "${#files[@]} files checked, $bad not formatted"
[ "$bad" -eq 0 ] && echo "PASS"

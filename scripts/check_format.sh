#!/usr/bin/env bash
# Fails (exit 1) listing every C++ file of the project (include/, tests/, examples/, bench/, fuzz/, python/)
# that does not match .clang-format; exits 77 (skipped) without clang-format.
# With --fix, formats them in place instead.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "check_format: clang-format not found (scripts/deps.sh installs it); skipped"
  exit 77
fi
mapfile -t files < <(find include tests examples bench fuzz python \( -name '*.hpp' -o -name '*.cpp' \) | sort)
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} file(s) do not match .clang-format (run scripts/check_format.sh --fix):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "check_format: ${#files[@]} files match .clang-format"

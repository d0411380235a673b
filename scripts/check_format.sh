#!/usr/bin/env bash
# Fails, naming each file, when a C++ file differs from .clang-format (Debian's clang-format).
# Usage: scripts/check_format.sh [FILE...]   (default: every tracked *.cpp, *.hpp, *.h)
# To fix: clang-format -i FILE...
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "check_format: clang-format is not installed (scripts/deps.sh installs it)" >&2
  exit 2
fi
if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h'); fi
bad=()
for f in "${files[@]}"; do
  clang-format --style=file:"$PWD/.clang-format" --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} file(s) differ from .clang-format (fix with: clang-format -i FILE):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "check_format: ${#files[@]} file(s) formatted"

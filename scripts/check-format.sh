#!/usr/bin/env bash
# Lists the tracked C++ files that do not match .clang-format (clang-format 14, Debian's clang-format-14)
# and exits 1 if there are any; it changes nothing.
#   scripts/check-format.sh            every tracked .cpp/.hpp/.h
#   scripts/check-format.sh FILE...    only these
# To see where a file differs: clang-format-14 --dry-run FILE; to format it: clang-format-14 -i FILE.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v clang-format-14 >/dev/null; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "check-format: installing Debian's clang-format-14"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends clang-format-14
fi
# Without a .clang-format, clang-format would silently check against its LLVM default.
if [ ! -f .clang-format ]; then
  echo "check-format: no .clang-format at the project root" >&2
  exit 2
fi

if [ $# -gt 0 ]; then
  files=("$@")
else
  mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h' '*.cc' '*.cxx' '*.hh' '*.ipp' '*.inl')
fi
if [ ${#files[@]} -eq 0 ]; then
  echo "check-format: no C++ files to check"
  exit 0
fi

# One run over all files; each difference is reported as "file:line:col: error: code should be
# clang-formatted". Any other failure (a bad .clang-format, a missing file) is shown as it is.
status=0
output="$(clang-format-14 --style=file --dry-run -Werror "${files[@]}" 2>&1)" || status=$?
mapfile -t unformatted < <(sed -nE 's/^(.*):[0-9]+:[0-9]+: (error|warning): code should be clang-formatted.*/\1/p' \
                             <<<"$output" | awk '!seen[$0]++')
if [ ${#unformatted[@]} -gt 0 ]; then
  printf '%s\n' "${unformatted[@]}"
  echo "check-format: ${#unformatted[@]} of ${#files[@]} files differ from .clang-format"
  exit 1
fi
if [ "$status" -ne 0 ]; then
  echo "$output" >&2
  echo "check-format: clang-format-14 failed (status $status)" >&2
  exit 2
fi
echo "check-format: all ${#files[@]} files match .clang-format"

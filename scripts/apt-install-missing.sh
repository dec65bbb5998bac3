#!/usr/bin/env bash
# Installs those of the Debian packages given that are not installed yet (as root, or through sudo):
#   bash scripts/apt-install-missing.sh [--label NAME] PACKAGE...
# scripts/install-deps.sh calls it, and the benchmark scripts for what they need beyond that.
set -euo pipefail
label="install"
if [ "${1:-}" = "--label" ]; then
  label=$2
  shift 2
fi
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "$label: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"

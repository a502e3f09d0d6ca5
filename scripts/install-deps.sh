#!/usr/bin/env bash
# Installs the Debian packages listed in scripts/debian-packages.txt that are missing.
# Idempotent: with everything present it only checks (a dpkg query, no network).
# Extra lists can be named as arguments (e.g. scripts/debian-packages-browser.txt).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
lists=("$here/debian-packages.txt" "$@")
wanted=()
for list in "${lists[@]}"; do
  [ -f "$list" ] || { echo "install-deps: package list '$list' not found" >&2; exit 2; }
  while read -r pkg; do
    [ -z "$pkg" ] && continue
    wanted+=("$pkg")
  done < <(sed -e 's/#.*//' -e 's/[[:space:]]//g' "$list")
done
missing=()
for pkg in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$pkg")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#wanted[@]} Debian packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
if ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: apt-get not found; this project targets Debian 12. Install by hand: ${missing[*]}" >&2
  exit 1
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
    echo "install-deps: not root and no sudo; install by hand: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
if ! $sudo apt-get install -y --no-install-recommends "${missing[@]}"; then
  echo "install-deps: first attempt failed; refreshing the package index and retrying" >&2
  $sudo apt-get update || { echo "install-deps: apt-get update failed (no network to the Debian mirror?)" >&2; exit 1; }
  $sudo apt-get install -y --no-install-recommends "${missing[@]}" || {
    echo "install-deps: could not install: ${missing[*]}" >&2; exit 1; }
fi
echo "install-deps: done"

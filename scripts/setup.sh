#!/usr/bin/env bash
# Installs what the project needs from Debian's archive. Idempotent and quiet when all is present.
set -euo pipefail

packages=(cmake g++ make ccache patch dpkg-dev libopenmpi-dev openmpi-bin libgtest-dev
          python3-numpy python3-matplotlib python3-pytest liggghts yade)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "setup: installing ${missing[*]}" >&2
$sudo apt-get update -q >&2
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >&2

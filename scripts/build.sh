#!/usr/bin/env bash
# Installs what is missing, then configures and builds LAMMPS, the plugin and the tests
# in build/ (incremental after the first time).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
if [ ! -f "$root/build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$root/build" "$@"
fi
cmake --build "$root/build" -j "$(nproc)"

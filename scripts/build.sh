#!/usr/bin/env bash
# Installs what is missing, then configures and builds LAMMPS, the plugin, LIGGGHTS with the
# law's models (with Debian 12's LAMMPS only) and the tests (incremental after the first time).
#   scripts/build.sh [--lammps debian12|2025|2026] [--serial] [cmake options for the first configure]
# debian12 (default): Debian 12's LAMMPS (29 Sep 2021), in build/
# 2025:               LAMMPS 4 Feb 2025 (Debian trixie's source), in build-2025/
# 2026:               LAMMPS 4 Jul 2026 (Debian sid's source), in build-2026/
# --serial:           that LAMMPS without MPI (its STUBS library, GRANMN_MPI=OFF), in
#                     build-serial/, build-2025-serial/, build-2026-serial/
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/lammps-generation.sh" "$@"
"$root/scripts/setup.sh"
# ccache keys on paths relative to the checkout, so that another clone on this machine (CI's)
# finds the objects this one compiled
export CCACHE_BASEDIR="$root"
if [ ! -f "$build/CMakeCache.txt" ]; then
  mpi=ON
  [ "$serial" = 1 ] && mpi=OFF
  cmake -S "$root" -B "$build" -DGRANMN_LAMMPS="$generation" -DGRANMN_MPI=$mpi "${args[@]}"
fi
cmake --build "$build" -j "$(nproc)"

#!/usr/bin/env bash
# The README's test command: build (installing what is missing) and run every test.
#   scripts/test.sh [--lammps debian12|2025|2026] [--serial] [ctest options]
# debian12 (default) tests against Debian 12's LAMMPS in build/, 2025 against LAMMPS 4 Feb 2025
# in build-2025/, 2026 against LAMMPS 4 Jul 2026 in build-2026/; --serial against that LAMMPS
# built without MPI (build-serial/, ...), where the tests that run mpirun are skipped. The
# post-processing tests (python.*, no lmp) run with the default build only.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/lammps-generation.sh" "$@"
"$root/scripts/build.sh" "${generation_args[@]}"
tree=$(sed -n 's/^LAMMPS_SOURCE_DIR:PATH=//p' "$build/CMakeCache.txt")
echo "== tests against LAMMPS $(sed -n 's/^#define LAMMPS_VERSION "\(.*\)"/\1/p' "$tree/src/version.h") ($tree), in $build"
cd "$build"
skip=()
if [ "$generation" != debian12 ] || [ "$serial" = 1 ]; then
  # tests/python/ analyses synthetic data and never runs lmp: one generation's run covers it
  echo "== python.* (post-processing, no lmp) left to ./scripts/test.sh with Debian 12's LAMMPS"
  skip=(-E '^python\.')
fi
ctest --output-on-failure -j "$(nproc)" "${skip[@]}" "${args[@]}"

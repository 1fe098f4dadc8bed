#!/usr/bin/env bash
# The main job on its built-in default: build everything, then run the two-disk collision
# demonstration and print the measured restitution next to the requested one.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh"
out="$root/results/demo"
mkdir -p "$out"
cd "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$root/build/lammps/lmp" -in "$root/inputs/two_disk_collision.lmp" \
  -var plugin "$root/build/plugin/granmnplugin.so" "$@" > lmp.out
sed -n '/^pair_style gran\/mn:/,/largest stable dt/p' lmp.out
grep -E '^(requested e|tau_c)' lmp.out
echo "log: $out/log.lammps"

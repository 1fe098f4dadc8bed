#!/usr/bin/env bash
# The main job. On its built-in default it builds everything, runs the two-disk demonstration,
# then the quick study of all three scenes (inputs/sweeps/quick.toml: short spans and kn ranges,
# about ten minutes on two cores), post-processes it and prints the report's path and the
# comparison with the paper. Resumable: run it again after an interruption.
#   scripts/main.sh                 the quick study
#   scripts/main.sh --full          the paper's ranges (prints the CPU-hour estimate first)
#   scripts/main.sh --transition    the transition study (docs/transition.md; estimate first)
#   scripts/main.sh --config FILE   any sweep config
#   --lammps debian12|2025|2026     against which LAMMPS (default debian12, in build/)
#   --serial                        that LAMMPS built without MPI (build-serial/, ...)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
configs=("$root/inputs/sweeps/quick.toml")
output=""
generation=debian12
serial_option=()
while [ $# -gt 0 ]; do
  case "$1" in
    --lammps) generation=${2:-}; shift 2 || shift $# ;;
    --serial) serial_option=(--serial); shift ;;
    --full) configs=("$root"/inputs/sweeps/paper_*.toml); shift ;;
    --transition) configs=("$root/inputs/sweeps/transition.toml"); shift ;;
    --config) configs=("$(realpath -m -- "$2")"); shift 2 ;;
    --output) output=$(realpath -m -- "$2"); shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "main.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
source "$root/scripts/lammps-generation.sh" --lammps "$generation" "${serial_option[@]}"
"$root/scripts/build.sh" "${generation_args[@]}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "== two-disk collision (inputs/two_disk_collision.lmp)"
demo="$root/results/demo"
mkdir -p "$demo"
(cd "$demo" && "$build/lammps/lmp" -in "$root/inputs/two_disk_collision.lmp" \
   -var plugin "$build/plugin/granmnplugin.so" > lmp.out)
grep -E '^(requested e|tau_c)' "$demo/lmp.out"

status=0
for config in "${configs[@]}"; do
  name=$(basename "$config" .toml)
  out=${output:-$root/results/$name}
  echo "== sweep $name"
  # the Python programs run from the repository root, where their packages are
  (cd "$root" && /usr/bin/python3 -m scripts.sweep "$config" --output "$out" --build "$build") || status=1
  echo "== post-processing $name"
  case "$name" in
    transition*) (cd "$root" && /usr/bin/python3 -m postprocess transition "$out") || status=1 ;;
    *) (cd "$root" && /usr/bin/python3 -m postprocess report "$out") || status=1
       (cd "$root" && /usr/bin/python3 -m postprocess compare "$out") || status=1 ;;
  esac
done
exit $status

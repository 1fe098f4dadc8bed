# Sourced by build.sh, test.sh and main.sh: reads the leading `--lammps debian12|2025|2026` and
# `--serial` (either order, both optional) and sets `generation`, `serial` (1: LAMMPS without
# MPI, its STUBS library), the build directory `build`, `generation_args` (the same options, to
# pass on) and the remaining arguments `args`.
generation=debian12
serial=0
while [ $# -gt 0 ]; do
  case $1 in
    --lammps) generation=${2:-}; shift 2 || shift $# ;;
    --serial) serial=1; shift ;;
    *) break ;;
  esac
done
case $generation in
  debian12) build="$root/build" ;;
  2025)     build="$root/build-2025" ;;
  2026)     build="$root/build-2026" ;;
  *) echo "$(basename "$0"): --lammps takes debian12 (Debian 12's LAMMPS, 29 Sep 2021), 2025 (LAMMPS 4 Feb 2025) or 2026 (LAMMPS 4 Jul 2026), not '$generation'" >&2
     exit 2 ;;
esac
generation_args=(--lammps "$generation")
if [ "$serial" = 1 ]; then
  build="$build-serial"
  generation_args+=(--serial)
fi
args=("$@")

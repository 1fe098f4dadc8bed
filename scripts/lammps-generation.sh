# Sourced by build.sh and test.sh: reads an optional leading `--lammps debian12|2025|2026` and sets
# `generation`, the build directory `build` and the remaining arguments `args`.
generation=debian12
if [ "${1:-}" = "--lammps" ]; then
  generation=${2:-}
  shift 2 || shift $#
fi
case $generation in
  debian12) build="$root/build" ;;
  2025)     build="$root/build-2025" ;;
  2026)     build="$root/build-2026" ;;
  *) echo "$(basename "$0"): --lammps takes debian12 (Debian 12's LAMMPS, 29 Sep 2021), 2025 (LAMMPS 4 Feb 2025) or 2026 (LAMMPS 4 Jul 2026), not '$generation'" >&2
     exit 2 ;;
esac
args=("$@")

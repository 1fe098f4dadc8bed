#!/usr/bin/env bash
# Prints the path of an unpacked LAMMPS or LIGGGHTS source tree from Debian's archive, fetching
# it with `apt-get source` into a cache directory on first use.
# Usage: get-debian-source.sh CACHE_DIR [debian12|2025|2026|liggghts]
#   debian12 (default): the LAMMPS Debian 12 packages (20220106, "29 Sep 2021 - Update 2")
#   2025:               the LAMMPS of Debian's trixie suite (20250204, "4 Feb 2025")
#   2026:               the LAMMPS of Debian's sid suite (20260704, "4 Jul 2026")
#   liggghts:           Debian 12's LIGGGHTS (3.8.0+repack1)
set -euo pipefail
cache=${1:?usage: get-debian-source.sh CACHE_DIR [debian12|2025|2026|liggghts]}
generation=${2:-debian12}
package=lammps
case $generation in
  debian12) tree="$cache/lammps-src"; suite=""; version=20220106 ;;
  2025)     tree="$cache/lammps-2025-src"; suite=trixie; version=20250204 ;;
  2026)     tree="$cache/lammps-2026-src"; suite=sid; version=20260704 ;;
  liggghts) tree="$cache/liggghts-src"; suite=""; version=3.8.0; package=liggghts ;;
  *) echo "get-debian-source.sh: unknown source '$generation' (debian12, 2025, 2026 or liggghts)" >&2
     exit 2 ;;
esac
if [ -f "$tree/.unpacked" ]; then echo "$tree"; exit 0; fi

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"

# Debian's deb entries for the main archive (not the security one); their deb-src twins are
# derived from them, for this machine's suites or for the generation's suite (trixie, sid).
debian_sources=$(grep -l '^URIs:.*debian' /etc/apt/sources.list.d/*.sources 2>/dev/null || true)
deb_src_entry() {  # $1: suite to name instead of the listed ones ("" keeps them all)
  if [ -n "$debian_sources" ]; then
    awk -v suite="$1" 'BEGIN { RS = ""; ORS = "\n\n" }
      suite != "" && /URIs:[^\n]*-security/ { next }
      /^Types: deb\n|\nTypes: deb\n/ {
        sub(/Types: deb\n/, "Types: deb-src\n")
        if (suite != "") sub(/Suites:[^\n]*/, "Suites: " suite)
        print }' $debian_sources
  else
    grep -h '^deb ' /etc/apt/sources.list | awk -v suite="$1" '
      suite != "" && $2 ~ /-security/ { next }
      { $1 = "deb-src"; if (suite != "") $3 = suite; print }'
  fi
}
# The Debian revision of the wanted upstream version.
source_version() {
  apt-cache showsrc "$package" 2>/dev/null | awk -v v="$version" '/^Version: / && index($2, v) == 1 {
    print $2; exit }'
}
src_list=/etc/apt/sources.list.d/granmn-${suite:-deb}-src.sources
if [ -z "$(source_version)" ]; then
  [ -z "$debian_sources" ] && src_list=${src_list%.sources}.list
  deb_src_entry "$suite" | $sudo tee "$src_list" >/dev/null
  $sudo apt-get update -q >&2
fi

mkdir -p "$cache"
work=$(mktemp -d "$cache/fetch.XXXXXX")
trap 'rm -rf "$work"' EXIT
# Debian's patches to LAMMPS only touch packaging (potential paths, docs), so where the archive
# serves the tarballs but not the .dsc (as it does for trixie and sid) the upstream tarball is the
# same tree. For LIGGGHTS the archive serves the .dsc and the upstream tarball but not Debian's
# patches (dpkg-source fails); what the project needs of them (building with this compiler) is in
# plugin/liggghts/.
(cd "$work" && { apt-get source --download-only "$package=$(source_version)" >&2 || true; }
 if ls ./*.dsc >/dev/null 2>&1 && dpkg-source -x ./*.dsc src >&2; then
   :
 elif ls ./*.orig.tar.* >/dev/null 2>&1; then
   echo "get-debian-source.sh: no Debian source package from the archive (the error above): unpacking the upstream tarball" >&2
   # trixie's tarball holds one top directory, sid's (20260704) the tree itself
   rm -rf src && mkdir unpacked && tar -xf ./*.orig.tar.* -C unpacked
   top=(unpacked/*)
   if [ ${#top[@]} -eq 1 ] && [ -d "${top[0]}" ]; then mv "${top[0]}" src; else mv unpacked src; fi
 else
   echo "get-debian-source.sh: apt-get source fetched no $package source" >&2; exit 1
 fi)
rm -rf "$tree"
mv "$work/src" "$tree"
touch "$tree/.unpacked"
echo "$tree"

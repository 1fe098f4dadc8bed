#!/usr/bin/env bash
# Prints the path of an unpacked LAMMPS source tree matching Debian's packaged LAMMPS,
# fetching it with `apt-get source` into a cache directory on first use.
# Usage: get-lammps-source.sh CACHE_DIR
set -euo pipefail
cache=${1:?usage: get-lammps-source.sh CACHE_DIR}
tree="$cache/lammps-src"
if [ -f "$tree/.unpacked" ]; then echo "$tree"; exit 0; fi

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"

# apt-get source needs a deb-src entry: derive one from the existing deb entries.
if ! apt-cache showsrc lammps 2>/dev/null | grep -q '^Package: lammps'; then
  src_list=/etc/apt/sources.list.d/granmn-deb-src.sources
  debian_sources=$(grep -l '^URIs:.*debian' /etc/apt/sources.list.d/*.sources 2>/dev/null || true)
  if [ -n "$debian_sources" ]; then
    cat $debian_sources | sed -e 's/^Types: deb$/Types: deb-src/' | $sudo tee "$src_list" >/dev/null
  else
    grep -h '^deb ' /etc/apt/sources.list | sed -e 's/^deb /deb-src /' \
      | $sudo tee /etc/apt/sources.list.d/granmn-deb-src.list >/dev/null
  fi
  $sudo apt-get update -q >&2
fi

work=$(mktemp -d "$cache/fetch.XXXXXX")
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get source --download-only lammps >&2 && dpkg-source -x ./*.dsc src >&2)
rm -rf "$tree"
mv "$work/src" "$tree"
touch "$tree/.unpacked"
echo "$tree"

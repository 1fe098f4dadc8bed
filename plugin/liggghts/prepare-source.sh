#!/bin/sh
# Makes the LIGGGHTS source tree the project builds: a copy of Debian's pristine LIGGGHTS 3.8.0
# (scripts/get-debian-source.sh liggghts), patched to build with this compiler and to report its
# one-process errors (the two .patch files here), with the law's contact models added. Run at
# every build: the copy and the patches are made once; the models' headers and the model list
# are copied only where they differ, so that make rebuilds just what includes them.
#   prepare-source.sh PRISTINE_TREE TREE PROJECT_ROOT
set -eu
pristine=$1 tree=$2 project=$3
here=$project/plugin/liggghts
set -- "$here/liggghts-3.8.0-gcc12.patch" "$here/liggghts-3.8.0-errors.patch"    # the patches
# .prepared holds the patches' checksum: a tree made with other patches is made again (the copy
# keeps the pristine files' times, and the files that the patches' headers touch recompile
# mostly from ccache)
prepared=$(cat "$@" | cksum)
if [ "$(cat "$tree/.prepared" 2>/dev/null)" != "$prepared" ]; then
  rm -rf "$tree"
  cp -a "$pristine" "$tree"
  for patch in "$@"; do patch -s -d "$tree" -p1 < "$patch"; done
  # VTK output needs VTK's headers (libvtk9-dev: ~1 GB with what it pulls in), and this file,
  # unlike LIGGGHTS's other VTK dumps, is not guarded by LAMMPS_VTK: left out
  rm -f "$tree/src/dump_mesh_vtk.cpp" "$tree/src/dump_mesh_vtk.h"
  echo "$prepared" > "$tree/.prepared"
fi
for file in "$here"/normal_model_mn.h "$here"/tangential_model_mn.h "$here"/granmn_liggghts_law.h \
            "$here"/fix_contacts_mn.h "$here"/fix_contacts_mn.cpp "$project/plugin/mn_contact.h" \
            "$project/plugin/mn_integration.h" "$project/plugin/mn_contact_events.h" \
            "$project/plugin/mn_output_schema.h" "$project/plugin/mn_energy.h" \
            "$here/style_contact_model.whitelist"; do
  target=$tree/src/${file##*/}
  # a source file new to the tree: LIGGGHTS's CMakeLists.txt globs *.cpp when it configures
  case $file in *.cpp) [ -f "$target" ] || touch "$tree/src/CMakeLists.txt" ;; esac
  cmp -s "$file" "$target" || cp "$file" "$tree/src/"
done

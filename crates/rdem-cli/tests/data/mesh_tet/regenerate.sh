#!/usr/bin/env bash
# Regenerates the LIGGGHTS 3.8 reference figures in this directory for `region mesh/tet`:
#  - mesh_tet.log: the screen output of the liggghts-doc tutorial mesh_tet, unmodified;
#  - counts.txt: for each case of cases.txt, the number of lattice points LIGGGHTS'
#    create_atoms puts in the region (case.in with the case's fields filled in).
# The .vtk meshes here are hand-made: a unit cube split into five and into six
# tetrahedra, one tetrahedron (corners at binary fractions: with decimal corners such as
# 0.8 0.1 0 a lattice point on a face may fall on the other side by round-off; one
# such point differed, 405 vs 406), an octahedron of eight. Nothing of LIGGGHTS is copied.
#
#   usage: bash regenerate.sh
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
TUT="${TUT:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
LIGGGHTS="${LIGGGHTS:-liggghts}"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-ref-mesh_tet-XXXXXX")"
cp -r "$TUT/mesh_tet/." "$tmp/"
mkdir -p "$tmp/post"
(cd "$tmp" && "$LIGGGHTS" -in in.mesh_tet -log none > "$HERE/mesh_tet.log" 2>&1)
rm -rf "$tmp"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-ref-mesh_tet-XXXXXX")"
cp "$HERE"/*.vtk "$tmp/"
{
  echo "# name created-atoms (LIGGGHTS 3.8, case.in with the fields of cases.txt)"
  grep -v '^#' "$HERE/cases.txt" | while read -r name file s mx my mz rx ry rz d; do
    sed -e "s|@FILE@|$file|" -e "s|@SCALE@|$s|" -e "s|@MOVE@|$mx $my $mz|" \
        -e "s|@ROTATE@|$rx $ry $rz|" -e "s|@D@|$d|" "$HERE/case.in" > "$tmp/in.case"
    n=$(cd "$tmp" && "$LIGGGHTS" -in in.case -log none | sed -n 's/^Created \([0-9]*\) atoms$/\1/p')
    echo "$name $n"
  done
} > "$HERE/counts.txt"
rm -rf "$tmp"

#!/usr/bin/env bash
# Regenerates the LIGGGHTS 3.8 reference files in this directory for `dump mesh/vtk ...
# stresscomponents`: runs in.plate (hand-written, with the hand-made plate.stl) and keeps
# the mesh dumps it writes at steps 50 and 100 as liggghts_plate_50.vtk and
# liggghts_plate_100.vtk. Nothing of LIGGGHTS is copied.
#
#   usage: bash regenerate.sh
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
LIGGGHTS="${LIGGGHTS:-liggghts}"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-ref-stresscomponents-XXXXXX")"
cp "$HERE/in.plate" "$HERE/plate.stl" "$tmp/"
(cd "$tmp" && "$LIGGGHTS" -in in.plate -log none > /dev/null)
for s in 50 100; do
  cp "$tmp/post/plate_$s.vtk" "$HERE/liggghts_plate_$s.vtk"
done
rm -rf "$tmp"

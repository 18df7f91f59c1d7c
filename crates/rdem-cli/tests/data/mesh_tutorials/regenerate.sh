#!/usr/bin/env bash
# Regenerates the LIGGGHTS 3.8 reference logs in this directory for the five mesh
# tutorial cases. The tutorial scripts are run unmodified from the liggghts-doc
# package, followed by `include stats.in` (atoms, mean and largest height, mean
# radius at the end). Nothing of LIGGGHTS is copied here.
#
#   usage: bash regenerate.sh [case...]     (default: all five, one after another)
#
# Writes <case>.log (the full screen output) next to this script.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
TUT="${TUT:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
LIGGGHTS="${LIGGGHTS:-liggghts}"
declare -A FILE=([meshGran]=in.meshGran [conveyor]=in.conveyor [insert_stream]=in.insert_stream
                 [chute_wear]=in.chute_wear [movingMeshGran]=in.movingMeshGran)
CASES=("$@")
[ ${#CASES[@]} -gt 0 ] || CASES=(meshGran conveyor insert_stream chute_wear movingMeshGran)
for c in "${CASES[@]}"; do
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/rdem-ref-$c-XXXXXX")"
  cp -r "$TUT/$c/." "$tmp/"
  mkdir -p "$tmp/post" "$tmp/restart"
  cp "$HERE/stats.in" "$tmp/stats.in"
  printf 'include %s\ninclude stats.in\n' "${FILE[$c]}" > "$tmp/wrapper.in"
  (cd "$tmp" && "$LIGGGHTS" -in wrapper.in -log none > "$HERE/$c.log" 2>&1) || {
    echo "LIGGGHTS failed for $c (see $HERE/$c.log)" >&2; exit 1; }
  rm -rf "$tmp"
done

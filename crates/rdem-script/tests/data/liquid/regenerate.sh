#!/bin/sh
# Regenerates the LIGGGHTS 3.8 reference outputs that tests/liquid_bridges.rs reads:
# item40.liggghts.txt (the fix print file of item40.in, renamed) and item41.liggghts.txt
# (the screen output of item41.in). Needs `liggghts` on PATH. Run from this directory.
set -e
cd "$(dirname "$0")"
liggghts -in item40.in -log none > /dev/null
mv item40.txt item40.liggghts.txt
liggghts -in item41.in -log none > item41.liggghts.txt

#!/bin/sh
# Regenerates the LIGGGHTS reference dumps of crates/rdem/tests/liggghts_golden.rs:
# runs every in.<scenario> of this folder with the installed LIGGGHTS 3.8
# (Debian package liggghts 3.8.0+repack1), each writing <scenario>.dump here.
# Usage: sh regenerate.sh   (from any directory)
set -eu
cd "$(dirname "$0")"
liggghts -log none -h | head -n 1
for script in in.*; do
    name=${script#in.}
    rm -f "$name.dump"
    liggghts -in "$script" -log none -echo none -screen none
    echo "$name.dump: $(grep -c '^ITEM: TIMESTEP' "$name.dump") dumped steps"
done

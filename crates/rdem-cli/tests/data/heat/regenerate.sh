#!/bin/sh
# Regenerates LIGGGHTS 3.8's reference output for crates/rdem-cli/tests/heat.rs: the
# thermo table (*.liggghts.thermo) and the dump (*.liggghts.dump) of each script here.
# Needs the Debian package (apt-get install liggghts, 3.8.0+repack1). Run from this folder.
set -e
liggghts -log none -h | head -n 1
tmp=$(mktemp -d)
for s in heat_bed heat_frozen; do
    cp in.$s floor.stl "$tmp/"
    (cd "$tmp" && liggghts -in in.$s -log none > out.txt 2>&1)
    grep -v '^\s*$' "$tmp/out.txt" | sed -n '/Step *Atoms *heattran/,/Loop/p' | grep -v Loop > $s.liggghts.thermo
    cp "$tmp/dump.$s" $s.liggghts.dump
done
rm -rf "$tmp"

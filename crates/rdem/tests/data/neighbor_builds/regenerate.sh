#!/bin/sh
# Regenerates reference.txt: LIGGGHTS 3.8 neighbor-list build counts for the cases of
# tests/neighbor_lists.rs::world_rebuilds_as_the_liggghts_reference.
# Needs the Debian package (apt-get install liggghts). Run from this directory.
set -e
tmp=$(mktemp -d)
: > reference.txt
for cfg in "0 1 1.1 yes" "2 1 1.1 yes" "0 3 1.1 yes" "7 1 1.1 yes" "0 1 5.5 yes" \
           "6 2 5.5 yes" "0 4 1.6 yes" "0 1 1.1 no" "0 4 1.1 no" "4 2 1.1 no"; do
    set -- $cfg
    sed -e "s/DELAY/$1/" -e "s/EVERY/$2/" -e "s/VX/$3/" -e "s/check yes/check $4/" \
        in.builds.template > "$tmp/in.case"
    out=$(liggghts -in "$tmp/in.case" -log none 2>&1 | grep -E 'Neighbor list builds|Dangerous builds' | tr '\n' ' ')
    echo "delay $1 every $2 vx $3 check $4: $out" >> reference.txt
done
rm -rf "$tmp"
cat reference.txt

#!/bin/sh
# Remakes the LIGGGHTS 3.8 figures of tests/multicontact.rs: each in.NAME run by the
# Debian liggghts (scripts/test.sh installs it) writes NAME.liggghts.dump.
set -e
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
cd "$tmp"
for s in static static_tworuns reach chain wall_candidate spinning_pair spinning_wall falling; do
    liggghts -in "$here/in.$s" -log none > "$s.log"
    mv dump.atoms "$here/$s.liggghts.dump"
done
rm -rf "$tmp"

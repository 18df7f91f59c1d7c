#!/bin/sh
# Regenerates the LIGGGHTS 3.8 outputs (NAME.liggghts.txt) that the tests hard-code
# (tests/temperature.rs, tests/settings.rs). Needs `liggghts` on PATH.
set -e
cd "$(dirname "$0")"
for f in temp_extra.in temp_dynamic.in; do
  liggghts -in "$f" -log none > "${f%.in}.liggghts.txt" 2>&1 || true
done
# thermo_log.in writes its files in the current directory: run it in a scratch one.
d=$(mktemp -d)
sed 's|include ../parity/|include '"$PWD"'/../parity/|' thermo_log.in > "$d/in.x"
(cd "$d" && liggghts -in in.x -log none > /dev/null 2>&1 || true)
cp "$d/thermo_log_a.txt" thermo_log_a.liggghts.txt
cp "$d/thermo_log_b.txt" thermo_log_b.liggghts.txt
rm -r "$d"

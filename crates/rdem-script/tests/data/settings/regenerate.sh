#!/bin/sh
# Regenerates the LIGGGHTS 3.8 outputs (NAME.liggghts.txt) that the tests hard-code
# (tests/temperature.rs). Needs `liggghts` on PATH.
set -e
cd "$(dirname "$0")"
for f in temp_extra.in temp_dynamic.in; do
  liggghts -in "$f" -log none > "${f%.in}.liggghts.txt" 2>&1 || true
done

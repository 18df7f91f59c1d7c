#!/bin/sh
# Writes cgs.in and micro.in from si.in (make.py) and records LIGGGHTS 3.8's output of
# each (NAME.liggghts.txt) that tests/units.rs hard-codes. Needs `liggghts` on PATH.
set -e
cd "$(dirname "$0")"
python3 make.py
for u in si cgs micro; do
  liggghts -in "$u.in" -log none > "$u.liggghts.txt" 2>&1 || true
done

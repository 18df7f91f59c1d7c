#!/bin/sh
# Regenerates the LIGGGHTS 3.8 reference dumps of tests/read_dump.rs: case.in with its
# READ line replaced by each read_dump command below and OUT by caseN.liggghts.dump.
# Needs `liggghts` on PATH. Run from this directory.
set -e
cd "$(dirname "$0")"
run() {
  sed -e "s|^READ\$|$2|" -e "s|OUT|$1.liggghts.dump|" case.in > "$1.in"
  liggghts -in "$1.in" -log none > "$1.liggghts.txt" 2>&1 || true
  rm -f "$1.in"
}
run case1 "read_dump h.dump 7 x y z radius vx vy vz box no add yes"
run case2 "read_dump h.dump 7 x y z radius vx vy vz purge yes replace no add yes"
run case3 "read_dump h.dump 7 x y radius vx trim yes"
run case4 "read_dump h.dump 7 x y z vx radius box no replace no add yes"
run case5 "read_dump h.dump 7 x y z radius vx vy vz purge yes replace no add yes box no"

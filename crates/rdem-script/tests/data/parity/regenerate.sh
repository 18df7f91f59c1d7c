#!/bin/sh
# Regenerates the LIGGGHTS 3.8 reference outputs (itemN.liggghts.txt, plus dumps) that
# tests/liggghts_parity.rs hard-codes. Needs `liggghts` on PATH. Run from this directory.
set -e
cd "$(dirname "$0")"
for f in item*.in; do
  b=${f%.in}
  liggghts -in "$f" -log none > "$b.liggghts.txt" 2>&1 || true
done
for d in item4.dump item8.dump item13.dump item19.dump; do
  [ -f "$d" ] && mv "$d" "${d%.dump}.liggghts.dump"
done
[ -f item10.dump ] && mv item10.dump item10.liggghts.dump
[ -f item12.dump ] && mv item12.dump item12.liggghts.dump
for h in item*-*.histo; do
  case "$h" in *.liggghts.histo) ;; *) mv "$h" "${h%.histo}.liggghts.histo" ;; esac
done

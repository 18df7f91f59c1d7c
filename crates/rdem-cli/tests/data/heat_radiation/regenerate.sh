#!/bin/sh
# Regenerates LIGGGHTS-PFM's reference output for crates/rdem-cli/tests/heat_radiation.rs:
# the thermo table of each script here (*.pfm.thermo). Needs the fork built: its src/ of
# ParticulateFlow/LIGGGHTS-PFM d075b97, MAKE/Makefile.openmpi copied to
# MAKE/Makefile.rdemref with FFT_INC = -DFFT_NONE and FFT_LIB empty, `make rdemref`
# (about 10 minutes on 2 cores); pass the binary as $1. Run from this folder.
set -e
lmp=${1:?usage: regenerate.sh path/to/lmp_binary}
tmp=$(mktemp -d)
for s in lone bed; do
    cp in.$s "$tmp/"
    (cd "$tmp" && stdbuf -o0 "$lmp" -in in.$s -log none > out.txt 2>&1)
    {
        echo "# LIGGGHTS-PFM d075b97 (built here), in.$s"
        # The last thermo table.
        awk '/^ *Step /{n=0; t=1; next} /^Loop/{t=0} t{rows[n++]=$0} END{for(i=0;i<n;i++) print rows[i]}' "$tmp/out.txt"
    } > $s.pfm.thermo
done
rm -rf "$tmp"

#!/usr/bin/env bash
# a: run Tutorials_public/cohesion/in.cohesion with ONE change: 'thermo 1000' is
# replaced by a variable-driven thermo output that prints every step for steps
# 3000k-2 .. 3000k+2 (plus the steps LIGGGHTS always prints). The modified
# script is generated from the installed tutorial at run time (not stored here).
# usage: bash a4_cohesion_thermo.sh > a4_cohesion_thermo.out   (run in a dir with post/)
set -euo pipefail
TUT="${TUT:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
sed 's/^thermo\t\t\t1000$/variable\ttf equal "step + 1 + (step%3000>=2 \&\& step%3000<2998)*(2998 - step%3000 - 1)"\nthermo\t\t\tv_tf/' \
  "$TUT/cohesion/in.cohesion" > a4_cohesion_thermo.gen.in
grep -qP '^thermo\t\t\tv_tf$' a4_cohesion_thermo.gen.in
mkdir -p post
liggghts -in a4_cohesion_thermo.gen.in -log none -nocite

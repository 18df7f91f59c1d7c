#!/usr/bin/env bash
# c: run a small variant of Tutorials_public/packing/in.packing to check whether
# fix adapt (atom diameter, atom-style variable) also rescales the mass.
# Changes, applied to the installed tutorial at run time (not stored here):
# growts 50000 -> 4000, relaxts 20000 -> 100, the dump is removed, thermo every
# 500 steps and extra columns: max/min radius, max/min mass, max/min of
# mass/(4/3 pi r^3).
# usage: bash c_adapt_mass.sh > c_adapt_mass.out
set -euo pipefail
TUT="${TUT:-/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public}"
cat > c_adapt_mass.block <<'BLK'
compute		pc_r all property/atom radius
compute		pc_m all property/atom mass
variable	pc_rho atom c_pc_m/(4.0/3.0*PI*c_pc_r^3)
compute		pc_rmax all reduce max c_pc_r
compute		pc_rmin all reduce min c_pc_r
compute		pc_mmax all reduce max c_pc_m
compute		pc_mmin all reduce min c_pc_m
compute		pc_dmax all reduce max v_pc_rho
compute		pc_dmin all reduce min v_pc_rho
thermo_style	custom step atoms ke c_1 vol c_pc_rmax c_pc_rmin c_pc_mmax c_pc_mmin c_pc_dmax c_pc_dmin
BLK
sed -e 's/^variable\tgrowts equal 50000$/variable\tgrowts equal 4000/' \
    -e 's/^variable\trelaxts equal 20000$/variable\trelaxts equal 100/' \
    -e '/^dump/d' \
    -e 's/^thermo\t\t1000$/thermo\t\t500/' \
    -e '/^thermo_style\tcustom step atoms ke c_1 vol$/{r c_adapt_mass.block' -e 'd}' \
    "$TUT/packing/in.packing" > c_adapt_mass.gen.in
# make sure every edit took effect
grep -q 'growts equal 4000' c_adapt_mass.gen.in && grep -q 'relaxts equal 100' c_adapt_mass.gen.in &&
  ! grep -q '^dump' c_adapt_mass.gen.in && grep -q 'c_pc_dmin' c_adapt_mass.gen.in &&
  grep -qP '^thermo\t\t500$' c_adapt_mass.gen.in
liggghts -in c_adapt_mass.gen.in -log none -nocite

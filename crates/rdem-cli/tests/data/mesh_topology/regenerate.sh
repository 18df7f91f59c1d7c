#!/bin/sh
# Writes the LIGGGHTS 3.8 reference files of this directory (run from it): the
# topology arrays of two tutorial meshes on 1 process, and the owners on 2.
set -e
TUT=/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public
tmp=$(mktemp -d)
cp in.topology "$tmp/"
cd "$tmp"
liggghts -in in.topology -var tut "$TUT" -log none > /dev/null
cp hopper_1.vtk "$OLDPWD/hopper.liggghts.vtk"
cp chute_1.vtk "$OLDPWD/chute.liggghts.vtk"
mpirun --allow-run-as-root -np 2 liggghts -in in.topology -var tut "$TUT" -log none > /dev/null
cp hopper_1.vtk "$OLDPWD/hopper.2procs.liggghts.vtk"
cd "$OLDPWD"
rm -r "$tmp"

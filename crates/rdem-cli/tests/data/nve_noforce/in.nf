# Reference: LIGGGHTS 3.8 (Debian liggghts), -var tn x: its dump is ref.txt
# nve/noforce: two spheres moved at their set velocity (forces ignored) push a free one
units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region box block 0 0.2 0 0.2 0 0.2 units box
create_box 1 box
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
create_atoms 1 single 0.05 0.1 0.1 units box
create_atoms 1 single 0.05 0.1 0.12 units box
create_atoms 1 single 0.075 0.1 0.112 units box
set atom * diameter 0.02 density 2500
set atom 1 vx 0.5 vz 0.1
set atom 2 vx 0.5 vz 0.1 omegay 3.0
group mover id 1 2
group free id 3
fix gr all gravity 9.81 vector 0 0 -1
fix push mover nve/noforce
fix integr free nve/sphere
dump d all custom 2000 d_${tn}.txt id x y z vx vy vz omegax omegay omegaz fx fz
dump_modify d sort id format "%d %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g"
run 10000

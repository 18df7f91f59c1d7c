# Reference: LIGGGHTS 3.8 (Debian liggghts), -var tn x: its dump is ref.txt
# fix store/state: attributes at the definition, computes and variables from the first run
units si
atom_style granular
atom_modify map array
boundary p f f
newton off
communicate single vel yes
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.3
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
create_atoms 1 single 0.095 0.05 0.05
create_atoms 1 single 0.02 0.05 0.052
create_atoms 1 single 0.05 0.03 0.06
create_atoms 1 single 0.05 0.07 0.04
create_atoms 1 single 0.03 0.03 0.03
set atom * diameter 0.01 density 2500
set atom 1 vx 1.0 vy 0.2 vz -0.1
set atom 2 vx -0.5 vy 0.0 vz 0.3
set atom 3 vx 0.1 vy 0.9 vz 0.0
set atom 4 vx 0.0 vy -0.4 vz 0.2
set atom 5 vx 0.3 vy 0.3 vz 0.3
group some id 1 2 4
fix gr all gravity 9.81 vector 1.0 0.5 -1.0
fix integr all nve/sphere
compute ke all ke/atom
variable sp atom sqrt(vx*vx+vy*vy)
fix s1 all store/state 0 xu yu zu vx com yes
fix s2 some store/state 300 c_ke v_sp x radius
variable dx atom x-f_s1[1]
dump d all custom 200 d_${tn}.txt id f_s1[1] f_s1[2] f_s1[3] f_s1[4] f_s2[1] f_s2[2] f_s2[3] f_s2[4] v_dx
dump_modify d sort id format "%d %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g"
run 1000

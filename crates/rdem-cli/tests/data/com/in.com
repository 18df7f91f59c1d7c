# compute com of spheres of unequal mass crossing a periodic face (tests/com.rs)
atom_style granular
atom_modify map array
boundary p f f
newton off
communicate single vel yes
units si
region reg block -0.05 0.05 -0.05 0.05 -0.05 0.05 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
create_atoms 1 single 0.04 0 0
create_atoms 1 single -0.03 0.02 0.01
create_atoms 1 single 0.0 -0.02 -0.01
set atom 1 diameter 0.01 density 2500
set atom 2 diameter 0.014 density 1500
set atom 3 diameter 0.008 density 4000
velocity all set 3.0 0.1 0.0
set atom 2 vx -2.0
group two id 1 2
fix integr all nve/sphere
compute cm all com
compute c2 two com
thermo_style custom step c_cm[1] c_cm[2] c_cm[3] c_c2[1] c_c2[2]
thermo_modify format float %20.15g
thermo 1000
run 10000

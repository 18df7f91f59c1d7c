# Reference: LIGGGHTS 3.8 (Debian liggghts): thermo at steps 0, 500, ..., 2000
# set_property: inserted particles get a per-particle property value
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.1 0 0.2 units box
create_box 2 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.9 0.9 0.9 0.9
fix m4 all property/global coefficientFriction peratomtypepair 2 0.05 0.05 0.05 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zwall all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix cp all property/atom customProperty scalar yes no no 0.5
create_atoms 1 single 0.05 0.05 0.01 units box
set atom 1 diameter 0.004 density 2500
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix pts2 all particletemplate/sphere 15485867 atom_type 2 density constant 2500 radius constant 0.002
fix pdd2 all particledistribution/discrete 49979687 1 pts2 1.0
region low block 0.01 0.09 0.01 0.09 0.02 0.08 units box
region high block 0.01 0.09 0.01 0.09 0.12 0.18 units box
fix ins1 all insert/pack seed 49979693 distributiontemplate pdd1 insert_every once overlapcheck yes set_property customProperty 1.0 particles_in_region 40 region low
fix ins2 all insert/rate/region seed 67867967 distributiontemplate pdd2 nparticles 30 particlerate 30000 insert_every 100 overlapcheck yes set_property customProperty 2.0 region high
fix integr all nve/sphere
compute c1 all reduce sum f_cp
variable n1 atom type==1&&f_cp==1.0
variable n2 atom type==2&&f_cp==2.0
variable n0 atom f_cp==0.5
compute r all reduce sum v_n0 v_n1 v_n2
thermo_style custom step atoms c_c1 c_r[1] c_r[2] c_r[3]
thermo 500
run 2000

# A stream of small spheres through a square face, 500 per packet every 500 steps, and
# a tracer/stream marking n_tracer of them from mark_step on, every `ev` steps (or once).
atom_style granular
atom_modify map array
boundary m m m
newton off
communicate single vel yes
units si
region reg block -1 1 -1 1 -0.05 2.85 units box
create_box 1 reg
neighbor 0.01 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix pts1 all particletemplate/sphere 999667 atom_type 1 density constant 2500 radius constant 0.002
fix pts2 all particletemplate/sphere 999671 atom_type 1 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete 999683 2 pts1 0.3 pts2 0.7
fix face all mesh/surface file face.stl type 1
group nve_group region reg
fix ins nve_group insert/stream seed 999721 distributiontemplate pdd1 nparticles 2000 &
    vel constant 0. -0.5 -2. particlerate 100000 &
    overlapcheck yes insertion_face face extrude_length 0.01
fix integr nve_group nve/sphere
fix tracer all property/atom/tracer/stream mark_step ${ms} insert_stream ins n_tracer ${nt} every ${ev}
variable s equal step
variable nmarked equal f_tracer
fix pr all print 500 "marked $s ${nmarked}"
thermo_style custom step atoms
thermo 1000
dump dmp all custom 100 post/dump*.t id x y z f_tracer f_release_fix_insert_stream[5]
dump_modify dmp sort id
run 3000

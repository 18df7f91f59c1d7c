# A sphere resting on a 500 K STL floor (fix mesh/surface temperature 500) conducts
# heat; the wall/gran line also says temperature ${T}, which LIGGGHTS 3.8 ignores.
atom_style granular
newton off
neigh_modify delay 0
atom_modify map array sort 0 0
communicate single vel yes
units si
region r block -1 1 -1 1 -1 1 units box
create_box 1 r
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
fix m5 all property/global thermalConductivity peratomtype 1.
fix m6 all property/global thermalCapacity peratomtype 1.
pair_style gran model hertz tangential history
pair_coeff * *
fix floor all mesh/surface file floor.stl type 1 temperature 500
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor temperature ${T}
fix ht all heat/gran initial_temperature 300
create_atoms 1 single 0 0 0.0049
set atom 1 diameter 0.01 density 1000
fix integr all nve/sphere
timestep 1e-5
compute t all reduce sum f_Temp
thermo_style custom step c_t
thermo 500
run 2000

# Reference: LIGGGHTS 3.8 (Debian liggghts) with -var tn a|b|c|d -var kw ... -var kw2 ... (see tests/ave_spatial.rs); its files are in this folder
units si
atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
region reg block 0 0.1 0 0.05 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix gravi all gravity 9.81 vector 0.3 0.0 -1.0
fix zwall all wall/gran model hertz tangential history primitive type 1 zplane 0.0
lattice sc 0.01
region fill block 0.002 0.098 0.002 0.048 0.002 0.06 units box
create_atoms 1 region fill
set group all diameter 0.008 density 2500
displace_atoms all random 0.0009 0.0009 0.0009 86028121 units box
variable vx0 atom 0.5*sin(200*x)+0.3*cos(300*y)
variable vz0 atom 0.8*cos(150*z+100*x)
set group all vx v_vx0 vz v_vz0
fix integr all nve/sphere
compute ke all ke/atom
variable sp atom sqrt(vx*vx+vz*vz)
group half id <= 100
fix prof all ave/spatial 10 5 100 z lower 0.01 vx vz density/mass density/number c_ke v_sp ${kw} file prof_${tn}.txt
fix prof2 half ave/spatial 20 3 100 x center 0.03 z 0.02 0.025 vx fz ${kw2} units box file prof2_${tn}.txt
region mid block 0.02 0.08 0 0.05 0 0.1 units box
fix prof3 all ave/spatial 100 1 100 y upper 0.01 vx density/number title1 "" title3 "# bins along y" file prof3_${tn}.txt
fix prof4 all ave/spatial 50 2 100 z 0.5 0.25 x lower 0.5 y 0.2 0.5 vz density/mass units reduced region mid ave running overwrite file prof4_${tn}.txt
fix prof5 all ave/spatial 25 4 100 x lower 0.02 vy write_ts no norm sample file prof5_${tn}.txt
thermo 100
dump d all custom 500 d_${tn}.txt id x y z vx vy vz
dump_modify d sort id format "%d %.12g %.12g %.12g %.12g %.12g %.12g"
run 500

//! `fix massflow/mesh ... file F [writeTime]` and `append F`: one line per particle that
//! crosses the face, byte for byte as LIGGGHTS 3.8 writes it.
//!
//! The reference lines were written by `liggghts -in in.mf -log none` (LIGGGHTS-PUBLIC
//! 3.8.0, Debian) on the script [`script`] makes, with the face `FACE` in `face.stl`:
//! two spheres falling under gravity through a square face at z = 0.05.

use crate::common;
use common::MATERIALS;

const FACE: &str = "solid face
facet normal 0 0 1
outer loop
vertex -0.05 -0.05 0.05
vertex 0.05 -0.05 0.05
vertex 0.05 0.05 0.05
endloop
endfacet
facet normal 0 0 1
outer loop
vertex -0.05 -0.05 0.05
vertex 0.05 0.05 0.05
vertex -0.05 0.05 0.05
endloop
endfacet
endsolid face
";

fn script(dir: &std::path::Path) -> String {
    let d = dir.display();
    format!(
        "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.05 0.05 -0.05 0.05 0. 0.15 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
{MATERIALS}pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix face all mesh/surface file {d}/face.stl type 1
create_atoms 1 single 0.01 0.0 0.06 units box
create_atoms 1 single -0.02 0.01 0.07 units box
set atom 1 diameter 0.004 density 2500
set atom 2 diameter 0.006 density 2500
velocity all set 0 0 -1
fix integr all nve/sphere
fix mf all massflow/mesh mesh face vec_side 0 0 -1 file {d}/out.txt writeTime
fix mf2 all massflow/mesh mesh face vec_side 0 0 -1 file {d}/out2.txt
fix mf3 all massflow/mesh mesh face vec_side 0 0 -1 append {d}/out3.txt writeTime
thermo 500
thermo_style custom step atoms f_mf[1] f_mf[2]
run 3000
"
    )
}

/// What LIGGGHTS 3.8 wrote with `writeTime`.
const WITH_TIME: &str = "# ID time  diameter x y z u v w  (ex ey ez, color)
1  0.00956  0.004 0.01    0 0.04999    0    0 -1.094
2  0.01835  0.006 -0.02 0.01 0.05    0    0 -1.18
";

/// What LIGGGHTS 3.8 wrote without.
const WITHOUT_TIME: &str = "# ID diameter x y z u v w  (ex ey ez, color)
1 0.004 0.01    0 0.04999    0    0 -1.094
2 0.006 -0.02 0.01 0.05    0    0 -1.18
";

#[test]
fn lines_per_crossing_particle_as_liggghts_writes_them() {
    let dir = std::env::temp_dir().join(format!("rdem-massflow-file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("face.stl"), FACE).unwrap();
    // `append` keeps what was there (checked on LIGGGHTS 3.8 too).
    std::fs::write(dir.join("out3.txt"), "previous\n").unwrap();
    let mut i = common::interpreter();
    i.run_source("in.mf", &script(&dir))
        .unwrap_or_else(|e| panic!("{e:?}"));
    let read = |n: &str| std::fs::read_to_string(dir.join(n)).unwrap();
    assert_eq!(read("out.txt"), WITH_TIME);
    assert_eq!(read("out2.txt"), WITHOUT_TIME);
    assert_eq!(read("out3.txt"), format!("previous\n{WITH_TIME}"));
    let _ = std::fs::remove_dir_all(&dir);
}

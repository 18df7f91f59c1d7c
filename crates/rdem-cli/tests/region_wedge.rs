//! `region wedge` (LIGGGHTS-INL) against LIGGGHTS-INL itself: the fork (idaholab/
//! LIGGGHTS-INL d69df36, built here) filled wedges on a simple cubic lattice with
//! `create_atoms 1 region w`; rdem creates the same number of atoms for each, about each
//! axis, off-centre, with negative start angles and at 180° (where lattice points lie on
//! both faces' planes, so the boundary rule counts too). The fork refuses wedges wider
//! than 180°, and so does rdem.

use crate::common;

/// The script: a wedge of radius 0.7 from -0.5 to 0.6 along its axis, filled on a
/// lattice of spacing 0.05; prints the atom count.
fn script(axis: &str, c1: f64, c2: f64, start: f64, span: f64) -> String {
    format!(
        "units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
lattice sc 0.05
region w wedge axis {axis} center {c1} {c2} radius 0.7 bounds -0.5 0.6 angle0 {start} angle {span} units box
create_atoms 1 region w
variable n equal count(all)
print \"COUNT ${{n}}\"
"
    )
}

/// The atom counts of the fork, per (axis, c1, c2, angle0, angle).
const FORK: [(&str, f64, f64, f64, f64, u64); 6] = [
    ("z", 0.0, 0.0, -22.5, 45.0, 1672),
    ("y", 0.1, -0.2, 30.0, 90.0, 3388),
    ("x", -0.1, 0.05, 100.0, 180.0, 6710),
    ("z", 0.02, 0.03, -170.0, 135.0, 5082),
    ("x", 0.013, -0.027, 47.0, 61.0, 2310),
    ("y", 0.0, 0.0, 0.0, 180.0, 6710),
];

#[test]
fn wedges_hold_the_atoms_the_fork_creates() {
    for (axis, c1, c2, start, span, want) in FORK {
        let out = common::run_script(&script(axis, c1, c2, start, span), None);
        let n: u64 = out
            .lines()
            .find_map(|l| l.strip_prefix("COUNT "))
            .and_then(|w| w.trim().parse().ok())
            .unwrap_or_else(|| panic!("no count in\n{out}"));
        assert_eq!(n, want, "wedge {axis} {c1} {c2} {start} {span}");
    }
}

#[test]
fn wedges_wider_than_180_degrees_are_refused() {
    let out = common::run_script_raw(&script("z", 0.0, 0.0, 0.0, 200.0), None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("region wedge") && err.contains("(0, 180]") && err.contains("in.test:10"),
        "{err}"
    );
}

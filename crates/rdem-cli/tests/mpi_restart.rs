//! Restart files across rank counts (feature `mpi`): a bed written on 1 rank continues
//! on 2, and one written on 2 continues on 1. Particles are redistributed by position
//! with their contact histories; the count and the mass are conserved exactly, and the
//! bed's statistics stay within 1 % of the unbroken serial run (the summation order of
//! the forces differs between rank counts, so the runs are not bit-identical).
#![cfg(feature = "mpi")]

use crate::common;

use common::{have_mpirun, run_kept, thermo_rows};

const HEAD: &str = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
";

const BOX: &str = "region box block -0.05 0.05 -0.05 0.05 0 0.12 units box\ncreate_box 1 box\n";

const DEFS: &str = concat!("neighbor 0.002 bin
neigh_modify delay 0
", common::materials!(), "\
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.1
pair_style gran model hertz tangential history rolling_friction cdt
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history rolling_friction cdt primitive type 1 zplane 0
fix cyl all wall/gran model hertz tangential history rolling_friction cdt primitive type 1 zcylinder 0.045 0 0
fix integr all nve/sphere
variable m equal mass(all)
variable zc equal xcm(all,z)
variable ztop equal bound(all,zmax)
thermo_style custom step atoms v_m v_zc v_ztop
thermo 1000
thermo_modify format float %.17g
");

const INIT: &str = "region ins cylinder z 0 0 0.04 0.005 0.11 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 250 region ins
";

fn ranks(n: usize) -> Option<usize> {
    (n > 1).then_some(n)
}

fn ok(tag: &str, script: &str, n: usize) -> (std::path::PathBuf, String) {
    let (dir, out) = run_kept(tag, script, &[], ranks(n));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{tag} on {n} rank(s): {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, text)
}

/// Writes after 8000 steps on `p` ranks, continues 6000 steps on `q`; returns the last
/// thermo row (step, atoms, mass, mean z, top) and the restart file's first lines.
fn split(p: usize, q: usize) -> Vec<f64> {
    let first = format!("{HEAD}{BOX}{DEFS}{INIT}run 8000\nwrite_restart state.restart\n");
    let (d1, _) = ok(&format!("mpirst-{p}{q}-a"), &first, p);
    let second = format!(
        "{HEAD}read_restart ../{}/state.restart\n{DEFS}run 6000\n",
        d1.file_name().unwrap().to_string_lossy()
    );
    let (d2, out) = ok(&format!("mpirst-{p}{q}-b"), &second, q);
    for d in [d1, d2] {
        let _ = std::fs::remove_dir_all(d);
    }
    assert!(
        out.contains(&format!(
            "written by rdem {} on {p} rank(s)",
            env!("CARGO_PKG_VERSION")
        )),
        "{out}"
    );
    thermo_rows(&out).pop().expect("a thermo row")
}

#[test]
fn a_bed_continues_on_another_number_of_ranks() {
    if !have_mpirun() {
        return;
    }
    let whole = format!("{HEAD}{BOX}{DEFS}{INIT}run 8000\nrun 6000\n");
    let (d0, out) = ok("mpirst-whole", &whole, 1);
    let _ = std::fs::remove_dir_all(d0);
    let reference = thermo_rows(&out).pop().unwrap();
    assert_eq!(reference[1], 250.0);
    for (p, q) in [(1, 2), (2, 1)] {
        let got = split(p, q);
        let what = format!("{p} -> {q} ranks");
        // Count and mass: exact (the same particles, each with its own mass).
        assert_eq!((got[0], got[1]), (14000.0, 250.0), "{what}");
        assert_eq!(got[2], reference[2], "{what}: mass");
        // The settled bed: mean height and top within 1 %.
        for (k, name) in [(3, "mean z"), (4, "top")] {
            let rel = (got[k] - reference[k]).abs() / reference[k];
            assert!(
                rel < 0.01,
                "{what}: {name} {} vs {} ({rel:e})",
                got[k],
                reference[k]
            );
        }
    }
}

//! `rolling_friction cdt` and `cdtnonlinear2` (LIGGGHTS-INL) under several normal laws,
//! against LIGGGHTS 3.8 and LIGGGHTS-INL (d69df36, built here: `make mpi_no_vtk`).
//!
//! `tests/data/rolling/in.roll`, written for these tests: a spinning sphere dropped on a
//! plane wall that bounces and rolls on, and two spinning spheres meeting obliquely. The
//! cdt torque is μ_r k_n δ R*, k_n the normal law's stiffness: for hooke/hysteresis and
//! the hysteretic nonlinear laws k_n δ is not the elastic force, and the torque follows
//! the programs only with k_n δ. cdtnonlinear2 takes the whole normal force (damping
//! included) instead. rdem agrees with every row to 3e-14 of each column's scale at
//! worst (measured); the test allows 1e-10.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/rolling")
}

/// The thermo rows of a reference file (comment lines skipped).
fn reference(name: &str) -> Vec<Vec<f64>> {
    common::reference_rows(&data().join(name))
}

fn run(roll: &str, model: &str) -> Vec<Vec<f64>> {
    let script = common::index_vars(&[("roll", roll), ("model", model)])
        + &std::fs::read_to_string(data().join("in.roll")).unwrap();
    common::thermo_rows(&common::run_script(&script, None))
}

/// Each law with each rolling model follows the program that has it.
#[test]
fn rolling_torques_follow_liggghts_and_the_fork() {
    for (roll, model, file) in [
        ("cdt", "hertz", "liggghts_cdt_hertz.txt"),
        ("cdt", "hooke/hysteresis", "liggghts_cdt_hooke.txt"),
        ("cdt", "hysteretic/nonlinear2", "inl_cdt_hysteretic.txt"),
        ("cdtnonlinear2", "hertz", "inl_cdtnonlinear2_hertz.txt"),
        (
            "cdtnonlinear2",
            "hysteretic/nonlinear2",
            "inl_cdtnonlinear2_hysteretic.txt",
        ),
    ] {
        let want = reference(file);
        common::assert_columns(
            &run(roll, model),
            &want,
            1,
            1e-10,
            &format!("{roll} {model}"),
        );
    }
}

/// The two models differ where the normal force is not k_n δ: the dropped sphere's spin
/// (column 4) after the bounce differs by more than a percent.
#[test]
fn cdtnonlinear2_is_not_cdt() {
    let a = reference("inl_cdt_hysteretic.txt");
    let b = reference("inl_cdtnonlinear2_hysteretic.txt");
    let (wa, wb) = (a.last().unwrap()[4], b.last().unwrap()[4]);
    assert!((wa - wb).abs() > 0.01 * wa.abs(), "{wa} {wb}");
}

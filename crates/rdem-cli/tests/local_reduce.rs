//! `compute reduce` over the columns of a local compute (every contact of `compute
//! pair/gran/local`, the group aside), as LAMMPS and LIGGGHTS 3.8 reduce them: the
//! largest and summed overlap, the mean normal and x forces, the smallest z force of 112
//! spheres piling in a box. The reference is LIGGGHTS 3.8's thermo of
//! `tests/data/local_reduce/in.lr` (%20.15g), with its −1e20 and 1e20 for the extremes of
//! no contact; rdem follows it to 1e-9 of each column's scale (measured 2e-12: the pile's
//! rounding drifts).

use crate::common;

use std::path::Path;

#[test]
fn local_columns_reduce_as_liggghts() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/local_reduce");
    let script = std::fs::read_to_string(data.join("in.lr")).unwrap();
    let got = common::thermo_rows(&common::run_script(&script, None));
    let want = common::reference_rows(&data.join("ref.txt"));
    common::assert_columns(&got, &want, 1, 1e-9, "local reduce");
    assert_eq!((got[0][2], got[0][6]), (-1e20, 1e20));
    assert!(got[8][2] > 6e-6, "{:?}", got[8]);
}

#[test]
fn a_local_array_needs_its_column() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/local_reduce");
    let script = std::fs::read_to_string(data.join("in.lr"))
        .unwrap()
        .replace("reduce max c_pl[7]", "reduce max c_pl");
    let out = common::run_script_raw(&script, None);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("gives 7 local column(s)") && err.contains("in.test:"),
        "{err}"
    );
}

/// `compute reduce/region`: the highest particle and the summed velocities of the
/// particles at or below z = 0.008 m (the region's surface included: the lattice's layer
/// at 0.008 counts at step 0, as in LIGGGHTS 3.8), to LIGGGHTS 3.8's thermo within 1e-9
/// of each column's scale.
#[test]
fn reduce_region_as_liggghts() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/local_reduce");
    let script = std::fs::read_to_string(data.join("in.rr")).unwrap();
    let got = common::thermo_rows(&common::run_script(&script, None));
    let want = common::reference_rows(&data.join("ref_region.txt"));
    common::assert_columns(&got, &want, 1, 1e-9, "reduce/region");
    assert_eq!(got[0][2], 0.008);
    // A local input has no position: refused.
    let bad = script.replace("reduce/region low max z", "reduce/region low max c_pl[7]");
    let out = common::run_script_raw(&bad, None);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("per-atom inputs") && err.contains("in.test:"),
        "{err}"
    );
}

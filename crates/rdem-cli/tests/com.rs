//! `compute com` (LIGGGHTS 3.8): the centre of mass of a group from unwrapped positions.
//! Three spheres of unequal mass cross a periodic face many times
//! (`tests/data/com/in.com`, 0.1 s at up to 3 m/s in a 0.1 m box); the centres of mass of
//! all of them and of a group of two equal LIGGGHTS 3.8's (stored beside the script)
//! within 1e-12 of each column's scale.

use crate::common;

#[test]
fn the_centre_of_mass_is_liggghts_centre_of_mass() {
    let data = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/com"));
    let (dir, out) = common::run_data_script("com", data, "in.com", &[]);
    let _ = std::fs::remove_dir_all(&dir);
    let start = out.rfind("Step").expect("a thermo table");
    let got = common::thermo_rows(&out[start..]);
    let want = common::reference_rows(&data.join("com.liggghts.thermo"));
    assert_eq!(got.len(), 11);
    common::assert_columns(&got, &want, 1, 1e-12, "compute com against LIGGGHTS 3.8");
    // Unwrapped: the centre of mass left the box (x within ±0.05) long ago.
    assert!(got[10][1] > 0.05, "{:?}", got[10]);
}

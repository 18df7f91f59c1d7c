//! `set_property NAME value` of the insertion fixes (LIGGGHTS 3.8): each particle a fix
//! inserts gets that value of a scalar `fix property/atom`; others keep theirs. In
//! `tests/data/set_property/in.sp` a created sphere keeps the default 0.5, 40 spheres of
//! `insert/pack` get 1 and 30 of `insert/rate/region` get 2. LIGGGHTS 3.8 printed, from
//! step 500 on: 71 atoms, Σ = 100.5, and the counts 1, 40, 30 of each (type, value).

use crate::common;

use std::path::Path;

fn script() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/set_property/in.sp"),
    )
    .unwrap()
}

#[test]
fn inserted_particles_get_the_property_value() {
    let (dir, out) = common::run_kept_ok("set_property", &script(), &[], None);
    let _ = std::fs::remove_dir_all(&dir);
    let rows = common::thermo_rows(&out[out.find("Step").unwrap()..]);
    assert_eq!(rows[0], [0.0, 1.0, 0.5, 1.0, 0.0, 0.0], "{out}");
    for r in &rows[1..] {
        assert_eq!(
            r[1..],
            [71.0, 100.5, 1.0, 40.0, 30.0],
            "step {}: {out}",
            r[0]
        );
    }
}

#[test]
fn a_missing_property_stops_the_run() {
    let s = script().replace("set_property customProperty 2.0", "set_property Temp 2.0");
    let out = common::run_script_raw(&s, None);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no scalar per-particle property 'Temp'"),
        "{err}"
    );
    assert!(err.contains("fix ins2"), "{err}");
}

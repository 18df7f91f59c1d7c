//! One atom's per-atom value in a formula, as LAMMPS and LIGGGHTS 3.8 read it:
//! `c_ID[I]` of a per-atom vector compute is atom I's value, `c_ID[I][J]` column J of a
//! per-atom array at atom I, and the same for fixes (`f_ID[I]`, `f_ID[I][J]`). The
//! reference is LIGGGHTS 3.8's thermo of `tests/data/peratom_index/in.idx` (four
//! spheres: contact counts, velocities, a property/atom value, a stored position),
//! printed with %20.15g.

use crate::common;

use std::path::Path;

#[test]
fn one_atoms_value_as_liggghts() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/peratom_index");
    let script = std::fs::read_to_string(data.join("in.idx")).unwrap();
    let (dir, out) = common::run_kept_ok("peratom_index", &script, &[], None);
    let _ = std::fs::remove_dir_all(&dir);
    // The second table is the run's (the first is `run 0`'s).
    let got: Vec<Vec<f64>> = common::thermo_rows(&out)
        .into_iter()
        .filter(|r| r.len() == 8)
        .collect();
    let want = common::reference_rows(&data.join("ref.txt"));
    common::assert_columns(&got, &want, 1, 1e-13, "per-atom index");
    // Contacts at step 100 (atom 2 touches 1 and 3), none once they part.
    assert_eq!((got[1][2], got[2][2]), (2.0, 0.0));
}

/// The script of `in.idx` up to its run, with `extra` lines before `run 10`.
fn with_lines(extra: &str) -> String {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/peratom_index");
    let script = std::fs::read_to_string(data.join("in.idx")).unwrap();
    let head: String = script
        .lines()
        .take_while(|l| !l.starts_with("variable"))
        .map(|l| format!("{l}\n"))
        .collect();
    format!("{head}{extra}\nthermo_style custom step v_bad\nrun 10\n")
}

#[test]
fn wrong_atom_indices_are_errors() {
    for (line, says) in [
        ("variable bad equal c_ca[9]", "c_ca[9]: no atom with ID 9"),
        ("variable bad equal c_pa[2]", "per-atom"),
        ("variable bad equal c_ca[1][1]", "has no per-atom array"),
        ("variable bad equal f_tag[2][1]", "has no per-atom array"),
        ("variable bad equal f_st[4][3]", "f_st"),
    ] {
        let out = common::run_script_raw(&with_lines(line), None);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{line}");
        assert!(err.contains(says), "{line}: {err}");
    }
}

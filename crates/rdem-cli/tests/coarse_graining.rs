//! LIGGGHTS-PFM's `coarsegraining` against the fork itself (ParticulateFlow/LIGGGHTS-PFM
//! d075b977, built here as `lmp_rdemref`), on scripts written for these tests
//! (`tests/data/coarse_graining`):
//!
//! - `in.cg`: `coarsegraining 2 model_check warn`, an oblique spinning pair and a sphere
//!   dropped on a plane under `hooke/stiffness`, with relative (`a`) and absolute (`b`)
//!   damping; the script's diameters, skin, kn and damping are the described particles';
//! - `in.cgt`: `coarsegraining 3`, a sphere and a two-sphere `multiplespheres` template
//!   inserted by `insert/pack`;
//! - `in.cgm`: `coarsegraining 2`, two spheres through a `massflow/mesh` face with a file
//!   (and, without the factor, against LIGGGHTS 3.8: `l38_flow.txt`).

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/coarse_graining")
}

fn setting(tag: &'static str) -> [(&'static str, &'static str); 6] {
    match tag {
        "a" => [
            ("tag", "a"),
            ("abs", "off"),
            ("gn", "gamman"),
            ("gnv", "0.4"),
            ("gt", "gammat"),
            ("gtv", "0.2"),
        ],
        _ => [
            ("tag", "b"),
            ("abs", "on"),
            ("gn", "gamman_abs"),
            ("gnv", "0.004"),
            ("gt", "gammat_abs"),
            ("gtv", "0.002"),
        ],
    }
}

/// rdem's dump rows (step first) of `in.cg` in `setting`, with `edit` applied to the
/// script, and the screen output.
fn run_cg(vars: &[(&str, &str)], edit: impl Fn(String) -> String) -> (Vec<Vec<f64>>, String) {
    let script =
        common::index_vars(vars) + &edit(std::fs::read_to_string(data().join("in.cg")).unwrap());
    let (dir, out) = common::run_kept_ok("coarse_graining", &script, &[], None);
    let tag = vars.iter().find(|(k, _)| *k == "tag").unwrap().1;
    let text = std::fs::read_to_string(dir.join(format!("d_{tag}.txt"))).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (common::dump_rows_with_step(&text), out)
}

/// The number after "Neighbor list builds = " in a run's output.
fn builds(out: &str) -> u64 {
    out.lines()
        .find_map(|l| l.strip_prefix("Neighbor list builds = "))
        .unwrap_or_else(|| panic!("no builds line in {out}"))
        .trim()
        .parse()
        .unwrap()
}

/// The pair and the wall contact follow the fork bit for bit (measured; the test allows
/// 1e-11 of each column's scale); so does the number of neighbor list builds, which the
/// skin (given 5e-5 m, scaled to 1e-4 m) sets: LIGGGHTS-PFM printed 11 (`a`) and 10
/// (`b`). With the skin as given (and the diameters scaled), rdem makes 22 in `a`.
#[test]
fn stiffness_model_follows_the_fork() {
    for (tag, fork_builds) in [("a", 11), ("b", 10)] {
        let (got, out) = run_cg(&setting(tag), |s| s);
        let want = common::reference_rows(&data().join(format!("pfm_{tag}.txt")));
        common::assert_columns(&got, &want, 2, 1e-11, tag);
        assert_eq!(builds(&out), fork_builds, "{tag}");
        // model_check warn: the fork's inconsistent model and create_atoms are warnings.
        assert!(
            out.contains("model hooke/stiffness does not give results consistent")
                && out.contains("create_atoms does not give results consistent"),
            "{out}"
        );
    }
    let (_, out) = run_cg(&setting("a"), |s| {
        s.replace("coarsegraining 2 model_check warn", "")
            .replace("diameter 0.0015", "diameter 0.003")
    });
    assert_eq!(builds(&out), 22);
}

/// A run at cg = 2 is the same run, bit for bit, as one whose script gives the particles
/// at their simulated size: diameters and skin doubled, kn doubled, gamman halved
/// (`a`) or gamman_abs four times (`b`).
#[test]
fn factor_equals_a_script_at_the_simulated_size() {
    for (tag, gn) in [("a", ("0.4", "0.2")), ("b", ("0.004", "0.016"))] {
        let vars = setting(tag);
        let (cg, cg_out) = run_cg(&vars, |s| s);
        let scaled: Vec<(&str, &str)> = vars
            .iter()
            .map(|&(k, v)| if k == "gnv" { (k, gn.1) } else { (k, v) })
            .collect();
        assert_eq!(vars.iter().find(|(k, _)| *k == "gnv").unwrap().1, gn.0);
        let (plain, out) = run_cg(&scaled, |s| {
            s.replace("coarsegraining 2 model_check warn", "")
                .replace("neighbor 0.00005 bin", "neighbor 0.0001 bin")
                .replace("kn peratomtypepair 1 2000", "kn peratomtypepair 1 4000")
                .replace("diameter 0.0015", "diameter 0.003")
        });
        assert_eq!(cg, plain, "{tag}");
        assert_eq!(builds(&out), builds(&cg_out));
        assert!(!out.contains("coarse graining"), "{out}");
    }
    // Without the factor the script's own sizes are used: the radius column is 0.00075.
    let (plain, _) = run_cg(&setting("a"), |s| {
        s.replace("coarsegraining 2 model_check warn", "")
    });
    assert!(plain.iter().all(|r| r[14] == 0.00075), "{:?}", plain[0]);
}

/// Templates: radii cg times the template's (sphere and multiplespheres), the spheres of
/// a multiplespheres template cg times as far apart; masses follow. LIGGGHTS-PFM's dump
/// of the same script holds the same radii and masses (its positions are other draws).
#[test]
fn templates_are_coarse_grained() {
    let (dir, _) = common::run_data_script("coarse_graining", &data(), "in.cgt", &[]);
    let text = std::fs::read_to_string(dir.join("d_t.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let frames = common::dump_frames(&text);
    let rows = &frames.last().unwrap().1;
    let want = common::reference_rows(&data().join("pfm_t.txt"));
    // Columns: id x y z radius mass. The fork drew other templates (3 clumps and 3
    // spheres for 6 insertions): compare the sizes each made.
    let sizes = |rows: &[Vec<f64>]| {
        let mut v: Vec<(f64, f64)> = rows.iter().map(|r| (r[4], r[5])).collect();
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v.dedup();
        v
    };
    let (got, fork) = (sizes(rows), sizes(&want));
    assert_eq!(got.len(), 2, "{got:?}");
    assert_eq!(fork.len(), 2, "{fork:?}");
    for (g, f) in got.iter().zip(&fork) {
        // The fork's dump has 6 significant digits.
        assert!(
            (g.0 - f.0).abs() < 1e-12 && (g.1 - f.1).abs() < 1e-5 * f.1,
            "{got:?} {fork:?}"
        );
    }
    let pi = std::f64::consts::PI;
    for &(r, m) in &got {
        assert!(r == 0.003 || r == 0.0024, "{got:?}");
        // The dump has 6 significant digits.
        assert!(
            (m / (2500.0 * 4.0 / 3.0 * pi * r.powi(3)) - 1.0).abs() < 1e-5,
            "{m}"
        );
    }
    // Each 0.0024 sphere is 3 × 0.0015 from its template's 0.003 sphere.
    for s in rows.iter().filter(|r| r[4] == 0.0024) {
        let d = rows
            .iter()
            .filter(|r| r[4] == 0.003)
            .map(|r| ((r[1] - s[1]).powi(2) + (r[2] - s[2]).powi(2) + (r[3] - s[3]).powi(2)).sqrt())
            .fold(f64::INFINITY, f64::min);
        assert!((d - 0.0045).abs() < 1e-6, "{d}");
    }
}

/// `massflow/mesh`'s file gives the diameters the script gave (2r/cg), as LIGGGHTS-PFM
/// writes them, on 1, 2 and 4 ranks; the counted mass is the simulated particles'. The
/// same script without the factor and with the diameters doubled writes LIGGGHTS 3.8's
/// file byte for byte: the velocities are the half-step ones of LIGGGHTS' post-integrate
/// stage (rdem wrote the end-of-step ones before, 5e-4 m/s off here).
#[test]
fn massflow_file_gives_the_described_diameter() {
    let (dir, out) = common::run_data_script("coarse_graining", &data(), "in.cgm", &["face.stl"]);
    let text = std::fs::read_to_string(dir.join("flow.txt")).unwrap();
    let want = std::fs::read_to_string(data().join("pfm_flow.txt")).unwrap();
    assert_eq!(text, want);
    let rows = common::thermo_rows(&out);
    let pi = std::f64::consts::PI;
    let m = 2500.0 * 4.0 / 3.0 * pi * (0.004f64.powi(3) + 0.006f64.powi(3));
    let last = rows.last().unwrap();
    assert!((last[2] - m).abs() < 1e-12 * m && last[3] == 2.0, "{out}");
    if common::have_mpirun() {
        for ranks in [2, 4] {
            std::fs::remove_file(dir.join("flow.txt")).unwrap();
            let run = common::rdem_in(&dir, "in.cgm", Some(ranks))
                .output()
                .unwrap();
            common::success("massflow on ranks", &run);
            let text = std::fs::read_to_string(dir.join("flow.txt")).unwrap();
            assert_eq!(text, want, "{ranks} ranks");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let script = std::fs::read_to_string(data().join("in.cgm"))
        .unwrap()
        .replace("coarsegraining 2 model_check warn", "")
        .replace("diameter 0.004", "diameter 0.008")
        .replace("diameter 0.006", "diameter 0.012");
    let stl = std::fs::read_to_string(data().join("face.stl")).unwrap();
    let (dir, _) = common::run_kept_ok("coarse_graining", &script, &[("face.stl", &stl)], None);
    let text = std::fs::read_to_string(dir.join("flow.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let want = std::fs::read_to_string(data().join("l38_flow.txt")).unwrap();
    assert_eq!(text, want);
}

/// The script of `in.cg` (setting a) with `edit` applied; must fail with `needle` in its
/// message, the caret under `word`.
fn fails(edit: impl Fn(String) -> String, needle: &str, word: &str) {
    let script = common::index_vars(&setting("a"))
        + &edit(std::fs::read_to_string(data().join("in.cg")).unwrap());
    let out = common::run_script_raw(&script, None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{needle}: ran");
    // The message as one line (the report wraps long ones).
    let flat = err
        .lines()
        .map(|l| l.trim().trim_start_matches('│').trim())
        .collect::<Vec<_>>()
        .join(" ");
    assert!(flat.contains(needle), "{needle}: {err}");
    // The source line shown (`N │ text`) holds the word, and the caret line under it
    // starts where the word does.
    let lines: Vec<&str> = err.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.contains(" │ ") && l.contains(word))
        .unwrap_or_else(|| panic!("{word}: no source line in {err}"));
    let col = lines[at][..lines[at].find(word).unwrap()].chars().count();
    let caret: Vec<char> = lines[at + 1].chars().collect();
    assert!(
        matches!(caret.get(col), Some('─' | '┬' | '^')),
        "{word}: {err}"
    );
}

/// `model_check error` (the default) stops on the fork's inconsistent models and
/// commands; a radius distribution is an error whatever model_check says; the command
/// must come first; bad words are located errors.
#[test]
fn errors_are_located() {
    let strict = |s: String| s.replace("coarsegraining 2 model_check warn", "coarsegraining 2");
    fails(
        strict,
        "model hooke/stiffness does not give results consistent with coarse graining",
        "hooke/stiffness",
    );
    fails(
        |s| {
            strict(s)
                .replace("hooke/stiffness", "hertz")
                .replace("absolute_damping ${abs}", "")
        },
        "create_atoms does not give results consistent",
        "create_atoms",
    );
    fails(
        |s| {
            strict(s)
                .replace("hooke/stiffness", "hertz")
                .replace("absolute_damping ${abs}", "rolling_friction epsd2")
        },
        "rolling_friction epsd2 does not give",
        "epsd2",
    );
    fails(
        |s| {
            strict(s)
                .replace("hooke/stiffness", "hertz")
                .replace("absolute_damping ${abs}", "")
                .replace("timestep 1e-6", "timestep 1e-6\nfix af all addforce 0 0 0")
        },
        "fix addforce does not give results consistent",
        "addforce",
    );
    fails(
        |s| {
            s.replace(
                "fix integr all nve/sphere",
                "fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius uniform 0.001 0.002",
            )
        },
        "a radius distribution cannot be coarse grained",
        "uniform",
    );
    fails(
        |s| s.replace("coarsegraining 2 model_check warn\n", "") + "coarsegraining 2\n",
        "coarsegraining after the simulation box is defined",
        "coarsegraining",
    );
    fails(
        |s| {
            s.replace("coarsegraining 2 model_check warn\n", "")
                .replace(
                    "units si\n",
                    "units si\nneighbor 0.001 bin\ncoarsegraining 2\n",
                )
        },
        "coarsegraining after neighbor gave the skin",
        "coarsegraining",
    );
    fails(
        |s| s.replace("coarsegraining 2 model_check warn", "coarsegraining 0.5"),
        "must be >= 1",
        "0.5",
    );
    fails(
        |s| s.replace("model_check warn", "model_check maybe"),
        "maybe",
        "maybe",
    );
}

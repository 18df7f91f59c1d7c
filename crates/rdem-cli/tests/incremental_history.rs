//! `tangential incremental_history` (LIGGGHTS-PFM) against LIGGGHTS-PFM itself, and the
//! real script that uses it (`../shared/wild/12`, the elastic normal impact of two glass
//! spheres) against Hertz.
//!
//! `tests/data/incremental_history/in.oblique` has three oblique impacts in one box: two
//! spinning spheres hitting off-centre and a spinning sphere hitting the plane z = −0.06
//! (`fix wall/gran ... primitive`). LIGGGHTS-PFM (ParticulateFlow/LIGGGHTS-PFM d075b977,
//! built here with its OpenMPI makefile) ran it for four settings (sliding μ = 0.35 and
//! sticking μ = 10, restitution 0.5 and 1, tangential damping on and off) and once with
//! the run split in two (`run 500`, `run 1000`: the set-up of the second run evaluates the
//! stored force), printing positions, velocities and spins every 25 steps at 15 digits.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/incremental_history")
}

/// The thermo rows of a reference file (comment lines skipped).
fn reference(name: &str) -> Vec<Vec<f64>> {
    common::reference_rows(&data().join(name))
}

/// in.oblique with `MU`, `E`, `TD` set, `tangential` for the model and `edit` applied.
fn script(mu: &str, e: &str, td: &str, edit: impl Fn(String) -> String) -> String {
    let text = std::fs::read_to_string(data().join("in.oblique")).unwrap();
    edit(format!(
        "variable MU index {mu}\nvariable E index {e}\nvariable TD index {td}\n{text}"
    ))
}

/// Every value of `got` within `rel` of the largest magnitude of its column in `want`
/// (columns of velocity or spin pass through zero).
fn assert_rows(got: &[Vec<f64>], want: &[Vec<f64>], rel: f64, what: &str) {
    common::assert_columns(got, want, 1, rel, what);
}

/// The largest difference of `a` from `b`, relative to each column's largest magnitude.
fn max_gap(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let mut worst = 0.0f64;
    for k in 1..b[0].len() {
        let scale = b.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
        for (x, y) in a.iter().zip(b) {
            worst = worst.max((x[k] - y[k]).abs() / scale);
        }
    }
    worst
}

/// The four settings follow LIGGGHTS-PFM to 1e-11 of each column's scale (measured:
/// 4e-13 and below). Each setting also differs from rdem's `tangential history` by far
/// more, so the comparison sees the model: the force kept as a force (not a spring), its
/// k_t/k_t,old scaling while the normal force falls, and the dashpot kept in it.
#[test]
fn oblique_impacts_follow_liggghts_pfm() {
    for (mu, e, td) in [
        ("0.35", "0.5", "on"),
        ("10", "0.5", "on"),
        ("0.35", "0.5", "off"),
        ("10", "1.0", "on"),
    ] {
        let what = format!("mu {mu} e {e} damping {td}");
        let want = reference(&format!("pfm_mu{mu}_e{e}_damping_{td}.txt"));
        let got = common::thermo_rows(&common::run_script(&script(mu, e, td, |s| s), None));
        assert_rows(&got, &want, 1e-11, &what);
        let history = common::thermo_rows(&common::run_script(
            &script(mu, e, td, |s| s.replace("incremental_history", "history")),
            None,
        ));
        let gap = max_gap(&history, &want);
        assert!(gap > 1e-6, "{what}: history is as close ({gap:e})");
    }
}

/// A run split in two: the set-up of the second run uses the stored tangential force as
/// it is (not capped at μ·F_n of the new velocities), as LIGGGHTS-PFM does; the pair is
/// sliding at step 500, so capping it would shift the spins by ~1e-4.
#[test]
fn a_split_run_follows_liggghts_pfm() {
    let s = script("0.35", "0.5", "on", |s| {
        s.replace("run 1500", "run 500\nrun 1000")
    });
    let got = common::thermo_rows(&common::run_script(&s, None));
    let want = reference("pfm_split_mu0.35_e0.5_damping_on.txt");
    assert_rows(&got, &want, 1e-11, "split run");
}

/// The plane as an STL mesh (`fix mesh/surface`: four triangles meeting at (0.02, 0.01);
/// the sphere lands inside one of them, away from its edges) gives the wall sphere the
/// same path as the primitive plane in LIGGGHTS-PFM.
#[test]
fn a_mesh_floor_gives_the_primitive_planes_impact() {
    let s = script("0.35", "0.5", "on", |s| {
        s.replace(
            "primitive type 1 zplane -0.06",
            "mesh n_meshes 1 meshes floor",
        )
        .replace(
            "fix wall all",
            "fix floor all mesh/surface file floor.stl type 1 move 0.02 0.01 -0.06\nfix wall all",
        )
    });
    let got = common::thermo_rows(&common::run_with_files(
        &s,
        &[("floor.stl", &common::floor_stl())],
        None,
    ));
    let want = reference("pfm_mu0.35_e0.5_damping_on.txt");
    // Columns 13..=17: x, z, vx, vz, ωy of the sphere on the floor.
    let pick = |rows: &[Vec<f64>]| -> Vec<Vec<f64>> {
        rows.iter()
            .map(|r| {
                std::iter::once(r[0])
                    .chain(r[13..].iter().copied())
                    .collect()
            })
            .collect()
    };
    assert_rows(&pick(&got), &pick(&want), 1e-11, "mesh floor");
}

/// wild/12 (LIGGGHTS-PFM's own test of the elastic normal impact, Chung & Ooi test 1: two
/// glass spheres, R = 10 mm, E = 48 GPa, ν = 0.2, ρ = 2800, 10 m/s each, hertz with
/// `tangential incremental_history limitForce on`), unmodified: its local dumps of the
/// normal force and overlap every 10 steps are LIGGGHTS-PFM's bytes
/// (`data/incremental_history/pfm_wild12_post.txt`); they give the largest overlap
/// 0.274087 mm, within 1e-4 of Hertz's (15 m* v²/(16 E* √R*))^(2/5) = 0.274113 mm; the
/// largest force within 1e-3 of (4/3) E* √R* δ_max^(3/2) = 10.697 kN; and a contact of
/// 400 steps (dt = 0.1 µs) against Hertz's duration 2.868 (m*²/(R* E*² v))^(1/5) = 40.34 µs.
#[test]
fn wild_case_12_matches_hertz_and_the_fork() {
    let script = "in.elastic_normal_impact_2_spheres";
    let Some(case) = common::wild_case("12_pfm_chung_normal_impact", script) else {
        return;
    };
    let (dir, _) = common::run_data_script("wild12", &case, script, &[]);
    let mut names: Vec<String> = std::fs::read_dir(dir.join("post"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut all = String::new();
    for name in &names {
        all += &format!("== {name}\n");
        all += &std::fs::read_to_string(dir.join("post").join(name)).unwrap();
    }
    // LIGGGHTS-PFM's 61 files of the same run, concatenated: the same bytes.
    let fork = std::fs::read_to_string(data().join("pfm_wild12_post.txt")).unwrap();
    assert!(all == fork, "the local dumps differ from LIGGGHTS-PFM's");
    let (mut dmax, mut fmax, mut touching) = (0.0f64, 0.0f64, 0);
    for name in &names {
        let text = std::fs::read_to_string(dir.join("post").join(name)).unwrap();
        let mut lines = text.lines();
        while let Some(l) = lines.next() {
            if l.starts_with("ITEM: ENTRIES") {
                for row in lines.by_ref() {
                    let v: Vec<f64> = row.split_whitespace().map(|x| x.parse().unwrap()).collect();
                    let f = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                    fmax = fmax.max(f);
                    dmax = dmax.max(v[3]);
                    touching += 1;
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let (r, rho, e, nu, v) = (0.01f64, 2800.0, 4.8e10, 0.2, 20.0);
    let m_star = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * rho / 2.0;
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let r_star = r / 2.0;
    let hertz = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    let f_hertz = 4.0 / 3.0 * e_star * r_star.sqrt() * hertz.powf(1.5);
    let tc = 2.868265 * (m_star * m_star / (r_star * e_star * e_star * v)).powf(0.2);
    assert_eq!(
        format!("{dmax:.6e}"),
        "2.740870e-4",
        "the fork's largest overlap"
    );
    assert!(
        (dmax - hertz).abs() < 1e-4 * hertz,
        "{dmax} against Hertz {hertz}"
    );
    assert!(
        (fmax - f_hertz).abs() < 1e-3 * f_hertz,
        "{fmax} against {f_hertz}"
    );
    // Dumps every 10 steps: 40 of them see the contact; Hertz's tc is 403 steps.
    assert_eq!(touching, 40, "dumps that see the contact");
    assert!((tc / 1e-7 - 10.0 * touching as f64).abs() < 10.0, "tc {tc}");
}

//! `fix ave/spatial` (LIGGGHTS 3.8): 216 spheres with scattered velocities fall in a box
//! periodic along x and y; five fixes bin them (1d, 2d and 3d bins; origins lower,
//! center, upper, a coordinate; units box and reduced; norm all and sample; ave one,
//! running, window; region; titles, `write_ts no`, `overwrite`) and write LIGGGHTS'
//! files. The references in `tests/data/ave_spatial/` are LIGGGHTS 3.8's files (the
//! Debian package) for four sets of keywords: rdem writes the same bytes, but for values
//! that are sums of ±1e-17 rounding (`vy`, printed as ~1e-21 or 0) and for the
//! densities under `units reduced`, which LIGGGHTS 3.8 prints as 0 and rdem computes
//! (count × mass / bin volume). On 2 MPI ranks the numbers agree to the 6 digits
//! printed.

use crate::common;

use std::path::Path;

fn data() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ave_spatial")
}

/// (case, keywords of prof, keywords of prof2).
const CASES: [(&str, &str, &str); 4] = [
    ("a", "ave one", "ave one"),
    ("b", "norm sample", "norm sample ave running"),
    ("c", "ave window 2", "norm all ave window 3"),
    ("d", "norm sample ave window 2", "ave running"),
];

/// Runs a case; the files it wrote, by name.
fn run(case: (&str, &str, &str), ranks: Option<usize>) -> Vec<(String, String)> {
    let (tn, kw, kw2) = case;
    let vars = [
        ("tn", tn.to_string()),
        ("kw", format!("\"{kw}\"")),
        ("kw2", format!("\"{kw2}\"")),
    ];
    let vars: Vec<(&str, &str)> = vars.iter().map(|(k, v)| (*k, v.as_str())).collect();
    let script =
        common::index_vars(&vars) + &std::fs::read_to_string(data().join("in.as")).unwrap();
    let (dir, _) = common::run_kept_ok("ave_spatial", &script, &[], ranks);
    let files = ["prof", "prof2", "prof3", "prof4", "prof5"]
        .iter()
        .map(|f| {
            let name = format!("{f}_{tn}.txt");
            let text = std::fs::read_to_string(dir.join(&name)).unwrap();
            (name, text)
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    files
}

/// The same lines, numbers within `rel` (relative) or 1e-15 (absolute).
fn assert_close_text(got: &str, want: &str, rel: f64, what: &str) {
    let (g, w): (Vec<&str>, Vec<&str>) = (got.lines().collect(), want.lines().collect());
    assert_eq!(g.len(), w.len(), "{what}: line count\n{got}");
    for (k, (a, b)) in g.iter().zip(&w).enumerate() {
        if a == b {
            continue;
        }
        let (x, y): (Vec<&str>, Vec<&str>) = (
            a.split_whitespace().collect(),
            b.split_whitespace().collect(),
        );
        assert_eq!(x.len(), y.len(), "{what} line {}: {a} | {b}", k + 1);
        for (p, q) in x.iter().zip(&y) {
            let (p, q): (f64, f64) = (p.parse().unwrap(), q.parse().unwrap());
            assert!(
                (p - q).abs() <= rel * q.abs().max(p.abs()) || (p - q).abs() <= 1e-15,
                "{what} line {}: {a} | LIGGGHTS {b}",
                k + 1
            );
        }
    }
}

/// prof4 (units reduced): every column but the density equals LIGGGHTS'; the density is
/// count × mass / bin volume, where LIGGGHTS 3.8 prints 0.
fn check_reduced(got: &str, want: &str) {
    let mass = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.004f64.powi(3);
    let volume = (0.25 * 0.1) * (0.5 * 0.1) * (0.5 * 0.05);
    for (a, b) in got.lines().zip(want.lines()) {
        let x: Vec<f64> = a
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        let y: Vec<f64> = b
            .split_whitespace()
            .filter_map(|w| w.parse().ok())
            .collect();
        if x.len() != 7 {
            assert_eq!(a, b);
            continue;
        }
        assert_eq!(x[..6], y[..6], "{a} | {b}");
        assert_eq!(y[6], 0.0, "{b}");
        let want = x[4] * mass / volume;
        assert!(
            (x[6] - want).abs() <= 1e-5 * want.max(1e-300),
            "{a}: {want}"
        );
    }
}

fn check(ranks: Option<usize>) {
    for case in CASES {
        for (name, text) in run(case, ranks) {
            let what = format!("{name}, {ranks:?} ranks");
            let reference = match name.as_str() {
                n if n.starts_with("prof_") || n.starts_with("prof2_") => name.clone(),
                n => format!("{}_a.txt", &n[..5]),
            };
            let want = std::fs::read_to_string(data().join(&reference)).unwrap();
            if name.starts_with("prof4") {
                check_reduced(&text, &want);
            } else if ranks.is_none() && !name.starts_with("prof5") {
                assert_eq!(text, want, "{what}");
            } else {
                assert_close_text(&text, &want, 2e-6, &what);
            }
        }
    }
}

#[test]
fn bins_and_averages_match_liggghts() {
    check(None);
}

#[cfg(feature = "mpi")]
#[test]
fn ranks_give_the_same_averages() {
    if common::have_mpirun() {
        check(Some(2));
    }
}

#[test]
fn ave_spatial_errors_are_located() {
    let script = std::fs::read_to_string(data().join("in.as")).unwrap();
    let head: String = script
        .lines()
        .take_while(|l| !l.starts_with("fix prof "))
        .map(|l| format!("{l}\n"))
        .collect();
    for (line, message) in [
        (
            "fix p all ave/spatial 10 5 30 z lower 0.01 vx",
            "Nfreq > (Nrepeat-1)*Nevery",
        ),
        (
            "fix p all ave/spatial 10 1 100 vx",
            "needs 'x|y|z origin delta'",
        ),
        (
            "fix p all ave/spatial 10 1 100 z lower 0.01",
            "needs at least one value",
        ),
        (
            "fix p all ave/spatial 10 1 100 z lower 0.01 vx overwrite",
            "overwrite needs 'ave running'",
        ),
        (
            "fix p all ave/spatial 10 1 100 z lower 0.01 c_nope",
            "no compute 'nope'",
        ),
        (
            "fix p all ave/spatial 10 1 100 z lower 0.01 vx std 1 2 f",
            "'write_ts'",
        ),
    ] {
        let out = common::run_script_raw(&format!("{head}{line}\n"), None);
        assert!(!out.status.success(), "{line}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{line}: {err}");
    }
}

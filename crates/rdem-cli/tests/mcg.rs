//! `fix mcg` (LIGGGHTS_Multi-level_CG) on the fork's own example, real script wild/52
//! (coarse spheres refined eight-fold as they fall through a band, merged back below it),
//! against the fork's published run of it: `example_MCG/log.liggghts` of
//! Lokisphere/LIGGGHTS_Multi-level_CG 0b7a599 (8 MPI ranks). The fork merges the fine
//! spheres in its storage order and rdem in tag order, so the counts follow the fork's
//! within a few percent, not to the particle (measured: 5 % at worst over these rows).

use crate::common;

/// The fork's atom counts at these steps (its log's thermo rows).
const FORK: [(u64, u64); 20] = [
    (2000, 715),
    (5000, 1275),
    (8000, 1863),
    (11000, 2318),
    (14000, 2486),
    (17000, 1940),
    (20000, 1366),
    (23000, 694),
    (26000, 400),
    (29000, 400),
    (32000, 400),
    (35000, 400),
    (38000, 400),
    (41000, 400),
    (44000, 400),
    (47000, 407),
    (50000, 407),
    (53000, 421),
    (56000, 428),
    (59000, 526),
];

/// The first 60000 of wild/52's 500000 steps: the first wave of refinement, its merging
/// back to the 400 coarse spheres, and the start of the second wave.
#[test]
fn hourglass_counts_follow_the_fork() {
    let Some(src) = common::wild_case("52_mcg_hourglass", "in.hourglassMCG") else {
        return;
    };
    let dir = common::scratch_dir("mcg");
    common::copy_dir(&src, &dir);
    let _ = std::fs::remove_dir_all(dir.join("post"));
    let script = std::fs::read_to_string(src.join("in.hourglassMCG"))
        .unwrap()
        .replace("run             500000 upto", "run 60000 upto");
    assert!(script.contains("run 60000 upto"));
    std::fs::write(dir.join("in.short"), script).unwrap();
    let out = common::rdem_in(&dir, "in.short", None).output().unwrap();
    let rows = common::thermo_rows(&common::success("wild/52", &out));
    let atoms = |step: u64| {
        rows.iter()
            .find(|r| r[0] == step as f64)
            .unwrap_or_else(|| panic!("no thermo row at step {step}"))[1] as u64
    };
    for (step, fork) in FORK {
        let got = atoms(step);
        let tol = (fork / 10).max(30);
        assert!(
            got.abs_diff(fork) <= tol,
            "step {step}: {got} spheres against the fork's {fork}"
        );
    }
    // Each refinement adds 7 spheres and each merge removes 7: the count stays 400 + 7k,
    // and the first wave merges back to exactly the 400 coarse spheres.
    for r in rows.iter().filter(|r| r[0] > 0.0) {
        assert_eq!((r[1] as u64) % 7, 400 % 7, "row {r:?}");
    }
    assert!((26000..=44000).step_by(1000).all(|s| atoms(s) == 400));
    let peak = rows.iter().map(|r| r[1] as u64).max().unwrap();
    assert!(peak > 2300, "peak {peak}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `fix mcg` takes no arguments: one is refused at its word.
#[test]
fn arguments_are_refused() {
    let script = "units si\natom_style granular\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\nfix M all mcg 100\n";
    let out = common::run_script_raw(script, None);
    assert!(!out.status.success());
    let text =
        String::from_utf8_lossy(&out.stderr).into_owned() + &String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("fix mcg takes no arguments"), "{text}");
    assert!(text.contains("in.test:5"), "{text}");
}

//! `fix insert/pack/dense` and `fix balance` (LIGGGHTS-PFM fixes; LIGGGHTS 3.8 has
//! neither) through the interpreter: the insertion at the first step of the run with its
//! report and `f_ID` values, the count against φ V / v_p, and the located errors of the
//! keywords rdem does not run.

use rdem_script::Interpreter;

use crate::common;

const HEAD: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.02 0.02 -0.02 0.02 0.0 0.05 units box
create_box 2 reg
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.9 0.9 0.9 0.9
fix m4 all property/global coefficientFriction peratomtypepair 2 0.05 0.05 0.05 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.001
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
region insReg block -0.015 0.015 -0.015 0.015 0.0 0.03 units box
fix integr all nve/sphere
";

fn run(tail: &str) -> Result<(Interpreter, String), String> {
    common::try_run_screen("in.dense", &format!("{HEAD}{tail}"))
}

/// φ = 0.5 of a 30 × 30 × 30 mm block of 1 mm spheres: φ V / v_p = 0.5 × 2.7e-5 /
/// 4.18879e-9 = 3222.9, so the report says about 3222; the packing inserts
/// within 2 % of it at step 1 (the first step of the run, in its pre-exchange stage), `f_ins[1]` and
/// `f_ins[2]` are the count and the mass, and nothing more is inserted later (once).
#[test]
fn inserts_once_near_the_closed_form_count() {
    let (i, out) = run("fix ins all insert/pack/dense seed 123 region insReg distributiontemplate pdd1 volumefraction_region 0.5
variable n equal f_ins[1]
variable m equal f_ins[2]
thermo_style custom step atoms v_n v_m
thermo 1
run 3
")
    .unwrap();
    let n = i.sim.natoms() as f64;
    let want = 0.5 * 2.7e-5 / (4.0 / 3.0 * std::f64::consts::PI * 1e-9);
    eprintln!("inserted {n}, closed form {want}");
    assert!((n / want - 1.0).abs() < 0.02, "{n} vs {want}\n{out}");
    assert!(
        out.contains("0.5 asked for (about 3222 particles;"),
        "{out}"
    );
    assert!(
        out.contains(&format!("inserted {n} particle templates")),
        "{out}"
    );
    let rows: Vec<Vec<f64>> = out
        .lines()
        .filter_map(|l| {
            let v: Option<Vec<f64>> = l.split_whitespace().map(|w| w.parse().ok()).collect();
            v.filter(|v| v.len() == 4)
        })
        .collect();
    assert_eq!(rows.len(), 4, "{out}");
    assert_eq!(rows[0][1], 0.0, "nothing before the run's first step");
    for r in &rows[1..] {
        assert_eq!(r[1], n);
        assert_eq!(r[2], n);
        let mass = n * 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-9;
        assert!((r[3] - mass).abs() < 1e-6 * mass, "{r:?}");
    }
}

/// A volume fraction above 0.57 runs at 0.57 with a warning (as LIGGGHTS-PFM), so the
/// radii are not enlarged (factor 1).
#[test]
fn too_dense_a_fraction_is_clamped_with_a_warning() {
    let (_, out) = run("fix ins all insert/pack/dense seed 5 region insReg distributiontemplate pdd1 volumefraction_region 0.64 verbose yes
").unwrap();
    assert!(
        out.contains("volumefraction_region 0.64 is more than the packing reaches; 0.57 is used"),
        "{out}"
    );
    let (_, out) = run("fix ins all insert/pack/dense seed 5 region insReg distributiontemplate pdd1 volumefraction_region 0.64
run 1
").unwrap();
    assert!(out.contains("radii enlarged 1 times"), "{out}");
}

/// Keywords rdem does not run, and missing ones: errors at the word (line 22 is the
/// fix), with what is supported.
#[test]
fn unsupported_keywords_are_located_errors() {
    let fix = "fix ins all insert/pack/dense seed 123 region insReg distributiontemplate pdd1";
    for (rest, col_word, message) in [
        (
            " maxattempt 10",
            "maxattempt",
            "'maxattempt' is not supported yet",
        ),
        (
            " overlapcheck no",
            "no",
            "'overlapcheck no' is not supported yet",
        ),
        (
            " particles_in_region 10",
            "particles_in_region",
            "not supported yet",
        ),
        (
            " volumefraction_region -1",
            "-1",
            "volume fraction must be > 0",
        ),
        (" insert_every 0", "0", "insert_every"),
        (" colour red", "colour", "unknown insert/pack/dense keyword"),
    ] {
        let line = format!("{fix}{rest}\n");
        let e = run(&line).err().expect("an error");
        let col = line.find(&format!(" {col_word}")).unwrap() + 2;
        assert!(e.contains(&format!("in.dense:22:{col}")), "{rest}: {e}");
        assert!(e.contains(message), "{rest}: {e}");
    }
    let e = run("fix ins all insert/pack/dense seed 123 distributiontemplate pdd1\n")
        .err()
        .expect("an error");
    assert!(e.contains("needs 'region ID'"), "{e}");
    let e = run("fix ins all insert/pack/dense region insReg seed 1\n")
        .err()
        .expect("an error");
    assert!(e.contains("the first keyword must be 'seed'"), "{e}");
}

/// `fix balance` (case 08's `fix loadBalancing all balance 10000 z 10 1.05`): checked and
/// accepted with a warning saying it changes nothing; bad words are located errors.
#[test]
fn fix_balance_warns_and_checks_its_words() {
    let (_, out) = run("fix lb all balance 10000 z 10 1.05\nrun 1\n").unwrap();
    assert!(
        out.contains("WARNING") && out.contains("fix balance: rdem keeps its equal MPI subdomains"),
        "{out}"
    );
    for (rest, message) in [
        ("1000 q 10 1.05", "dimstr 'q'"),
        ("1000 xx 10 1.05", "dimstr 'xx'"),
        ("1000 z 10 0.5", "thresh 0.5 must be >= 1"),
        ("1000 z 10 1.1 out bal.txt", "'out' is not supported yet"),
        ("1000 z", "Niter"),
    ] {
        let e = run(&format!("fix lb all balance {rest}\n"))
            .err()
            .expect("an error");
        assert!(e.contains("in.dense:22:"), "{rest}: {e}");
        assert!(e.contains(message), "{rest}: {e}");
    }
}

//! Parity with LIGGGHTS 3.8 of the computes `pe`, `erotate`, `erotate/sphere/atom`,
//! `ke/atom`, `displace/atom` and `pressure`, and of the averaging fixes: each test runs a
//! script of tests/data/parity/ and checks the numbers LIGGGHTS printed for it (hard-coded
//! below; the full LIGGGHTS outputs are the itemN.liggghts.* files next to the scripts,
//! made by regenerate.sh: `liggghts -in itemN.in -log none`).

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/parity");

/// Runs tests/data/parity/`name` with its includes inlined, every `(from, to)` of
/// `replace` applied (file names to scratch paths); returns the screen output.
fn run_item(name: &str, replace: &[(&str, &std::path::Path)]) -> String {
    let read = |f: &str| std::fs::read_to_string(format!("{DIR}/{f}")).unwrap();
    let mut src = read(name)
        .replace("include head.in\n", &read("head.in"))
        .replace("include mat.in\n", &read("mat.in"));
    for (from, to) in replace {
        src = src.replace(from, &to.display().to_string());
    }
    common::run_screen(name, &src)
}

/// The numbers of the last thermo row of step `step` in `out`.
fn thermo_row(out: &str, step: &str) -> Vec<f64> {
    let line = out
        .lines()
        .rfind(|l| l.split_whitespace().next() == Some(step))
        .unwrap_or_else(|| panic!("no thermo row for step {step} in\n{out}"));
    line.split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect()
}

/// Asserts rdem's thermo row of `step` equals LIGGGHTS' to a relative `tol` (absolute
/// below 1e-12 in magnitude).
fn check_row(out: &str, step: &str, liggghts: &str, tol: f64) {
    let r = thermo_row(out, step);
    let l: Vec<f64> = liggghts
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(r.len(), l.len(), "step {step}: {r:?} vs {l:?}");
    for (k, (a, b)) in r.iter().zip(&l).enumerate() {
        assert!(
            (a - b).abs() <= tol * b.abs().max(1e-12),
            "step {step}, column {k}: {a} vs LIGGGHTS {b}\n{r:?}\n{l:?}"
        );
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("rdem-computes-{name}-{}", std::process::id()))
}

/// Item 9: pe, erotate, erotate/sphere, erotate/sphere/atom and ke/atom (reduced),
/// pressure (scalar, tensor, `virial`, `ke`) with contacts at step 0, displace/atom
/// (atom 4 crosses the periodic x boundary at x = 1 before step 2000).
#[test]
fn energies_pressure_displacement() {
    let out = run_item("item9.in", &[]);
    // LIGGGHTS' thermo rows (item9.liggghts.txt). Columns: step pe er ers ser ska pr
    // pr[1..6] prv prv[4] prk prk[4] sda[1..4] mda[1] mda[2].
    check_row(&out, "0", "0 0 0 0 0 0.249966055470628 71.8206886148346 207.691653621979 7.31649135398862 0.453920868535555 31.7551459267316 0.391835143718987 -0.302613912357037 70.2223291758275 32.0163693558776 1.59835943900702 -0.261223429145991 0 0 0 0 0 0", 1e-9);
    check_row(&out, "1000", "1000 0 0.0323284327224431 0.0323284327224431 0.00893398980289616 6.91398782457713 10.2891822482115 29.1201486469484 1.29347722915065 0.453920868535555 2.88937980475931 0.391835143718985 -0.302613912357037 0 0 10.2891822482115 2.88937980475931 0.0399829798515366 -0.0106934609002237 0.011999999999901 0.102128026459382 0.0499999999999945 0.050129831437968", 1e-9);
    check_row(&out, "2000", "2000 0 0.0323284327224431 0.0323284327224431 0.00893398980289616 6.91398782457713 10.2891822482115 29.1201486469484 1.29347722915065 0.453920868535555 2.88937980475931 0.391835143718985 -0.302613912357037 0 0 10.2891822482115 2.88937980475931 0.0769367298858638 -0.0219707099183949 0.023999999999802 0.217407636950103 0.0999999999999974 0.100259662875944", 1e-9);
}

/// Item 10: displace/atom of a particle created after the compute (its origin is 0 in
/// LIGGGHTS 3.8, so its displacement is its position) and ke/atom (½ m v² =
/// 0.000818123 for a 5 cm sphere of 2500 kg/m³ at 0.1 m/s; 0 outside the group), in a
/// dump: the dump equals LIGGGHTS' byte for byte.
#[test]
fn displace_late_particle_and_ke_atom_dump() {
    let d = tmp("item10");
    run_item("item10.in", &[("item10.dump", &d)]);
    let ours = std::fs::read_to_string(&d).unwrap();
    let theirs = std::fs::read_to_string(format!("{DIR}/item10.liggghts.dump")).unwrap();
    assert_eq!(ours, theirs);
    let _ = std::fs::remove_file(&d);
}

/// Item 11: fix viscous with `scale 2 3.0` (type 2 gets γ = 1.5) and fix aveforce
/// `NULL 0.2 0.0` on three of four particles under gravity: the velocities of all four
/// and the aveforce vector (the group's total force before the fix: at step 0 its x
/// component is the viscous force −(0.5 + 1.5 + 0.5)·0.1 = −0.25).
#[test]
fn viscous_scale_and_aveforce() {
    let out = run_item("item11.in", &[]);
    // LIGGGHTS' thermo rows (item11.liggghts.txt): step f_af[1..3] then vx vy vz of
    // atoms 1-4.
    check_row(
        &out,
        "0",
        "0 -0.25 0.5 -22.9396972308354 0.1 -0.2 0.3 0.1 -0.2 0.3 0.1 -0.2 0.3 0.1 -0.2 0.3",
        1e-9,
    );
    check_row(&out, "500", "500 -0.24779739064483 0.491991739794174 -22.7726908085923 0.0998091959666728 -0.198604535826893 0.270898613065867 0.0988871675999841 -0.197274484036901 0.243161353644271 0.0991196956308648 -0.193539517717098 0.16527135678642 0.0955196001264206 -0.191039200252841 0.238613817418323", 1e-9);
    check_row(&out, "1000", "1000 -0.245615197958623 0.484033852739195 -22.6067348816483 0.0996187559947738 -0.197219241085266 0.242009302203688 0.0977867191472276 -0.19456883024466 0.186736918366575 0.0982471406118719 -0.18712611613549 0.0315245472392893 0.0912399398914008 -0.182479879782802 0.179977978656771", 1e-9);
    // Atom 4 (type 2) is outside the aveforce group and touches nothing: vx decays as
    // exp(−γ t / m) with γ = 1.5, m = 2500 · 4/3 π 0.025³, t = 0.01.
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.025f64.powi(3);
    let vx4 = thermo_row(&out, "1000")[13];
    assert!((vx4 - 0.1 * (-1.5 * 0.01 / m).exp()).abs() < 1e-6, "{vx4}");
}

/// The numbers of a text dump's rows (after each `ITEM: ATOMS` line), snapshot by snapshot.
fn dump_rows(text: &str) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        if l.starts_with("ITEM: NUMBER OF ATOMS") {
            let n: usize = lines.next().unwrap().trim().parse().unwrap();
            let mut l = lines.next().unwrap();
            while !l.starts_with("ITEM: ATOMS") {
                l = lines.next().unwrap();
            }
            for _ in 0..n {
                let row = lines.next().unwrap();
                rows.push(row.split_whitespace().map(|w| w.parse().unwrap()).collect());
            }
        }
    }
    rows
}

/// Item 12: fix ave/atom of a position, a velocity, a force, a per-atom compute and an
/// atom-style variable over 5 samples 10 steps apart every 100 steps on a group of two
/// (0 for the third particle), and a second ave/atom (`Nrepeat` 1, so step 0 is sampled
/// at the set-up) of the first one's column and vz, dumped every 100 steps: every value
/// equals LIGGGHTS' to 1e-9.
#[test]
fn ave_atom_dump() {
    let d = tmp("item12");
    run_item("item12.in", &[("item12.dump", &d)]);
    let ours = dump_rows(&std::fs::read_to_string(&d).unwrap());
    let theirs =
        dump_rows(&std::fs::read_to_string(format!("{DIR}/item12.liggghts.dump")).unwrap());
    assert_eq!(ours.len(), theirs.len());
    assert_eq!(ours.len(), 12);
    for (r, l) in ours.iter().zip(&theirs) {
        assert_eq!(r.len(), l.len());
        for (a, b) in r.iter().zip(l) {
            assert!(
                (a - b).abs() <= 1e-9 * b.abs().max(1e-9),
                "{r:?} vs LIGGGHTS {l:?}"
            );
        }
    }
    let _ = std::fs::remove_file(&d);
}

/// LIGGGHTS' general compute keyword `update_on_run_end yes|no`, read right after the
/// style and before the style's own words. LIGGGHTS 3.8 printed A 0.0010471975511966
/// (erotate/sphere of a 0.1 m sphere of 1000 kg/m³ spinning at 2 rad/s) and B 1 for this
/// script; after the style's words the keyword is the style's error, as in LIGGGHTS.
#[test]
fn update_on_run_end_is_read_after_the_style() {
    let head = "atom_style granular\natom_modify map array sort 0 0\ncommunicate single vel yes\n\
        units si\nregion reg block 0 1 0 1 0 1 units box\ncreate_box 1 reg\n\
        create_atoms 1 single 0.5 0.5 0.5\n\
        set atom 1 diameter 0.1 density 1000 vx 1 omegaz 2\n";
    let out = common::run_screen(
        "in.uore",
        &format!(
            "{head}compute rke all erotate/sphere update_on_run_end yes\n\
             compute r1 all reduce update_on_run_end no sum vx\n\
             fix integr all nve/sphere\ntimestep 1e-4\n\
             thermo_style custom step c_rke c_r1\nrun 1\n\
             variable a equal c_rke\nprint \"A $a\"\nvariable b equal c_r1\nprint \"B $b\"\n"
        ),
    );
    assert!(out.contains("A 0.0010471975511966\n"), "{out}");
    assert!(out.contains("B 1\n"), "{out}");
    for (line, at) in [
        (
            "compute r all reduce sum vx update_on_run_end yes",
            "in.e:9:29",
        ),
        ("compute r all ke update_on_run_end maybe", "in.e:9:36"),
        ("compute r all ke update_on_run_end", "in.e:9:"),
    ] {
        let e = common::error("in.e", &format!("{head}{line}\n"));
        assert!(e.contains(at), "{line}: {e}");
    }
}

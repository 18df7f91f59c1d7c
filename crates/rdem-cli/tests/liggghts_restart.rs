//! `read_restart` of LIGGGHTS 3.8 binary restart files (`tests/data/liggghts_restart`,
//! written by LIGGGHTS 3.8.0; its README says how): the particles as LIGGGHTS wrote them,
//! and a continued run against LIGGGHTS continuing the same file.

use crate::common;
use common::{have_mpirun, run_kept, scratch_dir, thermo_rows};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/liggghts_restart")
        .join(name)
}

const HEAD: &str =
    "atom_style granular\natom_modify map array\nnewton off\ncommunicate single vel yes\n";

/// `ITEM: ATOMS` rows of a dump by tag (the columns after id and type).
fn rows(text: &str) -> std::collections::BTreeMap<u64, Vec<f64>> {
    text.lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (
                w[0].parse().unwrap(),
                w[2..].iter().map(|x| x.parse().unwrap()).collect(),
            )
        })
        .collect()
}

#[test]
fn settled_bed_particles_are_those_liggghts_dumped() {
    // A dump written right after read_restart, in the format of LIGGGHTS' dump of the
    // step it wrote the file at: the same bytes.
    let script = format!(
        "{HEAD}read_restart {}\nwrite_dump all custom bed.dump id type x y z vx vy vz omegax omegay omegaz radius mass density modify sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n",
        data("bed.restart").display()
    );
    let (dir, out) = common::run_kept_ok("lig-bed-dump", &script, &[], None);
    let ours = std::fs::read_to_string(dir.join("bed.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(ours, std::fs::read_to_string(data("bed.dump")).unwrap());
    assert!(out.contains("Reading LIGGGHTS restart file ..."), "{out}");
    assert!(out.contains("written by LIGGGHTS-PUBLIC 3.8.0"), "{out}");
    assert!(out.contains("at step 30000"), "{out}");
    assert!(out.contains("  200 atoms"), "{out}");
    // 810 partner entries in the file, each pair from both sides.
    assert!(
        out.contains("405 pair contact histories, wall histories of 2 fix(es): floor cyl"),
        "{out}"
    );
    // One warning names what is not taken.
    let warn: Vec<&str> = out.lines().filter(|l| l.starts_with("WARNING")).collect();
    assert_eq!(warn.len(), 1, "{out}");
    for what in [
        "pair style gran",
        "fix pts (particletemplate/sphere)",
        "fix ins (insert/pack)",
    ] {
        assert!(warn[0].contains(what), "{}", warn[0]);
    }
}

#[test]
fn two_processor_periodic_file_gives_particles_images_and_groups() {
    let script = format!(
        "{HEAD}read_restart {}\nvariable n equal count(upper)\nprint \"upper: ${{n}}\"\nwrite_dump all custom bed2.dump id type ix iy iz x y z vx vy vz omegax omegay omegaz radius mass density modify sort id format \"%d %d %d %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n",
        data("bed2.restart").display()
    );
    let (dir, out) = common::run_kept_ok("lig-bed2-dump", &script, &[], None);
    let ours = std::fs::read_to_string(dir.join("bed2.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(ours, std::fs::read_to_string(data("bed2.dump")).unwrap());
    // LIGGGHTS: "27 atoms in group upper".
    assert!(out.contains("upper: 27"), "{out}");
    assert!(out.contains("on 2 processor(s) at step 20000"), "{out}");
}

/// The settled bed continued for 1000 steps from `restart` on `ranks`; returns the
/// largest differences from LIGGGHTS' continued run (position, velocity, angular
/// velocity) and the screen output.
fn continue_bed(prefix: &str, restart: &Path, ranks: Option<usize>) -> ([f64; 3], String) {
    let script = std::fs::read_to_string(data("in.continue"))
        .unwrap()
        .replace(
            "read_restart bed.restart",
            &format!("read_restart {}", restart.display()),
        );
    let (dir, out) = common::run_kept_ok(prefix, &script, &[], ranks);
    let ours = rows(&std::fs::read_to_string(dir.join("final.dump")).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
    let theirs = rows(&std::fs::read_to_string(data("final.dump")).unwrap());
    assert_eq!(ours.len(), 200);
    let mut d = [0.0f64; 3];
    for (t, a) in &theirs {
        let b = &ours[t];
        for (k, dk) in d.iter_mut().enumerate() {
            let s = 3 * k;
            let e = ((a[s] - b[s]).powi(2)
                + (a[s + 1] - b[s + 1]).powi(2)
                + (a[s + 2] - b[s + 2]).powi(2))
            .sqrt();
            *dk = dk.max(e);
        }
    }
    (d, out)
}

/// Measured (rdem serial against LIGGGHTS 3.8, 1000 steps of a settled bed of 200 with
/// pair and wall histories): positions 2.3e-17 m, velocities 1.1e-14 m/s (largest speed
/// 3.1e-3), angular velocities 6.4e-12 rad/s (largest 1.2): round-off. The bounds below
/// leave five orders of magnitude for round-off growing over the run, and stay five
/// orders below what a bed continued without its histories shows (next test).
const AGREE: [f64; 3] = [1e-12, 1e-9, 1e-6];

#[test]
fn settled_bed_continues_as_liggghts_continues_it() {
    let (d, out) = continue_bed("lig-bed-cont", &data("bed.restart"), None);
    assert!(
        d.iter().zip(AGREE).all(|(x, lim)| *x < lim),
        "largest differences from LIGGGHTS (x, v, omega): {d:?}"
    );
    // LIGGGHTS: kinetic energy 2.2375103774474262e-09 at step 31000, time 0 at the
    // file's step and 0.02 s at its end.
    let last = thermo_rows(&out).last().unwrap().clone();
    assert_eq!(
        (last[0], last[1], last[3]),
        (31000.0, 200.0, 0.02),
        "{last:?}"
    );
    assert!(
        (last[2] / 2.237_510_377_447_426e-9 - 1.0).abs() < 1e-9,
        "{last:?}"
    );
    assert_eq!(thermo_rows(&out)[0][3], 0.0);
}

#[test]
fn settled_bed_continues_as_liggghts_on_two_ranks() {
    if !have_mpirun() {
        return;
    }
    let (d, _) = continue_bed("lig-bed-cont-mpi", &data("bed.restart"), Some(2));
    assert!(
        d.iter().zip(AGREE).all(|(x, lim)| *x < lim),
        "largest differences from LIGGGHTS (x, v, omega): {d:?}"
    );
}

/// `bed.restart` with the shear values of the pair contact histories (`pair`) or of the
/// wall histories (`walls`) set to zero, written to a scratch file.
fn without_histories(pair: bool, walls: bool) -> PathBuf {
    let mut b = std::fs::read(data("bed.restart")).unwrap();
    let f64_at = |b: &[u8], o: usize| f64::from_le_bytes(b[o..o + 8].try_into().unwrap());
    // The atoms: the one block (one processor) of n doubles that ends the file.
    let at = (0..b.len() - 4)
        .find(|&o| {
            let n = i32::from_le_bytes(b[o..o + 4].try_into().unwrap());
            n > 0 && o + 4 + 8 * n as usize == b.len()
        })
        .unwrap();
    let mut p = at + 4;
    while p < b.len() {
        let size = f64_at(&b, p) as usize;
        // 17 values, then fix history_floor (4), history_cyl (4), contacthistory.
        let mut k = 17;
        for fix in 0..3 {
            let len = f64_at(&b, p + 8 * k) as usize;
            let zero: Vec<usize> = if fix < 2 {
                if walls {
                    (k + 1..k + len).collect()
                } else {
                    Vec::new()
                }
            } else if pair {
                // count, then (partner tag, three values) per partner
                (k + 2..k + len).filter(|q| (q - k - 2) % 4 != 0).collect()
            } else {
                Vec::new()
            };
            for q in zero {
                b[p + 8 * q..p + 8 * q + 8].copy_from_slice(&0f64.to_le_bytes());
            }
            k += len;
        }
        assert_eq!(k, size);
        p += 8 * size;
    }
    let dir = scratch_dir("lig-nohist");
    let path = dir.join("bed.restart");
    std::fs::write(&path, b).unwrap();
    path
}

#[test]
fn without_its_histories_the_bed_departs_from_liggghts() {
    // Measured largest position differences after 1000 steps: no histories 2.2e-5 m,
    // no pair histories 1.9e-5 m, no wall histories 2.5e-6 m (with them: 2.3e-17).
    for (pair, walls) in [(true, true), (true, false), (false, true)] {
        let f = without_histories(pair, walls);
        let (d, _) = continue_bed("lig-bed-nohist", &f, None);
        let _ = std::fs::remove_dir_all(f.parent().unwrap());
        assert!(
            d[0] > 1e-7 && d[1] > 1e-5,
            "pair {pair} walls {walls}: {d:?}"
        );
    }
}

#[test]
fn a_damaged_liggghts_file_is_a_located_error() {
    let good = std::fs::read(data("bed.restart")).unwrap();
    let dir = scratch_dir("lig-bad");
    std::fs::write(dir.join("cut.restart"), &good[..good.len() / 2]).unwrap();
    let (d2, out) = run_kept(
        "lig-bad-run",
        &format!("{HEAD}read_restart {}\n", dir.join("cut.restart").display()),
        &[],
        None,
    );
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&d2);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!out.status.success(), "{text}");
    assert!(
        text.contains("cut.restart' (a LIGGGHTS restart file): at byte"),
        "{text}"
    );
    assert!(text.contains("it is truncated"), "{text}");
    // Located: the script line, and the file name marked.
    assert!(text.contains("in.test:5:14"), "{text}");
    assert!(text.contains("here"), "{text}");
}

#[test]
fn restart_file_wildcards_are_refused() {
    for name in ["bed.*", "bed.%"] {
        let (d, out) = run_kept(
            "lig-wild",
            &format!("{HEAD}read_restart {name}\n"),
            &[],
            None,
        );
        let _ = std::fs::remove_dir_all(&d);
        let text = String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{text}");
        assert!(text.contains("wildcards are not supported yet"), "{text}");
    }
}

#[test]
fn property_atom_values_come_back_to_the_fix_of_their_id() {
    // As LIGGGHTS: `fix pa` defined again after read_restart (defaults 0 0) takes the
    // file's values (1.5 2.5, and 7 8 on 40 particles), by tag.
    let script = std::fs::read_to_string(data("in.read_pa"))
        .unwrap()
        .replace(
            "read_restart pa.restart",
            &format!("read_restart {}", data("pa.restart").display()),
        );
    let (dir, out) = common::run_kept_ok("lig-pa", &script, &[], None);
    let ours = std::fs::read_to_string(dir.join("back.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(ours, std::fs::read_to_string(data("pa.dump")).unwrap());
    assert!(
        out.contains("per-particle values of fix(es) pa kept"),
        "{out}"
    );
    // Another number of values than the file holds is a located error.
    let bad = script.replace(
        "property/atom pval vector yes no no 0 0",
        "property/atom pval scalar yes no no 0",
    );
    let (d, out) = run_kept("lig-pa-bad", &bad, &[], None);
    let _ = std::fs::remove_dir_all(&d);
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{text}");
    assert!(
        text.contains("holds 2 value(s) per particle for fix pa"),
        "{text}"
    );
}

#[test]
fn a_script_boundary_other_than_the_files_gives_way_with_a_warning() {
    // The file: boundary f f f. LIGGGHTS 3.8 (measured, `boundary p p f` before
    // read_restart) warns that the file's boundary differs and uses it.
    let script = format!(
        "{HEAD}boundary p p f\nread_restart {}\nvariable lx equal lx\nprint \"lx ${{lx}}\"\n",
        data("bed.restart").display()
    );
    let (dir, out) = common::run_kept_ok("lig-boundary", &script, &[], None);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        out.contains(
            "the script's boundary (pp pp ff) is not the file's (ff ff ff); the file's is used"
        ),
        "{out}"
    );
    // Nothing said when the script leaves the default.
    let (dir, out) = common::run_kept_ok(
        "lig-boundary-default",
        &format!("{HEAD}read_restart {}\n", data("bed.restart").display()),
        &[],
        None,
    );
    let _ = std::fs::remove_dir_all(&dir);
    assert!(!out.contains("boundary"), "{out}");
}

#[test]
fn a_run_without_the_pair_style_of_a_liggghts_file_is_an_error() {
    // LIGGGHTS 3.8 continues bed.restart without pair_style/pair_coeff lines (it takes
    // the pair style from the file); rdem does not decode it and says so.
    let script = std::fs::read_to_string(data("in.continue"))
        .unwrap()
        .replace(
            "read_restart bed.restart",
            &format!("read_restart {}", data("bed.restart").display()),
        )
        .replace("pair_style gran model hertz tangential history\n", "")
        .replace("pair_coeff * *\n", "");
    let (d, out) = run_kept("lig-nopair", &script, &[], None);
    let _ = std::fs::remove_dir_all(&d);
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{text}");
    // (The message is wrapped on screen.)
    assert!(
        text.contains("restart file read holds pair_style gran"),
        "{text}"
    );
    assert!(text.contains("0x83)"), "{text}");
}

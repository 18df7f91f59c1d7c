//! `bond_style gran` (LIGGGHTS_Flexible_Fibers' flexible-fiber bonds) against
//! LIGGGHTS_Flexible_Fibers itself and against Euler–Bernoulli beam theory.
//!
//! The fork (schrummy14/LIGGGHTS_Flexible_Fibers 0fc7c5b) was built here (`make auto`,
//! USE_VTK OFF) and ran the scripts of `tests/data/bond_gran/`, written for these tests:
//! `in.bonds` (two bonded pairs and a bent chain of three in general motion, radii and
//! densities unequal, for each damping style), `in.pull` (a pair pulled apart until the
//! bond breaks by its normal or its shear stress), `in.create` (bond creation on a 3 × 3
//! square), `in.cantilever` (wild/24's beam bent by a tip force, then released),
//! `in.soft` (a bond broken while its spheres overlap, break styles 3 to 5), `in.hot` (a
//! bond broken by temperature, break style 2), `in.molecule` (spheres of one molecule
//! deeper than half their radii sum), and a shortened wild/24 (deflection 2 mm, 1 ms of waiting and of vibration). Their output
//! is stored beside them (`fibers_*`).

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bond_gran")
}

fn read(name: &str) -> String {
    std::fs::read_to_string(data().join(name)).unwrap()
}

/// The rows of numbers of a reference file.
fn table(name: &str) -> Vec<Vec<f64>> {
    read(name)
        .lines()
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// A data script with index variables set first (as `-var NAME VALUE` would).
fn with_vars(name: &str, vars: &[(&str, &str)]) -> String {
    let mut s: String = vars
        .iter()
        .map(|(k, v)| format!("variable {k} index \"{v}\"\n"))
        .collect();
    s.push_str(&read(name));
    s
}

/// Every value of `got` within `rel` of the largest magnitude of its column group
/// (columns `groups` of three) in `want`.
fn assert_frames(
    got: &[(u64, Vec<Vec<f64>>)],
    want: &[(u64, Vec<Vec<f64>>)],
    rel: f64,
    what: &str,
) {
    assert_eq!(got.len(), want.len(), "{what}: frame count");
    let ncol = want[0].1[0].len();
    let mut worst = 0.0f64;
    for c0 in (1..ncol).step_by(3) {
        let scale = want
            .iter()
            .flat_map(|f| f.1.iter().flat_map(|r| r[c0..c0 + 3].to_vec()))
            .fold(0.0f64, |m, x| m.max(x.abs()));
        for ((gs, g), (ws, w)) in got.iter().zip(want) {
            assert_eq!(gs, ws, "{what}: steps");
            assert_eq!(g.len(), w.len(), "{what}: rows at step {ws}");
            for (gr, wr) in g.iter().zip(w) {
                assert_eq!(gr[0], wr[0], "{what}: ids");
                for c in c0..c0 + 3 {
                    let e = (gr[c] - wr[c]).abs() / scale;
                    worst = worst.max(e);
                    assert!(
                        e <= rel,
                        "{what}: step {ws} atom {} column {c}: {} against the fork's {} (scale {scale})",
                        wr[0],
                        gr[c],
                        wr[c]
                    );
                }
            }
        }
    }
    eprintln!("{what}: worst {worst:.1e}");
}

/// Runs `script`, which must say `created` ("Created N bonds at timestep 1"), and
/// compares its `atoms.txt` with the fork's dump `reference` ([`assert_frames`]).
fn assert_follows_dump(script: &str, created: &str, reference: &str, rel: f64, what: &str) {
    let (dir, out) = common::run_kept_ok("bond_gran", script, &[], None);
    assert!(out.contains(created), "{what}: {out}");
    let got = common::dump_frames(&std::fs::read_to_string(dir.join("atoms.txt")).unwrap());
    let want = common::dump_frames(&read(reference));
    assert_frames(&got, &want, rel, what);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The two pairs and the chain of `in.bonds` follow the fork for each damping style:
/// positions, velocities, angular velocities, forces and torques of every sphere, every
/// 50 steps over 1000. Measured: 6e-11 (style 0), 3e-11 (style 1), 3e-9 (style 2, whose
/// sign functions amplify the last digits) of each column's scale.
#[test]
fn bonds_follow_the_fork_for_each_damping_style() {
    for (k, dval) in [(0, "0.0"), (1, "0.5"), (2, "1e-8 0.1 1e5")] {
        let what = format!("damping style {k}");
        let script = with_vars("in.bonds", &[("dtype", &k.to_string()), ("dval", dval)]);
        assert_follows_dump(
            &script,
            "Created 4 bonds at timestep 1",
            &format!("fibers_damping{k}.dump"),
            1e-7,
            &what,
        );
    }
}

/// The thermo rows of a screen output after the last occurrence of `header` (the
/// header's bond count column: Flexible_Fibers' `Step numbonds`, PFM's `numbond`).
fn pull_rows(out: &str, header: &str) -> Vec<Vec<f64>> {
    let tail = out.rsplit(header).next().unwrap();
    tail.lines()
        .skip(1)
        .map_while(|l| {
            let v: Vec<f64> = l.split_whitespace().map_while(|x| x.parse().ok()).collect();
            (v.len() == 7 && l.split_whitespace().count() == 7).then_some(v)
        })
        .collect()
}

/// A pair pulled apart breaks at the fork's step, by its normal stress (σ_c 3.5e5 Pa:
/// free from step 30) and by its shear stress (τ_c 1.2e5 Pa: from step 23), the
/// breaking step's force still acting; `numbonds` drops at the next re-neighboring
/// (steps 168 and 163), as in the fork. Each of the 401 rows (position, velocity, force
/// and spin of the second sphere) follows the fork to 1e-12 of its column's scale
/// (measured 4e-15).
#[test]
fn a_pulled_pair_breaks_at_the_forks_step() {
    for (name, sigc, tauc, free, drop) in [
        ("sigma", "3.5e5", "1.0e9", 30.0, 168.0),
        ("tau", "1.0e9", "1.2e5", 23.0, 163.0),
    ] {
        let out = common::run_script(
            &with_vars("in.pull", &[("sigc", sigc), ("tauc", tauc)]),
            None,
        );
        let got = pull_rows(&out, "Step numbonds");
        let want = table(&format!("fibers_pull_{name}.txt"));
        common::assert_columns(&got, &want, 1, 1e-12, name);
        // Free (the force on the second sphere is the applied 0.5 N alone) from the
        // step after the breaking one.
        let first_free = got.iter().skip(1).find(|r| r[5] == 0.5).map(|r| r[0]);
        assert_eq!(first_free, Some(free), "{name}");
        let first_zero = got.iter().find(|r| r[1] == 0.0).map(|r| r[0]);
        assert_eq!(first_zero, Some(drop), "{name}");
    }
}

/// The bonds of one step of a `dump local` of `batom1 batom2`, as sorted pairs.
fn bond_lists(text: &str) -> Vec<(u64, Vec<(u64, u64)>)> {
    common::dump_frames(text)
        .into_iter()
        .map(|(s, rows)| {
            let mut v: Vec<(u64, u64)> = rows.iter().map(|r| (r[0] as u64, r[1] as u64)).collect();
            v.sort_unstable();
            (s, v)
        })
        .collect()
}

/// `fix bond/create/gran` on a 3 × 3 square (tags 1–9 row by row, spacing d): with at
/// most `newperts` new bonds per sphere and step it makes the fork's bonds at step 1,
/// pair by pair (listed here as the fork wrote them), and the fork's total after step 2
/// (8 and 12). With newperts 6 and the diagonals within the cutoff, the fork's run
/// stopped after step 1; rdem's 18 after step 2 is the centre sphere full at 6.
#[test]
fn creation_makes_the_forks_bonds() {
    let b = |v: &[(u64, u64)]| v.to_vec();
    // (newperts, cutoff, the bonds of step 1, the bonds after step 2)
    type Case<'a> = (&'a str, &'a str, Vec<(u64, u64)>, usize);
    let cases: [Case; 4] = [
        ("1", "0.00201", b(&[(1, 2), (3, 6), (4, 5), (7, 8)]), 8),
        (
            "2",
            "0.00201",
            b(&[
                (1, 2),
                (1, 4),
                (2, 3),
                (3, 6),
                (4, 5),
                (5, 6),
                (7, 8),
                (8, 9),
            ]),
            12,
        ),
        (
            "3",
            "0.00201",
            b(&[
                (1, 2),
                (1, 4),
                (2, 3),
                (2, 5),
                (3, 6),
                (4, 5),
                (4, 7),
                (5, 6),
                (6, 9),
                (7, 8),
                (8, 9),
            ]),
            12,
        ),
        (
            "6",
            "0.00285",
            b(&[
                (1, 2),
                (1, 4),
                (1, 5),
                (2, 3),
                (2, 4),
                (2, 5),
                (2, 6),
                (3, 5),
                (3, 6),
                (4, 5),
                (4, 7),
                (4, 8),
                (5, 6),
                (5, 7),
                (6, 8),
                (6, 9),
                (7, 8),
                (8, 9),
            ]),
            18,
        ),
    ];
    for (np, cut, step1, total) in cases {
        let script = with_vars("in.create", &[("np", np), ("cut", cut)]);
        let (dir, out) = common::run_kept_ok("bond_create", &script, &[], None);
        let lists = bond_lists(&std::fs::read_to_string(dir.join("bonds.txt")).unwrap());
        assert_eq!(
            lists[1],
            (1, step1.clone()),
            "newperts {np} cutoff {cut}: step 1"
        );
        assert_eq!(
            lists[2].1.len(),
            total,
            "newperts {np} cutoff {cut}: step 2"
        );
        assert!(
            out.contains(&format!("Created {} bonds at timestep 1", step1.len())),
            "{out}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// (step, value) rows.
type Series = Vec<(f64, f64)>;

/// The tip deflection and the free vibration of the thermo rows after each `Step
/// numbonds` header: (static rows, free rows) as (step, z of the tip).
fn cantilever(out: &str) -> (Series, Series) {
    let mut parts = out.split("Step numbonds").skip(1).map(|t| {
        t.lines()
            .skip(1)
            .map_while(|l| {
                let v: Vec<f64> = l.split_whitespace().map_while(|x| x.parse().ok()).collect();
                (v.len() == 4 && l.split_whitespace().count() == 4).then(|| (v[0], v[2]))
            })
            .collect::<Vec<_>>()
    });
    (parts.next().unwrap(), parts.next().unwrap())
}

/// wild/24's beam (54 spheres, d 2.83 mm, ρ 420, E 1e9; the first sphere clamped):
/// - a tip force of 1e-5 N bends it by F/k with k = 2.7991 N/m, Euler–Bernoulli's
///   3EI/L³ = 2.7993 N/m (L = 53 d) within 1e-3 (measured 8e-5);
/// - released, it vibrates at 32.614 Hz, the fork's figure to 1e-6, 1.9 % below
///   Euler–Bernoulli's first frequency 33.25 Hz (the chain's masses are lumped at 54
///   points, with their own rotary inertia), checked within 2.5 %.
#[test]
fn a_cantilever_bends_and_vibrates_as_a_beam() {
    let pi = std::f64::consts::PI;
    let (d, e, rho): (f64, f64, f64) = (2.83e-3, 1e9, 420.0);
    let r = 0.5 * d;
    let inertia = pi * r.powi(4) / 4.0;
    let m = 4.0 / 3.0 * pi * r.powi(3) * rho;
    let len = 53.0 * d;
    let k_beam = 3.0 * e * inertia / len.powi(3);
    let f_beam = 1.875f64.powi(2) / (2.0 * pi) * (e * inertia / (m / d * len.powi(4))).sqrt();
    let dt = 0.95 / (e * pi * r * r / d / m).sqrt();

    let out = common::run_script(&read("in.cantilever"), None);
    let (bent, free) = cantilever(&out);
    let k = 1e-5 / bent.last().unwrap().1;
    assert!(
        (k / k_beam - 1.0).abs() < 1e-3,
        "tip stiffness {k} against {k_beam}"
    );
    // The period from the zero crossings of the tip.
    let mut cross = Vec::new();
    for w in free.windows(2) {
        let ((s0, z0), (s1, z1)) = (w[0], w[1]);
        if (z0 > 0.0 && z1 <= 0.0) || (z0 < 0.0 && z1 >= 0.0) {
            cross.push((s0 + (s1 - s0) * (-z0) / (z1 - z0)) * dt);
        }
    }
    assert!(cross.len() >= 6, "{} crossings", cross.len());
    let f = (cross.len() - 1) as f64 / (2.0 * (cross[cross.len() - 1] - cross[0]));
    assert!(
        (f / 32.614 - 1.0).abs() < 1e-4,
        "frequency {f} against the fork's 32.614"
    );
    assert!(
        (f / f_beam - 1.0).abs() < 0.025,
        "frequency {f} against {f_beam}"
    );
}

/// wild/24 (the fork's cantilever tutorial: a mesh pushes the beam's end down, holds,
/// lets go) with a deflection of 2 mm and 1 ms of waiting and of vibration: its
/// `beam.csv` (time, tip x, tip z, kinetic energy every 5e-5 s) follows the fork's to
/// 1e-8 of each column's scale (measured 3e-10).
#[test]
fn wild_24_shortened_follows_the_fork() {
    let Some(dir) = common::wild_case("24_fibers_cantilever_beam", "in.liggghts") else {
        return;
    };
    let mut script = std::fs::read_to_string(dir.join("in.liggghts")).unwrap();
    for (from, to) in [
        (
            "deflection_distance     equal 20.0e-3",
            "deflection_distance     equal 2.0e-3",
        ),
        (
            "wait_time               equal 25.0e-3",
            "wait_time               equal 1.0e-3",
        ),
        (
            "vibrate_time            equal 0.125",
            "vibrate_time            equal 1.0e-3",
        ),
    ] {
        assert!(script.contains(from), "wild/24 changed: no '{from}'");
        script = script.replace(from, to);
    }
    let mesh = std::fs::read_to_string(dir.join("Mesh.stl")).unwrap();
    let (run, _) = common::run_kept_ok("wild24", &script, &[("Mesh.stl", &mesh)], None);
    let parse = |t: &str| -> Vec<Vec<f64>> {
        t.lines()
            .skip(1)
            .map(|l| l.split(',').map(|x| x.trim().parse().unwrap()).collect())
            .collect()
    };
    let got = parse(&std::fs::read_to_string(run.join("beam.csv")).unwrap());
    let want = parse(&read("fibers_wild24_short.csv"));
    common::assert_columns(&got, &want, 0, 1e-8, "beam.csv");
    let _ = std::fs::remove_dir_all(&run);
}

/// Runs `in.block` in a fresh directory on `threads` threads (`ranks` MPI ranks); returns
/// its end state (`final.dump`), thermo rows and "Created N bonds" lines.
fn block(threads: &str, ranks: Option<usize>) -> (String, Vec<Vec<f64>>, Vec<String>) {
    let d = common::scratch_dir("bond-block");
    std::fs::write(d.join("in.block"), read("in.block")).unwrap();
    let out = common::rdem_in(&d, "in.block", ranks)
        .arg("--threads")
        .arg(threads)
        .output()
        .unwrap();
    let text = common::success(threads, &out);
    // The rows of the last table (`step atoms numbonds ke`).
    let rows = common::thermo_rows(&text[text.rfind("Step").unwrap()..]);
    let end = std::fs::read_to_string(d.join("final.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&d);
    let created = text
        .lines()
        .filter(|l| l.starts_with("Created") && l.contains("bonds"))
        .map(str::to_string)
        .collect();
    (end, rows, created)
}

/// A block of 2352 bonded spheres (enough for the bond pass to run on the thread pool)
/// spinning onto a floor, where 620 of its 6524 bonds break: 2 threads give the end
/// state of 1 byte for byte.
#[test]
fn threads_give_the_same_bonded_block() {
    let (one, rows, created) = block("1", None);
    assert_eq!(rows[0][2], 6524.0, "{rows:?}");
    assert_eq!(rows.last().unwrap()[2], 5904.0, "{rows:?}");
    assert_eq!(created, ["Created 6524 bonds at timestep 1"]);
    let (two, _, _) = block("2", None);
    assert!(one == two, "2 threads give another end state");
}

/// The block on 2 and 4 MPI ranks (bonds across the subdomains' faces, each computed on
/// both sides; created on both sides, though the neighbor list holds a pair across two
/// ranks on one of them): the serial "Created N bonds" line, the serial bond count at
/// every output and the serial end
/// state to 1e-10 of each column's scale (measured 6e-12). `create_atoms` numbers the
/// spheres by rank, so the spheres are matched by position.
#[cfg(feature = "mpi")]
#[test]
fn ranks_give_the_serial_bonded_block() {
    if !common::have_mpirun() {
        return;
    }
    let (serial, rows, created) = block("1", None);
    let want = &common::dump_frames(&serial)[0].1;
    let counts = |r: &[Vec<f64>]| r.iter().map(|r| r[2]).collect::<Vec<_>>();
    for ranks in [2, 4] {
        let (end, got_rows, got_created) = block("1", Some(ranks));
        let what = format!("{ranks} ranks");
        assert_eq!(counts(&got_rows), counts(&rows), "{what}: numbonds");
        // Counted once over the ranks (rank 0's own count was printed before).
        assert_eq!(got_created, created, "{what}");
        let got = &common::dump_frames(&end)[0].1;
        assert_eq!(got.len(), want.len(), "{what}");
        for c0 in (1..13).step_by(3) {
            let scale = want
                .iter()
                .flat_map(|r| r[c0..c0 + 3].to_vec())
                .fold(0.0f64, |m, x| m.max(x.abs()));
            for w in want {
                let d2 = |g: &Vec<f64>| (1..4).map(|k| (g[k] - w[k]).powi(2)).sum::<f64>();
                let g = got.iter().min_by(|a, b| d2(a).total_cmp(&d2(b))).unwrap();
                for c in c0..c0 + 3 {
                    assert!(
                        (g[c] - w[c]).abs() <= 1e-10 * scale,
                        "{what}: sphere at {:?} column {c}: {} against {}",
                        &w[1..4],
                        g[c],
                        w[c]
                    );
                }
            }
        }
    }
}

/// Bonded templates (`particletemplate/multiplespheres ... bonded`): 40 fibres of four
/// spheres inserted by `insert/pack` hold 120 bonds, as in the fork (whose run of the
/// same script prints 160 atoms and 120 bonds), each joining two consecutive spheres of
/// a fibre at their template distance 2.5 mm (L₀ to 1e-12); `bonded yes` (spheres closer
/// than r_i + r_j + skin) bonds the same pairs as the explicit list. On two MPI ranks
/// (the box cut at z = 25 mm, which 4 of the 120 bonds cross as they are inserted,
/// measured), each rank makes the sides of the spheres it holds, knowing the other's
/// tag: the same tags, bonds, lengths and thermo rows as one rank.
#[test]
fn bonded_templates_make_their_bonds() {
    let mut runs = vec![None];
    if common::have_mpirun() {
        runs.push(Some(2));
    }
    let mut serial = Vec::new();
    for (bonded, ranks) in ["yes/explicit", "yes"]
        .into_iter()
        .flat_map(|b| runs.iter().map(move |&r| (b, r)))
    {
        let script = with_vars("in.template", &[("bonded", bonded)]);
        let (dir, out) = common::run_kept_ok("bond_template", &script, &[], ranks);
        if ranks.is_some() {
            assert!(out.contains("1 by 1 by 2 MPI processor grid"), "{out}");
        }
        let rows = common::thermo_rows(&out[out.rfind("Step").unwrap()..]);
        let last = rows.last().unwrap();
        assert_eq!((last[1], last[2]), (160.0, 120.0), "{bonded}: {out}");
        let bonds = common::dump_frames(&std::fs::read_to_string(dir.join("bonds.txt")).unwrap());
        let (_, rows) = bonds.last().unwrap();
        assert_eq!(rows.len(), 120, "{bonded}");
        for r in rows {
            assert_eq!(r[1], r[0] + 1.0, "{bonded}: bond {} {}", r[0], r[1]);
            assert!(
                (r[2] - 0.0025).abs() < 1e-12 * 0.0025,
                "{bonded}: L0 {}",
                r[2]
            );
        }
        let mut pairs: Vec<(u64, u64)> = rows.iter().map(|r| (r[0] as u64, r[1] as u64)).collect();
        pairs.sort_unstable();
        let all_rows = common::thermo_rows(&out[out.rfind("Step").unwrap()..]);
        match ranks {
            None => serial.push((pairs, all_rows)),
            Some(_) => {
                let (want_pairs, want_rows) = serial.last().unwrap();
                assert_eq!(&pairs, want_pairs, "{bonded}: 2 ranks");
                common::assert_columns(&all_rows, want_rows, 1, 1e-10, "2 ranks");
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// `disableNormalContact`: two spheres bonded while they overlap by 0.1 mm, then pushed
/// together. With 0 their contact pushes back, as in the fork; with 1 the bonded pair has
/// no contact at all and they pass through each other, as in the fork. The rows
/// (distance and force on the second sphere every 50 steps) follow the fork's to 1e-9 of
/// each column's scale. (Beyond step 1450 of this script the fork drops the bond's force
/// while still counting the bond, with the spheres 16.8 mm apart in a 20 mm box; rdem
/// keeps it: not compared.)
#[test]
fn disable_normal_contact_leaves_bonded_pairs_without_contact() {
    for dnc in ["0", "1"] {
        let out = common::run_script(&with_vars("in.contact", &[("dnc", dnc)]), None);
        let got = common::thermo_rows(&out[out.rfind("Step").unwrap()..]);
        let want = table(&format!("fibers_contact{dnc}.txt"));
        common::assert_columns(&got, &want, 1, 1e-9, &format!("disableNormalContact {dnc}"));
    }
}

/// LIGGGHTS-PFM's form of `bond_coeff` (`ro ri lb Sn St Sben Stor damp bn bt`): the three
/// pairs of `in.pfm` (bonded at rest, then set moving) follow LIGGGHTS-PFM 24.01 (built
/// here) every 50 of 1000 steps, with the FENE factor strong (bn 2.5 and 3 mm against
/// pair lengths of 1.6–2 mm), pairs squeezed (lb 0.98, no damping) and stretched
/// (lb 1.02, damping ratio 0.5). Measured: 2e-10 and 1e-11 of each column's scale.
#[test]
fn pfm_bonds_follow_liggghts_pfm() {
    for (name, lb, damp, bn) in [
        ("f0", "0.98", "0", "0.0025"),
        ("f3", "1.02", "0.5", "0.003"),
    ] {
        let script = with_vars(
            "in.pfm",
            &[
                ("lb", lb),
                ("damp", damp),
                ("bn", bn),
                ("bt", "0"),
                ("nrun", "1000"),
                ("de", "50"),
            ],
        );
        assert_follows_dump(
            &script,
            "Created 3 bonds at timestep 1",
            &format!("pfm_{name}.dump"),
            1e-8,
            name,
        );
    }
}

/// Break style 0 (`0 r_b`: the bond breaks when the centres are farther apart than
/// 2 r_b), in LIGGGHTS-PFM's form: a pair bonded at 1.8005 mm with L₀ = 1.0005·1.8 mm is
/// pushed apart by its bond and breaks past 2 r_b = 1.8006 mm: free from step 7 and
/// `numbond` 0 from step 152, as in LIGGGHTS-PFM; its 401 rows within 1e-12 of the
/// fork's (measured 1e-15). (LIGGGHTS_Flexible_Fibers stops with "ERROR: broken" where
/// such a bond breaks; its manual describes the style as PFM runs it.)
#[test]
fn break_style_0_breaks_apart_beyond_twice_the_radius() {
    let out = common::run_script(&read("in.pfm_pull"), None);
    let got = pull_rows(&out, "numbond");
    let want = table("pfm_pull.txt");
    common::assert_columns(&got, &want, 1, 1e-12, "break style 0");
    let first_free = got.iter().skip(1).find(|r| r[5] == 0.5).map(|r| r[0]);
    assert_eq!(first_free, Some(7.0));
    let first_zero = got.iter().find(|r| r[1] == 0.0).map(|r| r[0]);
    assert_eq!(first_zero, Some(152.0));
}

/// The thermo rows of every run of a screen output whose header is `header`, in order.
fn all_rows(out: &str, header: &str) -> Vec<Vec<f64>> {
    out.split(header)
        .skip(1)
        .flat_map(|run| pull_rows(&format!("{header}{run}"), header))
        .collect()
}

/// Break styles 3 to 5 (`in.soft`): two bonded spheres that overlap by 0.11 mm are
/// thrown at each other; the bond breaks by its normal stress at step 25 while they
/// still overlap, leaves `numbonds` at once, and pushes them apart until they separate:
/// weakly (style 3, force-free from step 1405), with the bond's stiffness from the
/// length at the break (style 4, from step 105) or by Hertz (style 5, from step 635);
/// style 4 also with the pair contact on (`disableNormalContact 0`: the bond breaks at
/// step 30, free from step 450). Each of the 401 rows (numbonds, position, velocity,
/// force and spin of the second sphere) within 1e-12 of its column's scale of the fork's
/// (measured 1.2e-14).
#[test]
fn bonds_broken_while_overlapping_push_apart_as_the_forks() {
    for (style, dnc, name, broken, free) in [
        ("3", "1", "fibers_soft3.txt", 25.0, 1405.0),
        ("4", "1", "fibers_soft4.txt", 25.0, 105.0),
        ("5", "1", "fibers_soft5.txt", 25.0, 635.0),
        ("4", "0", "fibers_soft4_contact.txt", 30.0, 450.0),
    ] {
        let out = common::run_script(
            &with_vars("in.soft", &[("bstyle", style), ("dnc", dnc)]),
            None,
        );
        let got = pull_rows(&out, "Step numbonds");
        common::assert_columns(&got, &table(name), 1, 1e-12, name);
        let first_zero = got.iter().find(|r| r[1] == 0.0).map(|r| r[0]);
        assert_eq!(first_zero, Some(broken), "{name}");
        let first_free = got.iter().find(|r| r[5] == 0.0).map(|r| r[0]);
        assert_eq!(first_free, Some(free), "{name}");
    }
}

/// Break style 2 (`in.hot`): a bonded pair pulled gently apart holds at 300 K (T_break
/// 500) for 20 steps; `set` raises the second sphere to 800 K and the bond breaks at the
/// next run's set-up (step 21): free from step 22, `numbonds` 0 from the re-neighboring
/// at step 163, as in the fork; the 222 rows within 1e-12 of the fork's (measured
/// 4e-15). Without a per-particle `Temp` the run stops with the reason.
#[test]
fn break_style_2_breaks_by_temperature_as_the_fork() {
    let out = common::run_script(&read("in.hot"), None);
    let got = all_rows(&out, "Step numbonds");
    common::assert_columns(&got, &table("fibers_hot.txt"), 1, 1e-12, "break style 2");
    let first_free = got.iter().skip(1).find(|r| r[5] == 0.5).map(|r| r[0]);
    assert_eq!(first_free, Some(22.0));
    let first_zero = got.iter().find(|r| r[1] == 0.0).map(|r| r[0]);
    assert_eq!(first_zero, Some(163.0));

    let cold = read("in.hot").replace("fix temp all property/atom Temp scalar yes no no 300\n", "");
    let out = common::run_script_raw(&cold, None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("break style 2") && err.contains("temperature 'Temp'"),
        "{err}"
    );
    // Styles 3 to 5 are Flexible_Fibers' only; style 5 takes ν = Y/(2G) − 1 in (−1, 1).
    for (coeff, says) in [
        (
            "bond_coeff 1 1.0 0.0 1.0 1.0e9 4.0e8 1.0e9 4.0e8 0.2 2.0 0.0 3 1.0e9 1.0e9",
            "unknown break style 3 in LIGGGHTS-PFM's form",
        ),
        (
            "bond_coeff 1 1.0 0.0 1.0e9 1.0e8 1 0.2 5 1.0e9 1.0e9",
            "must lie within (-1, 1)",
        ),
        (
            "bond_coeff 1 1.0 0.0 1.0e9 4.0e8 1 0.2 6 1.0e9 1.0e9",
            "unknown break style 6",
        ),
    ] {
        let bad = read("in.hot").replace(
            "bond_coeff 1 1.0 0.0 1.0e9 4.0e8 1 0.2 2 1.0e9 1.0e9 500",
            coeff,
        );
        let out = common::run_script_raw(&bad, None);
        let err = String::from_utf8_lossy(&out.stderr).replace('\n', " ");
        assert!(
            !out.status.success() && err.contains(says),
            "{coeff}: {err}"
        );
    }
}

/// A half cylinder of radius 1.5 and length 3 (mm) along y, as the fork's test_suite
/// meshes are made: the flat base (2 triangles), then 19 facets of 2 triangles from x > 0
/// round to x < 0 (without end caps, which the fiber never reaches), its curved side up,
/// or down when `flip` (turned half a turn about y). Vertices written to 7 digits.
fn half_cylinder_mm(flip: bool) -> String {
    let s = if flip { -1.0 } else { 1.0 };
    let mut out = String::from("solid rod\n");
    let mut tri = |c: [[f64; 3]; 3]| {
        out += "facet normal 0 0 0\nouter loop\n";
        for v in c {
            out += &format!("vertex {:.6e} {:.6e} {:.6e}\n", s * v[0], v[1], s * v[2]);
        }
        out += "endloop\nendfacet\n";
    };
    let at = |k: usize, y: f64| {
        let a = std::f64::consts::PI * k as f64 / 19.0;
        [1.5 * a.cos(), y, 1.5 * a.sin()]
    };
    tri([[1.5, 1.5, 0.0], [1.5, -1.5, 0.0], [-1.5, 1.5, 0.0]]);
    tri([[-1.5, 1.5, 0.0], [1.5, -1.5, 0.0], [-1.5, -1.5, 0.0]]);
    for k in 0..19 {
        tri([at(k, -1.5), at(k, 1.5), at(k + 1, 1.5)]);
        tri([at(k, -1.5), at(k + 1, 1.5), at(k + 1, -1.5)]);
    }
    out + "endsolid rod\n"
}

/// The stiffness of a three-point bending test as Flexible_Fibers' test_suite measures
/// it: the least-squares slope of the plunger's force against its depth over the samples
/// where it presses down (depth rising faster than 0.002 m/s, by numpy's `gradient`) with
/// a positive force.
fn bending_slope(csv: &str) -> f64 {
    let rows: Vec<[f64; 3]> = csv
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            [v[0], -v[1], v[2]]
        })
        .collect();
    let n = rows.len();
    let rate = |k: usize| {
        let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
        (rows[b][1] - rows[a][1]) / (rows[b][0] - rows[a][0])
    };
    let pts: Vec<(f64, f64)> = (0..n)
        .filter(|&k| rate(k) > 0.002 && rows[k][2] > 0.0)
        .map(|k| (rows[k][1], rows[k][2]))
        .collect();
    let m = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (sxx, sxy) = pts
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.0 * p.0, a.1 + p.0 * p.1));
    (m * sxy - sx * sy) / (m * sxx - sx * sx)
}

/// Flexible_Fibers' test_suite/3_point_bending (`in.three_point`, written from its
/// description, with the fork's half-cylinder meshes rebuilt by [`half_cylinder_mm`]): a
/// 20-sphere fiber on two rods pressed in its middle. The stiffness 16.647 N/m of the
/// fork's truth file within 0.1 %; measured 16.6509. The fork built here gives 16.64693
/// both on its own script and meshes and on this script with these meshes. The fiber
/// rests on faceted rods, so this holds only with the edge contacts that LIGGGHTS counts
/// (with rdem's earlier rule the fiber slid through its supports at 0.5 s and a bonded
/// sphere was lost).
#[test]
fn three_point_bending_has_the_forks_stiffness() {
    let (dir, out) = common::run_kept(
        "three_point",
        &read("in.three_point"),
        &[
            ("rod.stl", &half_cylinder_mm(false)),
            ("plunger.stl", &half_cylinder_mm(true)),
        ],
        None,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    // Every sphere and bond kept to the end.
    let last = common::thermo_rows(&text).pop().unwrap();
    assert_eq!((last[1], last[2]), (20.0, 19.0), "{last:?}");
    let slope = bending_slope(&std::fs::read_to_string(dir.join("post/bending.csv")).unwrap());
    eprintln!("three-point bending stiffness {slope}");
    assert!((slope / 16.64693 - 1.0).abs() < 1e-3, "{slope}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Flexible_Fibers' test_suite/bond_break as a replay (`in.fibre_drop`): its ten
/// five-sphere fibres, at the places where the fork's insertion put them, bonded by
/// `doNorm yes`, thrown onto the floor at 5 m/s with break style 5. Bonds break by stress
/// and where a sphere comes within 0.75 radius of the box's floor face (the fork's rule);
/// two spheres leave the box. Atoms and `numbonds` equal the fork's at each of the 43
/// thermo rows (40 bonds, 24 at step 14000, 11 from step 22000; 48 atoms at the end),
/// the kinetic energy within 1e-8 of its scale (measured 5e-10, the fork's printed
/// digits). Without the box-face rule 30 bonds were left.
#[test]
fn a_fibre_drop_breaks_its_bonds_as_the_fork() {
    let out = common::run_script(&read("in.fibre_drop"), None);
    // The creation's line comes inside the first run's table.
    let table: String = out
        .lines()
        .filter(|l| !l.starts_with("Created"))
        .map(|l| format!("{l}\n"))
        .collect();
    let got = common::thermo_rows(&table);
    let want = common::reference_rows(&data().join("fibers_fibre_drop.txt"));
    assert_eq!(got.len(), want.len(), "{out}");
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(&g[..3], &w[..3], "step, atoms, numbonds");
    }
    common::assert_columns(&got, &want, 3, 1e-8, "fibre drop");
}

/// wild/06 (CFDEMcoupling-PFM's red blood cell: a ring of ten spheres of one bonded
/// template placed by insert/pack's `pos`, LIGGGHTS-PFM's `bond_coeff`, `neigh_modify
/// exclude molecule all`), shortened to 1000 + 2000 steps: ten spheres, ten bonds, one
/// molecule, no pair in the neighbor list (the ring's spheres overlap, all of one
/// molecule), and the dump's forces equal LIGGGHTS-PFM's to its six digits; the ring's
/// shape (positions about its centre) too. The ring's centre differs by 4e-3 µm: rdem
/// places a template by its Monte Carlo centre of mass, LIGGGHTS-PFM by a bounding
/// sphere's centre.
#[test]
fn wild_06_shortened_holds_the_forks_ring() {
    let Some(src) = common::wild_case("06_cfdem_rbc_bonds_init", "DEM/in.liggghts_init") else {
        return;
    };
    let top = common::scratch_dir("wild06");
    common::copy_dir(&src, &top);
    let dem = top.join("DEM");
    let script = std::fs::read_to_string(dem.join("in.liggghts_init")).unwrap();
    assert!(script.contains("run\t\t100000"), "wild/06 changed");
    std::fs::write(
        dem.join("in.short"),
        script.replace("run\t\t100000", "run 2000"),
    )
    .unwrap();
    let out = common::rdem_in(&dem, "in.short", None)
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    let out = common::success("wild06", &out);
    assert!(out.contains("Total # of neighbors = 0"), "{out}");
    let rows = |t: &str| -> Vec<Vec<f64>> {
        let mut v: Vec<Vec<f64>> = t
            .split("ITEM: ATOMS")
            .nth(1)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect();
        v.sort_by(|a, b| a[0].total_cmp(&b[0]));
        v
    };
    let got = rows(&std::fs::read_to_string(dem.join("post/dump3000.liggghts")).unwrap());
    let want = rows(&format!("ITEM: ATOMS\n{}", read("pfm_wild06_dump3000.txt")));
    assert_eq!(got.len(), 10);
    let centre = |r: &[Vec<f64>], c: usize| r.iter().map(|x| x[c]).sum::<f64>() / r.len() as f64;
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g[..3], w[..3], "id, mol, type");
        for c in 3..6 {
            let (gc, wc) = (g[c] - centre(&got, c), w[c] - centre(&want, c));
            assert!(
                (gc - wc).abs() < 1e-3,
                "atom {} column {c}: {gc} against {wc}",
                g[0]
            );
        }
        for c in 9..12 {
            assert!(
                (g[c] - w[c]).abs() <= 1e-5 * w[c].abs() + 1e-11,
                "atom {} force column {c}: {} against the fork's {}",
                g[0],
                g[c],
                w[c]
            );
        }
    }
    let last = out
        .lines()
        .rfind(|l| l.trim_start().starts_with("3000"))
        .unwrap();
    assert_eq!(
        last.split_whitespace().collect::<Vec<_>>(),
        ["3000", "10", "10"]
    );
    let _ = std::fs::remove_dir_all(&top);
}

/// Spheres of one molecule (`in.molecule`): as in the fork's pair style, a sphere
/// closer to a sphere of its molecule that holds a bond than half their radii sum has
/// no contact with it. Sphere 3, 0.8 mm from bonded sphere 2 (radii 1 mm), moves off
/// at 0.5 m/s untouched until the pair is 1 mm apart (step 390, as the fork), then is
/// pushed; sphere 4, 1.2 mm from bonded sphere 1, is pushed from the first step. The
/// 151 rows agree with the fork's within 1e-10 of the column scale (measured 2e-12).
#[test]
fn spheres_of_one_molecule_deeper_than_half_have_no_contact_as_the_fork() {
    let out = common::run_script(&read("in.molecule"), None);
    let got = pull_rows(&out, "Step numbonds");
    common::assert_columns(&got, &table("fibers_molecule.txt"), 1, 1e-10, "molecule");
    let first_pushed = got.iter().find(|r| r[3] != 0.5).map(|r| r[0]);
    assert_eq!(first_pushed, Some(390.0));
    assert!(
        got[1][6] < -0.03,
        "sphere 4 is pushed at once: {:?}",
        got[1]
    );
}

/// The rows of `width` numbers of the last thermo table headed by `header`, skipping
/// the "Created N bonds" lines within it.
fn rows_of_width(out: &str, header: &str, width: usize) -> Vec<Vec<f64>> {
    let tail = out.rsplit(header).next().unwrap();
    tail.lines()
        .skip(1)
        .take_while(|l| !l.starts_with("Loop time"))
        .filter_map(|l| {
            let v: Vec<f64> = l.split_whitespace().map_while(|x| x.parse().ok()).collect();
            (v.len() == width && l.split_whitespace().count() == width).then_some(v)
        })
        .collect()
}

/// `iparam` and `jparam` of `fix bond/create/gran` (`in.limit`): spheres of type 1 take
/// at most 2 bonds of the creator's type, those of type 2 at most 1. Two rows of
/// touching spheres bond all 11 pairs at the first creation, the limits counted at the
/// step's start, as in the fork; a lone sphere of type 1 with one bond then bonds with a
/// passing sphere of type 2 (step 700: 12 bonds) and not with the next one (13 without
/// the limits, in the fork too). With `newtype` 3 and 4 the spheres turn into those
/// types as each new bond brings them to their limit, by their type at that moment;
/// with 1 and 2 they keep their types. `numbonds` and eight spheres' types equal the
/// fork's at each of the 31 rows, for both.
#[test]
fn bond_creation_limits_and_new_types_as_the_fork() {
    for (inew, jnew, name) in [
        ("3", "4", "fibers_limit34.txt"),
        ("1", "2", "fibers_limit12.txt"),
    ] {
        let out = common::run_script(
            &with_vars("in.limit", &[("inew", inew), ("jnew", jnew)]),
            None,
        );
        let got = rows_of_width(&out, "Step numbonds", 10);
        assert_eq!(got, table(name), "{name}");
    }
    let bad = read("in.limit").replace("1 2 0.00105 1 6 iparam", "1 1 0.00105 1 6 iparam");
    let out = common::run_script_raw(&bad, None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("inconsistent iparam and jparam"), "{err}");
}

/// `prob fraction seed` of `fix bond/create/gran` (`in.prob`, 7080 neighbour pairs): a
/// pair bonds when the mean of its spheres' draws is below the fraction, so 2f² of the
/// pairs for f ≤ 1/2: 566 for f = 0.2 and 3540 for f = 0.5. rdem's draws are its own
/// (a hash of seed, tag and step); over seeds 1 and 2 it makes 545 and 596, 3413 and
/// 3649 bonds: means within 3 % of those figures (each draw is shared by a sphere's four
/// pairs, so one run scatters by about 40 and 120). The fork over three seeds made 573,
/// 601, 494 and 3589, 3506, 3410. f = 1 bonds every pair.
#[test]
fn bond_creation_probability_bonds_the_forks_share_of_pairs() {
    let bonds = |frac: &str, seed: &str| {
        let out = common::run_script(
            &with_vars("in.prob", &[("frac", frac), ("seed", seed)]),
            None,
        );
        rows_of_width(&out, "Step Atoms numbonds", 3)[1][2]
    };
    for (frac, want) in [("0.2", 7080.0 * 2.0 * 0.04), ("0.5", 7080.0 * 0.5)] {
        let mean = (bonds(frac, "1") + bonds(frac, "2")) / 2.0;
        assert!(
            (mean - want).abs() < 0.03 * want,
            "f = {frac}: {mean} against {want}"
        );
    }
    assert_eq!(bonds("1.0", "1"), 7080.0);
}

/// The box-face rule in LIGGGHTS-PFM's form (`in.pfm_face`): a bonded pair thrown at
/// 5 m/s towards the box's upper x face breaks, without acting, once a sphere's centre
/// is within the neighbor skin of it (skin 2 mm: between steps 970 and 980, as the
/// fork; `numbond` 0 from the re-neighboring at step 1210); with a skin of 0.5 mm no
/// centre gets that close before a wall plane turns the pair back, and the bond holds.
/// Both runs' 182 rows within 1e-10 of the fork's column scale (measured 2e-14); the
/// fork (LIGGGHTS-PFM d075b97) takes the skin where Flexible_Fibers takes 0.75 R.
#[test]
fn pfm_bonds_break_within_the_skin_of_a_box_face() {
    for (skin, name) in [("0.002", "pfm_face.txt"), ("0.0005", "pfm_face_small.txt")] {
        let out = common::run_script(&with_vars("in.pfm_face", &[("skin", skin)]), None);
        let got = rows_of_width(&out, "v2             y2", 7);
        common::assert_columns(&got, &table(name), 1, 1e-10, name);
        // Free (constant velocity) from the break on.
        let free = got.windows(2).find(|w| w[0][3] == w[1][3]).map(|w| w[0][0]);
        let bonds = got.last().unwrap()[1];
        if skin == "0.002" {
            assert_eq!((free, bonds), (Some(980.0), 0.0), "{name}");
        } else {
            assert_eq!((free, bonds), (None, 1.0), "{name}");
        }
    }
}

/// `disableNormalContact 1` after a bond of break style 3 leaves (`in.gone`): two
/// spheres bonded 0.1 mm apart and thrown together break the bond by its normal stress
/// within the first 10 steps, before they touch; the bond leaves at once (`numbonds` 0
/// at step 10) and the pair collides from step 170 with its contact, as in the fork,
/// long before the next re-neighboring (skin 2 mm). The 162 rows within 1e-10 of the
/// fork's column scale (measured 1e-16); before, the pair stayed out of the neighbor
/// list until that re-neighboring and passed through itself.
#[test]
fn a_bond_that_leaves_gives_the_contact_back_at_once() {
    let out = common::run_script(&read("in.gone"), None);
    let got = rows_of_width(&out, "numbonds             x2", 5);
    common::assert_columns(&got, &table("fibers_gone.txt"), 1, 1e-10, "gone");
    let free = got.iter().find(|r| r[1] == 0.0).map(|r| r[0]);
    let first_touch = got
        .iter()
        .skip_while(|r| r[1] != 0.0)
        .find(|r| r[4] != 0.0)
        .map(|r| r[0]);
    assert_eq!((free, first_touch), (Some(10.0), Some(170.0)));
}

/// Runs `in.pfm_data` (with `vars` set first and `extra` appended) on `ranks` MPI
/// ranks; returns the directory (kept) and the screen output.
fn pfm_data(vars: &[(&str, &str)], extra: &str, ranks: Option<usize>) -> (PathBuf, String) {
    let mut script = with_vars("in.pfm_data", vars);
    if ranks.is_some() {
        script = script.replace(
            "read_data pairs.data",
            "processors 2 1 1\nread_data pairs.data",
        );
    }
    script.push_str(extra);
    common::run_kept_ok(
        "bond_gran_data",
        &script,
        &[("pairs.data", &read("pairs.data"))],
        ranks,
    )
}

/// Dump frames: (step, rows).
type Frames = Vec<(u64, Vec<Vec<f64>>)>;

/// The frames of a dump of `id mol x y z ...`: the (id, molecule ID) rows of the first
/// frame, and the frames without the molecule IDs.
fn frames_and_molecules(text: &str) -> (Vec<Vec<f64>>, Frames) {
    let mut frames = common::dump_frames(text);
    let mol = frames[0].1.iter().map(|r| r[..2].to_vec()).collect();
    for f in &mut frames {
        for r in &mut f.1 {
            r.remove(1);
        }
    }
    (mol, frames)
}

/// `read_data` of a data file of `atom_style hybrid granular bond/gran` (atom lines
/// `id type x y z diameter density molecule`, a `Velocities` and a `Bonds` section)
/// and `delete_bonds`, against LIGGGHTS-PFM 24.01 (built here) running `in.pfm_data`:
/// the bond of atom 7 (type 2) to atom 1 removed (`delete_bonds all atom 2 remove`,
/// then atom 7 deleted) or turned off (`delete_bonds all atom 2`, atom 7 kept). The
/// molecule IDs equal the file's, every sphere follows the fork's every 50 of 1000
/// steps within 1e-8 of each column's scale (measured 2e-10), `numbond` and the counts
/// `delete_bonds` prints equal the fork's, and `compute property/local` lists the three
/// bonds turned on with the fork's forces (the fork also lists the turned-off one, with
/// its type negative and the force of the bond listed before it; rdem leaves it out).
#[test]
fn read_data_bonds_and_delete_bonds_follow_liggghts_pfm() {
    for (name, rm, gone, counts, numbond) in [
        (
            "remove",
            "remove",
            "1",
            "3 total bonds, 3 turned on, 0 turned off",
            3.0,
        ),
        (
            "off",
            "",
            "0",
            "4 total bonds, 3 turned on, 1 turned off",
            4.0,
        ),
    ] {
        let (dir, out) = pfm_data(&[("rm", rm), ("gone", gone)], "", None);
        assert!(out.contains("  7 velocities\n  4 bonds\n"), "{name}: {out}");
        assert!(
            out.contains(&format!("Deleting bonds ...\n  {counts}\n")),
            "{name}: {out}"
        );
        let rows = common::thermo_rows(&out);
        assert_eq!(rows.len(), 11, "{name}: {out}");
        assert!(rows.iter().all(|r| r[2] == numbond), "{name}: {rows:?}");
        let (mol, got) =
            frames_and_molecules(&std::fs::read_to_string(dir.join("atoms.txt")).unwrap());
        let (want_mol, want) = frames_and_molecules(&read(&format!("pfm_data_{name}.dump")));
        assert_eq!(mol, want_mol, "{name}: molecule IDs");
        assert_frames(&got, &want, 1e-8, name);
        let bonds = common::dump_frames(&std::fs::read_to_string(dir.join("bonds.txt")).unwrap());
        let last = &bonds.last().unwrap().1;
        // The fork's rows at step 1000 (its dump rounds to 6 digits).
        let want = [
            [1.0, 2.0, 1.0, 0.16087, -0.00019938, 0.000150347],
            [3.0, 4.0, 1.0, 0.0482615, 0.0336814, 0.0120287],
            [5.0, 6.0, 1.0, -1.75872e-06, 8.14418e-05, -0.0620375],
        ];
        assert_eq!(last.len(), 3, "{name}: {last:?}");
        for (g, w) in last.iter().zip(want) {
            assert_eq!(g.as_slice(), w.as_slice(), "{name}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// `delete_bonds ... undo` turns a bond on again (atom 7, 4 cm from atom 1, is then
/// pulled towards it), `remove` drops every bond turned off before, and `stats`
/// changes nothing.
#[test]
fn delete_bonds_undo_remove_and_stats() {
    let ke = |extra: &str| {
        let (dir, out) = pfm_data(&[("rm", ""), ("gone", "0")], extra, None);
        let _ = std::fs::remove_dir_all(&dir);
        (out.clone(), common::thermo_rows(&out).last().unwrap()[3])
    };
    let (out, on) = ke("delete_bonds all atom 2 undo\nrun 10\n");
    assert!(
        out.contains("Deleting bonds ...\n  4 total bonds, 4 turned on, 0 turned off\n"),
        "{out}"
    );
    let (_, off) = ke("run 10\n");
    // Off: the three pairs alone (3.32e-6 J); on: atom 7 pulled towards atom 1.
    assert!((off - 3.3191775e-06).abs() < 1e-12, "{off}");
    assert!(on > 3.0 * off, "the bond 1-7 pulls: {on} against {off}");
    // Nothing selected in group dummy (atom 7 alone), yet `remove` drops the bond 1-7
    // turned off before; `undo` finds nothing to turn on; `multi` turns all off.
    let later = "delete_bonds all stats\ndelete_bonds dummy multi remove\n\
                 delete_bonds all multi undo\ndelete_bonds all multi\n";
    let (dir, out) = pfm_data(&[("rm", ""), ("gone", "0")], later, None);
    let tail = out.rsplit("Dangerous builds").next().unwrap();
    let want = [
        "4 total bonds, 3 turned on, 1 turned off",
        "3 total bonds, 3 turned on, 0 turned off",
        "3 total bonds, 3 turned on, 0 turned off",
        "3 total bonds, 0 turned on, 3 turned off",
    ]
    .map(|c| format!("Deleting bonds ...\n  {c}\n"))
    .concat();
    assert!(tail.contains(&want), "{tail}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `read_data` with bonds and `delete_bonds` on two MPI ranks (`processors 2 1 1`:
/// the bond 1-7 joins spheres of different ranks) give the serial run's dump.
#[test]
fn read_data_bonds_on_two_ranks_give_the_serial_run() {
    if !common::have_mpirun() {
        eprintln!("skipped: no mpirun");
        return;
    }
    for (rm, gone) in [("remove", "1"), ("", "0")] {
        let vars = [("rm", rm), ("gone", gone)];
        let (d1, _) = pfm_data(&vars, "", None);
        let (d2, out) = pfm_data(&vars, "", Some(2));
        assert!(out.contains("Deleting bonds"), "{out}");
        for f in ["atoms.txt", "bonds.txt"] {
            let a = std::fs::read_to_string(d1.join(f)).unwrap();
            let b = std::fs::read_to_string(d2.join(f)).unwrap();
            assert_eq!(a, b, "{f} with rm '{rm}'");
        }
        let _ = std::fs::remove_dir_all(&d1);
        let _ = std::fs::remove_dir_all(&d2);
    }
}

/// `write_data` under `hybrid granular bond/gran` writes the hybrid columns with the
/// molecule IDs and the bonds turned on (LIGGGHTS-PFM 24.01 reads the file back and
/// runs on), and `read_data` reads it back: the same particles and bonds.
#[test]
fn write_data_keeps_molecules_and_bonds() {
    let (dir, out) = pfm_data(&[("rm", ""), ("gone", "0")], "write_data back.data\n", None);
    assert!(out.contains("Deleting bonds"), "{out}");
    let text = std::fs::read_to_string(dir.join("back.data")).unwrap();
    assert!(
        text.contains("\n7 atoms\n2 atom types\n3 bonds\n1 bond types\n"),
        "{text}"
    );
    assert!(
        text.ends_with("\nBonds\n\n1 1 1 2\n2 1 3 4\n3 1 5 6\n"),
        "{text}"
    );
    let atoms: Vec<Vec<&str>> = text
        .split("\nAtoms\n\n")
        .nth(1)
        .unwrap()
        .lines()
        .take_while(|l| !l.is_empty())
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(atoms.len(), 7);
    // id type x y z diameter density molecule ix iy iz
    assert!(atoms.iter().all(|a| a.len() == 11), "{atoms:?}");
    let mols: Vec<&str> = atoms.iter().map(|a| a[7]).collect();
    assert_eq!(mols, ["1", "1", "2", "2", "3", "3", "4"]);
    assert_eq!((atoms[3][5], atoms[3][6]), ("0.0012", "1500"));
    let back = read("in.pfm_data")
        .replace("read_data pairs.data", "read_data back.data")
        .replace("delete_bonds all atom 2 ${rm}\n", "")
        .replace("run 1000", "run 0\nwrite_data again.data");
    let script = format!("variable rm index \"\"\nvariable gone index 0\n{back}");
    std::fs::write(dir.join("in.back"), script).unwrap();
    let o = common::rdem_in(&dir, "in.back", None).output().unwrap();
    let o = common::success("read back", &o);
    assert!(o.contains("  7 atoms\n  7 velocities\n  3 bonds\n"), "{o}");
    let again = std::fs::read_to_string(dir.join("again.data")).unwrap();
    let body = |t: &str| t.split_once('\n').unwrap().1.to_string();
    assert_eq!(body(&again), body(&text));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `read_data` refuses what the atom style cannot hold, each error pointing at the
/// file's line: more bonds on an atom than `bonds_per_atom`, a bond type beyond
/// `n_bondtypes`, bonds under `atom_style granular`, and plain `atom_style bond/gran`
/// (whose lines have no diameter).
#[test]
fn read_data_refuses_bonds_the_style_cannot_hold() {
    let data = read("pairs.data");
    let script = read("in.pfm_data");
    for (what, s, d, msg) in [
        (
            "per atom",
            script.replace("bonds_per_atom 6", "bonds_per_atom 1"),
            data.clone(),
            "atom 1 has more than the atom style's bonds_per_atom = 1 bonds",
        ),
        (
            "types",
            script.clone(),
            data.replace("1 bond types", "2 bond types")
                .replace("4 1 7 1\n", "4 2 7 1\n"),
            "bond 4 has type 2, beyond the atom style's n_bondtypes 1",
        ),
        (
            "granular",
            script.replace(
                "atom_style hybrid granular bond/gran n_bondtypes 1 bonds_per_atom 6",
                "atom_style granular",
            ),
            data.clone(),
            "'bonds' is not supported by atom_style",
        ),
        (
            "plain",
            script.replace(
                "atom_style hybrid granular bond/gran",
                "atom_style bond/gran",
            ),
            data.clone(),
            "use atom_style hybrid granular bond/gran",
        ),
        (
            "missing atom",
            script.clone(),
            data.replace("4 1 7 1\n", "4 1 8 1\n"),
            "atom-ID 8 is not in the Atoms section",
        ),
    ] {
        let s = format!("variable rm index \"\"\nvariable gone index 0\n{s}");
        let (dir, out) = common::run_kept("bond_gran_bad", &s, &[("pairs.data", &d)], None);
        assert!(!out.status.success(), "{what}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(msg), "{what}: {err}");
        assert!(err.contains("read_data pairs.data"), "{what}: {err}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

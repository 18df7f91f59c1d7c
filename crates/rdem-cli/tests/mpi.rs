//! MPI runs (feature `mpi`): the same script on 1, 2 and 4 ranks (`mpirun --oversubscribe`)
//! against the serial binary run without mpirun. Skipped, with a note, when `mpirun` is
//! not installed.
#![cfg(feature = "mpi")]

use crate::common;

use std::path::Path;

use common::have_mpirun;

/// Runs `script` in a fresh directory, serially (`ranks == 0`, no mpirun) or on `ranks`
/// MPI ranks, with one thread per rank; returns the screen output.
fn run(script: &str, ranks: usize) -> String {
    common::run_script(script, (ranks > 0).then_some(ranks))
}

/// The numbers of the last thermo row.
fn last_row(out: &str) -> Vec<f64> {
    common::thermo_rows(out).pop().expect("a thermo row")
}

/// The processor grid line.
fn grid(out: &str) -> String {
    out.lines()
        .find(|l| l.contains("MPI processor grid"))
        .unwrap()
        .trim()
        .to_string()
}

fn assert_close(a: &[f64], b: &[f64], rel: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let scale = x.abs().max(y.abs()).max(1e-300);
        assert!(
            (x - y).abs() <= rel * scale,
            "{what}: column {k}: {x} vs {y} (relative {:e})",
            (x - y).abs() / scale
        );
    }
}

/// The common head of the small scripts: a box 0.1 long in x (periodic) and 0.02 in y
/// and z, split along x by the default grid, Hertz with tangential history.
const HEAD: &str = "\
atom_style granular
atom_modify map array
boundary p f f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.02 0 0.02 units box
create_box 1 reg
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.000005
fix integr all nve/sphere
";

/// Full-precision thermo numbers (after `thermo_style`, which resets them).
const FORMAT: &str = "thermo_modify format float %24.17g\n";

/// Two oblique impacts with spin, one across the inner faces of the subdomains
/// (x = 0.05, and 0.025/0.075 with four ranks) and one across the periodic face x = 0,
/// end in the same state on 1, 2 and 4 ranks as serially, within 1e-12 relative.
#[test]
fn impacts_across_subdomain_and_periodic_faces_match_serial() {
    if !have_mpirun() {
        return;
    }
    let script = format!(
        "{HEAD}\
create_atoms 1 single 0.043 0.0102 0.01 units box
create_atoms 1 single 0.057 0.0098 0.0103 units box
create_atoms 1 single 0.094 0.01 0.0097 units box
create_atoms 1 single 0.006 0.0101 0.01 units box
set atom * diameter 0.008 density 2500
set atom 1 vx 1.0 vy 0.05 omega 0 0 30
set atom 2 vx -1.0 vy -0.1
set atom 3 vx 0.8 vz 0.02
set atom 4 vx -0.7 omega 10 0 0
variable a1 equal x[1]
variable b1 equal vx[1]
variable c1 equal vy[1]
variable d2 equal vz[2]
variable e3 equal x[3]
variable f3 equal vx[3]
variable g4 equal vy[4]
variable h4 equal vz[4]
thermo_style custom step atoms ke v_a1 v_b1 v_c1 v_d2 v_e3 v_f3 v_g4 v_h4
{FORMAT}thermo 1000
run 4000
"
    );
    let serial = run(&script, 0);
    let reference = last_row(&serial);
    // The particles did collide: speeds changed.
    assert!((reference[4] - 1.0).abs() > 0.1, "{reference:?}");
    assert!((reference[8] - 0.8).abs() > 0.1, "{reference:?}");
    for (ranks, g) in [(1, "1 by 1 by 1"), (2, "2 by 1 by 1"), (4, "4 by 1 by 1")] {
        let out = run(&script, ranks);
        assert!(grid(&out).starts_with(g), "{}", grid(&out));
        assert_close(
            &last_row(&out),
            &reference,
            1e-12,
            &format!("{ranks} ranks"),
        );
    }
}

/// Two touching spheres, squeezed between two y walls, roll side by side on a floor wall (z = 0) in +x at different
/// speeds, across the subdomain face x = 0.05: the tangential springs of their contact
/// with each other (pair history, which changes rank with the pair) and with the floor
/// (wall history, a per-particle property) must follow them to the other rank, so the 2-
/// and 4-rank runs end where the serial run does. Without history the end state differs
/// by far more than the tolerance (checked too, so the comparison sees the springs).
#[test]
fn sliding_spheres_keep_their_tangential_springs_across_a_subdomain_face() {
    if !have_mpirun() {
        return;
    }
    let script = |tangential: &str| {
        format!(
            "{}\
fix floor all wall/gran model hertz {tangential} primitive type 1 zplane 0.0
fix ylo all wall/gran model hertz {tangential} primitive type 1 yplane 0.00201
fix yhi all wall/gran model hertz {tangential} primitive type 1 yplane 0.01799
create_atoms 1 single 0.0485 0.0060 0.00399 units box
create_atoms 1 single 0.0483 0.0140 0.00399 units box
set atom * diameter 0.008 density 2500
set atom 1 vx 0.05
set atom 2 vx 0.04
fix g all gravity 9.81 vector 0.0 0.0 -1.0
variable x1 equal x[1]
variable x2 equal x[2]
variable v1 equal vx[1]
variable v2 equal vx[2]
variable o1 equal omegay[1]
variable o2 equal omegaz[2]
variable y2 equal y[2]
thermo_style custom step atoms v_x1 v_x2 v_v1 v_v2 v_o1 v_o2 v_y2
{FORMAT}thermo 1000
run 40000
",
            HEAD.replace("tangential history", tangential)
        )
    };
    let no_history = last_row(&run(&script("tangential no_history"), 0));
    // `incremental_history` (LIGGGHTS-PFM) keeps the force and two scalars (k_t and the
    // normal force of the step before), which must not change sign when the pair's
    // listing flips.
    for model in ["tangential history", "tangential incremental_history"] {
        let serial = last_row(&run(&script(model), 0));
        // Both crossed x = 0.05 (each spends steps with its partner on the other rank).
        assert!(
            serial[2] > 0.0505 && serial[3] > 0.0505,
            "{model}: {serial:?}"
        );
        let gap = (no_history[4] - serial[4]).abs() / serial[4].abs();
        assert!(
            gap > 1e-3,
            "{model} must matter here: {no_history:?} vs {serial:?}"
        );
        for ranks in [2, 4] {
            let out = run(&script(model), ranks);
            assert_close(
                &last_row(&out),
                &serial,
                1e-10,
                &format!("{model}, {ranks} ranks"),
            );
        }
    }
}

/// The pour example (2500 beads through a box split in z at half height, so every bead
/// crosses a rank boundary on its way down) on 2 ranks: no bead lost, the same mass, and
/// the settled bed's centre of mass within 1 % of the serial run's.
#[test]
fn pour_on_two_ranks_conserves_particles_and_matches_the_serial_bed() {
    if !have_mpirun() {
        return;
    }
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/pour/in.pour");
    let script = std::fs::read_to_string(example)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("dump"))
        .map(|l| {
            if l.starts_with("thermo_style") {
                "variable zcm equal xcm(all,z)\nvariable m equal mass(all)\n\
                 thermo_style custom step atoms ke v_zcm v_m"
                    .to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let serial = last_row(&run(&script, 0));
    let out = run(&script, 2);
    assert!(grid(&out).starts_with("1 by 1 by 2"), "{}", grid(&out));
    let mpi = last_row(&out);
    assert_eq!(serial[1], 2500.0);
    assert_eq!(mpi[1], 2500.0, "every bead kept");
    assert!(
        (mpi[4] - serial[4]).abs() < 1e-12 * serial[4],
        "mass {mpi:?} {serial:?}"
    );
    assert!(
        serial[2] < 1e-6 && mpi[2] < 1e-6,
        "settled: {serial:?} {mpi:?}"
    );
    let dz = (mpi[3] - serial[3]).abs() / serial[3];
    assert!(
        dz < 0.01,
        "bed centre of mass {} vs {} ({dz:e})",
        mpi[3],
        serial[3]
    );
}

/// A script error on 2 ranks: every rank stops (exit status 1) and the report, with its
/// caret, appears once.
#[test]
fn an_error_is_reported_once_and_every_rank_stops() {
    if !have_mpirun() {
        return;
    }
    let script = format!(
        "{HEAD}create_atoms 1 single 0.05 0.01 0.01 units box\nset atom 1 charge 3\nrun 10\n"
    );
    let out = common::run_script_raw(&script, Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(
        err.matches("unknown set keyword 'charge'").count(),
        1,
        "{err}"
    );
    assert!(err.contains("in.test:20:12"), "{err}");
}

/// Sphere 2 (x > 0.05, rank 1 of 2) slides down along sphere 1 (x < 0.05, rank 0, held by
/// `fix freeze`) at a constant velocity (`fix setforce`), touching it all the way; its
/// spin comes only from the tangential spring of the contact. While sphere 2 is higher,
/// rank 0 lists the pair (the ghost lies above); once it passes below sphere 1 the listing
/// moves to rank 1, which needs the spring rank 0 built (the mirrored history entry). The
/// 2-rank spin equals serial within 1e-10; it differs without history.
#[test]
fn contact_history_follows_the_pair_when_the_listing_rank_changes() {
    if !have_mpirun() {
        return;
    }
    let script = |tangential: &str| {
        format!(
            "{}\
create_atoms 1 single 0.0461 0.01 0.0100 units box
create_atoms 1 single 0.0539 0.01 0.0110 units box
set atom * diameter 0.008 density 2500
set atom 2 vz -0.05 vx -0.0005
group base id 1
group mover id 2
fix hold base freeze
fix glide mover setforce 0.0 0.0 0.0
variable z2 equal z[2]
variable o2 equal omegay[2]
variable p2 equal omegax[2]
thermo_style custom step atoms v_z2 v_o2 v_p2
{FORMAT}thermo 1000
run 7000
",
            HEAD.replace("tangential history", tangential)
        )
    };
    let no_history = last_row(&run(&script("tangential no_history"), 0));
    // Both stored-tangential models: `incremental_history`'s scalars (k_t, the normal
    // force) cross with the mirrored entry unnegated.
    for model in ["tangential history", "tangential incremental_history"] {
        let serial = last_row(&run(&script(model), 0));
        assert!(
            serial[2] < 0.0100 - 5e-4,
            "{model}: passed below sphere 1: {serial:?}"
        );
        assert!(serial[3].abs() > 1e-3, "{model}: spun: {serial:?}");
        assert!(
            (no_history[3] - serial[3]).abs() > 1e-4 * serial[3].abs(),
            "{model} must matter: {no_history:?} vs {serial:?}"
        );
        let out = run(&script(model), 2);
        assert!(grid(&out).starts_with("2 by 1 by 1"), "{}", grid(&out));
        assert_close(
            &last_row(&out),
            &serial,
            1e-10,
            &format!("{model}, 2 ranks"),
        );
    }
}

/// A particle of rank 1 leaves a fixed face: every rank stops with the same error, which
/// names the global count and the particle's tag (not rank 0's empty view of it).
#[test]
fn a_lost_particle_on_another_rank_is_reported_with_its_tag() {
    if !have_mpirun() {
        return;
    }
    let script = format!(
        "{HEAD}create_atoms 1 single 0.02 0.01 0.01 units box\n\
         create_atoms 1 single 0.07 0.01 0.01 units box\n\
         set atom * diameter 0.004 density 2500\nset atom 2 vz 1e6\n\
         thermo_modify lost error\nrun 10\n"
    );
    let out = common::run_script_raw(&script, Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(
        err.matches("1 particle(s) lost at step 1").count(),
        1,
        "{err}"
    );
    // The report may wrap the message: compare its words.
    let words = err
        .replace('│', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(words.contains("first lost tag 2"), "{err}");
}

/// A box periodic along z and shorter than twice the neighbor cutoff (0.02 against
/// 2 × 0.011; the contact distance is 0.008): an oblique impact with spin across the
/// periodic face z = 0.02, which also crosses the subdomain face x = 0.05. Split along x
/// (`processors 2 1 1`, z unsplit: each rank makes the images through both z faces
/// itself) it ends as serially within 1e-12. Split along z (`processors 1 1 2`) the
/// subdomains (0.01) are shorter than the cutoff: every rank stops with that error.
#[test]
fn a_short_periodic_axis_runs_when_unsplit_and_is_refused_when_split() {
    if !have_mpirun() {
        return;
    }
    let head = HEAD
        .replace("boundary p f f", "boundary f f p")
        .replace("neighbor 0.001 bin", "neighbor 0.003 bin");
    let body = "\
create_atoms 1 single 0.047 0.01 0.0165 units box
create_atoms 1 single 0.052 0.0101 0.0035 units box
set atom * diameter 0.008 density 2500
set atom 1 vx 0.3 vz 0.8 omega 0 20 0
set atom 2 vz -0.8
variable a1 equal x[1]
variable b1 equal vz[1]
variable c1 equal omegay[1]
variable d2 equal vx[2]
variable e2 equal vz[2]
thermo_style custom step atoms ke v_a1 v_b1 v_c1 v_d2 v_e2
";
    // `processors` must come before the box.
    let script = |grid: &str| {
        let head = head.replace("region reg", &format!("processors {grid}\nregion reg"));
        format!("{head}{body}{FORMAT}thermo 1000\nrun 4000\n")
    };
    let serial = run(&script("1 1 1"), 0);
    let reference = last_row(&serial);
    // They collided: atom 1's vz is no longer 0.8 (-0.093 at step 4000, serially and on
    // 2 ranks alike, run by hand with the dev binary).
    assert!((reference[4] - 0.8).abs() > 0.1, "{reference:?}");
    let out = run(&script("2 1 1"), 2);
    assert!(grid(&out).starts_with("2 by 1 by 1"), "{}", grid(&out));
    assert_close(&last_row(&out), &reference, 1e-12, "2 ranks along x");
    let out = common::run_script_raw(&script("1 1 2"), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(
        err.matches("the subdomains are 0.01 long along z").count(),
        1,
        "{err}"
    );
}

/// Four tilted, spinning dumbbells (rigid clumps of `fix multisphere`, inserted one by one
/// by `insert/pack` in tiny regions): two meet across the inner faces of the subdomains
/// (x = 0.05) and two across the periodic face x = 0. On 2 and 4 ranks every rank holds
/// every body and its own spheres, which change rank as they move; the bodies' velocities,
/// angular momenta and heights must end as in the serial run within 1e-10 relative (the
/// ranks add up the spheres' forces in another order, so the last bits may differ, and a
/// collision amplifies that a little). A restart file written on 2 ranks and read
/// serially gives back the 2-rank run's bodies exactly.
#[test]
fn clumps_across_subdomain_and_periodic_faces_match_serial() {
    if !have_mpirun() {
        return;
    }
    // The common head, without its integrator (clumps integrate themselves); the
    // settings after the box are what a restarted run gives again.
    let head = HEAD.strip_suffix("fix integr all nve/sphere\n").unwrap();
    let settings = &head[head.find("neighbor").unwrap()..];
    let mut script = format!(
        "{head}fix pts all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 100000 spheres 0 0 0 0.002 0.0032 0 0 0.0016 type 1
fix pdd all particledistribution/discrete 15485867 1 pts 1.0
fix ms all multisphere
",
    );
    let seeds = [32452843, 32452867, 49979687, 49979693];
    for (k, (x, y, z, v, q, w)) in [
        (
            0.043,
            0.0102,
            0.01,
            "1.0 0.05 0",
            "0.9659258 0 0 0.2588190",
            "0 0 30",
        ),
        (
            0.057,
            0.0098,
            0.0103,
            "-1.0 -0.1 0",
            "0.9238795 0 0.3826834 0",
            "0 0 0",
        ),
        (0.094, 0.0100, 0.0097, "0.8 0 0.02", "1 0 0 0", "0 20 0"),
        (
            0.006,
            0.0101,
            0.0100,
            "-0.7 0 0",
            "0.8660254 0.5 0 0",
            "10 0 0",
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let d = 1e-9;
        script.push_str(&format!(
            "region r{k} block {x} {} {y} {} {z} {} units box
fix i{k} all insert/pack seed {} distributiontemplate pdd vel constant {v} omega constant {w} orientation constant {q} insert_every once overlapcheck yes all_in no region r{k} particles_in_region 1
run 1
",
            x + d,
            y + d,
            z + d,
            seeds[k]
        ));
    }
    let mut cols = String::new();
    let mut computes = String::new();
    for b in 1..=4 {
        computes.push_str(&format!(
            "compute v{b} all multisphere/single id {b} property vcm
compute l{b} all multisphere/single id {b} property angmom
compute x{b} all multisphere/single id {b} property xcm
"
        ));
        cols.push_str(&format!(
            " c_v{b}[1] c_v{b}[2] c_v{b}[3] c_l{b}[1] c_l{b}[2] c_l{b}[3] c_x{b}[2] c_x{b}[3]"
        ));
    }
    let thermo = format!("{computes}thermo_style custom step atoms{cols}\n{FORMAT}thermo 1000\n");
    script.push_str(&format!("{thermo}run 4000\n"));
    let serial = run(&script, 0);
    let reference = last_row(&serial);
    assert_eq!(reference[1], 8.0, "{serial}");
    // Each pair collided: the x velocities changed.
    assert!((reference[2] - 1.0).abs() > 0.1, "{reference:?}");
    assert!((reference[2 + 16] - 0.8).abs() > 0.1, "{reference:?}");
    for (ranks, g) in [(2, "2 by 1 by 1"), (4, "4 by 1 by 1")] {
        let out = run(&script, ranks);
        assert!(grid(&out).starts_with(g), "{}", grid(&out));
        let row = last_row(&out);
        assert_eq!(row.len(), reference.len());
        for (k, (a, b)) in row.iter().zip(&reference).enumerate() {
            // A component that stays zero may come out as round-off: 1e-18 absolute.
            let tol = 1e-10 * a.abs().max(b.abs()) + 1e-18;
            assert!(
                (a - b).abs() <= tol,
                "{ranks} ranks, column {k}: {a} vs {b}"
            );
        }
    }
    let dir = common::scratch_dir("ms-restart");
    let file = dir.join("ms.restart");
    let two = last_row(&run(
        &format!("{script}write_restart {}\n", file.display()),
        2,
    ));
    let back = last_row(&run(
        &format!(
            "read_restart {}\n{settings}fix ms all multisphere\n{thermo}run 0\n",
            file.display()
        ),
        0,
    ));
    assert_eq!(back[1], 8.0);
    for (k, (a, b)) in back[2..].iter().zip(&two[2..]).enumerate() {
        assert!(
            (a - b).abs() <= 1e-14 * a.abs().max(b.abs()),
            "read back, column {k}: {a} vs {b}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

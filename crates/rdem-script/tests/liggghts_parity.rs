//! Parity with LIGGGHTS 3.8: each test runs a script of tests/data/parity/ and checks the
//! numbers LIGGGHTS printed for it (hard-coded below; the full LIGGGHTS outputs are the
//! itemN.liggghts.* files next to the scripts, made by regenerate.sh).

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/parity");

/// Runs tests/data/parity/`name` with its includes inlined and `dump_to` (if any) as
/// the path of its dump file.
fn run_item(name: &str, dump: Option<(&str, &std::path::Path)>) -> String {
    let read = |f: &str| std::fs::read_to_string(format!("{DIR}/{f}")).unwrap();
    let mut src = read(name)
        .replace("include head.in\n", &read("head.in"))
        .replace("include mat.in\n", &read("mat.in"));
    if let Some((from, to)) = dump {
        src = src.replace(from, &to.display().to_string());
    }
    common::run_screen(name, &src)
}

/// Asserts each `key=value` line LIGGGHTS printed appears as is in rdem's output.
fn assert_lines(out: &str, liggghts: &[&str]) {
    for l in liggghts {
        assert!(
            out.lines().any(|o| o.trim_end() == *l),
            "missing '{l}' in\n{out}"
        );
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("rdem-parity-{name}-{}", std::process::id()))
}

/// Item 1: lattice sc/bcc/fcc + create_atoms box/region counts, with lattice points on
/// the upper box face (excluded) and on region faces (included); `units lattice`.
#[test]
fn lattice_create_atoms_counts() {
    let out = run_item("item1.in", None);
    // LIGGGHTS: `print "sc_box=${n}"` ... `print "sc_lat_sphere=${n}"` in item1.in.
    assert_lines(
        &out,
        &[
            "sc_box=64",
            "bcc_box=128",
            "fcc_box=256",
            "sc_block=27",
            "sc_sphere=7",
            "fcc_sphere=19",
            "bcc_block=35",
            "sc_lat_block=27 0.5 1.5",
            "sc_lat_sphere=33",
        ],
    );
}

/// Item 2: group region counts on an sc lattice, points on the boundaries included.
#[test]
fn group_region_counts() {
    let out = run_item("item2.in", None);
    // LIGGGHTS: `print "block=${nb}"` ... `print "sphere_out=${nso}"` in item2.in.
    assert_lines(
        &out,
        &[
            "block=27",
            "sphere=7",
            "cylinder=15",
            "cone=19",
            "plane=75",
            "union=27",
            "intersect=7",
            "block_out=98",
            "sphere_out=118",
        ],
    );
}

/// Item 3: group functions after set diameter/density, velocity set/ramp and zero linear.
#[test]
fn group_functions() {
    let out = run_item("item3.in", None);
    // LIGGGHTS: the `print "count=${c}"` ... `print "ke0=${k}"` lines of item3.in.
    assert_lines(
        &out,
        &[
            "count=64",
            "mass=40698.2856297046",
            "masslo=38603.8905273114",
            "xcm=1.10292301358584",
            "ycmlo=1.5",
            "vcmx=2.06710580485797",
            "vcmy=-2",
            "vcmxlo=2.125",
            "bxmin=0 bxmax=3 bzmaxlo=3",
            "ke=188263.081359022",
            "kelo=182765.29421524",
            "vcmx0=8.84811369598304e-16",
            "vcmy0=0",
            "ke0=14828.8346724372",
        ],
    );
}

/// Item 4: compute reduce sum/min/max/ave (sumsq/avesq through atom variables, as
/// LIGGGHTS 3.8 has neither mode), property/atom and contact/atom.
#[test]
fn reduce_property_contact() {
    let d = tmp("item4");
    let out = run_item("item4.in", Some(("item4.dump", &d)));
    // LIGGGHTS: the `print "sum=..."` ... `print "contacts=..."` lines of item4.in.
    assert_lines(
        &out,
        &[
            "sum=2.36 1.3 0.235 6.35256214494636",
            "sumsq=1.2646 2.53",
            "min=0.3 -0.5 0.025 0.163624617374468",
            "max=0.8 1.5 0.06 2.26194671058465",
            "ave=0.472 0.26 0.047 1.27051242898927",
            "avesq=0.25292 0.506",
            "contacts=6 3 0.235",
        ],
    );
    // LIGGGHTS: `dump d all custom 1 item4.dump id c_ca c_pr` (item4.liggghts.dump).
    let dump = std::fs::read_to_string(&d).unwrap();
    let rows: Vec<&str> = dump.lines().skip(9).map(str::trim_end).collect();
    assert_eq!(
        rows,
        ["1 1 0.05", "2 3 0.05", "3 1 0.06", "4 1 0.05", "5 0 0.025"]
    );
    let _ = std::fs::remove_file(&d);
}

/// Item 5: fix check/timestep/gran Rayleigh and Hertz fractions (Hertz time as LIGGGHTS
/// computes it: the particle's own m and r, E* = E/(2(1-nu^2)), v = largest speed).
#[test]
fn check_timestep_fractions() {
    let out = run_item("item5.in", None);
    // LIGGGHTS: `print "rayleigh=${fr}"`, `print "hertz=${fh}"` and the vmax 10 pair.
    assert_lines(
        &out,
        &[
            "rayleigh=0.00397061199331605",
            "hertz=0.00195779126419247",
            "rayleigh_vmax=0.00397061199331605",
            "hertz_vmax=0.002701222678156",
        ],
    );
}

/// Item 6: insert/rate/region events. With a whole number per event (second fix) the
/// steps and counts are LIGGGHTS'; with 25.9 per event the first two events and the
/// total agree, the rounding of later events does not (LIGGGHTS rounds at random).
#[test]
fn insert_rate_region_events() {
    let out = run_item("item6.in", None);
    // LIGGGHTS (item6.liggghts.txt): the INFO lines below, `print "count=${n}"` and
    // `print "count2=${n}"`.
    assert_lines(
        &out,
        &[
            "INFO: Particle insertion ins: inserted 25 particle templates (mass 2.094395e-03) at step 1",
            "INFO: Particle insertion ins: inserted 26 particle templates (mass 2.178171e-03) at step 71",
            " - a total of 51 particle templates (mass 4.272566e-03) inserted so far.",
            "INFO: Particle insertion ins2: inserted 20 particle templates (mass 1.675516e-03) at step 450",
            "count=130",
            "count2=150",
        ],
    );
}

/// Item 7: thermo time/dt/lx.../zhi, c_/f_/v_ columns and `thermo_modify norm yes`
/// (ke, c_ of extensive computes and f_ of check/timestep/gran divided by the atom count;
/// v_ columns not).
#[test]
fn thermo_norm_and_keywords() {
    let out = run_item("item7.in", None);
    // LIGGGHTS: rows of `thermo_style custom step atoms time dt lx ... v_n f_ts[1] f_ts[2]`
    // in item7.liggghts.txt (norm yes at 0, 200; norm no at 300).
    let row = |step: &str| -> Vec<f64> {
        out.lines()
            .rfind(|l| l.split_whitespace().next() == Some(step))
            .unwrap_or_else(|| panic!("no row {step} in\n{out}"))
            .split_whitespace()
            .map(|w| w.parse().unwrap())
            .collect()
    };
    let check = |step: &str, liggghts: &str| {
        let r = row(step);
        let l: Vec<f64> = liggghts
            .split_whitespace()
            .map(|w| w.parse().unwrap())
            .collect();
        assert_eq!(r.len(), l.len());
        for (a, b) in r.iter().zip(&l) {
            assert!(
                (a - b).abs() <= 1e-13 * b.abs().max(1e-3),
                "step {step}: {r:?} vs {l:?}"
            );
        }
    };
    check("0", "0 27 0 1e-05 0.1 0.1 0.15 -0.05 0.05 -0.04 0.06 0 0.15 4.69144502936076e-05 4.69144502936076e-05 0 0 0.3 9.38289005872152e-05 27 0 0");
    check("200", "200 27 0.002 1e-05 0.1 0.1 0.15 -0.05 0.05 -0.04 0.06 0 0.15 0.00116366250609676 0.00116366250609676 0 0.00540000000000359 7.57026000000005 0.00232732501219351 27 0.0198530599665802 0.00694158841456652");
    check("300", "300 27 0.003 1e-05 0.1 0.1 0.15 -0.05 0.05 -0.04 0.06 0 0.15 0.00111476085133945 0.00111476085133945 0 0.00810000000000542 7.30539000000008 0.00222952170267889 27 0.0198530599665802 0.00691185034633564");
    assert!(out.contains("100       27 0.001 1e-05 0.1 0.1 0.15 -0.05 0.05 -0.04 0.06 0 0.15 4.49742817886201e-05 4.49742817886201e-05 0 "));
}

/// Item 8: delete_atoms region compress yes renumbers the survivors 1..N.
#[test]
fn delete_atoms_compress_ids() {
    let d = tmp("item8");
    let out = run_item("item8.in", Some(("item8.dump", &d)));
    // LIGGGHTS: "Deleted 2 atoms, new total = 2" and `write_dump all custom item8.dump id x y z`.
    assert_lines(&out, &["Deleted 2 atoms, new total = 2", "count=2"]);
    let dump = std::fs::read_to_string(&d).unwrap();
    let rows: Vec<&str> = dump.lines().skip(9).map(str::trim_end).collect();
    assert_eq!(rows, ["1 0 0 0", "2 3 0 0"]);
    let _ = std::fs::remove_file(&d);
}

/// Item 19: `lattice custom` with axis-aligned cell vectors, two basis atoms and an origin
/// shift: the spacings LIGGGHTS prints, the counts it creates in a box-units and a
/// lattice-units region, and its dump of every position, byte for byte.
#[test]
fn lattice_custom_matches_liggghts() {
    let d = tmp("item19");
    let out = run_item("item19.in", Some(("item19.dump", &d)));
    assert_lines(
        &out,
        &[
            "Lattice spacing in x,y,z = 0.02 0.02 0.005",
            "Created 81 atoms",
            "Created 11 atoms",
        ],
    );
    let ours = std::fs::read_to_string(&d).unwrap();
    let theirs = std::fs::read_to_string(format!("{DIR}/item19.liggghts.dump")).unwrap();
    assert_eq!(ours, theirs);
    let _ = std::fs::remove_file(&d);
}

/// `lattice custom` errors: a cell vector off its axis, and no basis atom.
#[test]
fn lattice_custom_errors() {
    for (line, message) in [
        (
            "lattice custom 0.01 a1 1 1 0 a2 0 1 0 a3 0 0 1 basis 0 0 0",
            "a1 must lie along +x",
        ),
        (
            "lattice custom 0.01 a1 1 0 0 a2 0 1 0 a3 0 0 1",
            "needs at least one 'basis x y z'",
        ),
        (
            "lattice custom 0.01 a1 1 0 0 basis 0 0 1.5",
            "basis values must be in [0, 1)",
        ),
    ] {
        let mut i = common::interpreter();
        let e = i.run_source("in.lat", line).unwrap_err();
        let text = format!("{:?}", miette::Report::new(*e));
        assert!(text.contains(message), "{line}: {text}");
    }
}

/// `insert/rate/region` defined before `timestep`: the particles per insertion follow the
/// time step of the run (500 particles/s × 1e-4 s × 500 steps = 25), as LIGGGHTS 3.8
/// inserts them (25 at steps 1, 501 and 1001 for a public script written this way).
/// rdem used the default time step at the definition and inserted none.
#[test]
fn insert_rate_uses_the_timestep_of_the_run() {
    let src = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region domain block -0.9 0.9 -0.9 0.9 0.0 4.0 units box
create_box 1 domain
neighbor 0.03 bin
fix m1 all property/global youngsModulus peratomtype 1e8
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 1000 radius constant 0.03
fix pdd all particledistribution/discrete 15485867 1 pts 1.0
region factory cylinder z 0.0 0.0 0.25 2.3 2.5 units box
fix ins all insert/rate/region seed 32452843 distributiontemplate pdd nparticles 25000 particlerate 500 insert_every 500 overlapcheck yes vel constant 0. 0. -1.0 region factory
pair_style gran model hertz tangential history
pair_coeff * *
fix integrate all nve/sphere
fix grav all gravity 9.81 vector 0.0 0.0 -1.0
timestep 0.0001
run 1100
";
    let mut i = common::interpreter();
    i.run_source("in.rate", src).unwrap();
    let out = common::screen(&i);
    let steps: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("INFO: Particle insertion ins: inserted 25 "))
        .map(|l| l.rsplit(' ').next().unwrap())
        .collect();
    assert_eq!(steps, ["1", "501", "1001"], "{out}");
}

//! `units si|cgs|micro`: the same two-particle script (a sphere bouncing on a floor wall
//! and hitting a second one, tests/data/units/si.in) written in the three unit systems
//! (`make.py` converts every number) gives one motion, and the `cgs` run matches
//! LIGGGHTS 3.8 (`regenerate.sh`; outputs in `NAME.liggghts.txt`, hard-coded below).

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/units");

/// Runs the script file `name` and returns its captured screen output.
fn run(name: &str) -> String {
    common::run_screen(
        name,
        &std::fs::read_to_string(format!("{DIR}/{name}")).unwrap(),
    )
}

/// The thermo rows (step atoms ke rke temp) of an output.
fn rows(out: &str) -> Vec<Vec<f64>> {
    out.lines()
        .filter_map(|l| {
            let v: Option<Vec<f64>> = l.split_whitespace().map(|w| w.parse().ok()).collect();
            v.filter(|v| v.len() == 5)
        })
        .collect()
}

/// The numbers of the `res x1 z1 x2 z2 vz2` line.
fn res(out: &str) -> Vec<f64> {
    let l = out
        .lines()
        .find(|l| l.starts_with("res "))
        .expect("res line");
    l.split_whitespace()
        .skip(1)
        .map(|w| w.parse().unwrap())
        .collect()
}

fn close(a: f64, b: f64, rel: f64, what: &str) {
    assert!(
        (a - b).abs() <= rel * b.abs().max(1e-300),
        "{what}: {a} vs {b} (relative tolerance {rel})"
    );
}

/// (length, mass, time) of one unit of each system in SI.
const CGS: (f64, f64, f64) = (1e-2, 1e-3, 1.0);
const MICRO: (f64, f64, f64) = (1e-6, 1e-15, 1e-6);

/// The three runs give the same positions, velocities, kinetic energies and temperature
/// after conversion to SI: to round-off (1e-9 relative: the contacts amplify the
/// last-bit differences of the converted inputs over 10,000 steps; LIGGGHTS' three runs
/// differ as much, e.g. x1 0.00444202926367752 m in si and 0.444202926365927 cm in cgs).
#[test]
fn si_cgs_micro_are_one_motion() {
    let si = run("si.in");
    let (rs, ts) = (res(&si), rows(&si));
    assert_eq!(ts.len(), 6, "{si}");
    for (name, (l, m, t)) in [("cgs.in", CGS), ("micro.in", MICRO)] {
        let out = run(name);
        let (r, th) = (res(&out), rows(&out));
        let scale = [l, l, l, l, l / t];
        for k in 0..5 {
            close(r[k] * scale[k], rs[k], 1e-9, &format!("{name} res[{k}]"));
        }
        let energy = m * l * l / (t * t);
        assert_eq!(th.len(), ts.len(), "{out}");
        for (g, w) in th.iter().zip(&ts) {
            close(g[2] * energy, w[2], 1e-9, &format!("{name} ke at {}", w[0]));
            close(
                g[3] * energy,
                w[3],
                1e-7,
                &format!("{name} rke at {}", w[0]),
            );
            // The temperature is in kelvin in every system: k_B carries the unit.
            close(g[4], w[4], 1e-9, &format!("{name} temp at {}", w[0]));
        }
    }
}

/// The `cgs` run against LIGGGHTS 3.8 (cgs.liggghts.txt).
#[test]
fn cgs_matches_liggghts() {
    let out = run("cgs.in");
    let want = [
        [0.0, 2.0, 98.9601685880785, 0.0, 4.77843237689901e+17],
        [2000.0, 2.0, 479.901795798518, 0.0, 2.31727402195621e+18],
        [4000.0, 2.0, 1622.72667742995, 0.0, 7.83556637475569e+18],
        [
            6000.0,
            2.0,
            2611.8232627518,
            4.47841270627887,
            1.26115598018238e+19,
        ],
        [
            8000.0,
            2.0,
            2048.80981595167,
            65.1850973663226,
            9.89296936164613e+18,
        ],
        [
            10000.0,
            2.0,
            2272.06899836523,
            30.5980952083193,
            1.09710080522688e+19,
        ],
    ];
    let got = rows(&out);
    assert_eq!(got.len(), want.len(), "{out}");
    for (g, w) in got.iter().zip(&want) {
        for k in 0..5 {
            close(
                g[k],
                w[k],
                1e-9,
                &format!("thermo column {k} at step {}", w[0]),
            );
        }
    }
    // LIGGGHTS: res 0.444202926365927 0.511110339312445 2.27265151830982 2.60879903143439
    // 12.9673158465297
    let want = [
        0.444202926365927,
        0.511110339312445,
        2.27265151830982,
        2.60879903143439,
        12.9673158465297,
    ];
    for (k, (g, w)) in res(&out).iter().zip(want).enumerate() {
        close(*g, w, 1e-9, &format!("res[{k}]"));
    }
}

/// `units` sets LIGGGHTS' default time step and skin of the system (manual `units.txt`):
/// dt 1e-8 s in si and cgs, 2 µs in micro; skin 0.001 m, 0.1 cm, 0.1 µm.
#[test]
fn defaults_follow_the_unit_system() {
    for (u, dt, skin) in [("si", 1e-8, 0.001), ("cgs", 1e-8, 0.1), ("micro", 2.0, 0.1)] {
        let src = format!(
            "units {u}\nregion r block 0 1 0 1 0 1 units box\ncreate_box 1 r\nvariable d equal dt\nprint \"dt=${{d}}\"\n"
        );
        let mut i = common::interpreter();
        i.run_source("in.t", &src).unwrap();
        let w = i.sim.world.as_ref().unwrap();
        assert_eq!(w.dt, dt, "{u}");
        // The skin the box's neighbor lists get at the next run.
        assert_eq!(i.sim.setup.neighbor.skin, skin, "{u}");
        let out = common::screen(&i);
        let printed: f64 = out
            .lines()
            .find_map(|l| l.strip_prefix("dt="))
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{u}: {out}"));
        assert_eq!(printed, dt, "{u}");
    }
}

/// `units` after the box, and unit systems rdem does not run, are located errors.
#[test]
fn units_errors() {
    for (src, msg) in [
        ("units lj\n", "units lj is not supported by rdem yet"),
        ("units furlong\n", "unknown unit style 'furlong'"),
        (
            "region r block 0 1 0 1 0 1 units box\ncreate_box 1 r\nunits cgs\n",
            "units after the simulation box is defined",
        ),
    ] {
        let mut i = common::interpreter();
        let e = i.run_source("in.t", src).unwrap_err();
        let text = format!("{:?}", miette::Report::new(*e));
        assert!(text.contains(msg), "{text}");
    }
}

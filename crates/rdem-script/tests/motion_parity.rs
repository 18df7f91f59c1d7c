//! Parity with LIGGGHTS 3.8 for moving particles and regions, per-particle properties and
//! `read_dump`: each test runs a script of tests/data/parity/ (itemN.in; the LIGGGHTS
//! outputs are the itemN.liggghts.* files next to it, made by regenerate.sh) and checks
//! the numbers LIGGGHTS printed (hard-coded below) and closed forms.

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/parity");

/// Runs tests/data/parity/`name` with its includes inlined and each `(from, to)` of
/// `replace` replaced (dump and input file names). Returns the screen output.
fn run_item(name: &str, replace: &[(&str, String)]) -> String {
    let read = |f: &str| std::fs::read_to_string(format!("{DIR}/{f}")).unwrap();
    let mut src = read(name)
        .replace("include head.in\n", &read("head.in"))
        .replace("include mat.in\n", &read("mat.in"));
    for (from, to) in replace {
        src = src.replace(from, to);
    }
    common::run_screen(name, &src)
}

/// Asserts each line LIGGGHTS printed appears as is in rdem's output.
fn assert_lines(out: &str, liggghts: &[&str]) {
    for l in liggghts {
        assert!(
            out.lines().any(|o| o.trim_end() == *l),
            "missing '{l}' in\n{out}"
        );
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("rdem-motion-{name}-{}", std::process::id()))
}

/// The rows of the last snapshot of a text dump, as numbers.
fn last_snapshot(dump: &str) -> Vec<Vec<f64>> {
    let start = dump.rfind("ITEM: ATOMS").expect("a snapshot");
    dump[start..]
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// Asserts two snapshots agree: the same rows, each value within `rel` relative (LIGGGHTS
/// writes 6 significant digits) or `abs`.
fn assert_snapshot(rdem: &[Vec<f64>], liggghts: &[Vec<f64>], rel: f64, abs: f64) {
    assert_eq!(rdem.len(), liggghts.len());
    for (r, l) in rdem.iter().zip(liggghts) {
        assert_eq!(r.len(), l.len());
        for (a, b) in r.iter().zip(l) {
            assert!(
                (a - b).abs() <= rel * b.abs() + abs,
                "rdem row {r:?} vs LIGGGHTS {l:?}"
            );
        }
    }
}

/// Item 9: fix property/atom scalar and vector: defaults for existing and later
/// particles, `set group|region ... property/atom`, `f_T`, `f_U[i]` in atom variables,
/// `compute reduce` and a dump, values kept with their particles over 200 steps.
#[test]
fn property_atom_values() {
    let d = tmp("item13");
    let out = run_item("item13.in", &[("item13.dump", d.display().to_string())]);
    // LIGGGHTS (item13.liggghts.txt): the two `print "sumT=..."` lines of item13.in.
    // Closed form: 48 particles of `lo` at 350 and 16 at 300 (21600), the 65th at 300;
    // sum of f_U[2]*x = 5*16*(0+1+2) + 2*16*3 = 336, then + 2*3.5 and the drift along x
    // under gravity (274 * 0.5 g_x t^2, g_x = 9.81*0.3/|(0.3,0.2,-1)|, t = 0.002).
    assert_lines(
        &out,
        &[
            "sumT=21600 sumU2x=336 sumU3=336",
            "sumT=21900 sumU2x=343.00151716075 sumU3=339",
        ],
    );
    let gx = 9.81 * 0.3 / (0.3f64 * 0.3 + 0.2 * 0.2 + 1.0).sqrt();
    assert!((343.00151716075 - (343.0 + 274.0 * 0.5 * gx * 0.002f64.powi(2))).abs() < 1e-9);
    // LIGGGHTS: `dump d all custom 50 item13.dump id x f_T f_U[1] f_U[3]` (sorted by id,
    // item13.liggghts.dump).
    let mine = last_snapshot(&std::fs::read_to_string(&d).unwrap());
    let theirs =
        last_snapshot(&std::fs::read_to_string(format!("{DIR}/item13.liggghts.dump")).unwrap());
    assert_snapshot(&mine, &theirs, 1e-5, 0.0);
    let _ = std::fs::remove_file(&d);
}

/// The numbers of the line of `out` that starts with `key=`.
fn numbers(out: &str, key: &str) -> Vec<f64> {
    let line = out
        .lines()
        .find_map(|l| l.strip_prefix(&format!("{key}=")))
        .unwrap_or_else(|| panic!("no '{key}=' line in\n{out}"));
    line.split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect()
}

/// Item 10: fix move wiggle (y NULL), rotate (about z through (0, 0.5, 0)) and linear
/// (z NULL, integrated under gravity) and variable (equal-style displacement of x,
/// velocity of y) after 4321 steps, and a free particle hit from
/// below by one moving up at 1 m/s (group m, `units lattice` by default with no lattice:
/// spacing 1).
#[test]
fn fix_move_closed_forms() {
    let out = run_item("item14.in", &[]);
    let (dt, n) = (1e-5, 4321.0);
    let t = n * dt;
    let tau = 2.0 * std::f64::consts::PI;
    let close = |got: &[f64], want: &[f64], tol: f64| {
        assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= tol * (1.0 + w.abs()),
                "{got:?} vs {want:?}"
            );
        }
    };
    // Closed forms (positions to 1e-12).
    let w = tau / 0.01;
    close(
        &numbers(&out, "w"),
        &[
            0.5 + 0.2 * (w * t).sin(),
            0.0,
            0.1 * (w * t).sin(),
            0.2 * w * (w * t).cos(),
            0.1 * w * (w * t).cos(),
        ],
        1e-12,
    );
    let wr = tau / 0.004;
    let (s, c) = (wr * t).sin_cos();
    // (-1, 1, 0) about the z axis through (0, 0.5, 0): radial vector (-1, 0.5).
    let (ax, ay) = (-1.0, 0.5);
    let (rx, ry) = (ax * c - ay * s, ax * s + ay * c);
    close(
        &numbers(&out, "r"),
        &[rx, 0.5 + ry, 0.0, -wr * ry, wr * rx, wr],
        1e-12,
    );
    // z NULL: velocity Verlet under gravity from rest, exact: z = z0 - g (n dt)^2 / 2.
    let g = 9.81;
    close(
        &numbers(&out, "l"),
        &[1.5 + t, 1.5 + 0.5 * t, 1.5 - 0.5 * g * t * t, 1.0, -g * t],
        1e-12,
    );
    // LIGGGHTS (item14.liggghts.txt): the print lines of item14.in.
    close(
        &numbers(&out, "w"),
        &[
            0.68042679187364,
            0.0,
            0.0902133959368201,
            -54.2183657383287,
            -27.1091828691643,
        ],
        1e-12,
    );
    close(
        &numbers(&out, "r"),
        &[
            0.149125261215617,
            1.60804406792662,
            0.0,
            -1740.51155182601,
            234.245412549821,
            1570.7963267949,
        ],
        1e-9,
    );
    close(
        &numbers(&out, "l"),
        &[1.54321, 1.521605, 1.4908418543895, 1.0, -0.423890099999963],
        1e-9,
    );
    // variable: x = x0 + dx with dx = (time - 0.001)^2 / 2 (the fix starts at time
    // 0.001), vx left alone; y advanced by dt·vy with vy = 2; z NULL under gravity.
    let v = numbers(&out, "v");
    close(
        &v,
        &[
            1.0 + 0.5 * t * t,
            -1.0 + 2.0 * t,
            0.5 - 0.5 * g * t * t,
            0.0,
            2.0,
            -g * t,
        ],
        1e-12,
    );
    // LIGGGHTS: "v=1.00093355205 -0.913579999999914 0.490841854389501 0 2 -0.423890099999963".
    close(
        &v,
        &[
            1.00093355205,
            -0.913579999999914,
            0.490841854389501,
            0.0,
            2.0,
            -0.423890099999963,
        ],
        1e-9,
    );
    // The moving particle (z5, vz5) and the free one it hit (z6, vz6): LIGGGHTS
    // "m=-1.45679 1 -1.33712901172363 1.75311645678811". The bounce depends on the
    // contact model; the free particle leaves faster than the pusher (restitution 0.9).
    let m = numbers(&out, "m");
    close(&m[..2], &[-1.5 + t, 1.0], 1e-12);
    close(&m[2..], &[-1.33712901172363, 1.75311645678811], 1e-6);
}

/// Item 11: `velocity set` with an atom-style variable (2x + y), an equal-style one (3)
/// and NULL, then again with `sum yes`. Closed form over the 64 lattice points, 48 of
/// them (x = 0, 1, 2) in `lo`: Σvx = 16·2·(0+1+2) + 3·24 + 16 = 184, Σvy = 64,
/// Σvz = 3·48 + 16 = 160, Σvx·y = 336; after the sum: 352 208 160 648.
#[test]
fn velocity_set_with_variables() {
    let out = run_item("item15.in", &[]);
    // LIGGGHTS (item15.liggghts.txt): `print "set=..."`, `print "sum=..."`.
    assert_lines(&out, &["set=184 64 160 336", "sum=352 208 160 648"]);
}

//! `fix speedcontrol` (LIGGGHTS-PFM), added through the engine's post-force extension
//! point, against the closed form of its velocity under velocity Verlet.
//!
//! The force is f = −K·m/dt·(v − v_set), computed at the force pass from the velocity
//! after the first half kick. With d_n the error of that half-step velocity at step n and
//! e_n the error of the full-step velocity after it:
//! e_n = (1 − K/2)·d_n and d_{n+1} = e_n − (K/2)·d_n = (1 − K)·d_n. From rest, the set-up
//! force gives d_1 = −(1 − K/2)·v_set, so
//!
//! v_n = v_set·(1 − (1 − K/2)²·(1 − K)^(n−1)),
//!
//! which tends to v_set·(1 − e^(−K·t/dt)) for small K.

use crate::common;

/// Two spheres (d = 0.1 m, 1000 kg/m³) far apart in a 2 m box, dt = 1 ms, no gravity.
const FREE: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -1 1 -1 1 -1 1 units box
create_box 1 reg
neighbor 0.01 bin
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.001
create_atoms 1 single -0.5 0 0
create_atoms 1 single 0.5 0 0
set atom * diameter 0.1 density 1000
fix i all nve/sphere
";

/// Thermo every step: step, then the velocity of particle 1 and of particle 2.
const PROBE: &str = "\
variable ax equal vx[1]
variable ay equal vy[1]
variable az equal vz[1]
variable bx equal vx[2]
thermo_style custom step v_ax v_ay v_az v_bx
thermo_modify format float %.17g
thermo 1
run 30
";

/// Runs `script` and returns its thermo rows (each row's numbers).
fn rows(script: &str) -> Vec<Vec<f64>> {
    let (_, out) = common::try_run_screen("in.speed", script).unwrap_or_else(|e| panic!("{e}"));
    out.lines()
        .map(|l| {
            l.split_whitespace()
                .map(str::parse::<f64>)
                .collect::<Result<Vec<_>, _>>()
        })
        .filter_map(Result::ok)
        .filter(|r| r.len() == 5)
        .collect()
}

/// The script's error, rendered.
fn error(script: &str) -> String {
    common::error("in.speed", script)
}

/// v_n from rest with a constant set velocity and gain.
fn closed_form(vs: f64, k: f64, n: f64) -> f64 {
    if n == 0.0 {
        return 0.0;
    }
    vs * (1.0 - (1.0 - k / 2.0).powi(2) * (1.0 - k).powf(n - 1.0))
}

#[test]
fn velocity_follows_the_closed_form_with_the_default_gain() {
    let r = rows(&format!(
        "{FREE}fix s all speedcontrol 1.5 NULL NULL\n{PROBE}"
    ));
    assert_eq!(r.len(), 31);
    for row in &r {
        let n = row[0];
        let want = closed_form(1.5, 0.1, n);
        assert!(
            (row[1] - want).abs() < 1e-12,
            "step {n}: vx {} vs {want}",
            row[1]
        );
        // NULL axes are left alone, and both particles are in the group.
        assert_eq!((row[2], row[3]), (0.0, 0.0), "step {n}");
        assert_eq!(row[4], row[1], "step {n}");
    }
    // After 30 steps the error has shrunk by (1 − K/2)²(1 − K)^29 = 0.0425: close to the
    // continuous e^(−3) = 0.0498 within O(K).
    let last = r.last().unwrap()[1];
    assert!((last - 1.5 * (1.0 - 0.042_509)).abs() < 1e-5, "{last}");
    assert!(
        (last - 1.5 * (1.0 - (-3.0f64).exp())).abs() < 0.02,
        "{last}"
    );
}

#[test]
fn gain_and_set_velocity_from_variables() {
    // v_set changes at step 10 (time 0.01 s): the recursion d_{n+1} = (1 − K/2) d_n
    // − (K/2) d_n with v_set evaluated at each step, run by hand.
    let r = rows(&format!(
        "{FREE}variable k equal 0.25\nvariable vs equal (time<0.0095)*2-(time>0.0095)*1\n\
         fix s all speedcontrol NULL v_vs NULL gain v_k\n{PROBE}"
    ));
    let (k, dt) = (0.25, 1e-3);
    let vs = |n: u64| if (n as f64) * dt < 0.0095 { 2.0 } else { -1.0 };
    // Velocity Verlet with f = −K m/dt (v − v_set(n)) at the force pass of step n.
    let mut v = 0.0;
    let mut f = -k / dt * (v - vs(0)); // per unit mass, the set-up force
    for row in &r {
        let n = row[0] as u64;
        if n > 0 {
            v += 0.5 * dt * f;
            f = -k / dt * (v - vs(n));
            v += 0.5 * dt * f;
        }
        assert!((row[2] - v).abs() < 1e-12, "step {n}: vy {} vs {v}", row[2]);
        assert_eq!((row[1], row[3]), (0.0, 0.0));
    }
    assert!((r.last().unwrap()[2] + 1.0).abs() < 0.01);
}

#[test]
fn only_particles_in_the_region_and_group_are_controlled() {
    let r = rows(&format!(
        "{FREE}region right block 0 1 -1 1 -1 1 units box\n\
         fix s all speedcontrol 0.2 NULL NULL region right gain 0.5\n{PROBE}"
    ));
    for row in &r {
        assert_eq!(row[1], 0.0, "particle 1 is outside the region");
        let want = closed_form(0.2, 0.5, row[0]);
        assert!(
            (row[4] - want).abs() < 1e-12,
            "step {}: {} vs {want}",
            row[0],
            row[4]
        );
    }
    let r = rows(&format!(
        "{FREE}group one id 1\nfix s one speedcontrol 0.2 NULL NULL\n{PROBE}"
    ));
    for row in &r {
        assert!((row[1] - closed_form(0.2, 0.1, row[0])).abs() < 1e-12);
        assert_eq!(row[4], 0.0, "particle 2 is not in the group");
    }
}

#[test]
fn bad_input_gets_located_errors() {
    let text = error(&format!("{FREE}fix s all speedcontrol 1 0 0 gian 0.2\n"));
    assert!(text.contains("in.speed:21:30"), "{text}");
    assert!(
        text.contains("'region'") && text.contains("'gain'"),
        "{text}"
    );
    let text = error(&format!("{FREE}fix s all speedcontrol 1 fast 0\n"));
    assert!(text.contains("vy must be a number, not 'fast'"), "{text}");
    assert!(text.contains("a number, NULL or v_name"), "{text}");
    let text = error(&format!(
        "{FREE}variable a atom vx\nfix s all speedcontrol v_a 0 0\nrun 1\n"
    ));
    assert!(text.contains("atom-style is not supported yet"), "{text}");
}

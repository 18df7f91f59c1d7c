//! `fix addforce` with variables: equal-style components evaluated before each step,
//! atom-style components per particle in the force pass, with the velocities of that
//! moment (after the first half kick), as LIGGGHTS 3.8 evaluates them in its post-force
//! stage. And `fix aveforce` with equal-style variables.

use crate::common;

/// Two spheres in a 2 m box, dt = 1 ms, no gravity; particle 1 moves with (1, −2, 0.5)
/// m/s, particle 2 with (−1, 0, 0).
const HEAD: &str = "\
units si
atom_style granular
atom_modify map array sort 0 0
boundary f f f
newton off
communicate single vel yes
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-3
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0.5 0.5 0.5 units box
set atom 1 diameter 0.01 density 2000 vx 1.0 vy -2.0 vz 0.5
set atom 2 diameter 0.02 density 2000 vx -1.0 vy 0.0 vz 0.0
";

/// Thermo every `every` steps: vx, vy, vz of particle 1 and vx, vy of particle 2.
fn probe(every: u32, steps: u32) -> String {
    format!(
        "variable a1 equal vx[1]\nvariable a2 equal vy[1]\nvariable a3 equal vz[1]\n\
         variable b1 equal vx[2]\nvariable b2 equal vy[2]\n\
         thermo_style custom step atoms v_a1 v_a2 v_a3 v_b1 v_b2\n\
         thermo_modify format float %.15g\nthermo {every}\nrun {steps}\n"
    )
}

/// The thermo rows of `script`'s run (each row's numbers).
fn rows(script: &str) -> Vec<Vec<f64>> {
    let out = common::run_screen("in.addforce", script);
    out.lines()
        .filter_map(|l| {
            l.split_whitespace()
                .map(str::parse::<f64>)
                .collect::<Result<Vec<_>, _>>()
                .ok()
        })
        .filter(|r| r.len() == 7)
        .collect()
}

fn assert_close(got: f64, want: f64, rel: f64, what: &str) {
    assert!(
        (got - want).abs() <= rel * want.abs().max(1e-300),
        "{what}: {got} against {want}"
    );
}

/// A quadratic drag −c|v|v in x and y (as a real user's column-packing script writes it,
/// with `${c}` in the formula), plus an equal-style ramp 1e-4·step in y, and a drag
/// −0.5·m·vz/dt in z. LIGGGHTS 3.8 printed these rows for the same script (%.15g); rdem
/// agrees to 2 units in the 15th digit.
#[test]
fn atom_style_drag_matches_liggghts() {
    let script = format!(
        "{HEAD}variable c equal 0.003\nvariable t equal 1e-4*step\n\
         variable dx atom -${{c}}*sqrt(vx^2+vy^2+vz^2)*vx\n\
         variable dy atom -${{c}}*sqrt(vx^2+vy^2+vz^2)*vy+v_t\n\
         variable dz atom -0.5*mass*vz/dt\n\
         fix f all addforce v_dx v_dy v_dz\nfix integr all nve/sphere\n{}",
        probe(10, 30)
    );
    let liggghts = [
        [
            0.939315287442448,
            -1.8739381862397,
            0.00054931640625,
            -0.996430583368036,
            0.000596223896524983,
        ],
        [
            0.885933558115493,
            -1.75343844549366,
            5.36441802978516e-07,
            -0.992886495431112,
            0.00238208090455866,
        ],
        [
            0.838691381590526,
            -1.63659303333938,
            5.23868948221207e-10,
            -0.989367512427651,
            0.00535338324254991,
        ],
    ];
    let r = rows(&script);
    assert_eq!(r.len(), 4, "{r:?}");
    for (row, want) in r[1..].iter().zip(liggghts) {
        for (k, w) in want.iter().enumerate() {
            assert_close(
                row[2 + k],
                *w,
                2e-15,
                &format!("step {} column {k}", row[0]),
            );
        }
    }
}

/// A linear drag f = −c·v: with a = c·dt/(2m), each force pass sees the half-step
/// velocity, and v_n = v_0·(1 − a)²·(1 − 2a)^(n−1) (the set-up force acts on v_0).
/// Particle 2, outside the region, keeps its velocity.
#[test]
fn linear_drag_follows_the_velocity_verlet_closed_form() {
    let c = 0.002;
    let script = format!(
        "{HEAD}variable d atom -{c}*vx\nregion near sphere 0 0 0 0.2 units box\n\
         fix f all addforce v_d 0 0 region near\nfix integr all nve/sphere\n{}",
        probe(1, 30)
    );
    let m = 2000.0 * std::f64::consts::PI / 6.0 * 0.01f64.powi(3);
    let a = c * 1e-3 / (2.0 * m);
    let r = rows(&script);
    assert_eq!(r.len(), 31);
    for row in &r[1..] {
        let n = row[0] as i32;
        let want = (1.0 - a).powi(2) * (1.0 - 2.0 * a).powi(n - 1);
        assert_close(row[2], want, 1e-13, &format!("step {n}"));
        assert_eq!(row[5], -1.0, "particle 2 is outside the region");
    }
}

/// Equal-style components (here a ramp in time) act on every particle of the group.
#[test]
fn equal_style_components_are_evaluated_at_each_step() {
    let script = format!(
        "{HEAD}variable g equal 1e-3*step\ngroup one id 2\n\
         fix f one addforce 0 v_g 0\nfix integr all nve/sphere\n{}",
        probe(1, 5)
    );
    let m2 = 2000.0 * std::f64::consts::PI / 6.0 * 0.02f64.powi(3);
    let r = rows(&script);
    // vy_n = dt/m · (F_0/2 + F_1 + ... + F_{n-1} + F_n/2), F_k = 1e-3·k.
    for row in &r[1..] {
        let n = row[0];
        let want = 1e-3 / m2 * 1e-3 * (n * (n - 1.0) / 2.0 + n / 2.0);
        assert_close(row[6], want, 1e-13, &format!("step {n}"));
        assert_eq!(row[3], -2.0, "particle 1 is not in the group");
    }
}

#[test]
fn bad_formulas_and_keywords_are_errors() {
    let run = "fix integr all nve/sphere\nrun 5\n";
    let e = common::error(
        "in.bad",
        &format!("{HEAD}variable s atom sqrt(vx-2)\nfix f all addforce v_s 0 0\n{run}"),
    );
    assert!(e.contains("fix addforce: the force on atom"), "{e}");
    assert!(e.contains("not finite"), "{e}");
    let e = common::error(
        "in.bad",
        &format!("{HEAD}variable s atom density*vx\nfix f all addforce v_s 0 0\n{run}"),
    );
    assert!(
        e.contains("'density' cannot be read while the forces are summed"),
        "{e}"
    );
    let e = common::error(
        "in.bad",
        &format!(
            "{HEAD}compute k all ke/atom\nvariable s atom c_k\nfix f all addforce v_s 0 0\n{run}"
        ),
    );
    assert!(e.contains("c_k is per-atom"), "{e}");
    let line = HEAD.lines().count() + 1;
    let e = common::error(
        "in.bad",
        &format!("{HEAD}fix f all addforce 1 0 0 energy v_e\n"),
    );
    assert!(e.contains("addforce energy is not supported yet"), "{e}");
    assert!(e.contains(&format!("in.bad:{line}:26")), "{e}");
}

/// `fix aveforce v_g NULL v_h` with g = 1e-3·step and h = −2e-3·time/dt: with no contact
/// the group's mean force is 0, so each particle gets (g, its own fy, h). LIGGGHTS 3.8
/// printed these rows (%.15g) for the same script; rdem prints the same digits.
#[test]
fn aveforce_with_equal_style_variables_matches_liggghts() {
    let script = format!(
        "{HEAD}variable g equal 1e-3*step\nvariable h equal -2e-3*time/dt\n\
         fix f all aveforce v_g NULL v_h\nfix integr all nve/sphere\n{}",
        probe(10, 30)
    );
    let liggghts = [
        [
            1.04774648292757,
            -2.0,
            0.404507034144863,
            -0.994031689634054,
            0.0,
        ],
        [
            1.19098593171027,
            -2.0,
            0.118028136579451,
            -0.976126758536216,
            0.0,
        ],
        [
            1.42971834634811,
            -2.0,
            -0.359436692696235,
            -0.946285206706486,
            0.0,
        ],
    ];
    let r = rows(&script);
    assert_eq!(r.len(), 4, "{r:?}");
    for (row, want) in r[1..].iter().zip(liggghts) {
        for (k, w) in want.iter().enumerate() {
            assert_close(
                row[2 + k],
                *w,
                1e-15,
                &format!("step {} column {k}", row[0]),
            );
        }
    }
}

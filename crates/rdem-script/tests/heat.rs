//! `fix heat/gran` (heat conduction through contacts) and walls with a `temperature`:
//! closed forms, and the numbers LIGGGHTS 3.8 printed for the same scripts.
//!
//! The LIGGGHTS runs: [`HEAD`] plus the lines of each test, run with
//! `liggghts -in in.x -log none` (Debian package 3.8.0), a `dump custom` of `id f_Temp
//! f_heatFlux` every step with `%.17g`. LIGGGHTS 3.8 needs a `run 0` between the
//! definition of `heat/gran` and a `set ... property/atom Temp` (rdem does not).

// LIGGGHTS' figures are kept with the 17 digits it printed.
#![allow(clippy::excessive_precision)]

use rdem_script::Interpreter;

use crate::common;

/// Two atom types (conductivity 100 and 50, capacity 10 and 20), Hertz contacts, dt 1 ms,
/// no integration: the particles stay where they are created.
const HEAD: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.05 0.05 -0.05 0.05 -0.05 0.05 units box
create_box 2 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.7 0.7 0.7 0.7
fix m4 all property/global coefficientFriction peratomtypepair 2 0.05 0.05 0.05 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.001
fix ftco all property/global thermalConductivity peratomtype 100. 50.
fix ftca all property/global thermalCapacity peratomtype 10. 20.
";

/// Two spheres of diameter 0.01 at centre distance 0.0095: type 1 (density 8000) and
/// type 2 (density 4000).
const PAIR: &str = "\
create_atoms 1 single 0 0 0 units box
create_atoms 2 single 0.0095 0 0 units box
set atom 1 diameter 0.01 density 8000
set atom 2 diameter 0.01 density 4000
";

fn interp(src: &str) -> Interpreter {
    common::run("in.heat", src)
}

/// The error a script stops with, rendered.
fn error_of(src: &str) -> String {
    common::error("in.heat", src)
}

/// Per-atom property `name` of the particles, by tag.
fn prop(i: &Interpreter, name: &str) -> Vec<f64> {
    let w = i.sim.world.as_ref().unwrap();
    let p = &w.particles;
    let id = p
        .property(name)
        .unwrap_or_else(|| panic!("no property {name}"));
    let mut v: Vec<(u64, f64)> = (0..p.nlocal())
        .map(|k| (p.tag[k], p.props[id.0].get(k)[0]))
        .collect();
    v.sort_by_key(|e| e.0);
    v.into_iter().map(|e| e.1).collect()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

/// The conductance of the manual: h = 4 k1 k2 / (k1 + k2) √A, with A the area of the
/// circle where the spheres intersect (radius a, a² = R² − (d/2)² for equal radii).
fn pair_h(k1: f64, k2: f64, r: f64, d: f64) -> f64 {
    let a2 = r * r - 0.25 * d * d;
    4.0 * k1 * k2 / (k1 + k2) * (std::f64::consts::PI * a2).sqrt()
}

/// Closed form: two touching spheres held in place exchange heat until equal; the
/// difference decays as exp(−h (1/C1 + 1/C2) t), C = m c, and the explicit Euler step
/// gives exactly (1 − h dt (1/C1 + 1/C2))^n; Σ C T is conserved to round-off and equals
/// `f_ID`.
#[test]
fn two_spheres_decay_as_closed_form() {
    let n = 200;
    let src = format!(
        "{HEAD}{PAIR}fix ht all heat/gran initial_temperature 300.\n\
         set atom 1 property/atom Temp 400.\n\
         variable e equal f_ht\n\
         run {n}\n"
    );
    let i = interp(&src);
    let t = prop(&i, "Temp");
    let m1 = 8000.0 * std::f64::consts::PI / 6.0 * 1e-6;
    let m2 = 4000.0 * std::f64::consts::PI / 6.0 * 1e-6;
    let (c1, c2) = (m1 * 10.0, m2 * 20.0);
    let h = pair_h(100.0, 50.0, 0.005, 0.0095);
    let dt = 1e-3;
    let lambda = h * (1.0 / c1 + 1.0 / c2);
    let discrete = 100.0 * (1.0 - lambda * dt).powi(n);
    let exact = 100.0 * (-lambda * dt * n as f64).exp();
    let diff = t[0] - t[1];
    assert!(close(diff, discrete, 1e-10), "{diff} vs {discrete}");
    // λ dt = 0.0176: the Euler steps lag the exponential by n (λ dt)²/2 ≈ 3 %.
    assert!(close(diff, exact, 0.04), "{diff} vs {exact}");
    assert!(diff < 0.05 * 100.0 && diff > 0.0);
    let energy = c1 * t[0] + c2 * t[1];
    let start = c1 * 400.0 + c2 * 300.0;
    assert!(close(energy, start, 1e-14), "{energy} vs {start}");
    let f = rdem_script::fixes::fix_value(&i.sim, "ht", None).unwrap();
    assert!(close(f, energy, 1e-14), "f_ht {f} vs {energy}");
}

/// The same pair in LIGGGHTS 3.8 (`fix heattransfer all heat/gran initial_temperature
/// 300.`, `run 0`, `set atom 1 property/atom Temp 400.`, `run 5`): its temperatures and
/// heat flows after 5 steps, and f_heattransfer (printed with %20.15g).
#[test]
fn two_spheres_as_liggghts() {
    let src = format!(
        "{HEAD}{PAIR}fix heattransfer all heat/gran initial_temperature 300.\n\
         set atom 1 property/atom Temp 400.\n\
         run 5\n"
    );
    let i = interp(&src);
    let t = prop(&i, "Temp");
    let q = prop(&i, "heatFlux");
    // LIGGGHTS 3.8, step 5: "1 395.74826283135036 -34.364471383776646",
    // "2 304.25173716864964 34.364471383776646".
    assert!(close(t[0], 395.74826283135036, 1e-14), "{}", t[0]);
    assert!(close(t[1], 304.25173716864964, 1e-14), "{}", t[1]);
    assert!(close(q[0], -34.364471383776646, 1e-12), "{}", q[0]);
    assert!(close(q[1], 34.364471383776646, 1e-12), "{}", q[1]);
    let f = rdem_script::fixes::fix_value(&i.sim, "heattransfer", None).unwrap();
    assert!(close(f, 29.3215314335047, 1e-14), "{f}");
    // directionalHeatFlux[1]: half the flow times x_i − x_j, the same for both.
    let w = i.sim.world.as_ref().unwrap();
    let id = w.particles.property("directionalHeatFlux").unwrap();
    let d = &w.particles.props[id.0];
    let want = 0.5 * -34.364471383776646 * -0.0095;
    assert!(close(d.get(0)[0], want, 1e-12) && close(d.get(1)[0], want, 1e-12));
}

/// The contact-area keywords against LIGGGHTS 3.8 (the pair above, one step):
/// `contact_area constant 1e-4` T1 = 396.81690113816211, `projection` 397.17905208226119,
/// `area_correction yes` with `youngsModulusOriginal` 5e7 (Hertz: the overlap times
/// 0.1^(2/3)) 399.58705805434022; `initial_temperature 1e-7` is passed on as "%f", so
/// 0: T2 = 3.5233628199729665.
#[test]
fn keywords_as_liggghts() {
    for (words, tag, want) in [
        ("contact_area constant 1e-4", 0, 396.81690113816211),
        ("contact_area projection", 0, 397.17905208226119),
        ("area_correction yes", 0, 399.58705805434022),
    ] {
        let src = format!(
            "{HEAD}{PAIR}fix yo all property/global youngsModulusOriginal peratomtype 5.e7 5.e7\n\
             fix ht all heat/gran/conduction initial_temperature 300. {words}\n\
             set atom 1 property/atom Temp 400.\n\
             run 1\n"
        );
        let t = prop(&interp(&src), "Temp");
        assert!(close(t[tag], want, 1e-14), "{words}: {} vs {want}", t[tag]);
        assert!(close(t[0] + t[1], 700.0, 1e-14), "{words}");
    }
    let src = format!(
        "{HEAD}{PAIR}fix ht all heat/gran initial_temperature 1e-7\n\
         set atom 1 property/atom Temp 400.\n\
         run 1\n"
    );
    let t = prop(&interp(&src), "Temp");
    assert!(close(t[1], 3.5233628199729665, 1e-14), "{}", t[1]);
}

/// `heat/gran` (not `heat/gran/conduction`) ends its line at the first word that is not a
/// keyword, as LIGGGHTS 3.8 does, with one warning naming what is ignored. LIGGGHTS 3.8 on
/// the pair above, one step (`run 0` before the `set`): `initial_temperature 300. 300.
/// contact_area constant 1e-4` gives T1 = 399.11915929500674 (the overlap area, the same as
/// `initial_temperature 300.`: the constant area after the ignored `300.` is not read);
/// `initial_temperature 300. contact_area constant 1e-4 junk 2` gives 396.81690113816211
/// (the area read, `junk 2` ignored).
#[test]
fn heat_gran_ignores_the_rest_of_the_line_as_liggghts() {
    for (words, want, ignored) in [
        (
            "initial_temperature 300. 300. contact_area constant 1e-4",
            399.11915929500674,
            "'300. contact_area constant 1e-4' is ignored",
        ),
        (
            "initial_temperature 300. contact_area constant 1e-4 junk 2",
            396.81690113816211,
            "'junk 2' is ignored",
        ),
    ] {
        let src = format!(
            "{HEAD}{PAIR}fix ht all heat/gran {words}\n\
             set atom 1 property/atom Temp 400.\n\
             run 1\n"
        );
        let i = interp(&src);
        let t = prop(&i, "Temp");
        assert!(close(t[0], want, 1e-14), "{words}: {} vs {want}", t[0]);
        let out = common::screen(&i);
        let warnings: Vec<&str> = out.lines().filter(|l| l.contains("WARNING")).collect();
        let line = HEAD.lines().count() + PAIR.lines().count() + 1;
        let hits: Vec<&&str> = warnings
            .iter()
            .filter(|w| w.contains("heat/gran"))
            .collect();
        assert_eq!(hits.len(), 1, "{words}: {out}");
        assert!(
            hits[0].contains(&format!("line {line}:")) && hits[0].contains(ignored),
            "{words}: {}",
            hits[0]
        );
    }
    // Without extra words: no warning.
    let src = format!("{HEAD}{PAIR}fix ht all heat/gran initial_temperature 300.\nrun 1\n");
    let out = interp(&src)
        .sim
        .outputs
        .out
        .captured
        .clone()
        .unwrap_or_default();
    assert!(!out.contains("heat/gran:"), "{out}");
}

/// A sphere resting on walls at fixed temperature T_w: T_w − T decays as
/// (1 − h dt/(m c))^n ≈ exp(−h t/(m c)), with h = 4 k_p k_w/(k_p + k_w) √(π(r² − (r−δ)²)).
/// LIGGGHTS 3.8 on the first step (overlap 1e-4 with a type-2 `zplane` at 400 K): particle
/// 1 (type 1) 300.56136154777641, particle 2 (type 2) 300.21051058041616; with the floor
/// a `mesh/surface ... temperature 500.` instead, after 3 steps 303.34929705943154 and
/// 301.26040646597176.
#[test]
fn spheres_on_hot_walls() {
    let dir = std::env::temp_dir().join(format!("rdem-heat-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stl = dir.join("floor.stl");
    std::fs::write(
        &stl,
        "solid floor\nfacet normal 0 0 1\nouter loop\nvertex -0.04 -0.04 0\nvertex 0.04 -0.04 0\n\
         vertex 0.04 0.04 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex -0.04 -0.04 0\n\
         vertex 0.04 0.04 0\nvertex -0.04 0.04 0\nendloop\nendfacet\nendsolid floor\n",
    )
    .unwrap();
    let spheres = "\
create_atoms 1 single 0 0 0.0049 units box
create_atoms 2 single 0.02 0 0.0049 units box
set atom 1 diameter 0.01 density 8000
set atom 2 diameter 0.01 density 8000
fix heattransfer all heat/gran initial_temperature 300.
";
    let stl = stl.display();
    // Primitive wall at 400 touching, mesh at 500 1 mm below (not touching).
    let src = format!(
        "{HEAD}{spheres}\
         fix w1 all wall/gran model hertz tangential history primitive type 2 zplane 0.0 temperature 400.\n\
         fix m all mesh/surface file {stl} type 2 move 0 0 -0.001 temperature 500.\n\
         fix w2 all wall/gran model hertz tangential history mesh n_meshes 1 meshes m\n\
         run 1\n"
    );
    let t = prop(&interp(&src), "Temp");
    assert!(close(t[0], 300.56136154777641, 1e-14), "{}", t[0]);
    assert!(close(t[1], 300.21051058041616, 1e-14), "{}", t[1]);
    // Mesh at 500 touching, primitive wall 1 cm below.
    let src = format!(
        "{HEAD}{spheres}\
         fix w1 all wall/gran model hertz tangential history primitive type 2 zplane -0.01 temperature 400.\n\
         fix m all mesh/surface file {stl} type 2 temperature 500.\n\
         fix w2 all wall/gran model hertz tangential history mesh n_meshes 1 meshes m\n\
         run 3\n"
    );
    let t = prop(&interp(&src), "Temp");
    assert!(close(t[0], 303.34929705943154, 1e-14), "{}", t[0]);
    assert!(close(t[1], 301.26040646597176, 1e-14), "{}", t[1]);
    // Closed form over 2000 steps on the primitive wall.
    let n = 2000;
    let src = format!(
        "{HEAD}{spheres}\
         fix w1 all wall/gran model hertz tangential history primitive type 2 zplane 0.0 temperature 400.\n\
         run {n}\n"
    );
    let t = prop(&interp(&src), "Temp");
    let area = std::f64::consts::PI * (0.005f64.powi(2) - 0.0049f64.powi(2));
    let m = 8000.0 * std::f64::consts::PI / 6.0 * 1e-6;
    for (k, (kp, c)) in [(100.0, 10.0), (50.0, 20.0)].into_iter().enumerate() {
        let h = 4.0 * kp * 50.0 / (kp + 50.0) * area.sqrt();
        let rate = h / (m * c);
        let discrete = 100.0 * (1.0 - rate * 1e-3).powi(n);
        let exact = 100.0 * (-rate * 1e-3 * n as f64).exp();
        let left = 400.0 - t[k];
        assert!(close(left, discrete, 1e-9), "{left} vs {discrete}");
        // rate dt ≤ 5.6e-3: within n (rate dt)²/2 ≤ 3.2 % of the exponential.
        assert!(close(left, exact, 0.035), "{left} vs {exact}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// An empty box's thermal energy prints as `0`.
#[test]
fn no_particles_print_zero_not_minus_zero() {
    // LIGGGHTS 3.8 prints `0` for the thermal energy of an empty box (wild case 50's
    // first thermo row).
    let i = interp(&format!(
        "{HEAD}fix heattransfer all heat/gran initial_temperature 300\n\
         thermo_style custom step atoms f_heattransfer\nrun 0\n"
    ));
    let out = common::screen(&i);
    let row = out
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("Step"))
        .nth(1)
        .unwrap_or_default()
        .to_string();
    assert_eq!(
        row.split_whitespace().collect::<Vec<_>>(),
        ["0", "0", "0"],
        "{out}"
    );
}

/// Only the group's temperatures change; a pair with one particle in the group still
/// conducts, so particle 1 approaches particle 2's fixed temperature at h/C1.
#[test]
fn group_outside_keeps_its_temperature() {
    let n = 100;
    let src = format!(
        "{HEAD}{PAIR}group one id 1\n\
         fix ht one heat/gran initial_temperature 300.\n\
         set atom 1 property/atom Temp 400.\n\
         run {n}\n"
    );
    let t = prop(&interp(&src), "Temp");
    let m1 = 8000.0 * std::f64::consts::PI / 6.0 * 1e-6;
    let h = pair_h(100.0, 50.0, 0.005, 0.0095);
    let discrete = 100.0 * (1.0 - h * 1e-3 / (m1 * 10.0)).powi(n);
    assert_eq!(t[1], 300.0);
    assert!(
        close(t[0] - 300.0, discrete, 1e-10),
        "{} vs {discrete}",
        t[0]
    );
}

/// LIGGGHTS 1.x's syntax, `fix ID group heat/gran T0` with `set ... property/peratom`
/// (LIGGGHTS 3.8 refuses both: "Fix heat/gran (id h): not enough arguments" and "Illegal set
/// command"): rdem reads them as 3.x's `initial_temperature T0` and `property/atom`, with
/// a warning for the fix, and conducts exactly as the 3.x spelling does.
#[test]
fn liggghts_1x_syntax_conducts_as_the_3x_syntax() {
    let run = |fix: &str, set: &str| {
        let src =
            format!("{HEAD}{PAIR}group one id 1\n{fix}\nset atom 1 {set} Temp 400.\nrun 100\n");
        let i = interp(&src);
        (prop(&i, "Temp"), common::screen(&i))
    };
    let (new, _) = run(
        "fix ht one heat/gran initial_temperature 300.",
        "property/atom",
    );
    let (old, screen) = run("fix ht one heat/gran 300.", "property/peratom");
    assert_eq!(old, new);
    assert!(new[0] > 300.0 && new[0] < 400.0, "{new:?}");
    assert!(
        screen.contains("fix heat/gran T0 is LIGGGHTS 1.x syntax"),
        "{screen}"
    );
}

/// A `fix Temp all property/atom Temp ...` defined before heat/gran is replaced and its
/// values reset to T0 (LIGGGHTS 3.8: 350 and a `set` to 450 both become 300); `f_Temp[0]`
/// (LIGGGHTS' old spelling) reads the temperatures as `f_Temp`; the same name under
/// another fix ID is an error, as in LIGGGHTS.
#[test]
fn temp_property_defined_before() {
    let src = format!(
        "{HEAD}{PAIR}fix Temp all property/atom Temp scalar yes yes no 350.\n\
         set atom 1 property/atom Temp 450.\n\
         fix heattransfer all heat/gran initial_temperature 300.\n\
         variable t atom f_Temp[0]\n\
         compute s all reduce sum v_t f_heattransfer\n\
         variable s equal c_s[1]+c_s[2]\n\
         print \"sum=$s\"\n"
    );
    let i = interp(&src);
    assert_eq!(prop(&i, "Temp"), vec![300.0, 300.0]);
    let out = common::screen(&i);
    assert!(out.contains("sum=1200"), "{out}");
    let e = error_of(&format!(
        "{HEAD}{PAIR}fix myT all property/atom Temp scalar yes yes no 350.\n\
         fix heattransfer all heat/gran initial_temperature 300.\n"
    ));
    assert!(e.contains("fix myT already holds one of that name"), "{e}");
}

/// Bad input: located errors, never a silent keyword.
#[test]
fn errors() {
    for (tail, want) in [
        // (`heat/gran 300.` is LIGGGHTS 1.x syntax, which rdem reads; see above.)
        (
            "fix h all heat/gran/conduction 300.",
            "unknown heat/gran keyword '300.'",
        ),
        (
            "fix h all heat/gran/conduction initial_temperature 300. bogus 3",
            "unknown heat/gran keyword 'bogus'",
        ),
        (
            "fix h all heat/gran initial_temperature 300. store_contact_data yes",
            "store_contact_data yes is not supported yet",
        ),
        (
            "fix h all heat/gran initial_temperature 300. contact_area projection area_correction yes",
            "area_correction works only with contact_area overlap",
        ),
        (
            "fix h all heat/gran initial_temperature 300. contact_area constant -1",
            "contact area",
        ),
        (
            "fix h all heat/gran initial_temperature 300.\nfix h2 all heat/gran initial_temperature 300.",
            "there is already a heat conduction fix (fix h)",
        ),
        (
            "fix w all wall/gran model hertz tangential history primitive type 1 zplane 0 temperature -3",
            "wall temperature -3 is negative",
        ),
        (
            "fix w all wall/gran model hertz tangential history primitive type 1 zplane 0 temperature 400.\nrun 1",
            "has a temperature but the particles have none",
        ),
        (
            "unfix ftca\nfix h all heat/gran initial_temperature 300.\nrun 1",
            "heat/gran needs 'fix ID all property/global thermalCapacity peratomtype'",
        ),
    ] {
        let e = error_of(&format!("{HEAD}{PAIR}{tail}\n"));
        assert!(e.contains(want), "{tail}: {e}");
    }
}

//! Golden trajectory tests against LIGGGHTS 3.8 for every contact sub-model.
//!
//! Each scenario in `tests/data/liggghts/` is a small LIGGGHTS input script (`in.<name>`)
//! and the `dump custom` it wrote (`<name>.dump`, every step, `%.17g`; the README there
//! says how they were produced). Two spheres of different size and material (types 1 and
//! 2, so every coefficient is mixed) meet obliquely with spin, or one sphere hits a
//! primitive wall of type 2 (a `zplane`, or a `zcylinder` from inside) obliquely with
//! spin, so the normal, tangential, rolling and torsion terms all act through one whole
//! contact. Together they use hertz, hooke and hooke/hysteresis; tangential history and
//! no_history; rolling friction cdt, epsd and epsd2; cohesion sjkr and sjkr2; and
//! `tangential_damping off`, `limitForce on`, `torsionTorque on`, `tangential_reduce on`,
//! each for a pair and for a wall.
//!
//! The test reads the script (box, materials, contact model, wall, timestep, initial
//! state, `run` commands), builds the same state through the engine API, runs it with
//! `nve/sphere` (a `World::setup` before every `run`, as LIGGGHTS does), and compares every
//! dumped step — position, velocity, angular velocity, force and torque of every particle,
//! step 0 (the set-up force evaluation) included.
//!
//! Tolerance. Both codes evaluate the same closed-form contact law in double precision and
//! integrate it with the same velocity Verlet, so they may differ only by round-off (the
//! order of floating-point operations, e.g. in 4/3·π·r³·ρ for the mass or in the Hertz
//! √(R*δ)). Over one contact of ~150 steps this grows little: the forces are smooth in the
//! state except at the Coulomb stick/slip switch (the tangential damping drops out when the
//! spring reaches the cap) and the `limitForce` clamp, which round-off would only flip if
//! the comparison were tied to the last bits. So every compared vector must agree within
//! `TOL = 1e-9` relative to its natural scale: force and torque to the peak force and peak
//! torque of the run, velocity and angular velocity to their largest magnitude in the run,
//! position to the particle radius. The measured disagreement is at most 1.4e-14.
//!
//! A golden test only guards what its trajectory depends on, so
//! `scenarios_exercise_their_sub_models` flips each covered switch (or changes each covered
//! coefficient by 0.1 %) and requires the result to leave the LIGGGHTS trajectory by more
//! than 1e-6: this shows, e.g., that Coulomb sliding and sticking, the rolling-torque cap
//! and the hysteresis adhesive branch are all reached.
//!
//! Three scenarios start a `run` with a contact already present (`*_overlap_start`,
//! `*_tworuns`): they check that the set-up force evaluation, like LIGGGHTS', uses the
//! stored tangential spring as it is, adds rolling-spring increments without storing
//! them, and records the hysteresis largest overlap.
//!
//! Two scenarios (`pair_recontact_*`) let a pair part and touch again before the next
//! neighbor build, a falling sphere bouncing on a frozen one: LIGGGHTS keeps the contact's
//! histories (tangential spring, epsd rolling torque, the hysteresis largest overlap)
//! until that build, and so does rdem. They also check LIGGGHTS' effective mass with
//! `fix freeze`: the other particle's mass, as if the frozen one were infinitely heavy.

use std::collections::HashMap;

use rdem::contact::names::{
    COHESION_MODELS, NORMAL_MODELS, ROLLING_MODELS, SURFACE_MODELS, TANGENTIAL_MODELS,
};
use rdem::{
    Boundary, CohesionKind, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NeighborSettings,
    NewParticle, NormalKind, PairGran, PrimitiveWall, RollingKind, TangentialKind, WallShape,
    World,
};

/// Allowed disagreement, relative to the scale of each quantity (see the module docs).
const TOL: f64 = 1e-9;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/liggghts");

// ---------------------------------------------------------------------------------------
// The dump
// ---------------------------------------------------------------------------------------

/// One particle of one dumped step.
#[derive(Debug, Clone, Copy)]
struct Atom {
    id: u64,
    ty: u32,
    x: DVec3,
    v: DVec3,
    omega: DVec3,
    f: DVec3,
    torque: DVec3,
}

/// One dumped step.
#[derive(Debug, Clone)]
struct Frame {
    step: u64,
    atoms: Vec<Atom>,
}

/// Parses a LIGGGHTS `dump custom` text file: blocks of `ITEM:` headers, the atom lines
/// read by the column names of `ITEM: ATOMS`.
fn parse_dump(text: &str) -> Vec<Frame> {
    let mut frames = Vec::new();
    let mut lines = text.lines();
    let mut step = None;
    let mut natoms = 0usize;
    while let Some(line) = lines.next() {
        let line = line.trim();
        if line == "ITEM: TIMESTEP" {
            step = Some(lines.next().unwrap().trim().parse::<u64>().unwrap());
        } else if line == "ITEM: NUMBER OF ATOMS" {
            natoms = lines.next().unwrap().trim().parse().unwrap();
        } else if line.starts_with("ITEM: BOX BOUNDS") {
            for _ in 0..3 {
                lines.next().unwrap();
            }
        } else if let Some(cols) = line.strip_prefix("ITEM: ATOMS") {
            let cols: Vec<&str> = cols.split_whitespace().collect();
            let col = |name: &str| {
                cols.iter()
                    .position(|c| *c == name)
                    .unwrap_or_else(|| panic!("dump has no column {name}"))
            };
            let ix = |names: [&str; 3]| names.map(col);
            let (cx, cv, cw, cf, ct) = (
                ix(["x", "y", "z"]),
                ix(["vx", "vy", "vz"]),
                ix(["omegax", "omegay", "omegaz"]),
                ix(["fx", "fy", "fz"]),
                ix(["tqx", "tqy", "tqz"]),
            );
            let (cid, cty) = (col("id"), col("type"));
            let mut atoms = Vec::with_capacity(natoms);
            for _ in 0..natoms {
                let w: Vec<&str> = lines.next().unwrap().split_whitespace().collect();
                assert_eq!(w.len(), cols.len(), "dump line with a wrong column count");
                let num = |c: usize| w[c].parse::<f64>().unwrap();
                let vec3 = |c: [usize; 3]| DVec3::new(num(c[0]), num(c[1]), num(c[2]));
                atoms.push(Atom {
                    id: w[cid].parse().unwrap(),
                    ty: w[cty].parse().unwrap(),
                    x: vec3(cx),
                    v: vec3(cv),
                    omega: vec3(cw),
                    f: vec3(cf),
                    torque: vec3(ct),
                });
            }
            frames.push(Frame {
                step: step.take().expect("ITEM: ATOMS before ITEM: TIMESTEP"),
                atoms,
            });
        } else if !line.is_empty() {
            panic!("unexpected dump line {line:?}");
        }
    }
    frames
}

// ---------------------------------------------------------------------------------------
// The input script (only the commands these scenarios use)
// ---------------------------------------------------------------------------------------

/// A particle as `create_atoms ... single` and `set atom` give it.
#[derive(Debug, Clone, Copy, Default)]
struct ScriptAtom {
    ty: u32,
    /// Group bits (`all` is bit 1; `group NAME id N` adds the next bit).
    mask: u32,
    x: DVec3,
    v: DVec3,
    omega: DVec3,
    diameter: f64,
    density: f64,
}

/// What the test needs from a scenario script.
#[derive(Debug, Default)]
struct Script {
    lo: DVec3,
    hi: DVec3,
    ntypes: usize,
    skin: f64,
    dt: f64,
    /// Lengths of the `run` commands, in order.
    runs: Vec<u64>,
    /// `fix property/global` values by property name (for `peratomtypepair` without the
    /// leading matrix size).
    props: HashMap<String, Vec<f64>>,
    /// Words after `pair_style gran`.
    pair_style: Vec<String>,
    /// Words after `wall/gran`, if there is a wall.
    wall: Option<Vec<String>>,
    /// `freeze` and `gravity` fixes in definition order: (group bit, gravity's
    /// acceleration, or `None` for freeze).
    body_fixes: Vec<(u32, Option<DVec3>)>,
    /// Group names in definition order (`all` first): the bit of group k is 1 << k.
    groups: Vec<String>,
    atoms: Vec<ScriptAtom>,
}

impl Script {
    fn groupbit(&self, name: &str) -> u32 {
        let k = self.groups.iter().position(|g| g == name);
        1 << k.unwrap_or_else(|| panic!("no group {name}"))
    }
}

fn num(s: &str) -> f64 {
    s.parse()
        .unwrap_or_else(|_| panic!("not a number in script: {s}"))
}

fn parse_script(text: &str) -> Script {
    let mut s = Script {
        groups: vec!["all".into()],
        ..Script::default()
    };
    for raw in text.lines() {
        let line = raw.split('#').next().unwrap();
        let w: Vec<&str> = line.split_whitespace().collect();
        if w.is_empty() {
            continue;
        }
        match w[0] {
            "atom_style" | "atom_modify" | "boundary" | "newton" | "communicate" | "units"
            | "neigh_modify" | "pair_coeff" | "dump" | "dump_modify" => {}
            "region" => {
                assert_eq!(&w[2..3], ["block"]);
                let b: Vec<f64> = w[3..9].iter().map(|v| num(v)).collect();
                s.lo = DVec3::new(b[0], b[2], b[4]);
                s.hi = DVec3::new(b[1], b[3], b[5]);
            }
            "create_box" => s.ntypes = w[1].parse().unwrap(),
            "neighbor" => s.skin = num(w[1]),
            "timestep" => s.dt = num(w[1]),
            "run" => s.runs.push(w[1].parse().unwrap()),
            "pair_style" => {
                assert_eq!(w[1], "gran");
                s.pair_style = w[2..].iter().map(|x| x.to_string()).collect();
            }
            "create_atoms" => {
                assert_eq!(w[2], "single");
                s.atoms.push(ScriptAtom {
                    ty: w[1].parse().unwrap(),
                    mask: 1,
                    x: DVec3::new(num(w[3]), num(w[4]), num(w[5])),
                    ..Default::default()
                });
            }
            "set" => {
                assert_eq!(w[1], "atom");
                let a = &mut s.atoms[w[2].parse::<usize>().unwrap() - 1];
                for kv in w[3..].chunks(2) {
                    let v = num(kv[1]);
                    match kv[0] {
                        "diameter" => a.diameter = v,
                        "density" => a.density = v,
                        "vx" => a.v.x = v,
                        "vy" => a.v.y = v,
                        "vz" => a.v.z = v,
                        "omegax" => a.omega.x = v,
                        "omegay" => a.omega.y = v,
                        "omegaz" => a.omega.z = v,
                        k => panic!("set keyword {k} not handled"),
                    }
                }
            }
            "group" => {
                assert_eq!(w[2], "id");
                s.groups.push(w[1].to_string());
                let bit = s.groupbit(w[1]);
                for id in &w[3..] {
                    s.atoms[id.parse::<usize>().unwrap() - 1].mask |= bit;
                }
            }
            "fix" => match w[3] {
                "freeze" => s.body_fixes.push((s.groupbit(w[2]), None)),
                "gravity" => {
                    assert_eq!(w[5], "vector");
                    let dir = DVec3::new(num(w[6]), num(w[7]), num(w[8]));
                    let accel = num(w[4]) * dir.normalize();
                    s.body_fixes.push((s.groupbit(w[2]), Some(accel)));
                }
                "property/global" => {
                    let vals = match w[5] {
                        "scalar" | "peratomtype" => &w[6..],
                        "peratomtypepair" => &w[7..],
                        k => panic!("property/global style {k} not handled"),
                    };
                    s.props
                        .insert(w[4].to_string(), vals.iter().map(|v| num(v)).collect());
                }
                "wall/gran" => s.wall = Some(w[4..].iter().map(|x| x.to_string()).collect()),
                "nve/sphere" => {}
                k => panic!("fix style {k} not handled"),
            },
            c => panic!("command {c} not handled"),
        }
    }
    s
}

/// The kind that `table` (the script's own name table) gives the name `v` of model type `k`.
fn named<K: Copy>(table: &[(&str, K)], k: &str, v: &str) -> K {
    table
        .iter()
        .find(|(n, _)| *n == v)
        .unwrap_or_else(|| panic!("{k} {v}: not a name of rdem's table"))
        .1
}

/// The contact model and (for `wall/gran`) the wall type and shape from the words of
/// `pair_style gran` or `fix wall/gran`.
fn parse_model(words: &[String]) -> (ContactModel, Option<(u32, WallShape)>) {
    let mut m = ContactModel::hertz_history();
    let mut wall = None;
    let mut i = 0;
    let on = |v: &str| match v {
        "on" => true,
        "off" => false,
        _ => panic!("expected on/off, got {v}"),
    };
    while i < words.len() {
        let (k, v) = (words[i].as_str(), words[i + 1].as_str());
        i += 2;
        match k {
            "model" => m.normal = named(NORMAL_MODELS, k, v),
            "tangential" => m.tangential = named(TANGENTIAL_MODELS, k, v),
            "rolling_friction" => m.rolling = named(ROLLING_MODELS, k, v),
            "cohesion" => m.cohesion = named(COHESION_MODELS, k, v),
            "surface" => m.surface = named(SURFACE_MODELS, k, v),
            "tangential_damping" => m.flags.tangential_damping = on(v),
            "limitForce" => m.flags.limit_force = on(v),
            "torsionTorque" => m.flags.torsion_torque = on(v),
            "tangential_reduce" => m.flags.tangential_reduce = on(v),
            "absolute_damping" => m.flags.absolute_damping = on(v),
            "primitive" => {
                assert_eq!(v, "type");
                let ty: u32 = words[i].parse().unwrap();
                let shape = match words[i + 1].as_str() {
                    "zplane" => {
                        i += 3;
                        WallShape::Plane {
                            axis: 2,
                            pos: num(&words[i - 1]),
                        }
                    }
                    "zcylinder" => {
                        i += 5;
                        WallShape::Cylinder {
                            axis: 2,
                            radius: num(&words[i - 3]),
                            c1: num(&words[i - 2]),
                            c2: num(&words[i - 1]),
                        }
                    }
                    s => panic!("wall shape {s} not handled"),
                };
                wall = Some((ty, shape));
            }
            _ => panic!("model keyword {k} not handled"),
        }
    }
    (m, wall)
}

fn materials(s: &Script) -> Materials {
    let mut m = Materials {
        ntypes: s.ntypes,
        ..Default::default()
    };
    for (name, vals) in &s.props {
        let v = vals.clone();
        match name.as_str() {
            "youngsModulus" => m.youngs_modulus = v,
            "poissonsRatio" => m.poissons_ratio = v,
            "coefficientRestitution" => m.restitution = v,
            "coefficientFriction" => m.friction = v,
            "coefficientRollingFriction" => m.rolling_friction = v,
            "coefficientRollingViscousDamping" => m.rolling_viscous_damping = v,
            "cohesionEnergyDensity" => m.cohesion_energy_density = v,
            "characteristicVelocity" => m.characteristic_velocity = Some(v[0]),
            "coefficientAdhesionStiffness" => m.adhesion_stiffness = v,
            "coefficientPlasticityDepth" => m.plasticity_depth = v,
            "coefficientMaxElasticStiffness" => m.max_elastic_stiffness = v,
            "kn" => m.kn = v,
            "kt" => m.kt = v,
            "gamman" => m.gamman = v,
            "gammat" => m.gammat = v,
            "gamman_abs" => m.gamman_abs = v,
            "gammat_abs" => m.gammat_abs = v,
            "rollingStiffness" => m.rolling_stiffness = Some(v[0]),
            _ => panic!("property {name} not handled"),
        }
    }
    m
}

/// The world the script describes, before `run`.
fn build_world(s: &Script) -> World {
    let mut w = World::new(Domain::new(s.lo, s.hi, [Boundary::Fixed; 3]).unwrap());
    w.set_timestep(s.dt).unwrap();
    w.materials = materials(s);
    w.neighbor.settings = NeighborSettings {
        skin: s.skin,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    // `atom_modify sort 0 0`.
    w.sort.every = 0;
    let (pair_model, no_wall) = parse_model(&s.pair_style);
    assert!(no_wall.is_none());
    w.pair = Some(PairGran::new(pair_model));
    if let Some(words) = &s.wall {
        let (model, wall) = parse_model(words);
        assert_eq!(model, pair_model, "wall and pair models differ");
        let (ty, shape) = wall.expect("wall/gran without primitive");
        let wall = PrimitiveWall::new("wall", model, ty, shape).unwrap();
        w.add_fix(Fix::new("wall", 1, FixKind::WallGran(Box::new(wall))).unwrap())
            .unwrap();
    }
    for (k, &(bit, accel)) in s.body_fixes.iter().enumerate() {
        let kind = match accel {
            Some(accel) => FixKind::Gravity { accel },
            None => FixKind::Freeze,
        };
        w.add_fix(Fix::new(&format!("body{k}"), bit, kind).unwrap())
            .unwrap();
    }
    w.add_fix(Fix::new("integr", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    for (k, a) in s.atoms.iter().enumerate() {
        let mut new = NewParticle::at(a.x, 0.5 * a.diameter, a.density)
            .with_type(a.ty)
            .with_tag(k as u64 + 1)
            .with_v(a.v)
            .with_omega(a.omega);
        new.mask = a.mask;
        w.add_particle(&new).unwrap();
    }
    w
}

// ---------------------------------------------------------------------------------------
// Comparison
// ---------------------------------------------------------------------------------------

const KINDS: [&str; 5] = ["position", "velocity", "omega", "force", "torque"];

fn quantities(a: &Atom) -> [DVec3; 5] {
    [a.x, a.v, a.omega, a.f, a.torque]
}

/// A change to the contact model and materials of a scenario (for the sensitivity checks).
type Mutation = fn(&mut ContactModel, &mut Materials);

/// Runs scenario `name`, with its model and materials changed by `mutate`, and returns,
/// per quantity, the largest scaled disagreement with LIGGGHTS and the step where it
/// occurred.
fn run_scenario(
    name: &str,
    mutate: Mutation,
    setup: fn(&mut World),
    verbose: bool,
) -> [(f64, u64); 5] {
    let script = std::fs::read_to_string(format!("{DATA}/in.{name}")).unwrap();
    let dump = std::fs::read_to_string(format!("{DATA}/{name}.dump")).unwrap();
    let s = parse_script(&script);
    let frames = parse_dump(&dump);
    let nsteps: u64 = s.runs.iter().sum();
    assert_eq!(
        frames.len() as u64,
        nsteps + 1,
        "{name}: one frame per step"
    );
    // Steps after which a further `run` starts with its own set-up. LIGGGHTS dumps
    // that step once, before the set-up.
    let run_ends: Vec<u64> = s
        .runs
        .iter()
        .scan(0, |t, n| {
            *t += n;
            Some(*t)
        })
        .collect();
    // Scales: peak force and torque, largest speed and spin of the run, particle radius
    // for positions (per particle).
    let mut scale = [0.0f64; 5];
    for fr in &frames {
        for a in &fr.atoms {
            for (k, q) in quantities(a).iter().enumerate().skip(1) {
                scale[k] = scale[k].max(q.length());
            }
        }
    }
    assert!(scale[3] > 0.0, "{name}: no contact in the reference run");
    let mut w = build_world(&s);
    mutate(&mut w.pair.as_mut().unwrap().model, &mut w.materials);
    let mut scratch = w.materials.clone();
    for fix in &mut w.fixes {
        if let FixKind::WallGran(wall) = &mut fix.kind {
            mutate(&mut wall.model, &mut scratch);
        }
    }
    setup(&mut w);
    let mut worst = [(0.0f64, 0u64); 5];
    let mut reported = [false; 5];
    for fr in &frames {
        if fr.step > 0 {
            if run_ends.contains(&(fr.step - 1)) {
                setup(&mut w);
            }
            w.advance().unwrap();
        }
        assert_eq!(w.step, fr.step);
        let p = &w.particles;
        assert_eq!(p.nlocal(), fr.atoms.len());
        for a in &fr.atoms {
            let i = p.find_tag(a.id).expect("particle lost");
            assert_eq!(p.ty[i], a.ty);
            let ours = [p.x[i], p.v[i], p.omega[i], p.f[i], p.torque[i]];
            let theirs = quantities(a);
            for k in 0..5 {
                let sc = if k == 0 { p.radius[i] } else { scale[k] };
                let err = (ours[k] - theirs[k]).length() / sc;
                if err > worst[k].0 || err.is_nan() {
                    worst[k] = (err, fr.step);
                }
                if verbose && (err.is_nan() || err > TOL) && !reported[k] {
                    reported[k] = true;
                    eprintln!(
                        "{name}: step {} particle {} {}: rdem {:?} LIGGGHTS {:?} (scaled error {err:.3e})",
                        fr.step, a.id, KINDS[k], ours[k], theirs[k]
                    );
                }
            }
        }
    }
    worst
}

fn check(name: &str) {
    let worst = run_scenario(name, |_, _| {}, |w| w.setup().unwrap(), true);
    let report: Vec<String> = KINDS
        .iter()
        .zip(worst)
        .map(|(k, (e, st))| format!("{k} {e:.2e} (step {st})"))
        .collect();
    eprintln!("{name}: {}", report.join(", "));
    for (k, (e, st)) in KINDS.iter().zip(worst) {
        assert!(
            e <= TOL,
            "{name}: {k} differs from LIGGGHTS by {e:.3e} (scaled) at step {st}, tolerance {TOL:e}"
        );
    }
}

macro_rules! golden {
    ($($(#[$attr:meta])* $name:ident),* $(,)?) => {
        $(
            #[test]
            $(#[$attr])*
            fn $name() {
                check(stringify!($name));
            }
        )*
    };
}

golden!(
    pair_hertz_history,
    pair_hertz_history_cdt,
    pair_hertz_history_epsd,
    pair_hertz_history_epsd2_torsion,
    pair_hertz_history_epsd_tworuns,
    pair_recontact_hertz_history_epsd,
    pair_recontact_hysteresis,
    pair_hooke_history_notdamp,
    pair_hooke_nohistory_epsd2,
    pair_hertz_nohistory_limitforce,
    pair_hertz_history_sjkr,
    pair_hertz_history_sjkr2_reduce_epsd,
    pair_hysteresis,
    pair_hysteresis_overlap_start,
    wall_plane_hertz_history,
    wall_plane_hooke_history_epsd_notdamp,
    wall_plane_hertz_nohistory_limitforce_cdt,
    wall_plane_hertz_history_epsd2_sjkr2_reduce,
    wall_plane_hysteresis_torsion,
    wall_plane_hysteresis_overlap_start,
    wall_zcyl_hertz_history_cdt_sjkr,
    wall_zcyl_hooke_nohistory,
    pair_hooke_stiffness_history_epsd3,
    pair_hooke_stiffness_absdamp_nohistory_limitforce,
    pair_hertz_stiffness_history,
    wall_plane_hertz_stiffness_history_epsd3_torsion,
    wall_plane_hooke_stiffness_absdamp_notdamp,
);

/// The `pair_recontact_*` scenarios test what they are meant to: between the two contacts
/// (step 250: apart since 191 and 177) the pair is in the neighbor list that was built at
/// the set-up, untouched, with its contact history kept (a nonzero tangential spring).
/// LIGGGHTS goes on from that history when the pair touches again (steps 339 and 331), and
/// so does rdem: the golden tests above match it through the second contact.
#[test]
fn recontact_scenarios_keep_the_history_of_the_parted_pair() {
    for name in [
        "pair_recontact_hertz_history_epsd",
        "pair_recontact_hysteresis",
    ] {
        let script = std::fs::read_to_string(format!("{DATA}/in.{name}")).unwrap();
        let mut w = build_world(&parse_script(&script));
        w.setup().unwrap();
        let builds = w.neighbor.nbuilds;
        for _ in 0..250 {
            w.advance().unwrap();
        }
        assert_eq!(
            w.neighbor.nbuilds, builds,
            "{name}: no build between the contacts"
        );
        let list = &w.neighbor.list;
        assert_eq!(list.partner.len(), 1, "{name}: the pair is listed");
        assert_eq!(list.touch[0], 0, "{name}: apart at step 250");
        let spring = &list.hist[..list.width];
        assert!(
            spring.iter().any(|&h| h.abs() > 1e-9),
            "{name}: the contact history is kept: {spring:?}"
        );
    }
}

#[test]
fn every_scenario_is_tested() {
    // Every script in the data folder has a test above, and its dump exists.
    let this = include_str!("liggghts_golden.rs");
    for e in std::fs::read_dir(DATA).unwrap() {
        let f = e.unwrap().file_name().into_string().unwrap();
        if let Some(name) = f.strip_prefix("in.") {
            assert!(
                this.contains(&format!("    {name},")),
                "no golden test for {f}"
            );
            assert!(
                std::path::Path::new(&format!("{DATA}/{name}.dump")).exists(),
                "no dump for {f}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// The scenarios really exercise their sub-models
// ---------------------------------------------------------------------------------------

/// A change must move the trajectory by more than this (scaled as in the comparison) to
/// count as seen: a thousand times the tolerance.
const SEEN: f64 = 1e3 * TOL;

fn scale_table(t: &mut [f64], f: f64) {
    t.iter_mut().for_each(|x| *x *= f);
}

/// A golden test only guards what its trajectory depends on. For each scenario and each
/// sub-model, switch or coefficient it is meant to cover, flip the switch (or change the
/// coefficient by 0.1 %) and require the result to leave the LIGGGHTS trajectory by more
/// than [`SEEN`]. Coefficient changes also show which branch was reached: friction that
/// matters means Coulomb sliding happened, tangential damping that matters means sticking
/// happened, the epsd2 rolling coefficient (which only sets the cap there) means the
/// rolling torque reached its cap, epsd's viscous coefficient means it stayed below it,
/// the adhesion stiffness means the adhesive branch of hooke/hysteresis was reached.
#[test]
fn scenarios_exercise_their_sub_models() {
    let cases: &[(&str, &str, Mutation)] = &[
        (
            "pair_hertz_history",
            "tangential_damping off (sticking)",
            |c, _| c.flags.tangential_damping = false,
        ),
        ("pair_hertz_history", "friction +0.1 % (sliding)", |_, m| {
            scale_table(&mut m.friction, 1.001)
        }),
        (
            "pair_hertz_history",
            "limitForce on (pull at the end)",
            |c, _| c.flags.limit_force = true,
        ),
        ("pair_hertz_history", "restitution -0.1 %", |_, m| {
            scale_table(&mut m.restitution, 0.999)
        }),
        ("pair_hertz_history_cdt", "rolling off", |c, _| {
            c.rolling = RollingKind::Off
        }),
        ("pair_hertz_history_cdt", "torsionTorque on", |c, _| {
            c.flags.torsion_torque = true
        }),
        (
            "pair_hertz_history_cdt",
            "rolling friction +0.1 %",
            |_, m| scale_table(&mut m.rolling_friction, 1.001),
        ),
        ("pair_hertz_history_epsd", "rolling off", |c, _| {
            c.rolling = RollingKind::Off
        }),
        ("pair_hertz_history_epsd", "torsionTorque on", |c, _| {
            c.flags.torsion_torque = true
        }),
        (
            "pair_hertz_history_epsd",
            "rolling damping +0.1 % (below cap)",
            |_, m| scale_table(&mut m.rolling_viscous_damping, 1.001),
        ),
        (
            "pair_hertz_history_epsd2_torsion",
            "torsionTorque off",
            |c, _| c.flags.torsion_torque = false,
        ),
        (
            "pair_hertz_history_epsd2_torsion",
            "rolling friction +0.1 % (cap)",
            |_, m| scale_table(&mut m.rolling_friction, 1.001),
        ),
        (
            "pair_hertz_history_epsd2_torsion",
            "epsd instead of epsd2",
            |c, m| {
                c.rolling = RollingKind::Epsd;
                m.rolling_viscous_damping = vec![0.0; 4];
            },
        ),
        (
            "pair_hooke_history_notdamp",
            "tangential_damping on",
            |c, _| c.flags.tangential_damping = true,
        ),
        (
            "pair_hooke_history_notdamp",
            "hertz instead of hooke",
            |c, _| c.normal = NormalKind::Hertz,
        ),
        (
            "pair_hooke_nohistory_epsd2",
            "tangential history",
            |c, _| c.tangential = TangentialKind::History,
        ),
        (
            "pair_hooke_nohistory_epsd2",
            "friction +0.1 % (capped)",
            |_, m| scale_table(&mut m.friction, 1.001),
        ),
        ("pair_hooke_nohistory_epsd2", "rolling off", |c, _| {
            c.rolling = RollingKind::Off
        }),
        (
            "pair_hertz_nohistory_limitforce",
            "limitForce off",
            |c, _| c.flags.limit_force = false,
        ),
        (
            "pair_hertz_nohistory_limitforce",
            "tangential_damping off",
            |c, _| c.flags.tangential_damping = false,
        ),
        ("pair_hertz_history_sjkr", "cohesion off", |c, _| {
            c.cohesion = CohesionKind::Off
        }),
        (
            "pair_hertz_history_sjkr",
            "sjkr2 instead of sjkr",
            |c, _| c.cohesion = CohesionKind::Sjkr2,
        ),
        ("pair_hertz_history_sjkr", "tangential_reduce on", |c, _| {
            c.flags.tangential_reduce = true
        }),
        (
            "pair_hertz_history_sjkr2_reduce_epsd",
            "cohesion off",
            |c, _| c.cohesion = CohesionKind::Off,
        ),
        (
            "pair_hertz_history_sjkr2_reduce_epsd",
            "sjkr instead of sjkr2",
            |c, _| c.cohesion = CohesionKind::Sjkr,
        ),
        (
            "pair_hertz_history_sjkr2_reduce_epsd",
            "tangential_reduce off",
            |c, _| c.flags.tangential_reduce = false,
        ),
        (
            "pair_hysteresis",
            "hooke instead of hooke/hysteresis",
            |c, _| c.normal = NormalKind::Hooke,
        ),
        (
            "pair_hysteresis",
            "adhesion stiffness +0.1 % (adhesive branch)",
            |_, m| scale_table(&mut m.adhesion_stiffness, 1.001),
        ),
        ("pair_hysteresis", "max elastic stiffness +0.1 %", |_, m| {
            scale_table(&mut m.max_elastic_stiffness, 1.001)
        }),
        ("pair_hysteresis", "plasticity depth +0.1 %", |_, m| {
            scale_table(&mut m.plasticity_depth, 1.001)
        }),
        (
            "wall_plane_hertz_history",
            "tangential_damping off (sticking)",
            |c, _| c.flags.tangential_damping = false,
        ),
        (
            "wall_plane_hertz_history",
            "friction +0.1 % (sliding)",
            |_, m| scale_table(&mut m.friction, 1.001),
        ),
        ("wall_plane_hertz_history", "limitForce on", |c, _| {
            c.flags.limit_force = true
        }),
        (
            "wall_plane_hooke_history_epsd_notdamp",
            "tangential_damping on",
            |c, _| c.flags.tangential_damping = true,
        ),
        (
            "wall_plane_hooke_history_epsd_notdamp",
            "hertz instead of hooke",
            |c, _| c.normal = NormalKind::Hertz,
        ),
        (
            "wall_plane_hooke_history_epsd_notdamp",
            "rolling off",
            |c, _| c.rolling = RollingKind::Off,
        ),
        (
            "wall_plane_hooke_history_epsd_notdamp",
            "rolling damping +0.1 %",
            |_, m| scale_table(&mut m.rolling_viscous_damping, 1.001),
        ),
        (
            "wall_plane_hooke_history_epsd_notdamp",
            "torsionTorque on",
            |c, _| c.flags.torsion_torque = true,
        ),
        (
            "wall_plane_hertz_nohistory_limitforce_cdt",
            "limitForce off",
            |c, _| c.flags.limit_force = false,
        ),
        (
            "wall_plane_hertz_nohistory_limitforce_cdt",
            "tangential history",
            |c, _| c.tangential = TangentialKind::History,
        ),
        (
            "wall_plane_hertz_nohistory_limitforce_cdt",
            "friction +0.1 % (capped)",
            |_, m| scale_table(&mut m.friction, 1.001),
        ),
        (
            "wall_plane_hertz_nohistory_limitforce_cdt",
            "rolling off",
            |c, _| c.rolling = RollingKind::Off,
        ),
        (
            "wall_plane_hertz_nohistory_limitforce_cdt",
            "torsionTorque on",
            |c, _| c.flags.torsion_torque = true,
        ),
        (
            "wall_plane_hertz_history_epsd2_sjkr2_reduce",
            "cohesion off",
            |c, _| c.cohesion = CohesionKind::Off,
        ),
        (
            "wall_plane_hertz_history_epsd2_sjkr2_reduce",
            "sjkr instead of sjkr2",
            |c, _| c.cohesion = CohesionKind::Sjkr,
        ),
        (
            "wall_plane_hertz_history_epsd2_sjkr2_reduce",
            "tangential_reduce off",
            |c, _| c.flags.tangential_reduce = false,
        ),
        (
            "wall_plane_hertz_history_epsd2_sjkr2_reduce",
            "rolling friction +0.1 % (cap)",
            |_, m| scale_table(&mut m.rolling_friction, 1.001),
        ),
        (
            "wall_plane_hertz_history_epsd2_sjkr2_reduce",
            "torsionTorque on",
            |c, _| c.flags.torsion_torque = true,
        ),
        (
            "wall_plane_hysteresis_torsion",
            "hooke instead of hooke/hysteresis",
            |c, _| c.normal = NormalKind::Hooke,
        ),
        (
            "wall_plane_hysteresis_torsion",
            "adhesion stiffness +0.1 % (adhesive branch)",
            |_, m| scale_table(&mut m.adhesion_stiffness, 1.001),
        ),
        (
            "wall_plane_hysteresis_torsion",
            "max elastic stiffness +0.1 %",
            |_, m| scale_table(&mut m.max_elastic_stiffness, 1.001),
        ),
        (
            "wall_plane_hysteresis_torsion",
            "plasticity depth +0.1 %",
            |_, m| scale_table(&mut m.plasticity_depth, 1.001),
        ),
        (
            "wall_plane_hysteresis_torsion",
            "torsionTorque off",
            |c, _| c.flags.torsion_torque = false,
        ),
        (
            "wall_zcyl_hertz_history_cdt_sjkr",
            "cohesion off",
            |c, _| c.cohesion = CohesionKind::Off,
        ),
        (
            "wall_zcyl_hertz_history_cdt_sjkr",
            "sjkr2 instead of sjkr",
            |c, _| c.cohesion = CohesionKind::Sjkr2,
        ),
        (
            "wall_zcyl_hertz_history_cdt_sjkr",
            "tangential_reduce on",
            |c, _| c.flags.tangential_reduce = true,
        ),
        ("wall_zcyl_hertz_history_cdt_sjkr", "rolling off", |c, _| {
            c.rolling = RollingKind::Off
        }),
        (
            "wall_zcyl_hertz_history_cdt_sjkr",
            "torsionTorque on",
            |c, _| c.flags.torsion_torque = true,
        ),
        ("wall_zcyl_hooke_nohistory", "tangential history", |c, _| {
            c.tangential = TangentialKind::History
        }),
        (
            "wall_zcyl_hooke_nohistory",
            "hertz instead of hooke",
            |c, _| c.normal = NormalKind::Hertz,
        ),
        (
            "wall_zcyl_hooke_nohistory",
            "tangential_damping off",
            |c, _| c.flags.tangential_damping = false,
        ),
        (
            "wall_zcyl_hooke_nohistory",
            "friction +0.1 % (capped)",
            |_, m| scale_table(&mut m.friction, 1.001),
        ),
        ("pair_hooke_stiffness_history_epsd3", "kn +0.1 %", |c, m| {
            let _ = (&c, &m);
            scale_table(&mut m.kn, 1.001)
        }),
        (
            "pair_hooke_stiffness_history_epsd3",
            "gamman +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.gamman, 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_history_epsd3",
            "gammat +0.1 % (sticking)",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.gammat, 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_history_epsd3",
            "friction +0.1 % (sliding)",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.friction, 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_history_epsd3",
            "rollingStiffness +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                m.rolling_stiffness = m.rolling_stiffness.map(|k| k * 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_history_epsd3",
            "rolling damping +0.1 % (below the cap)",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.rolling_viscous_damping, 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_history_epsd3",
            "rolling friction +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.rolling_friction, 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_absdamp_nohistory_limitforce",
            "absolute_damping off (same numbers times m*)",
            |c, m| {
                let _ = (&c, &m);
                c.flags.absolute_damping = false;
                m.gamman = m.gamman_abs.clone();
                m.gammat = m.gammat_abs.clone()
            },
        ),
        (
            "pair_hooke_stiffness_absdamp_nohistory_limitforce",
            "limitForce off",
            |c, m| {
                let _ = (&c, &m);
                c.flags.limit_force = false
            },
        ),
        (
            "pair_hooke_stiffness_absdamp_nohistory_limitforce",
            "gamman_abs +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.gamman_abs, 1.001)
            },
        ),
        (
            "pair_hooke_stiffness_absdamp_nohistory_limitforce",
            "gammat_abs +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.gammat_abs, 1.001)
            },
        ),
        ("pair_hertz_stiffness_history", "kn +0.1 %", |c, m| {
            let _ = (&c, &m);
            scale_table(&mut m.kn, 1.001)
        }),
        ("pair_hertz_stiffness_history", "kt +0.1 %", |c, m| {
            let _ = (&c, &m);
            scale_table(&mut m.kt, 1.001)
        }),
        ("pair_hertz_stiffness_history", "gamman +0.1 %", |c, m| {
            let _ = (&c, &m);
            scale_table(&mut m.gamman, 1.001)
        }),
        ("pair_hertz_stiffness_history", "gammat +0.1 %", |c, m| {
            let _ = (&c, &m);
            scale_table(&mut m.gammat, 1.001)
        }),
        (
            "wall_plane_hertz_stiffness_history_epsd3_torsion",
            "torsionTorque off",
            |c, m| {
                let _ = (&c, &m);
                c.flags.torsion_torque = false
            },
        ),
        (
            "wall_plane_hertz_stiffness_history_epsd3_torsion",
            "rollingStiffness +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                m.rolling_stiffness = m.rolling_stiffness.map(|k| k * 1.001)
            },
        ),
        (
            "wall_plane_hertz_stiffness_history_epsd3_torsion",
            "kt +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.kt, 1.001)
            },
        ),
        (
            "wall_plane_hertz_stiffness_history_epsd3_torsion",
            "gammat +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.gammat, 1.001)
            },
        ),
        (
            "wall_plane_hooke_stiffness_absdamp_notdamp",
            "tangential_damping on",
            |c, m| {
                let _ = (&c, &m);
                c.flags.tangential_damping = true
            },
        ),
        (
            "wall_plane_hooke_stiffness_absdamp_notdamp",
            "absolute_damping off (same numbers times m*)",
            |c, m| {
                let _ = (&c, &m);
                c.flags.absolute_damping = false;
                m.gamman = m.gamman_abs.clone();
                m.gammat = m.gammat_abs.clone()
            },
        ),
        (
            "wall_plane_hooke_stiffness_absdamp_notdamp",
            "kt +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.kt, 1.001)
            },
        ),
        (
            "wall_plane_hooke_stiffness_absdamp_notdamp",
            "gamman_abs +0.1 %",
            |c, m| {
                let _ = (&c, &m);
                scale_table(&mut m.gamman_abs, 1.001)
            },
        ),
    ];
    let mut unseen = Vec::new();
    for &(name, what, mutate) in cases {
        let worst = run_scenario(name, mutate, |w| w.setup().unwrap(), false);
        let e = worst.iter().map(|x| x.0).fold(0.0, f64::max);
        eprintln!("{name}: {what}: {e:.1e}");
        if e.is_nan() || e <= SEEN {
            unseen.push(format!("{name}: {what} changes the result by only {e:.1e}"));
        }
    }
    assert!(unseen.is_empty(), "{}", unseen.join("\n"));
}

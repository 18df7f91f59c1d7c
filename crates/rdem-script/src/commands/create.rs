//! `create_box`, `create_atoms` and `create_particles`: the simulation box (and its
//! processor grid), particles on a lattice or at a point, and one particle of a template
//! at a point.

use glam::{DQuat, DVec3};
use rdem::{Domain, NewParticle, World};

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

use super::region::scale_of;

pub(super) fn create_box(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if sim.world.is_some() {
        return Err(a.error_cmd("create_box: the simulation box is already defined", None));
    }
    let n = a.count("number of atom types")?;
    if a.is_done() {
        let names: Vec<&str> = sim.defs.regions.keys().map(|s| s.as_str()).collect();
        return Err(a.error_at(
            a.pos(),
            "create_box: missing region ID",
            Some(if names.is_empty() {
                "create_box N REGION-ID: define the box region first, e.g. 'region reg block -1 1 -1 1 0 2 units box'".into()
            } else {
                format!("create_box N REGION-ID with a defined region: {}", crate::diagnostic::one_of(&names))
            }),
        ));
    }
    let r = sim.fixed_region(a, "create_box")?;
    if !a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "create_box: bonds and extra keywords are not supported",
            None,
        ));
    }
    if let rdem::region::Shape::Prism { tilt, .. } = r.shape {
        if tilt != glam::DVec3::ZERO {
            return Err(a.error_at(
                2,
                "create_box with a tilted prism region makes a triclinic box, which rdem does not support",
                Some("use a block region (or a prism with tilt factors 0 0 0)".into()),
            ));
        }
    }
    let (lo, hi) = r
        .bounding_box()
        .ok_or_else(|| a.error_at(2, "create_box needs a bounded region (e.g. a block)", None))?;
    if (0..3).any(|d| lo[d] <= -1e299 || hi[d] >= 1e299) {
        return Err(a.error_at(2, "create_box needs a region with finite bounds", None));
    }
    let boundary = super::settings::box_boundary(sim, a, 2)?;
    let domain =
        Domain::with_faces(lo, hi, boundary).map_err(|e| a.error_at(2, e.to_string(), None))?;
    sim.outputs.out.line(&format!(
        "Created orthogonal box = ({} {} {}) to ({} {} {})",
        crate::variables::g(lo.x),
        crate::variables::g(lo.y),
        crate::variables::g(lo.z),
        crate::variables::g(hi.x),
        crate::variables::g(hi.y),
        crate::variables::g(hi.z)
    ));
    let mut w = World::new(domain);
    decompose(sim, &mut w, a, 0)?;
    w.set_timestep(sim.setup.dt)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    w.materials.ntypes = n as usize;
    if sim.setup.sph {
        rdem::sph::SphProps::add(&mut w.particles).map_err(|e| a.error_cmd(e.to_string(), None))?;
    }
    sim.install_world(w);
    Ok(())
}

/// Splits the new box between the ranks (`processors`) and reports the grid as LIGGGHTS.
pub(super) fn decompose(sim: &mut Sim, w: &mut World, a: &Args, word: usize) -> CmdResult {
    w.decompose(sim.setup.procs)
        .map_err(|e| a.error_at(word, e.to_string(), None))?;
    let g = w.domain.procgrid;
    sim.outputs.out.line(&format!(
        "  {} by {} by {} MPI processor grid",
        g[0], g[1], g[2]
    ));
    Ok(())
}

pub(super) fn new_default(x: DVec3, ty: u32) -> NewParticle {
    // LIGGGHTS' granular defaults for created atoms: diameter 1, density 1.
    NewParticle::at(x, 0.5, 1.0).with_type(ty)
}

pub(super) fn create_atoms(sim: &mut Sim, a: &mut Args) -> CmdResult {
    crate::coarse_graining::check(sim, a, 0, "create_atoms")?;
    let ty = a.count("atom type")? as u32;
    if ty as usize > sim.ntypes() {
        return Err(a.error_prev(
            format!("atom type {ty} > the box's {} type(s)", sim.ntypes()),
            None,
        ));
    }
    let style = a.keyword("create_atoms style", &["single", "region", "box", "random"])?;
    let mut points = Vec::new();
    let mut reg = None;
    let mut single = None;
    match style {
        "single" => single = Some(a.vec3("position")?),
        "region" => reg = Some(sim.region(a)?),
        "box" => {}
        _ => {
            return Err(a.error_prev(
                "create_atoms random is not supported; use fix insert/pack",
                None,
            ))
        }
    }
    let mut lattice_units = false; // LIGGGHTS 3.8: units box
    while !a.is_done() {
        a.keyword("create_atoms keyword", &["units"])?;
        lattice_units = a.keyword("units", &["box", "lattice"])? == "lattice";
    }
    let w = sim
        .world
        .as_ref()
        .ok_or_else(|| a.error_cmd("create_atoms before the simulation box is defined", None))?;
    let (lo, hi) = (w.domain.boxlo, w.domain.boxhi);
    if let Some(x) = single {
        let s = scale_of(sim, a, lattice_units)?;
        points.push(x * s);
    } else {
        let l = sim
            .defs
            .lattice
            .as_ref()
            .filter(|l| l.style != "none")
            .ok_or_else(|| {
                a.error_cmd(
                    "create_atoms box/region needs a lattice",
                    Some("define one with 'lattice sc|bcc|fcc a'".into()),
                )
            })?;
        points = l.points(lo, hi);
        if let Some(r) = &reg {
            points.retain(|x| r.contains(*x));
        }
    }
    let w = sim.world.as_mut().expect("checked");
    let mut n = 0;
    for x in points {
        let mut p = new_default(x, ty);
        p.mask = 1;
        // Every rank sees every point; the one whose subdomain holds it creates it.
        w.domain
            .check_inside_fixed(x)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
        n += 1;
        if !w.owns_point(x) {
            continue;
        }
        w.add_particle(&p)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
    }
    w.extend_tags();
    super::settings::disc_masses(sim);
    sim.outputs.out.line(&format!("Created {n} atoms"));
    Ok(())
}

/// `create_particles TEMPLATE single x y z [units box|lattice] [velocity vx vy vz]
/// [omega wx wy wz] [orientation q1 q2 q3 q4] [rotate axis ax ay az angle deg] ...`
/// (LIGGGHTS-INL): one particle of a `particletemplate/sphere` (at the point) or
/// `particletemplate/multiplespheres` (its spheres with their bounding sphere's centre
/// at the point, turned about it). As the fork does (measured): `units` defaults to
/// `box` and scales the point only; `orientation` sets the turn (normalised), each
/// `rotate` turns further (right-hand rule, the axis normalised); every sphere gets the
/// velocity and the angular velocity; the new spheres take the next tags, in the
/// template's order.
pub(super) fn create_particles(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let tid = a.word("template ID")?;
    if !sim.defs.templates.contains_key(tid) {
        let names: Vec<&str> = sim.defs.templates.keys().map(|s| s.as_str()).collect();
        return Err(a.error_prev(
            format!("create_particles: no particle template '{tid}'"),
            Some(if names.is_empty() {
                "define one first with fix ID all particletemplate/sphere or particletemplate/multiplespheres".into()
            } else {
                suggest(tid, &names)
            }),
        ));
    }
    a.keyword("create_particles style", &["single"])?;
    let x = a.vec3("position")?;
    let (mut lattice_units, mut v, mut omega, mut turn) =
        (false, DVec3::ZERO, DVec3::ZERO, DQuat::IDENTITY);
    while !a.is_done() {
        match a.keyword(
            "create_particles keyword",
            &["units", "velocity", "omega", "orientation", "rotate"],
        )? {
            "units" => lattice_units = a.keyword("units", &["box", "lattice"])? == "lattice",
            "velocity" => v = a.vec3("velocity")?,
            "omega" => omega = a.vec3("angular velocity")?,
            "orientation" => {
                let at = a.pos();
                let q: [f64; 4] = [a.f64("q1")?, a.f64("q2")?, a.f64("q3")?, a.f64("q4")?];
                let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
                if !(q.length() > 0.0 && q.is_finite()) {
                    return Err(a.error_at(
                        at,
                        "create_particles: the orientation quaternion must be finite and not zero",
                        Some(
                            "q1 q2 q3 q4 with q1 the scalar part, e.g. 'orientation 1 0 0 0'"
                                .into(),
                        ),
                    ));
                }
                turn = q.normalize();
            }
            _ => {
                a.keyword("rotate", &["axis"])?;
                let at = a.pos();
                let axis = a.vec3("rotation axis")?;
                a.keyword("rotate", &["angle"])?;
                let deg = a.f64("rotation angle (degrees)")?;
                if !(axis.length() > 0.0 && axis.is_finite()) {
                    return Err(a.error_at(
                        at,
                        "create_particles: the rotation axis must be finite and not zero",
                        None,
                    ));
                }
                turn =
                    (DQuat::from_axis_angle(axis.normalize(), deg.to_radians()) * turn).normalize();
            }
        }
    }
    let x = x * scale_of(sim, a, lattice_units)?;
    let t = sim.defs.templates.get_mut(tid).expect("checked");
    let w = sim.world.as_mut().ok_or_else(|| {
        a.error_cmd(
            "create_particles before the simulation box is defined",
            None,
        )
    })?;
    let single = rdem::insert::Single { x, turn, v, omega };
    let n =
        rdem::insert::create_single(w, t, &single).map_err(|e| a.error_cmd(e.to_string(), None))?;
    super::settings::disc_masses(sim);
    sim.outputs.out.line(&format!("Created {n} atoms"));
    Ok(())
}

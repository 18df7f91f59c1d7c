//! The commands that change particles: `delete_atoms`, `set`, `velocity`.

use glam::DVec3;

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

fn select(sim: &Sim, a: &mut Args, style: &str) -> CmdResult<Vec<bool>> {
    let w = sim.world_ref(a)?;
    let p = &w.particles;
    let n = p.nlocal();
    Ok(match style {
        "group" => {
            let bit = sim.group_bit(a, "group ID")?;
            (0..n).map(|i| p.mask[i] & bit != 0).collect()
        }
        "region" => {
            let r = sim.region(a)?;
            (0..n).map(|i| r.contains(p.x[i])).collect()
        }
        "type" | "atom" => {
            let spec = a.word(if style == "type" {
                "type or range"
            } else {
                "atom ID or range"
            })?;
            let (lo, hi) = range(spec).ok_or_else(|| {
                a.error_prev(
                    format!("bad {style} range '{spec}'"),
                    Some("N, N*, *N, N*M or *".into()),
                )
            })?;
            (0..n)
                .map(|i| {
                    let v = if style == "type" {
                        p.ty[i] as u64
                    } else {
                        p.tag[i]
                    };
                    v >= lo && v <= hi
                })
                .collect()
        }
        _ => unreachable!(),
    })
}

/// LAMMPS ranges: `N`, `*`, `N*`, `*N`, `N*M`.
fn range(s: &str) -> Option<(u64, u64)> {
    match s.split_once('*') {
        None => s.parse().ok().map(|v| (v, v)),
        Some((l, h)) => {
            let lo = if l.is_empty() { 1 } else { l.parse().ok()? };
            let hi = if h.is_empty() {
                u64::MAX
            } else {
                h.parse().ok()?
            };
            Some((lo, hi))
        }
    }
}

pub(super) fn delete_atoms(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("delete_atoms style", &["group", "region"])?;
    let mut remove = select(sim, a, style)?;
    let mut compress = true;
    while !a.is_done() {
        a.keyword("delete_atoms keyword", &["compress"])?;
        compress = a.yes_no("compress")?;
    }
    let settings = sim.neighbor_settings();
    let w = sim.world_mut(a)?;
    w.neighbor.save_history(&w.particles);
    w.particles.clear_ghosts();
    // A clump goes whole (LIGGGHTS removes a body with any of its spheres).
    w.remove_whole_bodies(&mut remove);
    let n = w.comm.sum_count(w.particles.remove_locals(&remove) as u64);
    // Renumber tags 1..N keeping their order (LIGGGHTS' compress yes).
    let renumbered = compress && w.renumber_tags();
    let total = w.natoms();
    if renumbered {
        // Saved contact history is keyed by the old tags: start it afresh. Without
        // renumbering it carries over to the next run's set-up.
        w.neighbor = rdem::neighbor::Neighbor::new(settings);
    }
    sim.outputs
        .out
        .line(&format!("Deleted {n} atoms, new total = {total}"));
    Ok(())
}

pub(super) fn set(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if let Some(why) = crate::fixes::multisphere::refuses_set(sim) {
        return Err(a.error_cmd(
            why,
            Some("add 'allow_group_and_set yes' to the fix multisphere command".into()),
        ));
    }
    let cg = sim.setup.coarse_graining.factor;
    let style = a.keyword("set style", &["atom", "type", "group", "region"])?;
    let sel = select(sim, a, style)?;
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "set: missing keyword",
            Some(
                "type, diameter, density, mass, x, y, z, vx, vy, vz, omegax, omegay, omegaz, omega, property/atom (1.x: property/peratom), meso_rho, sphkernel"
                    .into(),
            ),
        ));
    }
    sim.outputs.out.line("Setting atom values ...");
    while !a.is_done() {
        let kw = a.keyword(
            "set keyword",
            &[
                "type",
                "diameter",
                "density",
                "mass",
                "x",
                "y",
                "z",
                "vx",
                "vy",
                "vz",
                "omegax",
                "omegay",
                "omegaz",
                "omega",
                "property/atom",
                "property/peratom",
                "meso_rho",
                "sphkernel",
            ],
        )?;
        if kw == "sphkernel" {
            // Sets the kernel of the SPH fixes that have none (LIGGGHTS 3.8: "Setting
            // undefined fix_sph kernel IDs"), whatever the selection.
            let k = crate::sph::kernel(a)?;
            let w = sim.world_mut(a)?;
            let n = rdem::sph::set_undefined_kernels(&mut w.fixes, k);
            sim.outputs
                .out
                .line(&format!("  {n} settings made for sphkernel"));
            continue;
        }
        // A per-particle component: a number, or an equal- or atom-style variable (as the
        // LIGGGHTS manual allows), read before the particles are borrowed.
        let component = match kw {
            "x" | "y" | "z" | "vx" | "vy" | "vz" | "omegax" | "omegay" | "omegaz" => {
                let at = a.pos();
                match set_component(sim, a, kw)? {
                    Some(vals) => Some(vals),
                    None => {
                        return Err(a.error_at(
                            at,
                            format!("set {kw}: NULL is not a value"),
                            Some("give a number or v_name".into()),
                        ))
                    }
                }
            }
            _ => None,
        };
        let (ntypes, dim) = (sim.ntypes(), sim.setup.dimension);
        let w = sim.world.as_mut().expect("select checked");
        w.neighbor.save_history(&w.particles);
        w.particles.clear_ghosts();
        let p = &mut w.particles;
        let mut count = 0;
        match kw {
            "type" => {
                let t = a.count("type")?;
                if t as usize > ntypes {
                    return Err(
                        a.error_prev(format!("type {t} > the box's {ntypes} type(s)"), None)
                    );
                }
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.ty[i] = t as u32;
                    count += 1;
                }
            }
            "diameter" => {
                // LIGGGHTS-PFM's coarse graining scales the diameter given.
                let d = a.positive("diameter")? * cg;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.set_radius(i, 0.5 * d)
                        .map_err(|e| a.error_prev(e.to_string(), None))?;
                    count += 1;
                }
            }
            "density" => {
                let rho = a.positive("density")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.density[i] = rho;
                    let r = p.radius[i];
                    p.set_radius(i, r)
                        .map_err(|e| a.error_prev(e.to_string(), None))?;
                    count += 1;
                }
            }
            "mass" => {
                let m = a.positive("mass")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.rmass[i] = m;
                    // Mass per volume, or per area in 2d (see settings::disc_masses).
                    let r = p.radius[i];
                    let size = if dim == 2 {
                        std::f64::consts::PI * r * r
                    } else {
                        4.0 / 3.0 * std::f64::consts::PI * r.powi(3)
                    };
                    p.density[i] = m / size;
                    count += 1;
                }
            }
            "x" | "y" | "z" | "vx" | "vy" | "vz" | "omegax" | "omegay" | "omegaz" => {
                let vals = component.expect("read above");
                let d = (kw.as_bytes()[kw.len() - 1] - b'x') as usize;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    // One value for a number or an equal-style variable, one per owned
                    // particle for an atom-style variable.
                    let x = if vals.len() == 1 { vals[0] } else { vals[i] };
                    match kw.len() {
                        1 => p.x[i][d] = x,
                        2 => p.v[i][d] = x,
                        _ => p.omega[i][d] = x,
                    }
                    count += 1;
                }
            }
            "meso_rho" => {
                let rho = a.f64("density")?;
                let Some(id) = p.property(rdem::sph::RHO) else {
                    return Err(a.error_at(a.pos() - 2, "set meso_rho needs atom_style sph", None));
                };
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.props[id.0].data[i] = rho;
                    count += 1;
                }
            }
            "omega" => {
                let o = a.vec3("omega")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.omega[i] = o;
                    count += 1;
                }
            }
            _ => {
                let name = a.word("property name")?;
                let Some(id) = p.property(name) else {
                    let names: Vec<&str> = p.props.iter().map(|q| q.name.as_str()).collect();
                    return Err(a.error_prev(
                        format!("no per-atom property '{name}'"),
                        Some(suggest(name, &names)),
                    ));
                };
                let width = p.props[id.0].width;
                let mut vals = Vec::new();
                for _ in 0..width {
                    vals.push(a.f64("property value")?);
                }
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.props[id.0].get_mut(i).copy_from_slice(&vals);
                    count += 1;
                }
            }
        }
        super::settings::disc_masses(sim);
        let count = sim.world_ref(a)?.comm.sum_count(count as u64);
        sim.outputs
            .out
            .line(&format!("  {count} settings made for {kw}"));
    }
    Ok(())
}

pub(super) fn velocity(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let bit = sim.group_bit(a, "group ID")?;
    let style = a.keyword("velocity style", &["set", "zero", "ramp", "create"])?;
    enum Op {
        Set([Option<Vec<f64>>; 3]),
        Zero(bool),
        Ramp(usize, f64, f64, usize, f64, f64),
        Create(f64, u64),
    }
    let op = match style {
        "set" => {
            let mut comps: [Option<Vec<f64>>; 3] = Default::default();
            for (d, c) in comps.iter_mut().enumerate() {
                *c = set_component(sim, a, ["vx", "vy", "vz"][d])?;
            }
            Op::Set(comps)
        }
        "zero" => Op::Zero(a.keyword("zero what", &["linear", "angular"])? == "angular"),
        "ramp" => {
            let vd = a.keyword("velocity component", &["vx", "vy", "vz"])?;
            let (vlo, vhi) = (a.f64("vlo")?, a.f64("vhi")?);
            let d = a.keyword("coordinate", &["x", "y", "z"])?;
            let (clo, chi) = (a.f64("coordinate lo")?, a.f64("coordinate hi")?);
            Op::Ramp(
                (vd.as_bytes()[1] - b'x') as usize,
                vlo,
                vhi,
                (d.as_bytes()[0] - b'x') as usize,
                clo,
                chi,
            )
        }
        _ => Op::Create(a.non_negative("temperature")?, a.count("seed")?),
    };
    let mut sum = false;
    while !a.is_done() {
        match a.keyword(
            "velocity keyword",
            &["sum", "units", "dist", "mom", "rot", "loop"],
        )? {
            "sum" => sum = a.yes_no("sum")?,
            "units" => {
                if a.keyword("units", &["box", "lattice"])? == "lattice" {
                    return Err(a.error_prev(
                        "velocity units lattice is not supported: give box units",
                        None,
                    ));
                }
            }
            "dist" => {
                a.keyword("dist", &["uniform", "gaussian"])?;
            }
            "mom" | "rot" => {
                a.yes_no("mom/rot")?;
            }
            _ => {
                a.keyword("loop", &["all", "local", "geom"])?;
            }
        }
    }
    // LIGGGHTS 3.8 in 2d: "Cannot set non-zero z velocity for 2d simulation".
    if sim.setup.dimension == 2 {
        let z_set = match &op {
            Op::Set(v) => v[2].as_ref().is_some_and(|z| z.iter().any(|&x| x != 0.0)),
            Op::Ramp(vd, vlo, vhi, ..) => *vd == 2 && (*vlo != 0.0 || *vhi != 0.0),
            _ => false,
        };
        if z_set {
            return Err(a.error_cmd(
                "cannot set a non-zero z velocity in a 2d simulation",
                Some("dimension 2: give vz as 0 or NULL".into()),
            ));
        }
    }
    let (boltzmann, dim) = (sim.setup.units.boltzmann(), sim.setup.dimension);
    let w = sim.world_mut(a)?;
    let p = &mut w.particles;
    let sel: Vec<usize> = (0..p.nlocal()).filter(|&i| p.mask[i] & bit != 0).collect();
    match op {
        Op::Set(v) => {
            for &i in &sel {
                for (d, vd) in v.iter().enumerate() {
                    if let Some(vals) = vd {
                        // One value for a number or an equal-style variable, one per
                        // particle for an atom-style variable.
                        let x = if vals.len() == 1 { vals[0] } else { vals[i] };
                        p.v[i][d] = if sum { p.v[i][d] + x } else { x };
                    }
                }
            }
        }
        Op::Zero(angular) => {
            if angular {
                for &i in &sel {
                    p.omega[i] = DVec3::ZERO;
                }
            } else {
                let vcm = group_vcm(&*w.comm, p, &sel);
                for &i in &sel {
                    p.v[i] -= vcm;
                }
            }
        }
        Op::Ramp(vd, vlo, vhi, d, clo, chi) => {
            for &i in &sel {
                let f = ((p.x[i][d] - clo) / (chi - clo)).clamp(0.0, 1.0);
                let v = vlo + f * (vhi - vlo);
                p.v[i][vd] = if sum { p.v[i][vd] + v } else { v };
            }
        }
        Op::Create(t, seed) => {
            use rand::SeedableRng;
            use rand_distr::Distribution;
            let normal = rand_distr::StandardNormal;
            for &i in &sel {
                // One stream per particle tag, so the velocities do not depend on how the
                // particles are stored or split between ranks.
                let mut rng = rand_pcg::Pcg64::seed_from_u64(
                    seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ p.tag[i],
                );
                let s = (boltzmann * t / p.rmass[i]).sqrt();
                let mut g: [f64; 3] = [
                    normal.sample(&mut rng),
                    normal.sample(&mut rng),
                    normal.sample(&mut rng),
                ];
                if dim == 2 {
                    g[2] = 0.0;
                }
                p.v[i] = DVec3::from_array(g) * s;
            }
            let vcm = group_vcm(&*w.comm, p, &sel);
            for &i in &sel {
                p.v[i] -= vcm;
            }
        }
    }
    Ok(())
}

/// One component of `velocity set`: NULL (`None`), a number, or `v_name` of an
/// equal-style (one value) or atom-style variable (one value per owned particle, as
/// LAMMPS evaluates it for every particle of the group).
fn set_component(sim: &Sim, a: &mut Args, what: &str) -> CmdResult<Option<Vec<f64>>> {
    let w = a.word(&format!("{what} (a number, v_name or NULL)"))?;
    if w == "NULL" {
        return Ok(None);
    }
    let Some(name) = w.strip_prefix("v_") else {
        a.seek(a.pos() - 1);
        return Ok(Some(vec![
            a.f64(&format!("{what} (a number, v_name or NULL)"))?
        ]));
    };
    let values = match sim.script.vars.get(name) {
        Some(crate::variables::Variable::Atom(f)) => {
            sim.world_ref(a)?;
            crate::context::eval_atom(sim, f)
                .map_err(|m| a.error_prev(format!("variable {name}: {m}"), None))?
        }
        Some(crate::variables::Variable::Equal(f)) => vec![crate::context::eval_equal(sim, f)
            .map_err(|e| a.error_prev(format!("variable {name}: {}", e.message), None))?],
        Some(_) => {
            return Err(a.error_prev(
                format!("variable '{name}' is neither equal- nor atom-style"),
                Some("velocity set takes equal- or atom-style variables".into()),
            ))
        }
        None => {
            return Err(a.error_prev(
                format!("no variable '{name}'"),
                Some(crate::args::id_help(
                    "variable",
                    name,
                    &sim.script.vars.names(),
                )),
            ))
        }
    };
    Ok(Some(values))
}

/// Mass-weighted mean velocity of the particles `sel` over all ranks (zero for no mass).
fn group_vcm(comm: &dyn rdem::comm::Comm, p: &rdem::Particles, sel: &[usize]) -> DVec3 {
    let m = comm.sum(sel.iter().map(|&i| p.rmass[i]).sum());
    let mv = sel.iter().map(|&i| p.v[i] * p.rmass[i]).sum::<DVec3>();
    let mut mv = mv.to_array();
    comm.sum_slice(&mut mv);
    if m > 0.0 {
        DVec3::from_array(mv) / m
    } else {
        DVec3::ZERO
    }
}

//! `read_restart` of a LIGGGHTS 3.8 binary restart file ([`rdem_io::liggghts_restart`]):
//! the box, the particles and their histories, so that a study begun in LIGGGHTS goes on
//! in rdem.
//!
//! What is taken: units, dimension, boundary, box, step, groups (names by bit and every
//! particle's mask), and per particle tag, type, position, velocity, angular velocity,
//! radius, density, mass and image counts; the pair contact histories of `pair_style gran
//! ... tangential history` (three shear values per contact, kept for the next set-up as
//! rdem's own restart files keep them) and the wall histories of primitive walls (fix
//! `history_ID` of wall `ID`, three values per particle) when they have that layout.
//!
//! The values of a `fix property/atom` wait for the fix defined again with its ID, which
//! takes them by tag ([`crate::restart_state::Restored::peratom`]), as LIGGGHTS gives a
//! fix defined again with its ID its per-atom state.
//!
//! What is not taken: the timestep (LIGGGHTS 3.8 does not store it: the script sets it
//! after `read_restart`, as LIGGGHTS requires), fix states (insertion counters, random
//! generators), the per-particle values of other fixes (mesh wall histories) and the pair
//! style with its coefficients (LIGGGHTS scripts define the pair style, materials, walls
//! and fixes again after `read_restart`). One warning lists what the file held that is
//! not taken.
//!
//! LIGGGHTS 3.8 starts the `time` of a continued run at 0 at the file's step (measured:
//! thermo `time` is 0 at the first step after `read_restart`), and so does this reader.

use crate::error::Error;
use rdem::restart::HistoryState;
use rdem::{Boundary, Domain, NewParticle, World};
use rdem_io::liggghts_restart::LiggghtsRestart;

use crate::restart_state::{PeratomValues, Restored};
use crate::sim::Sim;

/// Values per contact of the tangential history rdem maps (the shear displacement).
const SHEAR: usize = 3;

/// What a LIGGGHTS restart brought, for the lines `read_restart` prints.
pub(crate) struct Taken {
    /// Contacts whose history was taken (each pair once).
    pub contacts: usize,
    /// Wall fix IDs whose histories were taken.
    pub walls: Vec<String>,
    /// `fix property/atom` IDs whose values wait for the fix defined again.
    pub kept: Vec<String>,
    /// What the file held that was not taken (one warning).
    pub not_taken: Vec<String>,
}

/// Builds the world of the LIGGGHTS restart `f`; `decompose` splits the box between the
/// ranks.
pub(crate) fn restore(
    sim: &mut Sim,
    f: &LiggghtsRestart,
    decompose: impl FnOnce(&mut Sim, &mut World) -> Result<(), Error>,
) -> Result<Taken, Error> {
    if f.tilt.is_some() {
        return Err("its box is triclinic, which rdem does not support".into());
    }
    sim.setup.units = crate::units::Units::from_name(&f.units)
        .ok_or_else(|| format!("its units '{}' are not rdem's", f.units))?;
    sim.setup.dimension = f.dimension as u8;
    let boundary = f.boundary.map(|faces| {
        faces.map(|c| Boundary::from_letter(c).expect("the reader gives p, f, s or m"))
    });
    // As LIGGGHTS: a boundary the script set before read_restart (other than the
    // default, periodic everywhere) that differs from the file's gives way to the file's,
    // with a warning.
    let script = sim.setup.boundary;
    if script != [[Boundary::Periodic; 2]; 3] && script != boundary {
        let letters = |b: [[Boundary; 2]; 3]| {
            b.map(|faces| {
                faces
                    .map(|x| crate::restart_state::letter(x).to_string())
                    .concat()
            })
            .join(" ")
        };
        sim.warn_once(&format!(
            "read_restart: the script's boundary ({}) is not the file's ({}); the file's is used",
            letters(script),
            letters(boundary)
        ));
    }
    let domain = Domain::with_faces(f.boxlo.into(), f.boxhi.into(), boundary)?;
    let mut w = World::new(domain);
    decompose(sim, &mut w)?;
    w.set_timestep(sim.setup.dt)?;
    w.step = f.step;
    w.materials.ntypes = f.ntypes as usize;
    let mut taken = Taken {
        contacts: 0,
        walls: Vec::new(),
        kept: Vec::new(),
        not_taken: Vec::new(),
    };
    // Wall histories: fix `history_ID` (property/atom) of wall `ID`, three values each.
    let mut walls = Vec::new();
    let mut peratom = std::collections::BTreeMap::new();
    for (k, p) in f.peratom.iter().enumerate() {
        let wall =
            p.id.strip_prefix("history_")
                .filter(|_| p.style == "property/atom");
        let uniform = (0..f.atoms.len()).all(|a| p.of(a).len() == SHEAR);
        match wall {
            Some(id) if uniform => {
                let prop =
                    w.particles
                        .add_property(&format!("wallhist_{id}"), SHEAR, &[0.0; SHEAR])?;
                walls.push((k, prop));
                taken.walls.push(id.to_string());
            }
            _ if p.style == "contacthistory" => {}
            _ if p.style == "property/atom" && p.maxsize > 1 && wall.is_none() => {
                let width = p.maxsize as usize - 1;
                if (0..f.atoms.len()).all(|a| p.of(a).len() == width) {
                    let mut order: Vec<usize> = (0..f.atoms.len()).collect();
                    order.sort_unstable_by_key(|&a| f.atoms.tag[a]);
                    let values = PeratomValues {
                        width,
                        tags: order.iter().map(|&a| f.atoms.tag[a]).collect(),
                        values: order.iter().flat_map(|&a| p.of(a)).copied().collect(),
                    };
                    peratom.insert(p.id.clone(), values);
                    taken.kept.push(p.id.clone());
                } else {
                    taken.not_taken.push(format!(
                        "the per-particle values of fix {} ({})",
                        p.id, p.style
                    ));
                }
            }
            _ => taken.not_taken.push(format!(
                "the per-particle values of fix {} ({})",
                p.id, p.style
            )),
        }
    }
    let a = &f.atoms;
    for k in 0..a.len() {
        let x = a.x[k].into();
        if !w.owns_point(x) {
            continue;
        }
        let np = NewParticle {
            tag: a.tag[k],
            ty: a.ty[k],
            mask: a.mask[k] | 1,
            x,
            v: a.v[k].into(),
            omega: a.omega[k].into(),
            radius: a.radius[k],
            density: a.density[k],
        };
        let i = w.add_particle(&np)?;
        let p = &mut w.particles;
        p.rmass[i] = a.rmass[k];
        p.image[i] = a.image[k].into();
        for &(fix, prop) in &walls {
            p.props[prop.0]
                .get_mut(i)
                .copy_from_slice(f.peratom[fix].of(k));
        }
    }
    let placed = w.comm.sum_count(w.particles.nlocal() as u64);
    if placed != f.natoms {
        return Err(format!(
            "{} of its {} particles lie outside the box",
            f.natoms - placed,
            f.natoms
        )
        .into());
    }
    if let Some(h) = f.contact_history() {
        let h = h.map_err(|e| Error::Decode(e.to_string()))?;
        match pair_history(&h) {
            Ok(state) => {
                taken.contacts = state.entries.len() / (2 + SHEAR);
                w.restore_history(state);
            }
            Err(why) => taken.not_taken.push(why.to_string()),
        }
    }
    sim.setup.dt = w.dt;
    sim.script.time_origin = (f.step, 0.0);
    let mut groups = f.groups.clone();
    groups.resize(32, None);
    sim.defs.groups.set_table(groups)?;
    sim.defs.restored = Restored {
        peratom,
        liggghts_pair: f.pair.as_ref().map(|p| {
            format!(
                "pair_style {} (LIGGGHTS model code {:#x})",
                p.style, p.model_hash
            )
        }),
        ..Restored::default()
    };
    for g in &f.fixes {
        let kept = g.style == "contacthistory"
            || taken.walls.iter().any(|id| g.id == format!("history_{id}"))
            || taken.kept.contains(&g.id);
        if !kept {
            taken
                .not_taken
                .push(format!("the state of fix {} ({})", g.id, g.style));
        }
    }
    sim.install_world(w);
    Ok(taken)
}

/// The file's pair contact histories as rdem keeps them: each pair once, in the row of
/// its lower tag (the other side is its mirror image). Only the tangential history
/// (three shear values, each changing sign from one particle of a pair to the other, as
/// the file shows: LIGGGHTS stores every pair from both sides) is mapped.
fn pair_history(h: &rdem_io::liggghts_restart::ContactHistory) -> Result<HistoryState, Error> {
    if h.entries.is_empty() {
        return Ok(HistoryState::default());
    }
    if h.width != SHEAR {
        return Err(format!(
            "the pair contact histories ({} values per contact; rdem maps those of tangential \
             history, {SHEAR}): every contact starts afresh",
            h.width
        )
        .into());
    }
    let stride = 2 + SHEAR;
    let mut from_i: Vec<(u64, u64, &[f64])> = h
        .entries
        .chunks_exact(stride)
        .map(|c| (c[0] as u64, c[1] as u64, &c[2..]))
        .collect();
    from_i.sort_unstable_by_key(|&(i, j, _)| (i, j));
    let find = |i: u64, j: u64| {
        from_i
            .binary_search_by_key(&(i, j), |&(a, b, _)| (a, b))
            .ok()
            .map(|k| from_i[k].2)
    };
    let mut entries = Vec::with_capacity(h.entries.len() / 2 + stride);
    for &(i, j, v) in &from_i {
        // The other side, where present, must be the mirror image.
        if let Some(u) = find(j, i) {
            if v.iter().zip(u).any(|(a, b)| *a != -*b) {
                return Err(format!(
                    "the pair contact histories (the contact of particles {i} and {j} is not \
                     stored as mirror images from its two sides, as tangential history's \
                     shear is): every contact starts afresh"
                )
                .into());
            }
            if i > j {
                continue;
            }
        }
        entries.extend_from_slice(&[i as f64, j as f64]);
        entries.extend_from_slice(v);
    }
    Ok(HistoryState {
        width: SHEAR,
        odd: SHEAR,
        entries,
    })
}

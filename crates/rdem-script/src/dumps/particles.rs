//! What the particle dumps (`custom`, `custom/vtk`, `atom/vtk`) share: their columns
//! (fields, per-atom computes, atom-style variables), the gathering of every rank's
//! particles on rank 0, and the snapshot written from them.

use crate::error::Error;
use std::path::PathBuf;

use rdem::comm::Comm;
use rdem::{DVec3, Particles};
use rdem_io::{Column, Field};

use super::DumpHead;
use crate::args::{suggest, Args, CmdResult};
use crate::context;
use crate::sim::Sim;
use crate::thermo::split_reference;
use crate::variables::Variable;

/// Checks a column argument: a field, or `c_`/`f_`/`v_` of a per-atom quantity.
pub(super) fn check_column(sim: &Sim, a: &Args, k: usize, arg: &str) -> CmdResult {
    if Column::field(arg).is_some() {
        return Ok(());
    }
    match split_reference(arg) {
        Some(('c', id, col)) => match sim.defs.computes.iter().find(|c| c.id() == id) {
            Some(c) if c.is_peratom() => {
                let n = c.peratom_cols();
                match col {
                    None if n == 0 => Ok(()),
                    Some(j) if n > 0 && j >= 1 && j <= n => Ok(()),
                    _ => Err(a.error_at(
                        k,
                        format!("'{arg}' does not match compute {id}'s columns"),
                        None,
                    )),
                }
            }
            Some(_) => Err(a.error_at(
                k,
                format!("compute {id} is not per-atom"),
                Some("a dump column needs a per-atom compute (property/atom, contact/atom)".into()),
            )),
            None => {
                let ids: Vec<&str> = sim.defs.computes.iter().map(|c| c.id()).collect();
                Err(a.error_at(
                    k,
                    format!("no compute '{id}'"),
                    Some(crate::args::id_help("compute", id, &ids)),
                ))
            }
        },
        Some(('f', id, col)) => {
            let every = sim
                .defs
                .fixes
                .iter()
                .find(|f| f.id() == id)
                .and_then(|f| f.imp.peratom_shape())
                .map(|(_, freq)| freq);
            match (every, dump_every(a)) {
                (Some(freq), Some(n)) if n % freq != 0 => Err(a.error_at(
                    k,
                    format!("fix {id} is not computed at compatible times: every {freq} steps, the dump every {n}"),
                    Some(format!("dump every multiple of {freq} steps, as LIGGGHTS requires")),
                )),
                _ => crate::fixes::check_fix_peratom(sim, id, col).map_err(|m| {
                    a.error_at(
                        k,
                        m,
                        Some("a dump column needs per-atom values (fix ave/atom, fix property/atom)".into()),
                    )
                }),
            }
        }
        Some(('v', id, None)) => match sim.script.vars.get(id) {
            Some(Variable::Atom(_)) => Ok(()),
            Some(_) => Err(a.error_at(
                k,
                format!("variable {id} is not atom-style"),
                Some(format!(
                    "a dump column needs a value per particle: define 'variable {id} atom FORMULA'"
                )),
            )),
            None => Err(a.error_at(
                k,
                format!("no variable '{id}'"),
                Some(crate::args::id_help(
                    "variable",
                    id,
                    &sim.script.vars.names(),
                )),
            )),
        },
        _ => Err(a.error_at(
            k,
            format!("unknown dump column '{arg}'"),
            Some(suggest(arg, &rdem_io::Field::NAMES)),
        )),
    }
}

/// The N of `dump ID group style N file ...` (`None` for `write_dump`, which writes once).
fn dump_every(a: &Args) -> Option<u64> {
    let w = a.words();
    (w.first()?.text == "dump")
        .then(|| w.get(4)?.text.parse().ok())
        .flatten()
}

pub(super) fn read_columns(sim: &Sim, a: &mut Args) -> CmdResult<Vec<String>> {
    let mut cols = Vec::new();
    while let Some(w) = a.peek() {
        if w == "modify" {
            break;
        }
        check_column(sim, a, a.pos(), w)?;
        cols.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    if cols.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "dump custom needs at least one column",
            Some(format!(
                "e.g. id type x y z radius; valid fields: {}",
                rdem_io::Field::NAMES.join(" ")
            )),
        ));
    }
    Ok(cols)
}

pub(super) fn columns(sim: &Sim, args: &[String]) -> Result<Vec<Column>, Error> {
    args.iter()
        .map(|arg| {
            if let Some(f) = Field::parse(arg) {
                if !f.reads_properties() {
                    return Ok(Column::Field(f));
                }
                // A field read from a named property, which the gathered copies lack:
                // its values go as a column of their own.
                let w = sim
                    .world
                    .as_ref()
                    .ok_or("dump before the simulation box is defined")?;
                let p = &w.particles;
                let values = (0..p.nlocal()).map(|i| f.value(p, &w.domain, i)).collect();
                return Ok(Column::Custom {
                    name: arg.clone(),
                    values,
                });
            }
            let values = match split_reference(arg) {
                Some(('c', id, col)) => context::compute_peratom(sim, id, col)?,
                Some(('f', id, col)) => crate::fixes::fix_peratom(sim, id, col)?,
                Some(('v', id, None)) => match sim.script.vars.get(id) {
                    Some(Variable::Atom(f)) => context::eval_atom(sim, f)?,
                    _ => return Err(Error::invalid(format!("variable {id} is not atom-style"))),
                },
                _ => return Err(Error::invalid(format!("bad dump column '{arg}'"))),
            };
            Ok(Column::Custom {
                name: arg.clone(),
                values,
            })
        })
        .collect()
}

/// The owned particles of every rank, gathered on rank 0 by [`gather_owned`].
pub(crate) struct Gathered {
    /// The particles, all owned (`nlocal` = their number), in rank order then each rank's
    /// storage order; positions, velocities, forces, torques, radii, masses, densities,
    /// types, masks and image flags (no named properties).
    pub particles: Particles,
    /// The rank that owns each gathered particle (the `proc` of `dump atom/vtk`).
    pub procs: Vec<i32>,
    /// The values of each custom column, by gathered particle index.
    pub custom: Vec<Vec<f64>>,
}

/// Gathers the owned particles `selection` of every rank, with their values of the
/// `custom` columns (`custom[k][i]` for owned particle index `i`), on rank 0: `None` on
/// the other ranks. A collective call: every rank must make it, in the same order.
pub(crate) fn gather_owned(
    comm: &dyn Comm,
    p: &Particles,
    selection: &[usize],
    custom: &[&[f64]],
) -> Option<Gathered> {
    // The fixed part of `Particles::pack` (no named properties): tag, type, mask, x, v,
    // omega, radius, mass, density, image flags; then force, torque, rank, custom values.
    let fixed = Particles::new().packed_len();
    let rec = fixed + 7 + custom.len();
    let rank = comm.rank() as f64;
    let mut buf = Vec::with_capacity(selection.len() * rec);
    let mut one = Vec::with_capacity(p.packed_len());
    for &i in selection {
        one.clear();
        p.pack(i, DVec3::ZERO, &mut one);
        // The position exactly as stored (a zero shift would turn -0.0 into +0.0).
        one[3..6].copy_from_slice(&p.x[i].to_array());
        buf.extend_from_slice(&one[..fixed]);
        buf.extend_from_slice(&p.f[i].to_array());
        buf.extend_from_slice(&p.torque[i].to_array());
        buf.push(rank);
        buf.extend(custom.iter().map(|c| c[i]));
    }
    let all = comm.gather(&buf)?;
    let n = all.len() / rec;
    let mut g = Gathered {
        particles: Particles::new(),
        procs: Vec::with_capacity(n),
        custom: vec![Vec::with_capacity(n); custom.len()],
    };
    for r in all.chunks_exact(rec) {
        let q = &mut g.particles;
        q.unpack(&r[..fixed], None);
        let k = q.nlocal() - 1;
        q.f[k] = DVec3::from_slice(&r[fixed..fixed + 3]);
        q.torque[k] = DVec3::from_slice(&r[fixed + 3..fixed + 6]);
        g.procs.push(r[fixed + 6] as i32);
        for (c, &v) in g.custom.iter_mut().zip(&r[fixed + 7..]) {
            c.push(v);
        }
    }
    Some(g)
}

/// The particles of the dump's group with their columns, gathered on rank 0 (`None` on
/// the other ranks). Collective.
pub(super) fn gather(
    sim: &Sim,
    head: &DumpHead,
    args: &[String],
) -> Result<Option<(Gathered, Vec<Column>)>, Error> {
    let cols = columns(sim, args)?;
    let w = sim
        .world
        .as_ref()
        .ok_or("dump before the simulation box is defined")?;
    let mut sel = rdem_io::fields::group_selection(&w.particles, head.groupbit);
    if let Some(id) = &head.region {
        let r =
            crate::regions::region_now(sim, id).map_err(|e| format!("dump_modify region: {e}"))?;
        sel.retain(|&i| r.contains(w.particles.x[i]));
    }
    let custom: Vec<&[f64]> = cols
        .iter()
        .filter_map(|c| match c {
            Column::Custom { values, .. } => Some(values.as_slice()),
            Column::Field(_) => None,
        })
        .collect();
    // Every rank sends its particles; rank 0 writes them all (also for a name with `%`,
    // which becomes 0: one file, not one per rank).
    let Some(mut g) = gather_owned(&*w.comm, &w.particles, &sel, &custom) else {
        return Ok(None);
    };
    // The custom columns' values, now by gathered particle.
    let mut values = std::mem::take(&mut g.custom).into_iter();
    let cols = cols
        .into_iter()
        .map(|c| match c {
            Column::Custom { name, .. } => Column::Custom {
                name,
                values: values.next().unwrap_or_default(),
            },
            field => field,
        })
        .collect();
    Ok(Some((g, cols)))
}

/// A snapshot's finished files, for the `.pvd`.
pub(super) type Done = Vec<(f64, PathBuf)>;

//! The input values of `fix ave/histo`: what each word names and how it is sampled.

use super::{global_value, is_atom_variable, unknown_id};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::thermo::split_reference;
use crate::variables::Variable;

/// The particle attributes LIGGGHTS' ave/histo reads.
pub(super) const ATTRIBUTES: [&str; 9] = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"];

/// One input.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Input {
    /// `mode scalar`: a global scalar or vector element (`c_ID`, `c_ID[i]`, `f_ID`,
    /// `f_ID[i]`, `v_name`), read as thermo reads it.
    Scalar(String),
    /// `mode vector`: all elements of a compute's global vector.
    ComputeVector(String, usize),
    /// `mode vector`: all global values of a fix.
    FixVector(String),
    /// A particle attribute.
    Field(String),
    /// A per-atom compute's vector or column.
    ComputeAtom(String, Option<usize>),
    /// A per-atom fix's vector or column.
    FixAtom(String, Option<usize>),
    /// An atom-style variable.
    AtomVariable(String),
}

impl Input {
    /// True for per-atom values (binned for the group's particles only).
    pub(super) fn is_peratom(&self) -> bool {
        !matches!(
            self,
            Input::Scalar(_) | Input::ComputeVector(..) | Input::FixVector(_)
        )
    }

    /// The values to bin now (per-atom ones: those of the owned particles in `groupbit`).
    pub(super) fn values(&self, sim: &Sim, groupbit: u32) -> Result<Vec<f64>, Error> {
        let all = match self {
            Input::Scalar(w) => return Ok(vec![global_value(sim, w)?]),
            Input::ComputeVector(id, n) => {
                return (1..=*n)
                    .map(|k| crate::context::compute_global(sim, id, Some(k)))
                    .collect()
            }
            Input::FixVector(id) => {
                let f = &sim.defs.fixes[sim.fix_index(id).ok_or("its fix is gone")?];
                return f.imp.values(sim, &f.head);
            }
            Input::Field(f) => {
                let w = sim.world.as_ref().ok_or("no simulation box")?;
                crate::computes::kernels::field_values(w, f)
                    .ok_or_else(|| format!("bad attribute {f}"))?
            }
            Input::ComputeAtom(id, col) => crate::context::compute_peratom(sim, id, *col)?,
            Input::FixAtom(id, col) => crate::fixes::fix_peratom(sim, id, *col)?,
            Input::AtomVariable(v) => match sim.script.vars.get(v) {
                Some(Variable::Atom(f)) => crate::context::eval_atom(sim, f)?,
                _ => return Err(format!("variable '{v}' is not atom-style").into()),
            },
        };
        let mask = &sim
            .world
            .as_ref()
            .ok_or("no simulation box")?
            .particles
            .mask;
        Ok(all
            .into_iter()
            .zip(mask)
            .filter(|(_, m)| *m & groupbit != 0)
            .map(|(v, _)| v)
            .collect())
    }
}

/// Reads every value word (`(index, word)`), checks each names something of the kind
/// `mode` asks for, and that all are global or all per-atom.
pub(super) fn parse_all(
    sim: &Sim,
    a: &Args,
    words: &[(usize, &str)],
    vector: bool,
    nevery: u64,
) -> CmdResult<Vec<Input>> {
    let mut inputs = Vec::new();
    for &(k, w) in words {
        if !vector {
            if ATTRIBUTES.contains(&w) {
                return Err(a.error_at(
                    k,
                    format!("'{w}' is a per-atom value: it needs mode vector"),
                    None,
                ));
            }
            let (kind, id, _) = split_reference(w).expect("a reference");
            unknown_id(sim, a, k, kind, id)?;
            if kind == 'v' && is_atom_variable(sim, id) {
                return Err(a.error_at(
                    k,
                    format!("'{w}' is an atom-style variable: it needs mode vector"),
                    None,
                ));
            }
            if kind == 'c' && sim.defs.computes[sim.compute_index(id).expect("known")].is_peratom()
            {
                return Err(a.error_at(
                    k,
                    format!("compute {id} is per-atom: it needs mode vector"),
                    None,
                ));
            }
            inputs.push(Input::Scalar(w.to_string()));
            continue;
        }
        inputs.extend(vector_input(sim, a, k, w, nevery)?);
    }
    let peratom = inputs[0].is_peratom();
    if let Some(i) = inputs.iter().position(|i| i.is_peratom() != peratom) {
        return Err(a.error_at(
            words[i.min(words.len() - 1)].0,
            "ave/histo inputs must be all global or all per-atom",
            None,
        ));
    }
    Ok(inputs)
}

/// One word of `mode vector`: the inputs it stands for (an array gives its columns).
fn vector_input(sim: &Sim, a: &Args, k: usize, w: &str, nevery: u64) -> CmdResult<Vec<Input>> {
    if ATTRIBUTES.contains(&w) {
        return Ok(vec![Input::Field(w.to_string())]);
    }
    let (kind, id, col) = split_reference(w).expect("a reference");
    unknown_id(sim, a, k, kind, id)?;
    match kind {
        'c' => {
            let c = &sim.defs.computes[sim.compute_index(id).expect("known")];
            let shape = c.imp.shape();
            match (shape.peratom, col) {
                (Some(0), None) => Ok(vec![Input::ComputeAtom(id.into(), None)]),
                (Some(n), None) => Ok((1..=n)
                    .map(|j| Input::ComputeAtom(id.into(), Some(j)))
                    .collect()),
                (Some(n), Some(j)) if j >= 1 && j <= n => {
                    Ok(vec![Input::ComputeAtom(id.into(), Some(j))])
                }
                (None, None) if shape.vector > 0 => {
                    Ok(vec![Input::ComputeVector(id.into(), shape.vector)])
                }
                _ => Err(a.error_at(
                    k,
                    format!("'{w}' is not a vector or array column of compute {id}"),
                    None,
                )),
            }
        }
        'f' => {
            let f = &sim.defs.fixes[sim.fix_index(id).expect("known")];
            match (f.imp.peratom_shape(), col) {
                (Some((n, freq)), _) => {
                    if nevery % freq != 0 {
                        return Err(a.error_at(
                            k,
                            format!("fix {id} is not computed at compatible times (every {freq} steps; Nevery is {nevery})"),
                            None,
                        ));
                    }
                    match (n, col) {
                        (0, None) => Ok(vec![Input::FixAtom(id.into(), None)]),
                        (n, None) => Ok((1..=n)
                            .map(|j| Input::FixAtom(id.into(), Some(j)))
                            .collect()),
                        (n, Some(j)) if j >= 1 && j <= n => {
                            Ok(vec![Input::FixAtom(id.into(), Some(j))])
                        }
                        _ => Err(a.error_at(
                            k,
                            format!("'{w}' does not match fix {id}'s columns"),
                            None,
                        )),
                    }
                }
                (None, None) if f.stages.has(super::Stages::VALUES) => {
                    Ok(vec![Input::FixVector(id.into())])
                }
                _ => Err(a.error_at(
                    k,
                    format!("'{w}' is not a vector or per-atom column of fix {id}"),
                    None,
                )),
            }
        }
        _ if col.is_none() && is_atom_variable(sim, id) => Ok(vec![Input::AtomVariable(id.into())]),
        _ => Err(a.error_at(
            k,
            format!("'{w}': mode vector needs an atom-style variable"),
            None,
        )),
    }
}

//! A reference to per-atom values as the averaging and storing fixes read them: `c_ID`
//! or `c_ID[i]` of a per-atom compute, `f_ID` or `f_ID[i]` of a fix with per-atom values,
//! `v_name` of an atom-style variable (`fix ave/spatial`, `fix store/state`).

use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::thermo::split_reference;
use crate::variables::Variable;

/// One per-atom reference.
pub(super) enum PerAtomRef {
    /// A per-atom compute's vector or column.
    Compute(String, Option<usize>),
    /// A fix's per-atom vector or column.
    Fix(String, Option<usize>),
    /// An atom-style variable.
    Variable(String),
}

impl PerAtomRef {
    /// Word `k` of `a` as a reference: `None` if it is not a `c_`, `f_` or `v_` word; an
    /// error at it if what it names does not exist or has no per-atom values.
    pub(super) fn parse(sim: &Sim, a: &Args, k: usize, w: &str) -> CmdResult<Option<Self>> {
        let Some((kind, id, col)) = split_reference(w) else {
            return Ok(None);
        };
        super::ave_histo::unknown_id(sim, a, k, kind, id)?;
        Ok(Some(match kind {
            'c' => {
                let c = &sim.defs.computes[sim.compute_index(id).expect("known")];
                if !c.is_peratom() {
                    return Err(a.error_at(k, format!("compute {id} is not per-atom"), None));
                }
                Self::Compute(id.to_string(), col)
            }
            'f' => {
                crate::fixes::check_fix_peratom(sim, id, col)
                    .map_err(|m| a.error_at(k, m, None))?;
                Self::Fix(id.to_string(), col)
            }
            _ => {
                if !matches!(sim.script.vars.get(id), Some(Variable::Atom(_))) {
                    return Err(a.error_at(k, format!("variable {id} is not atom-style"), None));
                }
                Self::Variable(id.to_string())
            }
        }))
    }

    /// The values of the owned particles now.
    pub(super) fn values(&self, sim: &Sim) -> Result<Vec<f64>, Error> {
        match self {
            Self::Compute(id, col) => crate::context::compute_peratom(sim, id, *col),
            Self::Fix(id, col) => crate::fixes::fix_peratom(sim, id, *col),
            Self::Variable(name) => match sim.script.vars.get(name) {
                Some(Variable::Atom(f)) => crate::context::eval_atom(sim, f),
                _ => Err(format!("variable {name} is not atom-style").into()),
            },
        }
    }
}

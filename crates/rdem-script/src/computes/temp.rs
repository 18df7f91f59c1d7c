//! `compute ID group temp`: the translational temperature of the group, a global scalar,
//! T = Σ m v² / (dof k_B) with dof = d N − extra in d dimensions (`extra` d by default,
//! changed by `compute_modify ID extra N`; k_B of the `units` system), T = 0 when
//! dof ≤ 0. Every script has one implicitly,
//! `thermo_temp` on group `all` (see [`thermo_temp`]), as LIGGGHTS 3.8 creates it at
//! start-up.
//!
//! N is counted when a run is set up (LAMMPS' `init`) and kept through the run, unless
//! `compute_modify ID dynamic yes` asks for a count at each evaluation: so a pour that
//! starts with no particle prints T = 0 throughout without `dynamic yes`. LIGGGHTS 3.8,
//! `liggghts -in in.dyn` (20 particles inserted at 0.1 0.2 0.3 m/s into an empty box,
//! tests/temperature.rs) prints `c_thermo_temp` 0 while N counted at set-up is 0,
//! 8.73251530866047e+17 in a later run that inserts 10 more (N counted at its set-up is
//! 20), and 5.72130313326031e+17 for 30 with `dynamic yes`.

use crate::error::Error;
use rdem::World;

use super::kernels::kinetic;
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "temp",
    parse,
    "translational temperature of the group; `compute_modify` `extra`, `dynamic`",
)
.notes("every script has `thermo_temp` (group all), as LIGGGHTS");

fn parse(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(Temp::default()))
}

/// The implicit `thermo_temp` compute every script starts with.
pub fn thermo_temp() -> super::Compute {
    super::Compute {
        head: ComputeHead {
            id: "thermo_temp".into(),
            groupbit: 1,
        },
        style: "temp",
        imp: Box::new(Temp::default()),
    }
}

/// `compute temp`.
#[derive(Debug, Default)]
pub struct Temp {
    /// Degrees of freedom subtracted from d N (`compute_modify extra`); `None`: d, the
    /// dimension (3, or 2 after `dimension 2`, as LIGGGHTS 3.8 counts).
    pub extra_dof: Option<i64>,
    /// Count N at each evaluation (`compute_modify dynamic yes`).
    pub dynamic: bool,
    /// N counted at the last run set-up (None before the first run: counted when
    /// evaluated).
    counted: Option<u64>,
}

/// Number of owned particles in the group, summed over ranks.
fn group_count(w: &World, groupbit: u32) -> u64 {
    let p = &w.particles;
    let n = (0..p.nlocal())
        .filter(|&i| p.mask[i] & groupbit != 0)
        .count();
    w.comm.sum(n as f64) as u64
}

impl Temp {
    /// The degrees of freedom for `n` particles in `dim` dimensions.
    pub fn dof(&self, n: u64, dim: u8) -> f64 {
        let extra = self.extra_dof.unwrap_or(i64::from(dim));
        f64::from(dim) * n as f64 - extra as f64
    }
}

impl ScriptCompute for Temp {
    fn shape(&self) -> Shape {
        Shape::scalar()
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        if let Some(k) = idx {
            let id = &c.id;
            return Err(format!("c_{id}[{k}]: compute {id} has no global vector").into());
        }
        let w = super::world(sim)?;
        let n = match self.counted {
            Some(n) if !self.dynamic => n,
            _ => group_count(w, c.groupbit),
        };
        let dof = self.dof(n, sim.setup.dimension);
        Ok(if dof > 0.0 {
            2.0 * kinetic(w, c.groupbit) / (dof * sim.setup.units.boltzmann())
        } else {
            0.0
        })
    }

    fn init(&mut self, w: &World, c: &ComputeHead) {
        self.counted = Some(group_count(w, c.groupbit));
    }

    fn modify(&mut self, keyword: &str, a: &mut Args) -> CmdResult<bool> {
        match keyword {
            "extra" | "extra/dof" => {
                let w = a.word("number of extra degrees of freedom")?;
                // LIGGGHTS 3.8 reads an integer (`extra 4.5` is an error there).
                self.extra_dof = Some(w.parse().map_err(|_| {
                    a.error_prev(
                        format!("{keyword} must be an integer, not '{w}'"),
                        Some("LIGGGHTS 3.8 reads a whole number here (negative adds degrees of freedom)".into()),
                    )
                })?);
            }
            "dynamic" | "dynamic/dof" => self.dynamic = a.yes_no(keyword)?,
            _ => return Ok(false),
        }
        Ok(true)
    }
}

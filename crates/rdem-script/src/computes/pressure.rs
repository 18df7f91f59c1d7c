//! `compute ID all pressure temp-ID [ke pair bond angle dihedral improper kspace fix
//! virial]`: the pressure, a global scalar (Σ m v² + Σ W_aa)/(3V), and the pressure
//! tensor, a vector of 6 (Σ m v_a v_b + Σ W_ab)/V in the order xx yy zz xy xz yz, with W
//! the contact virial of the owned particles ([`rdem::World::current_virial`], the same
//! sum `compute stress/atom` reports per particle) and V the box volume.
//!
//! The kinetic term is that of LIGGGHTS' `thermo_temp` (translation of every particle;
//! zero when the 3N − 3 degrees of freedom are none). rdem has no bonded, long-range or
//! fix virials (LIGGGHTS' `wall/gran` adds none), so those keywords select nothing.

use super::kernels::STRESS_KEYWORDS;
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "pressure",
    parse,
    "scalar and tensor (6) of group `all`: `thermo_temp`; `ke`, `pair`, `virial`, ...",
)
.notes("the temperature compute must be `thermo_temp` (rdem has no `compute temp`)");

/// Which terms it sums.
#[derive(Debug)]
pub struct Pressure {
    /// The kinetic term.
    ke: bool,
    /// The contact virial.
    pair: bool,
}

impl ScriptCompute for Pressure {
    fn shape(&self) -> Shape {
        Shape {
            scalar: true,
            vector: 6,
            peratom: None,
        }
    }

    fn needs_virial(&self) -> bool {
        self.pair
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let w = super::world(sim)?;
        let k = match idx {
            None => None,
            Some(k) if (1..=6).contains(&k) => Some(k - 1),
            Some(k) => {
                return Err(format!("c_{}[{k}]: compute {} gives 6 values", c.id, c.id).into())
            }
        };
        const AB: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
        let p = &w.particles;
        let n = p.nlocal();
        // Σ m v_a v_b and Σ W_ab for the 6 components, summed over ranks.
        let mut t = [0.0; 12];
        if self.ke {
            for i in 0..n {
                for (j, (a, b)) in AB.iter().enumerate() {
                    t[j] += p.rmass[i] * p.v[i][*a] * p.v[i][*b];
                }
            }
        }
        if self.pair {
            let v = w.current_virial().ok_or_else(|| {
                format!("compute {}: the contact virial is not available at this step (a run computes it on every step while the compute exists)", c.id)
            })?;
            for vi in v {
                for j in 0..6 {
                    t[6 + j] += vi[j];
                }
            }
        }
        w.comm.sum_slice(&mut t);
        let size = w.domain.boxhi - w.domain.boxlo;
        let volume = size.x * size.y * size.z;
        Ok(match k {
            Some(j) => (t[j] + t[6 + j]) / volume,
            None => {
                // LIGGGHTS: dof·k_B·T of thermo_temp, which is Σ m v² unless there are
                // no degrees of freedom (3N − 3 ≤ 0), then 0.
                let dof = 3 * w.natoms() as i64 - 3;
                let kin = if dof > 0 { t[0] + t[1] + t[2] } else { 0.0 };
                (kin + t[6] + t[7] + t[8]) / (3.0 * volume)
            }
        } + 0.0)
    }
}

fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    super::pe::require_group_all(a, "pressure")?;
    let temp = a.word("temperature compute ID")?;
    if temp != "thermo_temp" {
        let what = match sim.compute_index(temp) {
            Some(_) => format!("compute {temp} is not a temperature compute"),
            None => format!("no temperature compute '{temp}'"),
        };
        return Err(a.error_prev(
            what,
            Some(
                "rdem's compute pressure takes 'thermo_temp' (compute temp is not supported yet)"
                    .into(),
            ),
        ));
    }
    // No keyword: every term; otherwise only the listed ones (`virial`: all but ke).
    let (mut ke, mut pair, mut any) = (false, false, false);
    while !a.is_done() {
        match a.keyword("pressure keyword", &STRESS_KEYWORDS)? {
            "ke" => ke = true,
            "pair" | "virial" => pair = true,
            _ => {}
        }
        any = true;
    }
    if !any {
        (ke, pair) = (true, true);
    }
    Ok(Box::new(Pressure { ke, pair }))
}

//! `compute ID group pair/gran/local/bond` (LIGGGHTS-INL): one row per intact bond of
//! `cohesion bond` between two particles of the group, for `dump local` and `dump
//! local/gran/vtk`. As in LIGGGHTS-INL the columns are fixed (the style takes no
//! keywords there: it sets its own whatever follows): pos (6: centres of i and j), id (3:
//! the two IDs and 1 when j is a periodic image, else 0), force (3: on i), force_normal
//! (3: its part along the line of centres), force_tangential (3: the rest), torque (3: on
//! i), torque_normal (3), torque_tangential (3) and history (the pair's history row).
//!
//! Force and torque are the whole of what the pair gives i, the contact law's (when the
//! spheres touch) and the bond's, as LIGGGHTS-INL's post-force callback sees them. They
//! are evaluated from the state when the compute is invoked, as `compute pair/gran/local`
//! is ([`rdem::pair::PairGran::bonds`]). The history columns are rdem's layout, not
//! LIGGGHTS-INL's: the bond's shear force, twisting torque and bending torque on i (9),
//! the contact law's values, then the bond flag (1) and its length at creation d₀.

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "pair/gran/local/bond",
    parse,
    "per-bond values of `cohesion bond` (LIGGGHTS-INL; `dump local`, `dump local/gran/vtk`)",
)
.notes(
    "fixed columns pos, id, force, force_normal, force_tangential, torque, torque_normal, \
     torque_tangential, history (rdem's history layout); takes no keywords",
);

/// The column groups before the history: (name, width).
const FIXED: [(&str, usize); 8] = [
    ("pos", 6),
    ("id", 3),
    ("force", 3),
    ("force_normal", 3),
    ("force_tangential", 3),
    ("torque", 3),
    ("torque_normal", 3),
    ("torque_tangential", 3),
];

/// Columns before the history.
const NFIXED: usize = 27;

/// The compute.
#[derive(Debug)]
pub struct PairGranLocalBond {
    /// History values per pair.
    hist_width: usize,
}

/// `v` split along the unit vector `n` and across it.
fn split(v: rdem::DVec3, n: rdem::DVec3) -> (rdem::DVec3, rdem::DVec3) {
    let along = n * v.dot(n);
    (along, v - along)
}

impl ScriptCompute for PairGranLocalBond {
    fn shape(&self) -> Shape {
        Shape::default()
    }

    fn local_cols(&self) -> Option<usize> {
        Some(NFIXED + self.hist_width)
    }

    fn local_groups(&self) -> Vec<(&'static str, usize, usize)> {
        let mut out = Vec::new();
        let mut at = 0;
        for (name, n) in FIXED.into_iter().chain([("history", self.hist_width)]) {
            out.push((name, at, n));
            at += n;
        }
        out
    }

    fn local(&self, sim: &Sim, c: &ComputeHead) -> Result<Vec<f64>, Error> {
        let w = super::world(sim)?;
        let Some(pair) = w.pair.as_ref().filter(|p| p.model.has_bonds()) else {
            return Err(format!(
                "compute {} (pair/gran/local/bond) needs a pair style with cohesion bond",
                c.id
            )
            .into());
        };
        let p = &w.particles;
        let rec = pair.bonds(p, &w.neighbor.list, w.dt);
        let nlocal = p.nlocal();
        let mut out = Vec::with_capacity(rec.len() * (NFIXED + self.hist_width));
        let hw = rec.width.min(self.hist_width);
        for k in 0..rec.len() {
            let (i, j) = (rec.i[k] as usize, rec.j[k] as usize);
            if p.mask[i] & c.groupbit == 0 || p.mask[j] & c.groupbit == 0 {
                continue;
            }
            // The unit vector from i to j (a bond keeps its spheres apart: never zero).
            let n = (p.x[j] - p.x[i]).normalize_or_zero();
            let (f, t) = (rec.f[k], rec.t_i[k]);
            let (fnorm, ftan) = split(f, n);
            let (tnorm, ttan) = split(t, n);
            let periodic = j >= nlocal && !w.domain.is_in_domain(p.x[j]);
            let ids = rdem::DVec3::new(
                p.tag[i] as f64,
                p.tag[j] as f64,
                if periodic { 1.0 } else { 0.0 },
            );
            for v in [p.x[i], p.x[j], ids, f, fnorm, ftan, t, tnorm, ttan] {
                out.extend_from_slice(&[v.x, v.y, v.z]);
            }
            out.extend_from_slice(&rec.hist[k * rec.width..k * rec.width + hw]);
            out.extend(std::iter::repeat_n(0.0, self.hist_width - hw));
        }
        Ok(out)
    }
}

/// `compute ID group pair/gran/local/bond` (no keywords).
fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    if !a.is_done() {
        let _ = a.word("keyword")?;
        return Err(a.error_prev(
            "pair/gran/local/bond takes no keywords",
            Some(
                "its columns are fixed: pos, id, force, force_normal, force_tangential, \
                 torque, torque_normal, torque_tangential, history"
                    .to_string(),
            ),
        ));
    }
    let model = sim
        .world
        .as_ref()
        .and_then(|w| w.pair.as_ref())
        .map(|p| p.model);
    let hist_width = match model {
        Some(m) if m.has_bonds() => m.history_width(),
        _ => {
            return Err(a.error_at(
                3,
                "compute pair/gran/local/bond needs a pair style with a cohesion bond model",
                Some("define `pair_style gran model ... cohesion bond` before it".to_string()),
            ))
        }
    };
    Ok(Box::new(PairGranLocalBond { hist_width }))
}

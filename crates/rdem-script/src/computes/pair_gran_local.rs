//! `compute ID group pair/gran/local [keywords]`: one row per particle pair in contact
//! (both particles in the group), with the columns the keywords select, in LIGGGHTS
//! 3.8's order whatever the order of the keywords: pos (6), vel (6), id (3), force (3),
//! force_normal (3), force_tangential (3), torque (3), history (the contact law's
//! history values), contactArea (1), delta (1), contactPoint (3), heatFlux (1). Without
//! keywords: pos, vel, id, force, torque, history and contactArea. (The manual lists
//! heatFlux before contactPoint; LIGGGHTS 3.8 writes contactPoint first, measured with
//! `id heatFlux contactPoint`: `1 2 0 0.0097546 -2.38853e-05 4.48546e-05 8.3533`.)
//!
//! Values as LIGGGHTS 3.8 gives them (checked against its output in
//! `crates/rdem-cli/tests/local_dump.rs`): positions and velocities of i then j; the two
//! IDs and 1 when j is a periodic image (0 otherwise); the contact force on i; its
//! components along and across the line of centres; the contact law's torque on i
//! (without rolling friction, which LIGGGHTS leaves out too); the contact area of the
//! two spheres' geometric intersection, π a²; the overlap r_i + r_j − |x_i − x_j|; the
//! contact point, on the line of centres at the fraction r_i/(r_i + r_j) of the way from
//! i to j (LIGGGHTS 3.8's values, see `crates/rdem-cli/tests/local_dump.rs`); the
//! heat flow into i through the contact from the temperatures at the time of output
//! (`fix heat/gran`'s conductance, [`rdem::heat::HeatConduction::pair_flow`]; LIGGGHTS
//! 3.8 gives the same, measured, and stops without a `fix heat/gran`).
//! The contact law is evaluated from the state when the compute is invoked, as
//! LIGGGHTS does ([`rdem::pair::PairContacts`]).

use crate::error::Error;
use std::f64::consts::PI;

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "pair/gran/local",
    parse,
    "per-contact values of the pair contacts (`dump local`, `dump local/gran/vtk`)",
)
.notes("`heatFlux` needs `fix heat/gran`; `ms_id` is not supported yet");

/// The keywords, in LIGGGHTS' column order.
const KEYWORDS: [&str; 13] = [
    "pos",
    "vel",
    "id",
    "force",
    "force_normal",
    "force_tangential",
    "torque",
    "history",
    "contactArea",
    "delta",
    "contactPoint",
    "heatFlux",
    "ms_id",
];

/// Which column groups it gives (shared with `compute wall/gran/local`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Columns {
    pub(super) pos: bool,
    pub(super) vel: bool,
    pub(super) id: bool,
    pub(super) force: bool,
    pub(super) force_normal: bool,
    pub(super) force_tangential: bool,
    pub(super) torque: bool,
    pub(super) history: bool,
    pub(super) contact_area: bool,
    pub(super) delta: bool,
    pub(super) contact_point: bool,
    pub(super) heat_flux: bool,
}

/// The compute.
#[derive(Debug)]
pub struct PairGranLocal {
    cols: Columns,
    /// History values per contact (from the pair style when defined).
    hist_width: usize,
}

impl Columns {
    /// The groups it gives, in LIGGGHTS' order, with `hist_width` history values:
    /// (name, first column, width).
    pub(super) fn groups(&self, hist_width: usize) -> Vec<(&'static str, usize, usize)> {
        let c = self;
        let mut out = Vec::new();
        let mut at = 0;
        for (on, name, n) in [
            (c.pos, "pos", 6),
            (c.vel, "vel", 6),
            (c.id, "id", 3),
            (c.force, "force", 3),
            (c.force_normal, "force_normal", 3),
            (c.force_tangential, "force_tangential", 3),
            (c.torque, "torque", 3),
            (c.history, "history", hist_width),
            (c.contact_area, "contactArea", 1),
            (c.delta, "delta", 1),
            (c.contact_point, "contactPoint", 3),
            (c.heat_flux, "heatFlux", 1),
        ] {
            if on {
                out.push((name, at, n));
                at += n;
            }
        }
        out
    }

    /// Number of columns with `hist_width` history values.
    pub(super) fn count(&self, hist_width: usize) -> usize {
        self.groups(hist_width).iter().map(|g| g.2).sum()
    }
}

impl PairGranLocal {
    fn ncols(&self) -> usize {
        self.cols.count(self.hist_width)
    }
}

/// Area π a² of the circle where spheres of radii `ri`, `rj` at centre distance `d`
/// intersect.
fn contact_area(ri: f64, rj: f64, d: f64) -> f64 {
    let x = (d * d + ri * ri - rj * rj) / (2.0 * d);
    PI * (ri * ri - x * x).max(0.0)
}

impl ScriptCompute for PairGranLocal {
    fn shape(&self) -> Shape {
        Shape::default()
    }

    fn local_cols(&self) -> Option<usize> {
        Some(self.ncols())
    }

    fn local_groups(&self) -> Vec<(&'static str, usize, usize)> {
        self.cols.groups(self.hist_width)
    }

    fn local(&self, sim: &Sim, c: &ComputeHead) -> Result<Vec<f64>, Error> {
        let w = super::world(sim)?;
        let Some(pair) = &w.pair else {
            return Err(format!(
                "compute {} (pair/gran/local) needs a granular pair style",
                c.id
            )
            .into());
        };
        let heat = heat_for(w, &self.cols, c)?;
        let p = &w.particles;
        let rec = pair.contacts(p, &w.neighbor.list, w.dt);
        let cols = &self.cols;
        let nlocal = p.nlocal();
        let mut out = Vec::with_capacity(rec.len() * self.ncols());
        let hw = rec.width.min(self.hist_width);
        for k in 0..rec.len() {
            let (i, j) = (rec.i[k] as usize, rec.j[k] as usize);
            if p.mask[i] & c.groupbit == 0 || p.mask[j] & c.groupbit == 0 {
                continue;
            }
            let d = p.x[i] - p.x[j];
            let dist = d.length();
            let f = rec.f[k];
            // Along the unit vector from i to j, as LIGGGHTS takes it: x_j − x_i, whose zero
            // components are +0, so that a zero component of a force pushing i away from
            // j is −0, as LIGGGHTS writes it (measured: `-0.133184 -0.0147983 -0`).
            let fnorm = if dist > 0.0 {
                let n = (p.x[j] - p.x[i]) / dist;
                n * f.dot(n)
            } else {
                f
            };
            let mut push3 = |v: rdem::DVec3| out.extend_from_slice(&[v.x, v.y, v.z]);
            if cols.pos {
                push3(p.x[i]);
                push3(p.x[j]);
            }
            if cols.vel {
                push3(p.v[i]);
                push3(p.v[j]);
            }
            if cols.id {
                // A ghost outside the box is a periodic image.
                let periodic = j >= nlocal && !w.domain.is_in_domain(p.x[j]);
                let flag = if periodic { 1.0 } else { 0.0 };
                push3(rdem::DVec3::new(p.tag[i] as f64, p.tag[j] as f64, flag));
            }
            if cols.force {
                push3(f);
            }
            if cols.force_normal {
                push3(fnorm);
            }
            if cols.force_tangential {
                push3(f - fnorm);
            }
            if cols.torque {
                push3(rec.t_i[k]);
            }
            if cols.history {
                out.extend_from_slice(&rec.hist[k * rec.width..k * rec.width + hw]);
                out.extend(std::iter::repeat_n(0.0, self.hist_width - hw));
            }
            if cols.contact_area {
                out.push(contact_area(p.radius[i], p.radius[j], dist));
            }
            if cols.delta {
                out.push(rec.delta[k]);
            }
            if cols.contact_point {
                let (ri, rj) = (p.radius[i], p.radius[j]);
                let q = p.x[i] + (p.x[j] - p.x[i]) * (ri / (ri + rj));
                out.extend_from_slice(&[q.x, q.y, q.z]);
            }
            if let Some(h) = heat {
                out.push(h.pair_flow(p, i, j, dist));
            }
        }
        Ok(out)
    }
}

/// The heat conduction a `heatFlux` column reads (`None` without that column); an error
/// without `fix heat/gran`, as in LIGGGHTS 3.8.
pub(super) fn heat_for<'w>(
    w: &'w rdem::World,
    cols: &Columns,
    c: &ComputeHead,
) -> Result<Option<&'w rdem::heat::HeatConduction>, Error> {
    if !cols.heat_flux {
        return Ok(None);
    }
    w.heat.as_ref().map(Some).ok_or_else(|| {
        Error::invalid(format!(
            "compute {}: heatFlux needs the heat flows of a fix heat/gran, and there is none",
            c.id
        ))
    })
}

/// `compute ID group pair/gran/local [keywords]`.
fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let c = parse_columns(a, "pair/gran/local")?;
    let hist_width = sim
        .world
        .as_ref()
        .and_then(|w| w.pair.as_ref())
        .map_or(0, |p| p.model.contact_history_width());
    Ok(Box::new(PairGranLocal {
        cols: c,
        hist_width,
    }))
}

/// The keywords of `compute pair/gran/local` or `wall/gran/local` (`style`), LIGGGHTS'
/// default when there are none.
pub(super) fn parse_columns(a: &mut Args, style: &str) -> CmdResult<Columns> {
    let mut c = Columns::default();
    while !a.is_done() {
        match a.keyword(&format!("{style} keyword"), &KEYWORDS)? {
            "pos" => c.pos = true,
            "vel" => c.vel = true,
            "id" => c.id = true,
            "force" => c.force = true,
            "force_normal" => c.force_normal = true,
            "force_tangential" => c.force_tangential = true,
            "torque" => c.torque = true,
            "history" => c.history = true,
            "contactArea" => c.contact_area = true,
            "delta" => c.delta = true,
            "contactPoint" => c.contact_point = true,
            "heatFlux" => c.heat_flux = true,
            other => {
                return Err(a.error_prev(
                    format!("{style}: keyword '{other}' is not supported yet"),
                    Some(
                        "use pos, vel, id, force, force_normal, force_tangential, torque, \
                         history, contactArea, delta, contactPoint or heatFlux"
                            .to_string(),
                    ),
                ))
            }
        }
    }
    if c == Columns::default() {
        // LIGGGHTS' default: all but force_normal, force_tangential and delta.
        c = Columns {
            pos: true,
            vel: true,
            id: true,
            force: true,
            torque: true,
            history: true,
            contact_area: true,
            ..c
        };
    }
    Ok(c)
}

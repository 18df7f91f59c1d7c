//! `compute ID group wall/gran/local [keywords]`: one row per contact of a particle of
//! the group with a mesh wall, with the columns the keywords select, in LIGGGHTS 3.8's
//! order whatever the order of the keywords: pos (6), vel (6), id (3), force (3),
//! force_normal (3), force_tangential (3), torque (3), history (the wall model's history
//! values), contactArea (1), delta (1), contactPoint (3), heatFlux (1). Without keywords:
//! pos, vel, id, force, torque, history and contactArea.
//!
//! As in LIGGGHTS 3.8 (its manual: "only mesh walls can be used"), the contacts are
//! those of the last `fix wall/gran` with mesh walls defined before the compute; a
//! primitive wall gives a warning and no rows. Values as LIGGGHTS 3.8 gives them
//! (checked against its output in `crates/rdem-cli/tests/wall_local.rs`): the contact
//! point (the closest point of the wall) and the particle's centre; the wall's velocity
//! there and the particle's; the mesh's position among the wall's meshes (from 0), the
//! triangle (its order in the file) and the particle's ID; the contact force on the
//! particle, its parts along the wall normal and across it; the contact law's torque on
//! the particle; the history values; π (r² − d²) with d the centre's distance to the
//! wall; the overlap r − d; the contact point as LIGGGHTS 3.8 gives it for a wall: 0 0 0
//! (measured: `pos id delta contactPoint` on a sphere pressed into a mesh plate gives
//! `... 0 0 2 0.000149916 0 0 0`; the closest point of the wall is in `pos`); the heat flow into the particle from the wall's temperature
//! at the time of output (`fix heat/gran`'s conductance; 0 for a wall without a
//! temperature). Rows are ordered by mesh, triangle, then particle. The
//! contact law is evaluated from the state when the compute is invoked, as LIGGGHTS
//! does ([`rdem::wall::MeshWall::contacts`]); a wall bond's force is not included.

use crate::error::Error;
use std::f64::consts::PI;

use rdem::fix::FixKind;

use super::pair_gran_local::{heat_for, parse_columns, Columns};
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "wall/gran/local",
    parse,
    "per-contact values of the particle–mesh-wall contacts (`dump local`)",
)
.notes(
    "mesh walls only, as LIGGGHTS 3.8; one per script (LIGGGHTS: one per fix wall/gran); \
     `heatFlux` needs `fix heat/gran` (0 on a wall without a temperature); \
     `contactPoint` is 0 0 0 as in LIGGGHTS 3.8 (the wall's closest point is in `pos`); \
     `ms_id` is not supported yet",
);

/// The compute.
#[derive(Debug)]
pub struct WallGranLocal {
    cols: Columns,
    /// History values per contact (the wall model's).
    hist_width: usize,
    /// The ID of the `fix wall/gran` (mesh) whose contacts it gives.
    wall: String,
}

impl ScriptCompute for WallGranLocal {
    fn shape(&self) -> Shape {
        Shape::default()
    }

    fn local_cols(&self) -> Option<usize> {
        Some(self.cols.count(self.hist_width))
    }

    fn local_groups(&self) -> Vec<(&'static str, usize, usize)> {
        self.cols.groups(self.hist_width)
    }

    fn local(&self, sim: &Sim, c: &ComputeHead) -> Result<Vec<f64>, Error> {
        let w = super::world(sim)?;
        let wall = w.fixes.iter().find_map(|f| match &f.kind {
            FixKind::MeshWall(m) if f.id == self.wall => Some(m),
            _ => None,
        });
        let Some(wall) = wall else {
            return Err(format!(
                "compute {} (wall/gran/local): its fix wall/gran {} no longer exists",
                c.id, self.wall
            )
            .into());
        };
        let heat = heat_for(w, &self.cols, c)?;
        let p = &w.particles;
        let rec = wall.contacts(&w.meshes, p, w.dt);
        let cols = &self.cols;
        let ncols = self.cols.count(self.hist_width);
        let mut out = Vec::with_capacity(rec.rows.len() * ncols);
        let hw = rec.width.min(self.hist_width);
        for (k, r) in rec.rows.iter().enumerate() {
            let i = r.i as usize;
            if p.mask[i] & c.groupbit == 0 {
                continue;
            }
            // The normal as LIGGGHTS takes it: minus the unit vector from the centre to the
            // contact point (a zero component of it is written −0 then, as LIGGGHTS does).
            let normal = -((r.q - p.x[i]) / r.dist);
            let fnorm = normal * r.f.dot(normal);
            let mut push3 = |v: rdem::DVec3| out.extend_from_slice(&[v.x, v.y, v.z]);
            if cols.pos {
                push3(r.q);
                push3(p.x[i]);
            }
            if cols.vel {
                push3(r.v_wall);
                push3(p.v[i]);
            }
            if cols.id {
                push3(rdem::DVec3::new(
                    r.mesh as f64,
                    r.tri as f64,
                    p.tag[i] as f64,
                ));
            }
            if cols.force {
                push3(r.f);
            }
            if cols.force_normal {
                push3(fnorm);
            }
            if cols.force_tangential {
                push3(r.f - fnorm);
            }
            if cols.torque {
                push3(r.t);
            }
            if cols.history {
                out.extend_from_slice(&rec.hist[k * rec.width..k * rec.width + hw]);
                out.extend(std::iter::repeat_n(0.0, self.hist_width - hw));
            }
            let radius = p.radius[i];
            if cols.contact_area {
                out.push(PI * (radius * radius - r.dist * r.dist));
            }
            if cols.delta {
                out.push(radius - r.dist);
            }
            if cols.contact_point {
                // LIGGGHTS 3.8 leaves a wall contact's point at zero.
                out.extend_from_slice(&[0.0; 3]);
            }
            if let Some(h) = heat {
                let surface = &w.meshes[wall.meshes[r.mesh as usize]];
                out.push(h.wall_flow(
                    p,
                    i,
                    surface.wall_type,
                    surface.temperature,
                    radius - r.dist,
                ));
            }
        }
        Ok(out)
    }
}

/// `compute ID group wall/gran/local [keywords]`.
fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let cols = parse_columns(a, "wall/gran/local")?;
    let fixes = sim.world.as_ref().map_or(&[][..], |w| &w.fixes[..]);
    let primitive = fixes.iter().any(|f| matches!(f.kind, FixKind::WallGran(_)));
    let Some((id, wall)) = fixes.iter().rev().find_map(|f| match &f.kind {
        FixKind::MeshWall(m) => Some((f.id.clone(), m)),
        _ => None,
    }) else {
        return Err(a.error_at(
            3,
            "compute wall/gran/local needs a fix wall/gran with mesh walls defined before it",
            Some("only mesh walls can be used (as in LIGGGHTS 3.8)".to_string()),
        ));
    };
    if let Some(other) = sim
        .defs
        .computes
        .iter()
        .find(|c| c.style == "wall/gran/local")
    {
        return Err(a.error_at(
            3,
            format!(
                "only one compute wall/gran/local is supported (compute {} is one)",
                other.id()
            ),
            Some("LIGGGHTS 3.8 allows one per fix wall/gran; rdem one per script".into()),
        ));
    }
    if primitive {
        a.warn_at(
            3,
            "compute wall/gran/local: primitive walls found, only mesh wall contacts are output",
        );
    }
    let hist_width = wall.model.contact_history_width();
    if cols.history && hist_width == 0 {
        return Err(a.error_at(
            3,
            "compute wall/gran/local cannot give history values: the wall's model has none",
            Some("list the keywords without history".to_string()),
        ));
    }
    Ok(Box::new(WallGranLocal {
        cols,
        hist_width,
        wall: id,
    }))
}

//! `compute ID group nparticles/tracer/region region_count REGION tracer FIX
//! [periodic x|y|z IMAGE|all] [reset_marker yes|no]` (LIGGGHTS 3.8): a global vector of
//! 4, over the group's particles inside the region: (1) their number, (2) how many of
//! them the `fix property/atom/tracer` FIX has marked, (3) their mass, (4) the marked
//! ones' mass. With `periodic`, only particles in that periodic image along that axis
//! count. With `reset_marker yes` (the default) the marked particles counted are
//! unmarked, so that each is counted once.
//!
//! As in LIGGGHTS, the vector is computed once per step (the first time something asks
//! for it; later requests in that step get the same numbers), so the unmarking does not
//! change what thermo and the other readers see within the step. The fix writes the
//! cleared markers before the next step ([`crate::fixes::tracer`]).

use std::sync::{Arc, Mutex};

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::fixes::tracer::{Tracer, Unmarked};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "nparticles/tracer/region",
    parse,
    "`region_count REGION tracer FIX [periodic x|y|z IMAGE|all] [reset_marker yes|no]`: number of the group's particles in the region, how many are marked, their mass, the marked mass (a global vector of 4); counted marked particles are unmarked (reset_marker yes)",
);

#[derive(Debug)]
struct NParticlesTracer {
    region: String,
    /// The tracer fix's property and its queue of cleared markers.
    prop: String,
    unmarked: Arc<Unmarked>,
    /// Axis and image a particle must be in.
    periodic: Option<(usize, i32)>,
    reset: bool,
    /// The step of the last evaluation and its vector.
    last: Mutex<Option<(u64, [f64; 4])>>,
}

fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let (mut region, mut tracer) = (None, None);
    let (mut periodic, mut reset) = (None, true);
    while !a.is_done() {
        match a.keyword(
            "compute nparticles/tracer/region keyword",
            &["region_count", "tracer", "periodic", "reset_marker"],
        )? {
            "region_count" => region = Some(sim.region_id(a)?),
            "tracer" => {
                let id = a.word("tracer fix ID")?;
                let fix = sim
                    .defs
                    .fixes
                    .iter()
                    .find(|f| f.head.id == id)
                    .and_then(|f| f.imp.as_any().downcast_ref::<Tracer>());
                match fix {
                    Some(t) => tracer = Some((t.prop.clone(), t.unmarked.clone())),
                    None => {
                        return Err(a.error_prev(
                            format!("no fix property/atom/tracer '{id}'"),
                            Some("define it first with 'fix ID group property/atom/tracer region_mark REGION mark_step S'".into()),
                        ))
                    }
                }
            }
            "periodic" => {
                let axis = match a.keyword("periodic axis", &["x", "y", "z"])? {
                    "x" => 0,
                    "y" => 1,
                    _ => 2,
                };
                let w = a.word("periodic image")?;
                periodic = match w {
                    "all" => None,
                    _ => match w.parse::<i32>() {
                        Ok(n) => Some((axis, n)),
                        Err(_) => {
                            return Err(a.error_prev(
                                format!("periodic image must be an integer or 'all', not '{w}'"),
                                None,
                            ))
                        }
                    },
                };
            }
            _ => reset = a.yes_no("reset_marker")?,
        }
    }
    let (Some(region), Some((prop, unmarked))) = (region, tracer) else {
        return Err(a.error_cmd(
            "compute nparticles/tracer/region needs 'region_count REGION' and 'tracer FIX'",
            None,
        ));
    };
    Ok(Box::new(NParticlesTracer {
        region,
        prop,
        unmarked,
        periodic,
        reset,
        last: Mutex::new(None),
    }))
}

impl NParticlesTracer {
    fn evaluate(&self, sim: &Sim, c: &ComputeHead) -> Result<[f64; 4], Error> {
        let w = super::world(sim)?;
        let region = crate::regions::region_now(sim, &self.region)?;
        let p = &w.particles;
        let id = p
            .property(&self.prop)
            .ok_or_else(|| format!("compute {}: the tracer fix is gone", c.id))?;
        let mut s = [0.0; 4];
        let mut counted = Vec::new();
        let marker = |i: usize| p.props[id.0].get(i)[0] != 0.0;
        let queued: std::collections::HashSet<rdem::Tag> = self.unmarked.tags();
        for i in 0..p.nlocal() {
            if p.mask[i] & c.groupbit == 0 || !region.contains(p.x[i]) {
                continue;
            }
            if let Some((axis, image)) = self.periodic {
                if p.image[i].get()[axis] != image {
                    continue;
                }
            }
            s[0] += 1.0;
            s[2] += p.rmass[i];
            if marker(i) && !queued.contains(&p.tag[i]) {
                s[1] += 1.0;
                s[3] += p.rmass[i];
                counted.push(p.tag[i]);
            }
        }
        w.comm.sum_slice(&mut s);
        if self.reset {
            self.unmarked.push(&counted);
        }
        Ok(s)
    }
}

impl ScriptCompute for NParticlesTracer {
    fn shape(&self) -> Shape {
        Shape::vector(4)
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let k = super::pick_index(&c.id, idx, 4)?;
        let step = super::world(sim)?.step;
        let mut last = self.last.lock().expect("compute cache");
        let v = match *last {
            Some((s, v)) if s == step => v,
            _ => {
                let v = self.evaluate(sim, c)?;
                *last = Some((step, v));
                v
            }
        };
        Ok(v[k])
    }
}

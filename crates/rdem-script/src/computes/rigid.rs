//! `compute ID group multisphere property P` (also spelled `rigid`) and
//! `compute ID group multisphere/single id N property P`: a property of each rigid clump
//! of `fix multisphere`, as LIGGGHTS 3.8's `compute_rigid` gives it. `multisphere` is a
//! local vector (one value) or array (several), one row per body in tag order, for
//! `dump local`; `multisphere/single` is a global scalar or vector of the body with tag
//! N, for thermo and variables (0 while no such body exists). The group is ignored, as in
//! LIGGGHTS. Every rank holds every clump: on several ranks the first gives the rows.
//!
//! The properties and their widths: `xcm` 3 (the centre of mass, wrapped into the
//! periodic box), `vcm` 3 (under Lees–Edwards shear both as the box holds the body,
//! [`rdem::World::body_in_box`]), `fcm` 3 (the total force of the last step, gravity included),
//! `torque` 3 (about the centre of mass), `quat` 4 (w, x, y, z: body frame to space
//! frame), `angmom` 3, `omega` 3, `density` 1, `atomtype` 1, `clumptype` 1 (the
//! template's `type`), `id_multisphere` 1, `masstotal` 1, `inertia` 3 (the principal
//! moments), `ex_space`, `ey_space`, `ez_space` 3 each (the principal axes in the space
//! frame). Names and values as LIGGGHTS 3.8 writes them, checked against its `dump local`
//! of three dumbbells in `crates/rdem-script/tests/multisphere.rs`.

use crate::error::Error;
use glam::DVec3;

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;
use rdem::multisphere::Multisphere;
use rdem::World;

/// The registry row of `multisphere`.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "multisphere",
    parse_all,
    "a property of every clump of `fix multisphere`, one row each (`dump local`)",
);

/// The registry row of `rigid`, the same compute.
pub(super) const ROW_RIGID: ComputeRow =
    ComputeRow::runs("rigid", parse_all, "the same as `compute multisphere`");

/// The registry row of `multisphere/single`.
pub(super) const ROW_SINGLE: ComputeRow = ComputeRow::runs(
    "multisphere/single",
    parse_single,
    "a property of one clump of `fix multisphere` (`id N`), a global scalar or vector",
);

/// The properties and their widths, in the manual's order.
const PROPERTIES: [(&str, usize); 16] = [
    ("xcm", 3),
    ("vcm", 3),
    ("fcm", 3),
    ("torque", 3),
    ("quat", 4),
    ("angmom", 3),
    ("omega", 3),
    ("density", 1),
    ("atomtype", 1),
    ("clumptype", 1),
    ("id_multisphere", 1),
    ("masstotal", 1),
    ("inertia", 3),
    ("ex_space", 3),
    ("ey_space", 3),
    ("ez_space", 3),
];

const NAMES: [&str; 16] = {
    let mut n = [""; 16];
    let mut k = 0;
    while k < 16 {
        n[k] = PROPERTIES[k].0;
        k += 1;
    }
    n
};

/// `property P`: the index of P in [`PROPERTIES`].
fn property(a: &mut Args) -> CmdResult<usize> {
    a.keyword("keyword", &["property"])?;
    let p = a.keyword("multisphere property", &NAMES)?;
    Ok(NAMES.iter().position(|&n| n == p).expect("a valid name"))
}

fn parse_all(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let prop = property(a)?;
    a.done()?;
    Ok(Box::new(BodyProperty { prop, single: None }))
}

fn parse_single(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    a.keyword("keyword", &["id"])?;
    let tag = a.count("multisphere id")?;
    let prop = property(a)?;
    a.done()?;
    Ok(Box::new(BodyProperty {
        prop,
        single: Some(tag),
    }))
}

/// One property of every body, or of the body with tag `single`.
#[derive(Debug)]
pub struct BodyProperty {
    /// Index in [`PROPERTIES`].
    prop: usize,
    /// `multisphere/single`: the body's tag.
    single: Option<u64>,
}

impl BodyProperty {
    fn width(&self) -> usize {
        PROPERTIES[self.prop].1
    }

    /// The values of body `k` of `ms` (the first [`BodyProperty::width`] of them count).
    fn values(&self, w: &World, ms: &Multisphere, k: usize) -> [f64; 4] {
        let b = &ms.bodies[k];
        let info = &ms.info[k];
        let v3 = |v: DVec3| [v.x, v.y, v.z, 0.0];
        let one = |x: f64| [x, 0.0, 0.0, 0.0];
        match PROPERTIES[self.prop].0 {
            "xcm" => v3(w.body_in_box(k).map_or(b.x, |(x, _)| x)),
            "vcm" => v3(w.body_in_box(k).map_or(b.v, |(_, v)| v)),
            "fcm" => v3(b.force),
            "torque" => v3(b.torque),
            "quat" => [b.q.w, b.q.x, b.q.y, b.q.z],
            "angmom" => v3(b.angmom),
            "omega" => v3(b.omega()),
            "density" => one(info.density),
            "atomtype" => one(info.atom_type as f64),
            "clumptype" => one(info.clump_type as f64),
            "id_multisphere" => one(ms.tags[k] as f64),
            "masstotal" => one(b.mass),
            "inertia" => v3(b.moments),
            "ex_space" => v3(b.q * DVec3::X),
            "ey_space" => v3(b.q * DVec3::Y),
            "ez_space" => v3(b.q * DVec3::Z),
            other => unreachable!("property {other} is in PROPERTIES"),
        }
    }
}

impl ScriptCompute for BodyProperty {
    fn shape(&self) -> Shape {
        match (self.single, self.width()) {
            (Some(_), 1) => Shape::scalar(),
            (Some(_), n) => Shape::vector(n),
            (None, _) => Shape::default(),
        }
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let id = &c.id;
        let Some(tag) = self.single else {
            return Err(format!(
                "compute {id} gives local values (one row per clump): use it in dump local, \
                 or compute multisphere/single for one clump"
            )
            .into());
        };
        let n = self.width();
        let j = match (idx, n) {
            (None, 1) => 0,
            (Some(k), n) if k >= 1 && k <= n && n > 1 => k - 1,
            (None, n) => {
                return Err(format!("compute {id} gives a vector of {n}: use c_{id}[i]").into())
            }
            (Some(k), 1) => return Err(format!("c_{id}[{k}]: compute {id} gives a scalar").into()),
            (Some(k), n) => {
                return Err(format!("c_{id}[{k}]: compute {id} gives {n} values").into())
            }
        };
        let w = super::world(sim)?;
        let Some(ms) = &w.multisphere else {
            return Ok(0.0);
        };
        Ok(ms
            .body_of(tag as f64)
            .map_or(0.0, |k| self.values(w, ms, k)[j]))
    }

    fn local_cols(&self) -> Option<usize> {
        self.single.is_none().then(|| self.width())
    }

    fn local(&self, sim: &Sim, c: &ComputeHead) -> Result<Vec<f64>, Error> {
        if self.single.is_some() {
            return Err(format!("compute {} does not compute local values", c.id).into());
        }
        let w = super::world(sim)?;
        // Every rank holds every clump: the first rank gives the rows.
        let Some(ms) = w.multisphere.as_ref().filter(|_| w.comm.rank() == 0) else {
            return Ok(Vec::new());
        };
        let n = self.width();
        let mut out = Vec::with_capacity(n * ms.bodies.len());
        for k in 0..ms.bodies.len() {
            out.extend_from_slice(&self.values(w, ms, k)[..n]);
        }
        Ok(out)
    }
}

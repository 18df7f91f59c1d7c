//! `compute ID group property/local attribute ...` with the bond attributes of
//! LIGGGHTS_Flexible_Fibers: one row per bond of `bond_style gran` (both spheres in the
//! group), the columns in the order given:
//!
//! - `batom1`, `batom2`: the two tags (the lower first), `btype`: the bond type;
//! - `batom1x` … `batom2z`: the two centres (the second as the image bonded);
//! - `bforceX/Y/Z`: the bond's elastic force on the first sphere (without damping, as
//!   the fork reports it);
//! - `btorqueX/Y/Z`: its elastic twisting and bending torque on the first sphere
//!   (without damping, and without the lever arm of the shear force);
//! - `beqdist`: the bond's length at its first evaluation;
//! - `bbondbroken`: 1 for a bond broken since the last re-neighboring (it is listed
//!   until then, as `numbonds` counts it).
//!
//! The values are those of the last force evaluation, as in the fork. The pair
//! attributes (`natom1`, `patom1`, ...) stop with an error, as LIGGGHTS 3.8 stops with
//! `pair_style gran` ("Pair style does not support compute property/local", checked).

use crate::error::Error;

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "property/local",
    parse,
    "the bonds of `bond_style gran`: `batom1 batom2 btype batom1x batom1y batom1z batom2x batom2y batom2z bforceX bforceY bforceZ btorqueX btorqueY btorqueZ beqdist bbondbroken` (`dump local`)",
)
.notes("the pair attributes (`natom1`, `patom1`, `ntype1`, ...) stop with an error, as in LIGGGHTS 3.8, whose `pair_style gran` does not support them (checked)");

/// The bond attributes.
const ATTRIBUTES: [&str; 17] = [
    "batom1",
    "batom2",
    "btype",
    "batom1x",
    "batom1y",
    "batom1z",
    "batom2x",
    "batom2y",
    "batom2z",
    "bforceX",
    "bforceY",
    "bforceZ",
    "btorqueX",
    "btorqueY",
    "btorqueZ",
    "beqdist",
    "bbondbroken",
];

/// The compute: the attributes, as indices into [`ATTRIBUTES`].
#[derive(Debug)]
pub struct PropertyLocal {
    cols: Vec<usize>,
}

fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let mut cols = Vec::new();
    while !a.is_done() {
        let k = a.pos();
        let w = a.word("attribute")?;
        match ATTRIBUTES.iter().position(|x| *x == w) {
            Some(c) => cols.push(c),
            None => {
                let pair = [
                    "natom1", "natom2", "ntype1", "ntype2", "patom1", "patom2", "ptype1", "ptype2",
                ];
                let help = if pair.contains(&w) {
                    "the pair attributes are not supported: LIGGGHTS 3.8 stops here too \
                     (\"Pair style does not support compute property/local\"); for the pairs \
                     in contact use compute pair/gran/local; rdem has the bond attributes"
                        .to_string()
                } else {
                    crate::args::suggest(w, &ATTRIBUTES)
                };
                return Err(a.error_at(
                    k,
                    format!("property/local: unknown attribute '{w}'"),
                    Some(help),
                ));
            }
        }
    }
    if cols.is_empty() {
        return Err(a.error_cmd(
            "compute property/local needs attributes",
            Some(ATTRIBUTES.join(" ")),
        ));
    }
    if sim.setup.bond_gran.is_none() {
        return Err(a.error_cmd(
            "compute property/local with bond attributes needs an atom style with bonds",
            Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M".into()),
        ));
    }
    Ok(Box::new(PropertyLocal { cols }))
}

impl ScriptCompute for PropertyLocal {
    fn shape(&self) -> Shape {
        Shape::default()
    }

    fn local_cols(&self) -> Option<usize> {
        Some(self.cols.len())
    }

    fn local(&self, sim: &Sim, c: &ComputeHead) -> Result<Vec<f64>, Error> {
        let w = super::world(sim)?;
        let Some(bonds) = &w.bonds else {
            return Ok(Vec::new());
        };
        let rows = bonds.local_rows(&w.particles);
        let mut out = Vec::with_capacity(rows.len() * self.cols.len());
        for r in rows.iter().filter(|r| r.mask1 & r.mask2 & c.groupbit != 0) {
            for &k in &self.cols {
                out.push(match k {
                    0 => r.atom1 as f64,
                    1 => r.atom2 as f64,
                    // The fork negates a separating bond's type.
                    2 if r.separating => -f64::from(r.btype),
                    2 => f64::from(r.btype),
                    3..=5 => r.x1[k - 3],
                    6..=8 => r.x2[k - 6],
                    9..=11 => r.force[k - 9],
                    12..=14 => r.torque[k - 12],
                    15 => r.len0,
                    _ => f64::from(u8::from(r.broken)),
                });
            }
        }
        Ok(out)
    }
}

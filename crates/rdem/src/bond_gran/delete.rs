//! `delete_bonds`: bonds turned off, on again, or removed.
//!
//! A turned-off bond keeps its slot with its type negated: it exerts no force, is
//! counted by `numbonds` and keeps its spheres' contact off under
//! `disableNormalContact 1`, until `undo` turns it on again or `remove` drops it (every
//! turned-off bond, selected now or before, as LAMMPS' `delete_bonds` does).
//! `compute property/local` leaves it out: LIGGGHTS-PFM lists it, with its type
//! negative and the force of the bond listed before it, and only where its partner is
//! on the same rank or a ghost there.

use super::{broken, keep_slots, GranBonds, BROKEN, FORCE, SEPARATING, SLOT, TAG, TORQUE, TYPE};
use crate::comm::Comm;
use crate::error::{Error, Result};
use crate::particles::{Particles, Tag};

/// Which bonds `delete_bonds` acts on, besides the group test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BondSelect {
    /// `multi`: every bond.
    Multi,
    /// `atom T`: bonds with a sphere of atom type T.
    AtomType(u32),
    /// `bond T`: bonds of type T; type 0 selects the broken bonds not yet dropped.
    BondType(u32),
    /// `stats`: none (the counts are reported).
    Stats,
}

/// A `delete_bonds` command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DeleteBonds {
    /// The selection.
    pub select: BondSelect,
    /// The group's bit: both spheres in it (one of them with `any`).
    pub groupbit: u32,
    /// `any`.
    pub any: bool,
    /// `undo`: turn selected bonds on instead of off.
    pub undo: bool,
    /// `remove`: afterwards drop every turned-off bond.
    pub remove: bool,
}

/// Bonds after a `delete_bonds`, each counted once.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BondTally {
    /// All bonds.
    pub total: u64,
    /// Turned on.
    pub on: u64,
    /// Turned off.
    pub off: u64,
}

impl GranBonds {
    /// Applies `d` to the bonds of the owned particles of `p`. Each sphere of a bond
    /// decides from both spheres' group masks and types (those of partners on other
    /// ranks are gathered), so the two copies of a bond stay alike. Returns the global
    /// counts afterwards.
    pub fn delete(
        &mut self,
        p: &mut Particles,
        comm: &dyn Comm,
        d: &DeleteBonds,
    ) -> Result<BondTally> {
        let Some(id) = self.prop else {
            return Ok(BondTally::default());
        };
        let (m, nl, w) = (self.per_atom, p.nlocal(), self.width());
        // Tag, mask and type of every sphere that holds a bond, on every rank.
        let mut mine = Vec::new();
        for i in 0..nl {
            if Self::count(&p.props[id.0].data[i * w..(i + 1) * w]) > 0 {
                mine.extend([p.tag[i] as f64, p.mask[i] as f64, p.ty[i] as f64]);
            }
        }
        let all = comm.all_gather(&mine);
        let info: std::collections::HashMap<Tag, (u32, u32)> = all
            .chunks_exact(3)
            .map(|c| (c[0] as Tag, (c[1] as u32, c[2] as u32)))
            .collect();
        let mut tally = BondTally::default();
        for i in 0..nl {
            let (ta, ma, ya) = (p.tag[i], p.mask[i], p.ty[i]);
            let row = &mut p.props[id.0].data[i * w..(i + 1) * w];
            for s in 0..m {
                let h = &mut row[s * SLOT..(s + 1) * SLOT];
                if h[TYPE] == 0.0 {
                    continue;
                }
                let tb = h[TAG] as Tag;
                let Some(&(mb, yb)) = info.get(&tb) else {
                    return Err(Error::Invalid {
                        what: "delete_bonds",
                        reason: format!(
                            "particle {ta} is bonded to particle {tb}, which does not exist"
                        ),
                    });
                };
                let (ina, inb) = (ma & d.groupbit != 0, mb & d.groupbit != 0);
                let grouped = if d.any { ina || inb } else { ina && inb };
                let t = h[TYPE];
                let chosen = grouped
                    && match d.select {
                        BondSelect::Multi => true,
                        BondSelect::AtomType(k) => ya == k || yb == k,
                        BondSelect::BondType(0) => broken(h[BROKEN]) || h[BROKEN] == SEPARATING,
                        BondSelect::BondType(k) => t.abs() == f64::from(k),
                        BondSelect::Stats => false,
                    };
                if chosen && d.undo {
                    h[TYPE] = t.abs();
                } else if chosen {
                    h[TYPE] = -t.abs();
                    // It exerts nothing from now on.
                    h[FORCE..TORQUE + 3].fill(0.0);
                }
            }
            if d.remove {
                keep_slots(row, |h| h[TYPE] > 0.0);
            }
            for h in row.chunks_exact(SLOT) {
                if h[TYPE] != 0.0 && ta < h[TAG] as Tag {
                    tally.total += 1;
                    if h[TYPE] > 0.0 {
                        tally.on += 1;
                    } else {
                        tally.off += 1;
                    }
                }
            }
        }
        // The slots moved: partners are found again at the next re-neighboring.
        self.links.clear();
        Ok(BondTally {
            total: comm.sum_count(tally.total),
            on: comm.sum_count(tally.on),
            off: comm.sum_count(tally.off),
        })
    }
}

//! The `neighbor` and `neigh_modify` settings, and the pairs `neigh_modify exclude`
//! leaves out.

use crate::error::{check, Error, Result};
use crate::particles::Particles;

/// `neighbor` and `neigh_modify` settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeighborSettings {
    /// Skin distance added to r_i + r_j.
    pub skin: f64,
    /// Never rebuild until this many steps after the last build.
    pub delay: u64,
    /// Consider rebuilding only every this many steps.
    pub every: u64,
    /// Rebuild only if some particle moved more than skin/2 (`check yes`).
    pub check: bool,
    /// `neigh_modify contact_distance_factor f` (>= 1): pairs are listed up to
    /// f·(r_i + r_j) + skin, as LIGGGHTS lists them. The models may ask for more
    /// ([`crate::Neighbor::contact_factor`]: the larger one counts).
    pub contact_distance_factor: f64,
}

impl Default for NeighborSettings {
    /// LIGGGHTS defaults: `delay 10 every 1 check yes`; the skin must be set by the user
    /// (0.001 here as a placeholder for SI granular runs).
    fn default() -> Self {
        Self {
            skin: 0.001,
            delay: 10,
            every: 1,
            check: true,
            contact_distance_factor: 1.0,
        }
    }
}

impl NeighborSettings {
    /// Checks the settings as LIGGGHTS does for `neighbor` and `neigh_modify`: the skin
    /// must be finite and >= 0 (a NaN skin would silently list no pair at all, a negative
    /// one would miss contacts), `every` at least 1, and `delay` 0 or a multiple of
    /// `every`.
    pub fn validate(&self) -> Result<()> {
        check("neighbor skin", self.skin, self.skin >= 0.0, "must be >= 0")?;
        check(
            "neigh_modify contact_distance_factor",
            self.contact_distance_factor,
            self.contact_distance_factor >= 1.0,
            "must be >= 1",
        )?;
        if self.every == 0 {
            return Err(Error::InvalidParameter {
                what: "neigh_modify every",
                value: 0.0,
                reason: "must be >= 1",
            });
        }
        if self.delay > 0 && self.delay % self.every != 0 {
            return Err(Error::Invalid {
                what: "neigh_modify delay",
                reason: format!(
                    "{} must be 0 or a multiple of every ({})",
                    self.delay, self.every
                ),
            });
        }
        Ok(())
    }
}

/// Pairs that `neigh_modify exclude` leaves out of the neighbor list, so that they never
/// interact (LAMMPS' and LIGGGHTS' exclusion lists): by type pair and by group pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Exclusions {
    /// `exclude type M N`: a pair of types M and N (either way round).
    pub types: Vec<(u32, u32)>,
    /// `exclude group G1 G2` as group bit masks: one particle in G1, the other in G2.
    pub groups: Vec<(u32, u32)>,
    /// Pairs whose values of this per-particle property are equal and not zero: the
    /// spheres of one rigid clump ([`crate::multisphere`]; LIGGGHTS' `fix multisphere`
    /// excludes them so).
    pub same_body: Option<crate::particles::PropId>,
    /// `exclude molecule G` as group bit masks: both particles in G with the same
    /// molecule ID (LAMMPS' rule: ID 0 included).
    pub molecule_groups: Vec<u32>,
    /// The per-particle molecule IDs ([`crate::bond_gran::MOLECULE`]), set when the atom
    /// style has them.
    pub molecule: Option<crate::particles::PropId>,
}

impl Exclusions {
    /// True when nothing is excluded.
    pub fn is_empty(&self) -> bool {
        self.types.is_empty()
            && self.groups.is_empty()
            && self.same_body.is_none()
            && self.molecule_groups.is_empty()
    }

    /// True when the pair (i, j) is excluded.
    pub fn excludes(&self, p: &Particles, i: usize, j: usize) -> bool {
        if let Some(id) = self.same_body {
            let b = &p.props[id.0].data;
            if b[i] != 0.0 && b[i] == b[j] {
                return true;
            }
        }
        let (ti, tj) = (p.ty[i], p.ty[j]);
        let (mi, mj) = (p.mask[i], p.mask[j]);
        if let Some(id) = self.molecule {
            let m = &p.props[id.0].data;
            if m[i] == m[j]
                && self
                    .molecule_groups
                    .iter()
                    .any(|&g| mi & g != 0 && mj & g != 0)
            {
                return true;
            }
        }
        self.types
            .iter()
            .any(|&(a, b)| (ti == a && tj == b) || (ti == b && tj == a))
            || self
                .groups
                .iter()
                .any(|&(a, b)| (mi & a != 0 && mj & b != 0) || (mi & b != 0 && mj & a != 0))
    }
}

//! The [`Wall`] trait: what the engine's stages ask of every granular wall, primitive or
//! mesh. The stages (set-up, candidate lists, the post-force pass, bond counts, heat,
//! multicontact) go through it, so that a wall feature is one method here and its two
//! implementations, not an `if let` pair at each stage.
//!
//! Geometry queries that differ in kind stay with each type: the lost-particle report's
//! ray tracing ([`crate::lost`]) and the heat flow through a wall contact
//! ([`crate::heat`]).

use glam::DVec3;

use crate::bond::BondEvents;
use crate::contact::{ContactModel, Materials};
use crate::error::Result;
use crate::fix::FixKind;
use crate::multicontact::MultiContact;
use crate::par::View;
use crate::particles::{Particles, PropId, SparseId};

use super::{MeshSurface, MeshWall, PrimitiveWall, Touches};

/// The multicontact store a wall reads, with the number of the wall in it.
pub type MultiSlot = Option<(std::sync::Arc<MultiContact>, u64)>;

/// A granular wall (`fix wall/gran`), primitive or mesh. `meshes` is the world's list of
/// mesh surfaces; a primitive wall ignores it.
pub trait Wall {
    /// The contact model.
    fn model(&self) -> &ContactModel;

    /// Where `surface multicontact` puts its store ([`crate::multicontact`]).
    fn multicontact_slot(&mut self) -> &mut MultiSlot;

    /// Tells the wall the current step (bonds are created at a given step).
    fn set_step(&mut self, step: u64);

    /// Set-up: the coefficient table and the history property.
    fn setup(
        &mut self,
        materials: &Materials,
        meshes: &[MeshSurface],
        p: &mut Particles,
    ) -> Result<()>;

    /// Whether some surface of the wall has a fixed temperature (heat conduction).
    fn heats(&self, meshes: &[MeshSurface]) -> bool;

    /// The candidate lists of the group `groupbit` (particles within the skin).
    fn build_candidates(
        &mut self,
        meshes: &[MeshSurface],
        p: &mut Particles,
        groupbit: u32,
        skin: f64,
    );

    /// The history property, if the model keeps history.
    fn history_prop(&self) -> Option<SparseId>;

    /// The particles that hold rows of the history property, ascending.
    fn history_rows(&self) -> &[u32];

    /// The `store_force` property, if the wall writes one.
    fn store_prop(&self) -> Option<PropId>;

    /// The offset of the bond flag in a history row (with wall bonds).
    fn bond_flag_at(&self) -> Option<usize>;

    /// Wall bonds created and broken so far.
    fn bond_events(&self) -> &BondEvents;

    /// Intact wall bonds of the owned particles.
    fn count_bonds(&self, p: &Particles) -> u64;

    /// The forces and torques on the particles `lo..lo + f.len()`: `f` and `torque`
    /// start at particle `lo`, `hist` at the history row of the first of them (see
    /// [`super::chunk_rows`]).
    #[allow(clippy::too_many_arguments)]
    fn apply_range(
        &self,
        meshes: &[MeshSurface],
        view: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        hist: &mut [f64],
        touches: Touches,
        dt: f64,
        update: bool,
    );
}

impl FixKind {
    /// The fix as a granular wall, if it is one.
    pub fn as_wall(&self) -> Option<&dyn Wall> {
        match self {
            FixKind::WallGran(w) => Some(&**w),
            FixKind::MeshWall(w) => Some(&**w),
            _ => None,
        }
    }

    /// The fix as a granular wall, mutably.
    pub fn as_wall_mut(&mut self) -> Option<&mut dyn Wall> {
        match self {
            FixKind::WallGran(w) => Some(&mut **w),
            FixKind::MeshWall(w) => Some(&mut **w),
            _ => None,
        }
    }
}

impl Wall for PrimitiveWall {
    fn model(&self) -> &ContactModel {
        &self.model
    }

    fn multicontact_slot(&mut self) -> &mut MultiSlot {
        &mut self.multicontact
    }

    fn set_step(&mut self, step: u64) {
        self.step = step;
    }

    fn setup(&mut self, materials: &Materials, _: &[MeshSurface], p: &mut Particles) -> Result<()> {
        PrimitiveWall::setup(self, materials, p)
    }

    fn heats(&self, _: &[MeshSurface]) -> bool {
        self.temperature.is_some()
    }

    fn build_candidates(&mut self, _: &[MeshSurface], p: &mut Particles, groupbit: u32, skin: f64) {
        PrimitiveWall::build_candidates(self, p, groupbit, skin);
    }

    fn history_prop(&self) -> Option<SparseId> {
        PrimitiveWall::history_prop(self)
    }

    fn history_rows(&self) -> &[u32] {
        self.candidates()
    }

    fn store_prop(&self) -> Option<PropId> {
        PrimitiveWall::store_prop(self)
    }

    fn bond_flag_at(&self) -> Option<usize> {
        PrimitiveWall::bond_flag_at(self)
    }

    fn bond_events(&self) -> &BondEvents {
        &self.bond_events
    }

    fn count_bonds(&self, p: &Particles) -> u64 {
        PrimitiveWall::count_bonds(self, p)
    }

    fn apply_range(
        &self,
        _: &[MeshSurface],
        view: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        hist: &mut [f64],
        touches: Touches,
        dt: f64,
        update: bool,
    ) {
        PrimitiveWall::apply_range(self, view, lo, f, torque, hist, touches, dt, update);
    }
}

impl Wall for MeshWall {
    fn model(&self) -> &ContactModel {
        &self.model
    }

    fn multicontact_slot(&mut self) -> &mut MultiSlot {
        &mut self.multicontact
    }

    fn set_step(&mut self, step: u64) {
        self.step = step;
    }

    fn setup(
        &mut self,
        materials: &Materials,
        meshes: &[MeshSurface],
        p: &mut Particles,
    ) -> Result<()> {
        MeshWall::setup(self, materials, meshes, p)
    }

    fn heats(&self, meshes: &[MeshSurface]) -> bool {
        self.meshes
            .iter()
            .any(|&m| meshes.get(m).is_some_and(|m| m.temperature.is_some()))
    }

    fn build_candidates(
        &mut self,
        meshes: &[MeshSurface],
        p: &mut Particles,
        groupbit: u32,
        skin: f64,
    ) {
        MeshWall::build_candidates(self, meshes, p, groupbit, skin);
    }

    fn history_prop(&self) -> Option<SparseId> {
        MeshWall::history_prop(self)
    }

    fn history_rows(&self) -> &[u32] {
        self.rows()
    }

    fn store_prop(&self) -> Option<PropId> {
        MeshWall::store_prop(self)
    }

    fn bond_flag_at(&self) -> Option<usize> {
        MeshWall::bond_flag_at(self)
    }

    fn bond_events(&self) -> &BondEvents {
        &self.bond_events
    }

    fn count_bonds(&self, p: &Particles) -> u64 {
        MeshWall::count_bonds(self, p)
    }

    fn apply_range(
        &self,
        meshes: &[MeshSurface],
        view: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        hist: &mut [f64],
        touches: Touches,
        dt: f64,
        update: bool,
    ) {
        MeshWall::apply_range(self, meshes, view, lo, f, torque, hist, touches, dt, update);
    }
}

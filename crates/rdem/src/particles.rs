//! Particle storage (seed 002): struct of arrays, owned ("local") particles first, then
//! ghost copies. Every per-particle array, including the named properties that fixes add,
//! has the same length, grows, is permuted by the spatial sort and is compacted when
//! particles are removed, so data added by a fix always moves with its particle.

use glam::DVec3;

use crate::error::{check, Error, Result};

mod columns;
mod image;
mod sparse;
use columns::{particle_columns, Column, Wire};
pub use image::Image;
pub use sparse::{SparseId, SparseProperty};

/// Global particle identifier. 0 means "not yet assigned".
pub type Tag = u64;

/// Moment of inertia factor of a solid sphere: I = 0.4 m r².
pub const INERTIA_SPHERE: f64 = 0.4;

/// Handle of a named per-particle property.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PropId(pub usize);

/// A named per-particle property: `width` f64 values per particle.
#[derive(Debug, Clone, PartialEq)]
pub struct Property {
    /// Name, unique in the container.
    pub name: String,
    /// Values per particle.
    pub width: usize,
    /// Value given to new particles.
    pub default: Vec<f64>,
    /// `width * len` values, particle-major.
    pub data: Vec<f64>,
    /// Whether forward communication refreshes ghosts' values every step (LIGGGHTS'
    /// `comm_ghost_value yes`), for values that change during a run and that pair
    /// computations read on ghosts (a temperature, a liquid content). Ghosts always get
    /// every property's values when they are made.
    pub forward: bool,
}

impl Property {
    /// Values of particle `i`.
    pub fn get(&self, i: usize) -> &[f64] {
        &self.data[i * self.width..(i + 1) * self.width]
    }
    /// Mutable values of particle `i`.
    pub fn get_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.data[i * self.width..(i + 1) * self.width]
    }
}

/// Everything needed to create one particle.
#[derive(Debug, Clone, PartialEq)]
pub struct NewParticle {
    /// Tag, or 0 to have one assigned by [`Particles::extend_tags`].
    pub tag: Tag,
    /// Particle type, 1-based as in LIGGGHTS.
    pub ty: u32,
    /// Group bit mask (bit 0 is group `all` and is always set).
    pub mask: u32,
    /// Position.
    pub x: DVec3,
    /// Velocity.
    pub v: DVec3,
    /// Angular velocity.
    pub omega: DVec3,
    /// Radius (> 0).
    pub radius: f64,
    /// Density (> 0); the mass follows as density · 4/3 π r³.
    pub density: f64,
}

impl NewParticle {
    /// A particle of type 1 at rest, in group `all`.
    pub fn at(x: DVec3, radius: f64, density: f64) -> Self {
        Self {
            tag: 0,
            ty: 1,
            mask: 1,
            x,
            v: DVec3::ZERO,
            omega: DVec3::ZERO,
            radius,
            density,
        }
    }
    /// Sets the velocity.
    pub fn with_v(mut self, v: DVec3) -> Self {
        self.v = v;
        self
    }
    /// Sets the angular velocity.
    pub fn with_omega(mut self, omega: DVec3) -> Self {
        self.omega = omega;
        self
    }
    /// Sets the type.
    pub fn with_type(mut self, ty: u32) -> Self {
        self.ty = ty;
        self
    }
    /// Sets the tag.
    pub fn with_tag(mut self, tag: Tag) -> Self {
        self.tag = tag;
        self
    }
}

/// Mass of a sphere of `density` and `radius` (the one formula every particle's mass
/// comes from, so that masses computed apart agree bit for bit).
pub fn sphere_mass(density: f64, radius: f64) -> f64 {
    density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3)
}

/// `origin` of a ghost copied from another rank: this plus the owner's rank.
pub const REMOTE_GHOST: usize = 1 << 60;

particle_columns! {
    /// Global identifiers.
    tag: Tag, wire, once;
    /// Types, 1-based.
    ty: u32, wire, once;
    /// Group membership bits.
    mask: u32, wire, once;
    /// Positions.
    x: DVec3, shifted, forward;
    /// Velocities.
    v: DVec3, wire, forward;
    /// Angular velocities.
    omega: DVec3, wire, forward;
    /// Forces.
    f: DVec3, local, once;
    /// Torques.
    torque: DVec3, local, once;
    /// Radii.
    radius: f64, wire, forward;
    /// Masses.
    rmass: f64, wire, forward;
    /// Densities.
    density: f64, wire, once;
    /// Periodic image counts, packed ([`Image`]).
    image: Image, wire, once;
}

/// Applies `new[i] = old[perm[i]]` in place, cycle by cycle with one temporary
/// (seed 002 eq. 9). `done` is scratch of length `perm.len()`.
fn permute_in_place<T: Copy>(data: &mut [T], perm: &[usize], done: &mut [bool]) {
    done.iter_mut().for_each(|d| *d = false);
    for start in 0..perm.len() {
        if done[start] || perm[start] == start {
            done[start] = true;
            continue;
        }
        let tmp = data[start];
        let mut i = start;
        loop {
            done[i] = true;
            let src = perm[i];
            if src == start {
                data[i] = tmp;
                break;
            }
            data[i] = data[src];
            i = src;
        }
    }
}

/// Same as [`permute_in_place`] for `width` values per particle.
fn permute_chunks_in_place(data: &mut [f64], width: usize, perm: &[usize], done: &mut [bool]) {
    if width == 1 {
        return permute_in_place(data, perm, done);
    }
    done.iter_mut().for_each(|d| *d = false);
    let mut tmp = vec![0.0; width];
    for start in 0..perm.len() {
        if done[start] || perm[start] == start {
            done[start] = true;
            continue;
        }
        tmp.copy_from_slice(&data[start * width..(start + 1) * width]);
        let mut i = start;
        loop {
            done[i] = true;
            let src = perm[i];
            if src == start {
                data[i * width..(i + 1) * width].copy_from_slice(&tmp);
                break;
            }
            data.copy_within(src * width..(src + 1) * width, i * width);
            i = src;
        }
    }
}

impl Particles {
    /// An empty container.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of owned particles.
    pub fn nlocal(&self) -> usize {
        self.nlocal
    }
    /// Number of ghosts.
    pub fn nghost(&self) -> usize {
        self.tag.len() - self.nlocal
    }
    /// Owned plus ghosts.
    pub fn len(&self) -> usize {
        self.tag.len()
    }
    /// True when there are no particles at all.
    pub fn is_empty(&self) -> bool {
        self.tag.is_empty()
    }

    /// Adds a named property with `width` values per particle, filled with `default`
    /// for existing and future particles. Adding an existing name with the same width
    /// returns the existing handle.
    pub fn add_property(&mut self, name: &str, width: usize, default: &[f64]) -> Result<PropId> {
        if name.is_empty() || width == 0 || default.len() != width {
            return Err(Error::Invalid {
                what: "per-particle property",
                reason: format!(
                    "'{name}' needs a name, width >= 1 and one default per component (width {width}, {} defaults)",
                    default.len()
                ),
            });
        }
        if self.sparse_property(name).is_some() {
            return Err(Error::Invalid {
                what: "per-particle property",
                reason: format!("'{name}' exists as a wall's contact history"),
            });
        }
        if let Some(id) = self.property(name) {
            if self.props[id.0].width == width {
                return Ok(id);
            }
            return Err(Error::Invalid {
                what: "per-particle property",
                reason: format!(
                    "'{name}' exists with width {}, not {width}",
                    self.props[id.0].width
                ),
            });
        }
        let n = self.len();
        let mut data = Vec::with_capacity(n * width);
        for _ in 0..n {
            data.extend_from_slice(default);
        }
        self.props.push(Property {
            name: name.to_string(),
            width,
            default: default.to_vec(),
            data,
            forward: false,
        });
        Ok(PropId(self.props.len() - 1))
    }

    /// Makes forward communication refresh ghosts' values of property `id` every step
    /// (see [`Property::forward`]); once set it stays set.
    pub fn set_forward(&mut self, id: PropId) {
        self.props[id.0].forward = true;
    }

    /// Values per particle in [`Particles::pack_forward`]: [`FORWARD_LEN`] plus the
    /// widths of the properties forwarded every step.
    pub fn forward_len(&self) -> usize {
        FORWARD_LEN
            + self
                .props
                .iter()
                .filter(|p| p.forward)
                .map(|p| p.width)
                .sum::<usize>()
    }

    /// The masses contacts use for their effective mass: [`Particles::mass_of_contact`]
    /// when clumps exist, else [`Particles::rmass`].
    pub fn contact_mass(&self) -> &[f64] {
        if self.mass_of_contact.is_empty() {
            &self.rmass
        } else {
            &self.mass_of_contact
        }
    }

    /// Handle of the property called `name`.
    pub fn property(&self, name: &str) -> Option<PropId> {
        if name.is_empty() {
            return None;
        }
        self.props.iter().position(|p| p.name == name).map(PropId)
    }

    /// Adds a sparse property ([`SparseProperty`]) with `width` values per particle, zero
    /// for every particle. Adding an existing name with the same width returns the
    /// existing handle; a dense property of that name and width (read from a restart
    /// file) becomes the sparse one, its non-zero values kept.
    pub fn add_sparse_property(&mut self, name: &str, width: usize) -> Result<SparseId> {
        let exists = |w: usize| Error::Invalid {
            what: "per-particle property",
            reason: format!("'{name}' exists with width {w}, not {width}"),
        };
        if let Some(id) = self.sparse_property(name) {
            return match self.sparse[id.0].width {
                w if w == width => Ok(id),
                w => Err(exists(w)),
            };
        }
        let n = self.nlocal;
        let mut prop = SparseProperty::new(name, width);
        match self.property(name) {
            Some(id) if self.props[id.0].width != width => {
                return Err(exists(self.props[id.0].width))
            }
            Some(id) => {
                let dense = &mut self.props[id.0];
                for i in 0..n {
                    prop.push(i, dense.get(i));
                }
                // Retired: no lookup finds it, and it holds no values (width 0).
                dense.name.clear();
                dense.width = 0;
                dense.default.clear();
                dense.data = Vec::new();
            }
            None => {}
        }
        self.sparse.push(prop);
        Ok(SparseId(self.sparse.len() - 1))
    }

    /// Handle of the sparse property called `name`.
    pub fn sparse_property(&self, name: &str) -> Option<SparseId> {
        if name.is_empty() {
            return None;
        }
        self.sparse
            .iter()
            .position(|p| p.name == name)
            .map(SparseId)
    }

    /// Retires the property called `name` (`unfix` of the fix that defined it): no lookup
    /// by name finds it any more, so the name can be defined afresh. Its values stay in
    /// place with width and handle unchanged, because other properties' handles are
    /// indices that engine fixes keep. Returns false if there was no such property.
    pub fn retire_property(&mut self, name: &str) -> bool {
        match self.property(name) {
            Some(id) => {
                self.props[id.0].name.clear();
                true
            }
            None => false,
        }
    }

    /// Validates and appends an owned particle; returns its index. Ghosts must be
    /// cleared first (see [`Particles::clear_ghosts`]).
    pub fn add_local(&mut self, p: &NewParticle) -> Result<usize> {
        check("radius", p.radius, p.radius > 0.0, "must be > 0")?;
        check("density", p.density, p.density > 0.0, "must be > 0")?;
        for (what, vec) in [
            ("position", p.x),
            ("velocity", p.v),
            ("angular velocity", p.omega),
        ] {
            if !vec.is_finite() {
                return Err(Error::Invalid {
                    what,
                    reason: format!("{vec} is not finite"),
                });
            }
        }
        if p.ty == 0 {
            return Err(Error::Invalid {
                what: "particle type",
                reason: "types start at 1".into(),
            });
        }
        debug_assert_eq!(self.nghost(), 0, "add_local with ghosts present");
        self.clear_ghosts();
        self.push_row(Row {
            tag: p.tag,
            ty: p.ty,
            mask: p.mask | 1,
            x: p.x,
            v: p.v,
            omega: p.omega,
            f: DVec3::ZERO,
            torque: DVec3::ZERO,
            radius: p.radius,
            rmass: sphere_mass(p.density, p.radius),
            density: p.density,
            image: Image::new([0; 3]),
        });
        let i = self.len() - 1;
        for prop in &mut self.props {
            prop.data.extend_from_slice(&prop.default);
        }
        self.nlocal += 1;
        Ok(i)
    }

    /// Appends a ghost copy of particle `src` displaced by `shift`; returns its index.
    /// Properties are copied too, so pair code may read them on ghosts.
    pub fn push_ghost(&mut self, src: usize, shift: DVec3) -> usize {
        let origin = self.origin(src);
        self.push_row(self.copied_row(src, shift));
        let i = self.len() - 1;
        self.ghost_origin.push(origin);
        for prop in &mut self.props {
            let w = prop.width;
            prop.data.extend_from_within(src * w..(src + 1) * w);
        }
        i
    }

    /// Number of `f64` values [`Particles::pack`] writes per particle.
    pub fn packed_len(&self) -> usize {
        PACK_FIXED
            + self.props.iter().map(|p| p.width).sum::<usize>()
            + self.sparse.iter().map(|p| p.width).sum::<usize>()
    }

    /// Appends particle `i` (every per-particle array except forces, named properties
    /// included) to `buf`, with its position displaced by `shift`, for migration or a
    /// ghost copy on another rank. Integers travel as `f64` (exact below 2^53).
    pub fn pack(&self, i: usize, shift: DVec3, buf: &mut Vec<f64>) {
        self.pack_columns(i, shift, buf);
        for prop in &self.props {
            buf.extend_from_slice(prop.get(i));
        }
        for prop in &self.sparse {
            buf.extend_from_slice(prop.get(i));
        }
    }

    /// Appends one particle packed by [`Particles::pack`] (on a rank with the same named
    /// properties) as an owned particle (`ghost_of: None`; ghosts must have been cleared)
    /// or as a ghost owned by rank `ghost_of`. Returns the values read.
    pub fn unpack(&mut self, buf: &[f64], ghost_of: Option<usize>) -> usize {
        debug_assert!(ghost_of.is_some() || self.nghost() == 0);
        self.push_row(Self::unpack_row(buf));
        let i = self.len() - 1;
        let mut k = PACK_FIXED;
        for prop in &mut self.props {
            prop.data.extend_from_slice(&buf[k..k + prop.width]);
            k += prop.width;
        }
        for prop in &mut self.sparse {
            // Ghosts hold no rows.
            if ghost_of.is_none() {
                prop.push(i, &buf[k..k + prop.width]);
            }
            k += prop.width;
        }
        match ghost_of {
            Some(rank) => self.ghost_origin.push(REMOTE_GHOST + rank),
            None => {
                debug_assert_eq!(i, self.nlocal, "an owned particle unpacked after ghosts");
                self.nlocal += 1;
            }
        }
        k
    }

    /// Appends what forward communication refreshes of particle `i` (position displaced
    /// by `shift`, velocity, angular velocity, radius, mass: [`FORWARD_LEN`] values; then
    /// the values of the forwarded properties: [`Particles::forward_len`] in all).
    pub fn pack_forward(&self, i: usize, shift: DVec3, buf: &mut Vec<f64>) {
        self.pack_forward_columns(i, shift, buf);
        for prop in self.props.iter().filter(|p| p.forward) {
            buf.extend_from_slice(prop.get(i));
        }
    }

    /// Sets ghost `g` from values packed by [`Particles::pack_forward`].
    pub fn unpack_forward(&mut self, g: usize, c: &[f64]) {
        self.unpack_forward_columns(g, c);
        let mut k = FORWARD_LEN;
        for prop in self.props.iter_mut().filter(|p| p.forward) {
            let w = prop.width;
            prop.get_mut(g).copy_from_slice(&c[k..k + w]);
            k += w;
        }
    }

    /// Refreshes ghost `g` from particle `i` of this process (a periodic image displaced
    /// by `shift`), as forward communication does across ranks.
    pub fn copy_forward(&mut self, g: usize, i: usize, shift: DVec3) {
        self.copy_forward_columns(g, i, shift);
        for prop in self.props.iter_mut().filter(|p| p.forward) {
            let w = prop.width;
            prop.data.copy_within(i * w..(i + 1) * w, g * w);
        }
    }

    /// The rank owning particle `i` when it is a ghost of another rank's particle (none
    /// for an owned particle or a copy of one of this rank's).
    pub fn remote_owner(&self, i: usize) -> Option<usize> {
        self.origin(i).checked_sub(REMOTE_GHOST)
    }

    /// The particle that particle `i` copies: itself for an owned particle; for a ghost,
    /// its owner's index (serial periodic images), the index of the particle it was
    /// copied from, or [`REMOTE_GHOST`] plus the owner's rank.
    #[inline]
    pub fn origin(&self, i: usize) -> usize {
        if i < self.nlocal {
            i
        } else {
            self.ghost_origin[i - self.nlocal]
        }
    }

    /// [`Particles::origin`] of every ghost, in ghost order (index `g - nlocal`).
    pub fn ghost_origins(&self) -> &[usize] {
        &self.ghost_origin
    }

    /// Drops all ghosts.
    pub fn clear_ghosts(&mut self) {
        let n = self.nlocal;
        for c in self.columns_mut() {
            c.truncate(n);
        }
        self.ghost_origin.clear();
        for prop in &mut self.props {
            prop.data.truncate(n * prop.width);
        }
    }

    /// Gives back the capacity of the per-particle arrays (ghosts included) beyond the
    /// current count. Arrays grown one particle at a time by doubling hold up to twice
    /// what they use: 5 % more at a million particles, 31 % more at 800,000.
    pub fn shrink_to_fit(&mut self) {
        for c in self.columns_mut() {
            c.shrink();
        }
        self.ghost_origin.shrink_to_fit();
        for prop in &mut self.props {
            prop.data.shrink_to_fit();
        }
        for prop in &mut self.sparse {
            prop.shrink_to_fit();
        }
    }

    /// Removes the owned particles for which `remove[i]` is true, keeping the order of
    /// the others. Ghosts are dropped. Returns how many were removed.
    pub fn remove_locals(&mut self, remove: &[bool]) -> usize {
        self.clear_ghosts();
        let n = self.nlocal;
        assert_eq!(remove.len(), n);
        let mut dst = 0;
        for (src, &gone) in remove.iter().enumerate() {
            if gone {
                continue;
            }
            if dst != src {
                for c in self.columns_mut() {
                    c.copy(src, dst);
                }
                for prop in &mut self.props {
                    let w = prop.width;
                    prop.data.copy_within(src * w..(src + 1) * w, dst * w);
                }
            }
            dst += 1;
        }
        for prop in &mut self.sparse {
            prop.remove(remove);
        }
        let removed = n - dst;
        self.nlocal = dst;
        self.clear_ghosts();
        removed
    }

    /// Reorders the owned particles: new index `i` holds what was at `perm[i]`. Applied to
    /// every per-particle array, named properties included. Ghosts are dropped.
    pub fn permute(&mut self, perm: &[usize]) {
        self.clear_ghosts();
        assert_eq!(perm.len(), self.nlocal);
        let mut done = vec![false; perm.len()];
        for c in self.columns_mut() {
            c.permute(perm, &mut done);
        }
        for prop in &mut self.props {
            permute_chunks_in_place(&mut prop.data, prop.width, perm, &mut done);
        }
        for prop in &mut self.sparse {
            prop.permute(perm);
        }
    }

    /// Smallest and largest tag among owned particles (`(0, 0)` when empty).
    pub fn tag_extent(&self) -> (Tag, Tag) {
        let tags = &self.tag[..self.nlocal];
        let min = tags.iter().copied().min().unwrap_or(0);
        let max = tags.iter().copied().max().unwrap_or(0);
        (min, max)
    }

    /// Number of owned particles without a tag.
    pub fn untagged(&self) -> usize {
        self.tag[..self.nlocal].iter().filter(|&&t| t == 0).count()
    }

    /// Seed 002 eq. (2): gives untagged owned particles the tags `first, first+1, ...` in
    /// storage order, where `first` is one more than the global maximum tag plus the
    /// untagged counts of lower ranks (the caller provides `first`; serially it is max+1).
    pub fn assign_tags_from(&mut self, first: Tag) {
        let mut next = first;
        for t in &mut self.tag[..self.nlocal] {
            if *t == 0 {
                *t = next;
                next += 1;
            }
        }
    }

    /// Serial form of tag extension: untagged particles get max+1, max+2, ...
    pub fn extend_tags(&mut self) {
        let (_, max) = self.tag_extent();
        self.assign_tags_from(max + 1);
    }

    /// Seed 002 eq. (3): tags are consecutive iff min = 1 and max = N. Also reports a
    /// tag used twice.
    pub fn check_tags_consecutive(&self) -> Result<()> {
        let n = self.nlocal;
        if n == 0 {
            return Ok(());
        }
        let (min, max) = self.tag_extent();
        if min != 1 || max != n as Tag {
            return Err(Error::TagsNotConsecutive { min, max, count: n });
        }
        let mut seen = vec![false; n + 1];
        for &t in &self.tag[..n] {
            if seen[t as usize] {
                return Err(Error::DuplicateTag(t));
            }
            seen[t as usize] = true;
        }
        Ok(())
    }

    /// Seed 002 eq. (10): every particle of one type has the same radius.
    pub fn check_radius_per_type(&self) -> Result<()> {
        // Keyed by type in a map, not indexed: a type number can be as large as u32::MAX.
        let mut first: std::collections::HashMap<u32, f64> = std::collections::HashMap::new();
        for i in 0..self.nlocal {
            let t = self.ty[i];
            let r = *first.entry(t).or_insert(self.radius[i]);
            if r != self.radius[i] {
                return Err(Error::InconsistentRadius {
                    ty: t,
                    r1: r,
                    r2: self.radius[i],
                });
            }
        }
        Ok(())
    }

    /// Seed 002 eq. (13): bytes held by the per-particle arrays of this process
    /// (allocated capacity, so it is what the process really holds).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.columns().iter().map(|c| c.bytes()).sum::<usize>()
            + self.ghost_origin.capacity() * size_of::<usize>()
            + self
                .props
                .iter()
                .map(|p| p.data.capacity() * size_of::<f64>())
                .sum::<usize>()
            + self
                .sparse
                .iter()
                .map(SparseProperty::memory_bytes)
                .sum::<usize>()
    }

    /// Moment of inertia of particle `i` (solid sphere).
    pub fn inertia(&self, i: usize) -> f64 {
        INERTIA_SPHERE * self.rmass[i] * self.radius[i] * self.radius[i]
    }

    /// Sets the radius of particle `i`, keeping its density (the mass follows).
    pub fn set_radius(&mut self, i: usize, radius: f64) -> Result<()> {
        check("radius", radius, radius > 0.0, "must be > 0")?;
        self.radius[i] = radius;
        self.rmass[i] = sphere_mass(self.density[i], radius);
        Ok(())
    }

    /// Index of the owned particle with tag `t` (linear search; for tests and set-up).
    pub fn find_tag(&self, t: Tag) -> Option<usize> {
        self.tag[..self.nlocal].iter().position(|&x| x == t)
    }

    /// Total kinetic energy (translation + rotation) of the owned particles.
    pub fn kinetic_energy(&self) -> (f64, f64) {
        let mut et = 0.0;
        let mut er = 0.0;
        for i in 0..self.nlocal {
            et += 0.5 * self.rmass[i] * self.v[i].length_squared();
            er += 0.5 * self.inertia(i) * self.omega[i].length_squared();
        }
        (et, er)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn three() -> Particles {
        let mut p = Particles::new();
        for k in 0..3 {
            p.add_local(&NewParticle::at(
                DVec3::new(k as f64, 0.0, 0.0),
                0.1 + 0.1 * k as f64,
                1000.0,
            ))
            .unwrap();
        }
        p
    }

    /// Owned particles are their own origin and have no remote owner; a periodic image
    /// names its owner, a ghost from another rank that rank; dropping the ghosts, a
    /// permutation and a removal keep this.
    #[test]
    fn origins_of_locals_and_ghosts() {
        let mut p = three();
        let image = p.push_ghost(2, DVec3::X);
        let image_of_image = p.push_ghost(image, DVec3::Y);
        let mut buf = Vec::new();
        p.pack(1, DVec3::ZERO, &mut buf);
        p.unpack(&buf, Some(5));
        let remote = p.len() - 1;
        assert_eq!((0..3).map(|i| p.origin(i)).collect::<Vec<_>>(), [0, 1, 2]);
        assert!((0..3).all(|i| p.remote_owner(i).is_none()));
        assert_eq!(p.origin(image), 2);
        assert_eq!(p.origin(image_of_image), 2);
        assert_eq!(p.remote_owner(image), None);
        assert_eq!(p.remote_owner(remote), Some(5));
        assert_eq!(p.ghost_origins(), [2, 2, REMOTE_GHOST + 5]);
        p.permute(&[2, 0, 1]);
        assert!(p.ghost_origins().is_empty());
        p.push_ghost(0, DVec3::X);
        p.remove_locals(&[false, true, false]);
        assert_eq!(p.len(), 2);
        assert!(p.ghost_origins().is_empty());
        assert_eq!((p.origin(0), p.origin(1)), (0, 1));
    }

    #[test]
    fn tags_extend_from_max() {
        let mut p = three();
        p.tag[1] = 7;
        p.extend_tags();
        assert_eq!(p.tag, vec![8, 7, 9]);
        assert!(matches!(
            p.check_tags_consecutive(),
            Err(Error::TagsNotConsecutive {
                min: 7,
                max: 9,
                count: 3
            })
        ));
        p.tag = vec![1, 2, 3];
        assert!(p.check_tags_consecutive().is_ok());
        p.tag = vec![1, 3, 3];
        assert!(p.check_tags_consecutive().is_err());
    }

    #[test]
    fn mass_from_density() {
        let p = three();
        let m = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.1f64.powi(3);
        assert!((p.rmass[0] - m).abs() < 1e-15 * m);
    }

    #[test]
    fn bad_particles_are_refused() {
        let mut p = Particles::new();
        assert!(p
            .add_local(&NewParticle::at(DVec3::ZERO, 0.0, 1.0))
            .is_err());
        assert!(p
            .add_local(&NewParticle::at(DVec3::ZERO, -1.0, 1.0))
            .is_err());
        assert!(p
            .add_local(&NewParticle::at(DVec3::ZERO, 1.0, 0.0))
            .is_err());
        assert!(p.add_local(&NewParticle::at(DVec3::NAN, 1.0, 1.0)).is_err());
        assert!(p
            .add_local(&NewParticle::at(DVec3::ZERO, 1.0, 1.0).with_type(0))
            .is_err());
        assert_eq!(p.nlocal(), 0);
    }

    #[test]
    fn permutation_moves_properties() {
        let mut p = three();
        let id = p.add_property("hist", 2, &[0.0, 0.0]).unwrap();
        for i in 0..3 {
            p.props[id.0]
                .get_mut(i)
                .copy_from_slice(&[i as f64, 10.0 * i as f64]);
        }
        p.extend_tags();
        p.permute(&[2, 0, 1]);
        assert_eq!(p.tag, vec![3, 1, 2]);
        assert_eq!(p.props[id.0].data, vec![2.0, 20.0, 0.0, 0.0, 1.0, 10.0]);
        assert_eq!(p.x[0].x, 2.0);
    }

    #[test]
    fn retired_properties_are_not_found_and_keep_handles() {
        let mut p = three();
        let a = p.add_property("a", 1, &[1.0]).unwrap();
        let b = p.add_property("b", 2, &[2.0, 3.0]).unwrap();
        assert!(p.retire_property("a"));
        assert!(!p.retire_property("a"));
        assert_eq!(p.property("a"), None);
        assert_eq!(p.property("b"), Some(b));
        assert_eq!(p.property(""), None);
        let a2 = p.add_property("a", 1, &[7.0]).unwrap();
        assert_ne!(a2, a);
        assert_eq!(p.props[a2.0].data, vec![7.0; 3]);
        assert_eq!(p.props[b.0].get(2), &[2.0, 3.0]);
        assert!(p.add_property("", 1, &[0.0]).is_err());
    }

    #[test]
    fn forwarded_properties_refresh_ghosts() {
        let mut p = three();
        let t = p.add_property("t", 1, &[1.0]).unwrap();
        let q = p.add_property("q", 2, &[2.0, 3.0]).unwrap();
        p.set_forward(q);
        assert_eq!(p.forward_len(), FORWARD_LEN + 2);
        let g = p.push_ghost(1, DVec3::ZERO);
        p.props[t.0].get_mut(1)[0] = 5.0;
        p.props[q.0].get_mut(1).copy_from_slice(&[6.0, 7.0]);
        // A copy on this process: only the forwarded property follows.
        p.copy_forward(g, 1, DVec3::X);
        assert_eq!(p.props[q.0].get(g), &[6.0, 7.0]);
        assert_eq!(p.props[t.0].get(g), &[1.0]);
        assert_eq!(p.x[g], p.x[1] + DVec3::X);
        // Across ranks: packed and unpacked.
        p.props[q.0].get_mut(1).copy_from_slice(&[8.0, 9.0]);
        let mut buf = Vec::new();
        p.pack_forward(1, DVec3::ZERO, &mut buf);
        assert_eq!(buf.len(), p.forward_len());
        p.unpack_forward(g, &buf);
        assert_eq!(p.props[q.0].get(g), &[8.0, 9.0]);
    }

    #[test]
    fn remove_keeps_order() {
        let mut p = three();
        p.extend_tags();
        let id = p.add_property("w", 1, &[5.0]).unwrap();
        p.props[id.0].data[2] = 9.0;
        assert_eq!(p.remove_locals(&[false, true, false]), 1);
        assert_eq!(p.tag, vec![1, 3]);
        assert_eq!(p.props[id.0].data, vec![5.0, 9.0]);
    }

    #[test]
    fn radius_consistency() {
        let mut p = three();
        assert!(p.check_radius_per_type().is_err());
        p.radius = vec![0.1; 3];
        assert!(p.check_radius_per_type().is_ok());
    }

    #[test]
    fn memory_is_reported() {
        let p = three();
        assert!(p.memory_bytes() >= 3 * (8 * 3 * 5 + 8 * 3));
    }
}

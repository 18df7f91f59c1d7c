//! The per-particle columns of [`super::Particles`], declared once in the table of
//! `particles.rs` ([`particle_columns!`]): the struct fields, a new particle's row, the
//! packed form sent to another rank, what forward communication refreshes, and the
//! operations that treat every column alike (truncate, compact, permute, memory) all
//! come from that one table. A new column is one row there.

use glam::DVec3;

use super::{Image, Tag};

/// What every column does alike, whatever its element type.
pub(super) trait Column {
    /// Keeps the first `n` values.
    fn truncate(&mut self, n: usize);
    /// Gives back unused capacity.
    fn shrink(&mut self);
    /// Copies the value at `src` to `dst`.
    fn copy(&mut self, src: usize, dst: usize);
    /// `new[i] = old[perm[i]]` for the first `perm.len()` values (`done`: scratch).
    fn permute(&mut self, perm: &[usize], done: &mut [bool]);
    /// Bytes held (capacity).
    fn bytes(&self) -> usize;
}

impl<T: Copy> Column for Vec<T> {
    fn truncate(&mut self, n: usize) {
        Vec::truncate(self, n);
    }
    fn shrink(&mut self) {
        self.shrink_to_fit();
    }
    fn copy(&mut self, src: usize, dst: usize) {
        self[dst] = self[src];
    }
    fn permute(&mut self, perm: &[usize], done: &mut [bool]) {
        super::permute_in_place(&mut self[..perm.len()], perm, done);
    }
    fn bytes(&self) -> usize {
        self.capacity() * std::mem::size_of::<T>()
    }
}

/// A column's value as `f64`s on the wire (integers are exact below 2^53).
pub(super) trait Wire: Sized {
    /// Values per particle.
    const WIDTH: usize;
    /// Appends the value.
    fn put(&self, buf: &mut Vec<f64>);
    /// Reads a value from the front of `buf`.
    fn take(buf: &[f64]) -> Self;
}

impl Wire for f64 {
    const WIDTH: usize = 1;
    fn put(&self, buf: &mut Vec<f64>) {
        buf.push(*self);
    }
    fn take(buf: &[f64]) -> Self {
        buf[0]
    }
}

impl Wire for u32 {
    const WIDTH: usize = 1;
    fn put(&self, buf: &mut Vec<f64>) {
        buf.push(*self as f64);
    }
    fn take(buf: &[f64]) -> Self {
        buf[0] as u32
    }
}

impl Wire for Tag {
    const WIDTH: usize = 1;
    fn put(&self, buf: &mut Vec<f64>) {
        buf.push(*self as f64);
    }
    fn take(buf: &[f64]) -> Self {
        buf[0] as Tag
    }
}

impl Wire for DVec3 {
    const WIDTH: usize = 3;
    fn put(&self, buf: &mut Vec<f64>) {
        buf.extend_from_slice(&self.to_array());
    }
    fn take(buf: &[f64]) -> Self {
        DVec3::new(buf[0], buf[1], buf[2])
    }
}

impl Wire for Image {
    const WIDTH: usize = 3;
    fn put(&self, buf: &mut Vec<f64>) {
        buf.extend(self.get().map(|c| c as f64));
    }
    fn take(buf: &[f64]) -> Self {
        Image::new([buf[0] as i32, buf[1] as i32, buf[2] as i32])
    }
}

/// Declares [`super::Particles`] and its per-particle columns from one table. Each row:
/// doc comment, `name: Type`, then how the column travels to another rank — `wire`
/// (packed as it is), `shifted` (the position: packed displaced by the image shift) or
/// `local` (not sent; a new copy starts at the type's default, as forces do) — and
/// whether forward communication refreshes it every step (`forward` or `once`).
macro_rules! particle_columns {
    ($($(#[$doc:meta])* $name:ident: $t:ty, $travel:ident, $fwd:ident;)*) => {
        /// Struct-of-arrays particle container: indices `0..nlocal` are owned particles,
        /// `nlocal..len` are ghosts (periodic images or, with MPI, copies of other ranks'
        /// particles). The columns are declared once, in the table of `particles.rs`.
        #[derive(Debug, Clone, Default)]
        pub struct Particles {
            nlocal: usize,
            $($(#[$doc])* pub $name: Vec<$t>,)*
            /// For each ghost (index `g - nlocal`): index of the particle it copies (the
            /// owner, for serial periodic images), or [`REMOTE_GHOST`] plus the owner's
            /// rank. A local particle is its own origin and has no entry (see
            /// [`Particles::origin`]).
            ghost_origin: Vec<usize>,
            /// Named per-particle properties added by fixes.
            pub props: Vec<Property>,
            /// Named properties held for few owned particles ([`SparseProperty`]).
            pub sparse: Vec<SparseProperty>,
            /// With rigid clumps only (else empty): the mass each particle's contacts use
            /// for their effective mass, its body's for a clump's sphere and its own
            /// otherwise (as LIGGGHTS does), refreshed before each force computation
            /// ([`Particles::contact_mass`]).
            pub mass_of_contact: Vec<f64>,
        }

        /// One particle's value of every column, for [`Particles::push_row`].
        #[derive(Debug, Clone, Copy)]
        struct Row {
            $($name: $t,)*
        }

        /// How many columns there are.
        const COLUMNS: usize = 0 $(+ particle_columns!(@one $name))*;

        /// Values per particle in [`Particles::pack`] before the named properties.
        const PACK_FIXED: usize = 0 $(+ particle_columns!(@width $travel $t))*;

        /// Values per particle in [`Particles::pack_forward`] before the forwarded
        /// properties.
        pub const FORWARD_LEN: usize = 0 $(+ particle_columns!(@fwidth $fwd $t))*;

        impl Particles {
            /// Every column, for what treats them alike.
            fn columns_mut(&mut self) -> [&mut dyn Column; COLUMNS] {
                [$(&mut self.$name as &mut dyn Column,)*]
            }

            /// Every column, read only.
            fn columns(&self) -> [&dyn Column; COLUMNS] {
                [$(&self.$name as &dyn Column,)*]
            }

            /// Appends one particle's values to every column.
            fn push_row(&mut self, row: Row) {
                $(self.$name.push(row.$name);)*
            }

            /// The values of particle `i` (a copy of it).
            fn row(&self, i: usize) -> Row {
                Row { $($name: self.$name[i],)* }
            }

            /// The row of a copy of particle `i` displaced by `shift`: the `local`
            /// columns at their defaults.
            fn copied_row(&self, i: usize, shift: DVec3) -> Row {
                let mut row = self.row(i);
                $(particle_columns!(@copy $travel row.$name, shift);)*
                row
            }

            /// Appends the sent columns of particle `i` (position displaced by `shift`).
            fn pack_columns(&self, i: usize, shift: DVec3, buf: &mut Vec<f64>) {
                $(particle_columns!(@put $travel self.$name[i], shift, buf);)*
            }

            /// The row packed by [`Particles::pack_columns`] at the front of `buf`.
            fn unpack_row(buf: &[f64]) -> Row {
                let mut k = 0;
                $(let $name: $t = particle_columns!(@take $travel $t, buf, k);)*
                debug_assert_eq!(k, PACK_FIXED);
                Row { $($name,)* }
            }

            /// Appends the forwarded columns of particle `i` (position displaced by
            /// `shift`).
            fn pack_forward_columns(&self, i: usize, shift: DVec3, buf: &mut Vec<f64>) {
                $(particle_columns!(@fput $fwd $travel self.$name[i], shift, buf);)*
            }

            /// Sets the forwarded columns of ghost `g` from the front of `c`.
            fn unpack_forward_columns(&mut self, g: usize, c: &[f64]) {
                let mut k = 0;
                $(particle_columns!(@ftake $fwd self.$name[g], $t, c, k);)*
                debug_assert_eq!(k, FORWARD_LEN);
            }

            /// Copies the forwarded columns of particle `i` to ghost `g`, displaced by
            /// `shift`.
            fn copy_forward_columns(&mut self, g: usize, i: usize, shift: DVec3) {
                $(particle_columns!(@fcopy $fwd $travel self.$name, g, i, shift);)*
            }
        }
    };
    (@one $name:ident) => { 1 };
    (@width local $t:ty) => { 0 };
    (@width $travel:ident $t:ty) => { <$t as Wire>::WIDTH };
    (@fwidth forward $t:ty) => { <$t as Wire>::WIDTH };
    (@fwidth once $t:ty) => { 0 };
    (@copy local $v:expr, $shift:ident) => { $v = Default::default() };
    (@copy shifted $v:expr, $shift:ident) => { $v += $shift };
    (@copy wire $v:expr, $shift:ident) => {};
    (@put local $v:expr, $shift:ident, $buf:ident) => {};
    (@put shifted $v:expr, $shift:ident, $buf:ident) => { ($v + $shift).put($buf) };
    (@put wire $v:expr, $shift:ident, $buf:ident) => { $v.put($buf) };
    (@take local $t:ty, $buf:ident, $k:ident) => { <$t>::default() };
    (@take $travel:ident $t:ty, $buf:ident, $k:ident) => {{
        let v = <$t as Wire>::take(&$buf[$k..]);
        $k += <$t as Wire>::WIDTH;
        v
    }};
    (@fput once $travel:ident $v:expr, $shift:ident, $buf:ident) => {};
    (@fput forward shifted $v:expr, $shift:ident, $buf:ident) => { ($v + $shift).put($buf) };
    (@fput forward $travel:ident $v:expr, $shift:ident, $buf:ident) => { $v.put($buf) };
    (@ftake once $v:expr, $t:ty, $c:ident, $k:ident) => {};
    (@ftake forward $v:expr, $t:ty, $c:ident, $k:ident) => {{
        $v = <$t as Wire>::take(&$c[$k..]);
        $k += <$t as Wire>::WIDTH;
    }};
    (@fcopy once $travel:ident $col:expr, $g:ident, $i:ident, $shift:ident) => {};
    (@fcopy forward shifted $col:expr, $g:ident, $i:ident, $shift:ident) => {
        $col[$g] = $col[$i] + $shift
    };
    (@fcopy forward $travel:ident $col:expr, $g:ident, $i:ident, $shift:ident) => {
        $col[$g] = $col[$i]
    };
}

pub(super) use particle_columns;

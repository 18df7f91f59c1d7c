//! Per-particle values that few owned particles hold: a wall's contact history, non-zero
//! only for the particles near the wall. Each owned particle has a row index (4 bytes)
//! instead of `width` values; a particle without a row reads zeros.
//!
//! The rows follow their particles through the container's operations (sorting,
//! removal, migration), like a dense property's values. The owner of the values (the
//! wall) gives rows to exactly its candidates at each re-neighboring
//! ([`SparseProperty::keep_rows`]), in candidate order, so that a pass over the
//! candidates walks the rows in order and chunks of candidates own disjoint row ranges.
//! Ghosts hold no rows.

/// Row index of a particle without values.
const NONE: u32 = u32::MAX;

/// Handle of a sparse per-particle property.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SparseId(pub usize);

/// A named per-particle property of `width` values, zero for most particles (see the
/// module docs).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SparseProperty {
    /// Name, unique among the container's properties.
    pub name: String,
    /// Values per particle.
    pub width: usize,
    /// Row of each owned particle in `data`, or [`NONE`].
    slot: Vec<u32>,
    /// Rows of `width` values; rows of removed particles stay until the next
    /// [`SparseProperty::keep_rows`].
    pub(crate) data: Vec<f64>,
    /// `width` zeros: the values of a particle without a row.
    zeros: Vec<f64>,
}

impl SparseProperty {
    /// An empty property for `nlocal` owned particles (none with a row).
    pub(crate) fn new(name: &str, width: usize, nlocal: usize) -> Self {
        Self {
            name: name.to_string(),
            width,
            slot: vec![NONE; nlocal],
            data: Vec::new(),
            zeros: vec![0.0; width],
        }
    }

    /// The values of owned particle `i` (zeros without a row; also for a ghost index).
    pub fn get(&self, i: usize) -> &[f64] {
        match self.row_of(i) {
            Some(r) => &self.data[r * self.width..(r + 1) * self.width],
            None => &self.zeros,
        }
    }

    /// The row of owned particle `i`, if it has one.
    pub fn row_of(&self, i: usize) -> Option<usize> {
        self.slot
            .get(i)
            .copied()
            .filter(|&s| s != NONE)
            .map(|s| s as usize)
    }

    /// Mutable values of owned particle `i`, given a row if it has none.
    pub fn get_mut(&mut self, i: usize) -> &mut [f64] {
        let w = self.width;
        let r = match self.row_of(i) {
            Some(r) => r,
            None => {
                let r = self.data.len() / w.max(1);
                self.data.resize((r + 1) * w, 0.0);
                self.slot[i] = r as u32;
                r
            }
        };
        &mut self.data[r * w..(r + 1) * w]
    }

    /// Gives rows to exactly the owned particles `keep` (`n` of them): row `c` holds the
    /// values of `keep[c]` (zeros for one that had none); every other particle loses its
    /// values.
    pub fn keep_rows(&mut self, keep: impl IntoIterator<Item = usize>, n: usize) {
        let w = self.width;
        let mut data = Vec::with_capacity(n * w);
        let old = std::mem::take(&mut self.data);
        let mut kept: Vec<(usize, u32)> = Vec::with_capacity(n);
        for (c, i) in keep.into_iter().enumerate() {
            match self.row_of(i) {
                Some(r) => data.extend_from_slice(&old[r * w..(r + 1) * w]),
                None => data.extend_from_slice(&self.zeros),
            }
            kept.push((i, c as u32));
        }
        debug_assert_eq!(kept.len(), n);
        self.slot.fill(NONE);
        for (i, c) in kept {
            self.slot[i] = c;
        }
        self.data = data;
    }

    /// True when rows `0..rows.len()` belong to the particles `rows` (as after
    /// [`SparseProperty::keep_rows`] with them).
    pub fn rows_match(&self, rows: &[u32]) -> bool {
        self.data.len() >= rows.len() * self.width
            && rows
                .iter()
                .enumerate()
                .all(|(c, &i)| self.row_of(i as usize) == Some(c))
    }

    /// The values of the owned particles `0..n`, `width` each (zeros for those without a
    /// row), as a dense property holds them.
    pub fn dense(&self, n: usize) -> Vec<f64> {
        let mut out = Vec::with_capacity(n * self.width);
        for i in 0..n {
            out.extend_from_slice(self.get(i));
        }
        out
    }

    /// Owned particles with a row.
    pub fn rows(&self) -> usize {
        self.slot.iter().filter(|&&s| s != NONE).count()
    }

    /// Appends an owned particle with `values` (a row only when one is non-zero).
    pub(crate) fn push(&mut self, values: &[f64]) {
        debug_assert_eq!(values.len(), self.width);
        if values.iter().all(|&v| v == 0.0 && !v.is_sign_negative()) {
            self.slot.push(NONE);
        } else {
            let r = self.data.len() / self.width.max(1);
            self.data.extend_from_slice(values);
            self.slot.push(r as u32);
        }
    }

    /// Appends an owned particle without values.
    pub(crate) fn push_none(&mut self) {
        self.slot.push(NONE);
    }

    /// Keeps the owned particles `0..n` (called when particles are removed from the end).
    pub(crate) fn truncate(&mut self, n: usize) {
        self.slot.truncate(n);
    }

    /// The row indices, one per owned particle (for the container's permutation and
    /// compaction).
    pub(crate) fn slots_mut(&mut self) -> &mut Vec<u32> {
        &mut self.slot
    }

    /// Gives back spare capacity.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.slot.shrink_to_fit();
        self.data.shrink_to_fit();
    }

    /// Bytes held.
    pub(crate) fn memory_bytes(&self) -> usize {
        self.slot.capacity() * std::mem::size_of::<u32>()
            + (self.data.capacity() + self.zeros.capacity()) * std::mem::size_of::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_follow_keep_and_zeros_elsewhere() {
        let mut s = SparseProperty::new("h", 2, 4);
        assert_eq!(s.get(2), &[0.0, 0.0]);
        s.get_mut(2).copy_from_slice(&[1.0, 2.0]);
        s.get_mut(0).copy_from_slice(&[3.0, 4.0]);
        assert_eq!(s.rows(), 2);
        assert_eq!(s.dense(4), vec![3.0, 4.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0]);
        // Rows for 1 and 2 only: 2 keeps its values, 1 starts at zero, 0 loses its own.
        s.keep_rows([1, 2], 2);
        assert!(s.rows_match(&[1, 2]));
        assert_eq!(s.data, vec![0.0, 0.0, 1.0, 2.0]);
        assert_eq!(s.get(0), &[0.0, 0.0]);
        assert_eq!(s.get(2), &[1.0, 2.0]);
        assert_eq!(s.get(7), &[0.0, 0.0], "a ghost index reads zeros");
    }

    #[test]
    fn push_gives_rows_to_non_zero_values_only() {
        let mut s = SparseProperty::new("h", 2, 0);
        s.push(&[0.0, 0.0]);
        s.push(&[0.0, -0.0]);
        s.push(&[5.0, 0.0]);
        assert_eq!(s.rows(), 2, "-0.0 is kept, as the pair history keeps it");
        assert_eq!(s.get(1), &[0.0, -0.0]);
        assert_eq!(s.get(2), &[5.0, 0.0]);
        s.truncate(1);
        assert_eq!(s.rows(), 0);
    }
}

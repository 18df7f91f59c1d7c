//! Per-particle values that few owned particles hold: a wall's contact history, non-zero
//! only for the particles near the wall. The container keeps the list of particles that
//! hold values (4 bytes each) and their rows; every other particle reads zeros. Nothing
//! is stored per particle without values.
//!
//! The rows follow their particles through the container's operations (sorting,
//! removal, migration), like a dense property's values. The owner of the values (the
//! wall) gives rows to exactly its candidates at each re-neighboring
//! ([`SparseProperty::keep_rows`]), in candidate order, so that a pass over the
//! candidates walks the rows in order and chunks of candidates own disjoint row ranges.
//! Ghosts hold no rows.

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
    /// The owned particles holding rows, ascending: row `c` belongs to `owner[c]`.
    owner: Vec<u32>,
    /// Rows of `width` values, one per entry of `owner`.
    pub(crate) data: Vec<f64>,
    /// `width` zeros: the values of a particle without a row.
    zeros: Vec<f64>,
}

impl SparseProperty {
    /// An empty property (no particle holds values).
    pub(crate) fn new(name: &str, width: usize) -> Self {
        Self {
            name: name.to_string(),
            width,
            owner: Vec::new(),
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
        u32::try_from(i)
            .ok()
            .and_then(|i| self.owner.binary_search(&i).ok())
    }

    /// Mutable values of owned particle `i`, given a row (of zeros) if it has none.
    pub fn get_mut(&mut self, i: usize) -> &mut [f64] {
        let w = self.width;
        let r = match self.owner.binary_search(&(i as u32)) {
            Ok(r) => r,
            Err(r) => {
                self.owner.insert(r, i as u32);
                self.data.splice(r * w..r * w, self.zeros.iter().copied());
                r
            }
        };
        &mut self.data[r * w..(r + 1) * w]
    }

    /// Gives rows to exactly the owned particles `keep` (`n` of them, ascending): row `c`
    /// holds the values of `keep[c]` (zeros for one that had none); every other particle
    /// loses its values.
    pub fn keep_rows(&mut self, keep: impl IntoIterator<Item = usize>, n: usize) {
        let w = self.width;
        let mut owner = Vec::with_capacity(n);
        let mut data = Vec::with_capacity(n * w);
        for i in keep {
            debug_assert!(owner.last().is_none_or(|&l| (l as usize) < i), "ascending");
            data.extend_from_slice(self.get(i));
            owner.push(i as u32);
        }
        self.owner = owner;
        self.data = data;
    }

    /// True when rows `0..rows.len()` belong to the particles `rows` (as after
    /// [`SparseProperty::keep_rows`] with them).
    pub fn rows_match(&self, rows: &[u32]) -> bool {
        self.owner == rows
    }

    /// The values of the owned particles `0..n`, `width` each (zeros for those without a
    /// row), as a dense property holds them.
    pub fn dense(&self, n: usize) -> Vec<f64> {
        let mut out = vec![0.0; n * self.width];
        let w = self.width;
        for (c, &i) in self.owner.iter().enumerate() {
            let i = i as usize;
            if i < n {
                out[i * w..(i + 1) * w].copy_from_slice(&self.data[c * w..(c + 1) * w]);
            }
        }
        out
    }

    /// Owned particles with a row.
    pub fn rows(&self) -> usize {
        self.owner.len()
    }

    /// Records `values` for the owned particle `i` just appended (a row only when one is
    /// non-zero: -0.0 counts as non-zero, as in the pair history).
    pub(crate) fn push(&mut self, i: usize, values: &[f64]) {
        debug_assert_eq!(values.len(), self.width);
        debug_assert!(self.owner.last().is_none_or(|&l| (l as usize) < i));
        if values.iter().any(|v| v.to_bits() != 0) {
            self.owner.push(i as u32);
            self.data.extend_from_slice(values);
        }
    }

    /// Follows a reordering of the owned particles: new index `i` holds what was at
    /// `perm[i]`.
    pub(crate) fn permute(&mut self, perm: &[usize]) {
        if self.owner.is_empty() {
            return;
        }
        let w = self.width;
        let mut owner = Vec::with_capacity(self.owner.len());
        let mut data = Vec::with_capacity(self.data.len());
        for (i, &old) in perm.iter().enumerate() {
            if let Some(r) = self.row_of(old) {
                owner.push(i as u32);
                data.extend_from_slice(&self.data[r * w..(r + 1) * w]);
            }
        }
        self.owner = owner;
        self.data = data;
    }

    /// Follows the removal of the owned particles with `remove[i]` true (the others
    /// keep their order).
    pub(crate) fn remove(&mut self, remove: &[bool]) {
        let w = self.width;
        let (mut kept, mut gone, mut c) = (0, 0usize, 0);
        let mut next = 0;
        for r in 0..self.owner.len() {
            let i = self.owner[r] as usize;
            // Removed particles below i.
            gone += remove[next..i].iter().filter(|&&g| g).count();
            next = i;
            if remove[i] {
                continue;
            }
            self.owner[kept] = (i - gone) as u32;
            self.data.copy_within(r * w..(r + 1) * w, c);
            kept += 1;
            c += w;
        }
        self.owner.truncate(kept);
        self.data.truncate(c);
    }

    /// Gives back spare capacity.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.owner.shrink_to_fit();
        self.data.shrink_to_fit();
    }

    /// Bytes held.
    pub(crate) fn memory_bytes(&self) -> usize {
        self.owner.capacity() * std::mem::size_of::<u32>()
            + (self.data.capacity() + self.zeros.capacity()) * std::mem::size_of::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_follow_keep_and_zeros_elsewhere() {
        let mut s = SparseProperty::new("h", 2);
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
        let mut s = SparseProperty::new("h", 2);
        s.push(0, &[0.0, 0.0]);
        s.push(1, &[0.0, -0.0]);
        s.push(2, &[5.0, 0.0]);
        assert_eq!(s.rows(), 2, "-0.0 is kept, as the pair history keeps it");
        assert_eq!(s.get(1), &[0.0, -0.0]);
        assert_eq!(s.get(2), &[5.0, 0.0]);
        assert_eq!(s.dense(3), vec![0.0, 0.0, 0.0, -0.0, 5.0, 0.0]);
    }

    #[test]
    fn rows_follow_permutation_and_removal() {
        // Particles 0..6, values 10 + i for 1, 3, 4.
        let mut s = SparseProperty::new("h", 1);
        for i in [1, 3, 4] {
            s.get_mut(i)[0] = 10.0 + i as f64;
        }
        let perm = [4, 0, 5, 1, 3, 2];
        s.permute(&perm);
        let want: Vec<f64> = perm
            .iter()
            .map(|&o| {
                if [1, 3, 4].contains(&o) {
                    10.0 + o as f64
                } else {
                    0.0
                }
            })
            .collect();
        assert_eq!(s.dense(6), want);
        // Remove new indices 0 (old 4, with values), 2 (old 5) and 5 (old 2).
        let remove = [true, false, true, false, false, true];
        s.remove(&remove);
        assert_eq!(s.dense(3), vec![0.0, 11.0, 13.0]);
        assert!(s.rows_match(&[1, 2]));
    }
}

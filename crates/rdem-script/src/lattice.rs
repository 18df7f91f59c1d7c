//! The `lattice` command for SI units: cubic lattices `sc`, `bcc`, `fcc` and `diamond`,
//! the hexagonal close packing `hcp` (and the 2d `sq`, `sq2`, `hex`)
//! whose `scale` is the lattice constant in metres, and `custom` lattices with
//! axis-aligned cell vectors `a1 a2 a3` (in units of the scale) and `basis` atoms, with an
//! `origin` shift. `units
//! lattice` in `region` and `create_atoms` multiplies by the lattice spacings, which for
//! these unrotated cubic lattices all equal the constant. As in LIGGGHTS 3.8, `units box`
//! is those commands' default, and without a `lattice` command the scale is that of the
//! default lattice `none 1.0`.

use glam::DVec3;

/// A cubic lattice.
#[derive(Debug, Clone, PartialEq)]
pub struct Lattice {
    /// Style word.
    pub style: String,
    /// Lattice constant (m).
    pub a: f64,
    /// Basis atoms in unit-cell fractions.
    pub basis: Vec<DVec3>,
    /// Origin shift in unit-cell fractions.
    pub origin: DVec3,
    /// The unit cell's edges in units of `a` (1, 1, 1 for the cubic styles; `a1`, `a2`,
    /// `a3` along x, y, z for `custom`).
    pub cell: DVec3,
}

/// Valid lattice styles.
/// (`sq`, `sq2` and `hex` are the 2d lattices: `dimension 2` only.)
pub const STYLES: [&str; 10] = [
    "none", "sc", "bcc", "fcc", "hcp", "diamond", "custom", "sq", "sq2", "hex",
];

/// The 2d lattice styles.
pub const STYLES_2D: [&str; 3] = ["sq", "sq2", "hex"];

impl Lattice {
    /// A lattice of `style` with constant `a` (`None` for an unknown style). Style `none`
    /// has no points, only the `units lattice` scale (LIGGGHTS' default is `none 1.0`).
    pub fn new(style: &str, a: f64) -> Option<Self> {
        let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let basis = match style {
            "none" | "custom" => vec![],
            "sc" | "sq" => vec![v(0.0, 0.0, 0.0)],
            "sq2" | "hex" => vec![v(0.0, 0.0, 0.0), v(0.5, 0.5, 0.0)],
            "bcc" => vec![v(0.0, 0.0, 0.0), v(0.5, 0.5, 0.5)],
            "fcc" => vec![
                v(0.0, 0.0, 0.0),
                v(0.5, 0.5, 0.0),
                v(0.5, 0.0, 0.5),
                v(0.0, 0.5, 0.5),
            ],
            // LAMMPS' hcp: a1 = 1 0 0, a2 = 0 √3 0, a3 = 0 0 √(8/3).
            "hcp" => vec![
                v(0.0, 0.0, 0.0),
                v(0.5, 0.5, 0.0),
                v(0.5, 5.0 / 6.0, 0.5),
                v(0.0, 1.0 / 3.0, 0.5),
            ],
            "diamond" => vec![
                v(0.0, 0.0, 0.0),
                v(0.0, 0.5, 0.5),
                v(0.5, 0.0, 0.5),
                v(0.5, 0.5, 0.0),
                v(0.25, 0.25, 0.25),
                v(0.25, 0.75, 0.75),
                v(0.75, 0.25, 0.75),
                v(0.75, 0.75, 0.25),
            ],
            _ => return None,
        };
        // LAMMPS' 2d lattices: a square cell (sq, sq2), or a1 = 1 0 0, a2 = 0 √3 0 (hex);
        // a3 = 0 0 1.
        let cell = match style {
            "hex" => v(1.0, 3f64.sqrt(), 1.0),
            "hcp" => v(1.0, 3f64.sqrt(), (8.0f64 / 3.0).sqrt()),
            _ => DVec3::ONE,
        };
        Some(Self {
            style: style.to_string(),
            a,
            basis,
            origin: DVec3::ZERO,
            cell,
        })
    }

    /// Lattice spacing per axis (the `units lattice` scale).
    pub fn spacing(&self) -> DVec3 {
        self.a * self.cell
    }

    /// Every lattice point inside the box `lo..hi` (points on the upper faces excluded,
    /// as LAMMPS does for periodic boxes), in a fixed order (z, y, x cells, then basis).
    pub fn points(&self, lo: DVec3, hi: DVec3) -> Vec<DVec3> {
        let a = self.spacing();
        let cell_lo = ((lo / a) - self.origin).floor() - DVec3::ONE;
        let cell_hi = ((hi / a) - self.origin).ceil() + DVec3::ONE;
        let mut out = Vec::new();
        let mut k = cell_lo.z;
        while k <= cell_hi.z {
            let mut j = cell_lo.y;
            while j <= cell_hi.y {
                let mut i = cell_lo.x;
                while i <= cell_hi.x {
                    for b in &self.basis {
                        let x = (DVec3::new(i, j, k) + *b + self.origin) * a;
                        if (0..3).all(|d| x[d] >= lo[d] && x[d] < hi[d]) {
                            out.push(x);
                        }
                    }
                    i += 1.0;
                }
                j += 1.0;
            }
            k += 1.0;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_per_cell() {
        let lo = DVec3::ZERO;
        let hi = DVec3::splat(0.03);
        assert_eq!(Lattice::new("sc", 0.01).unwrap().points(lo, hi).len(), 27);
        assert_eq!(Lattice::new("fcc", 0.01).unwrap().points(lo, hi).len(), 108);
        assert_eq!(Lattice::new("bcc", 0.01).unwrap().points(lo, hi).len(), 54);
        assert!(Lattice::new("hcp2", 1.0).is_none());
    }
}

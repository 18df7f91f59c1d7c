//! Per-particle output quantities, named as LIGGGHTS' `dump custom` names them, and the
//! columns of a dump: one of those quantities, or values the front end computed
//! (`c_ID`, `c_ID[N]`, `f_ID`, `f_ID[N]`, `v_name`).

use rdem::{Domain, Particles};

use crate::printf::Value;

/// A built-in per-particle quantity of `dump custom`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// `id`: the particle's tag.
    Id,
    /// `type`.
    Type,
    /// `mass`.
    Mass,
    /// `x`.
    X,
    /// `y`.
    Y,
    /// `z`.
    Z,
    /// `xs`: x scaled to the box, `(x - xlo) / (xhi - xlo)`.
    Xs,
    /// `ys`.
    Ys,
    /// `zs`.
    Zs,
    /// `xu`: x unwrapped with the image flag, `x + ix (xhi - xlo)`.
    Xu,
    /// `yu`.
    Yu,
    /// `zu`.
    Zu,
    /// `ix`: periodic image flag.
    Ix,
    /// `iy`.
    Iy,
    /// `iz`.
    Iz,
    /// `vx`.
    Vx,
    /// `vy`.
    Vy,
    /// `vz`.
    Vz,
    /// `fx`.
    Fx,
    /// `fy`.
    Fy,
    /// `fz`.
    Fz,
    /// `omegax`: angular velocity.
    OmegaX,
    /// `omegay`.
    OmegaY,
    /// `omegaz`.
    OmegaZ,
    /// `tqx`: torque.
    Tqx,
    /// `tqy`.
    Tqy,
    /// `tqz`.
    Tqz,
    /// `radius`.
    Radius,
    /// `diameter`.
    Diameter,
    /// `density`.
    Density,
    /// `mol`: the tag of the clump a sphere belongs to (`fix multisphere`), -1 for a free
    /// sphere, as LIGGGHTS 3.8 writes it (which refuses the column without
    /// `fix multisphere`; rdem writes -1 for every sphere then).
    Mol,
    /// `id_multisphere`: the same as `mol` in LIGGGHTS 3.8.
    IdMultisphere,
    /// `p`: the SPH pressure (`atom_style sph`; 0 for other particles).
    P,
    /// `rho`: the SPH density (`atom_style sph`; 0 for other particles).
    Rho,
}

impl Field {
    /// Every field, in the order of [`Field::NAMES`].
    pub const ALL: [Field; 34] = [
        Field::Id,
        Field::Type,
        Field::Mass,
        Field::X,
        Field::Y,
        Field::Z,
        Field::Xs,
        Field::Ys,
        Field::Zs,
        Field::Xu,
        Field::Yu,
        Field::Zu,
        Field::Ix,
        Field::Iy,
        Field::Iz,
        Field::Vx,
        Field::Vy,
        Field::Vz,
        Field::Fx,
        Field::Fy,
        Field::Fz,
        Field::OmegaX,
        Field::OmegaY,
        Field::OmegaZ,
        Field::Tqx,
        Field::Tqy,
        Field::Tqz,
        Field::Radius,
        Field::Diameter,
        Field::Density,
        Field::Mol,
        Field::IdMultisphere,
        Field::P,
        Field::Rho,
    ];

    /// Every valid name, for error messages ("expected one of ...").
    pub const NAMES: [&'static str; 34] = [
        "id",
        "type",
        "mass",
        "x",
        "y",
        "z",
        "xs",
        "ys",
        "zs",
        "xu",
        "yu",
        "zu",
        "ix",
        "iy",
        "iz",
        "vx",
        "vy",
        "vz",
        "fx",
        "fy",
        "fz",
        "omegax",
        "omegay",
        "omegaz",
        "tqx",
        "tqy",
        "tqz",
        "radius",
        "diameter",
        "density",
        "mol",
        "id_multisphere",
        "p",
        "rho",
    ];

    /// The field called `name` in a `dump custom` command.
    pub fn parse(name: &str) -> Option<Field> {
        Self::NAMES
            .iter()
            .position(|&n| n == name)
            .map(|i| Self::ALL[i])
    }

    /// The name LIGGGHTS uses.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// True for integer quantities (`id`, `type`, `ix`, `iy`, `iz`, `mol`,
    /// `id_multisphere`), written with `%d`.
    pub fn is_integer(self) -> bool {
        matches!(
            self,
            Field::Id
                | Field::Type
                | Field::Ix
                | Field::Iy
                | Field::Iz
                | Field::Mol
                | Field::IdMultisphere
        )
    }

    /// True for the fields read from a named per-particle property (`mol`,
    /// `id_multisphere`: the clump of a sphere), which a bare copy of the particles lacks.
    pub fn reads_properties(self) -> bool {
        matches!(
            self,
            Field::Mol | Field::IdMultisphere | Field::P | Field::Rho
        )
    }

    /// The value for particle `i` (integers exactly, as long as tags stay below 2^53).
    pub fn value(self, p: &Particles, d: &Domain, i: usize) -> f64 {
        let scaled = |a: usize| (p.x[i][a] - d.boxlo[a]) / (d.boxhi[a] - d.boxlo[a]);
        let unwrapped =
            |a: usize| p.x[i][a] + p.image[i].get()[a] as f64 * (d.boxhi[a] - d.boxlo[a]);
        match self {
            Field::Id => p.tag[i] as f64,
            Field::Type => p.ty[i] as f64,
            Field::Mass => p.rmass[i],
            Field::X => p.x[i].x,
            Field::Y => p.x[i].y,
            Field::Z => p.x[i].z,
            Field::Xs => scaled(0),
            Field::Ys => scaled(1),
            Field::Zs => scaled(2),
            Field::Xu => unwrapped(0),
            Field::Yu => unwrapped(1),
            Field::Zu => unwrapped(2),
            Field::Ix => p.image[i].get()[0] as f64,
            Field::Iy => p.image[i].get()[1] as f64,
            Field::Iz => p.image[i].get()[2] as f64,
            Field::Vx => p.v[i].x,
            Field::Vy => p.v[i].y,
            Field::Vz => p.v[i].z,
            Field::Fx => p.f[i].x,
            Field::Fy => p.f[i].y,
            Field::Fz => p.f[i].z,
            Field::OmegaX => p.omega[i].x,
            Field::OmegaY => p.omega[i].y,
            Field::OmegaZ => p.omega[i].z,
            Field::Tqx => p.torque[i].x,
            Field::Tqy => p.torque[i].y,
            Field::Tqz => p.torque[i].z,
            Field::Radius => p.radius[i],
            Field::Diameter => 2.0 * p.radius[i],
            Field::Density => p.density[i],
            Field::Mol | Field::IdMultisphere => {
                // Atom style bond/gran's molecule ID; else the clump (multisphere body).
                if let (Field::Mol, Some(id)) = (self, p.property(rdem::bond_gran::MOLECULE)) {
                    return p.props[id.0].data[i];
                }
                let body = p
                    .property(rdem::multisphere::bodies::BODY_PROP)
                    .map_or(0.0, |id| p.props[id.0].data[i]);
                if body == 0.0 {
                    -1.0
                } else {
                    body
                }
            }
            Field::P => p
                .property(rdem::sph::PRESSURE)
                .map_or(0.0, |id| p.props[id.0].data[i]),
            Field::Rho => p
                .property(rdem::sph::RHO)
                .map_or(0.0, |id| p.props[id.0].data[i]),
        }
    }

    /// The value for particle `i`, typed for formatting (tags and image flags exactly).
    pub fn typed_value(self, p: &Particles, d: &Domain, i: usize) -> Value {
        match self {
            Field::Id => Value::Int(i64::try_from(p.tag[i]).unwrap_or(i64::MAX)),
            Field::Type => Value::Int(p.ty[i] as i64),
            Field::Ix => Value::Int(p.image[i].get()[0] as i64),
            Field::Iy => Value::Int(p.image[i].get()[1] as i64),
            Field::Iz => Value::Int(p.image[i].get()[2] as i64),
            Field::Mol | Field::IdMultisphere => Value::Int(self.value(p, d, i) as i64),
            _ => Value::Float(self.value(p, d, i)),
        }
    }
}

/// One column of a dump.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// A built-in quantity.
    Field(Field),
    /// Values computed by the front end for a `c_ID`, `c_ID[N]`, `f_ID`, `f_ID[N]` or
    /// `v_name` argument. `name` is the argument as written; `values[i]` belongs to the
    /// owned particle with index `i` (at least `nlocal` values).
    Custom {
        /// The argument as written in the dump command.
        name: String,
        /// One value per owned particle, by particle index.
        values: Vec<f64>,
    },
}

impl Column {
    /// A column for a dump argument: a built-in field if `arg` names one, otherwise
    /// `None` (the front end then computes a [`Column::Custom`] for `c_`/`f_`/`v_`).
    pub fn field(arg: &str) -> Option<Column> {
        Field::parse(arg).map(Column::Field)
    }

    /// The header label: the field name, or the custom argument as written.
    pub fn label(&self) -> &str {
        match self {
            Column::Field(f) => f.name(),
            Column::Custom { name, .. } => name,
        }
    }

    /// True for integer-valued built-in fields.
    pub fn is_integer(&self) -> bool {
        matches!(self, Column::Field(f) if f.is_integer())
    }

    /// The value for owned particle `i`.
    ///
    /// # Panics
    /// If a custom column has fewer values than `i + 1` (a front-end bug).
    pub fn value(&self, p: &Particles, d: &Domain, i: usize) -> Value {
        match self {
            Column::Field(f) => f.typed_value(p, d, i),
            Column::Custom { name, values } => Value::Float(*values.get(i).unwrap_or_else(|| {
                panic!(
                    "custom dump column '{name}' has {} values, particle index {i} asked for",
                    values.len()
                )
            })),
        }
    }
}

/// Indices of the owned particles in the group with bit mask `groupbit` (1 = `all`), in
/// storage order: the usual selection to hand to a dump writer.
pub fn group_selection(p: &Particles, groupbit: u32) -> Vec<usize> {
    (0..p.nlocal())
        .filter(|&i| p.mask[i] & groupbit != 0)
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use rdem::{Boundary, DVec3, NewParticle};

    /// Two particles in a box [0,2]x[-1,1]x[0,4], periodic in x.
    pub(crate) fn sample() -> (Particles, Domain) {
        let d = Domain::new(
            DVec3::new(0.0, -1.0, 0.0),
            DVec3::new(2.0, 1.0, 4.0),
            [Boundary::Periodic, Boundary::Fixed, Boundary::ShrinkMin],
        )
        .unwrap();
        let mut p = Particles::new();
        p.add_local(
            &NewParticle::at(DVec3::new(0.5, 0.0, 1.0), 0.1, 2500.0)
                .with_tag(7)
                .with_type(2)
                .with_v(DVec3::new(1.0, -2.0, 3.0))
                .with_omega(DVec3::new(0.1, 0.2, 0.3)),
        )
        .unwrap();
        p.add_local(&NewParticle::at(DVec3::new(1.5, 0.5, 3.0), 0.05, 1000.0).with_tag(3))
            .unwrap();
        p.image[0] = [-1, 0, 2].into();
        p.f[1] = DVec3::new(4.0, 5.0, 6.0);
        p.torque[1] = DVec3::new(-7.0, -8.0, -9.0);
        (p, d)
    }

    #[test]
    fn names_round_trip() {
        for (k, &n) in Field::NAMES.iter().enumerate() {
            let f = Field::parse(n).unwrap();
            assert_eq!(f, Field::ALL[k]);
            assert_eq!(f.name(), n);
        }
        assert_eq!(Field::parse("molecule"), None);
        assert_eq!(Field::parse("X"), None);
        assert_eq!(Field::parse("c_foo"), None);
    }

    #[test]
    fn values() {
        let (p, d) = sample();
        let v = |f: &str, i| Field::parse(f).unwrap().value(&p, &d, i);
        assert_eq!(v("id", 0), 7.0);
        assert_eq!(v("type", 0), 2.0);
        assert_eq!(v("x", 0), 0.5);
        assert_eq!(v("xs", 0), 0.25);
        assert_eq!(v("ys", 1), 0.75);
        assert_eq!(v("zs", 1), 0.75);
        assert_eq!(v("xu", 0), 0.5 - 2.0);
        assert_eq!(v("zu", 0), 1.0 + 8.0);
        assert_eq!(v("yu", 1), 0.5);
        assert_eq!(v("ix", 0), -1.0);
        assert_eq!(v("iz", 0), 2.0);
        assert_eq!(v("vy", 0), -2.0);
        assert_eq!(v("fz", 1), 6.0);
        assert_eq!(v("omegaz", 0), 0.3);
        assert_eq!(v("tqx", 1), -7.0);
        assert_eq!(v("radius", 1), 0.05);
        assert_eq!(v("diameter", 1), 0.1);
        assert_eq!(v("density", 0), 2500.0);
        let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.001;
        assert!((v("mass", 0) - m).abs() < 1e-12 * m);
        for f in Field::ALL {
            assert_eq!(
                f.is_integer(),
                matches!(f.typed_value(&p, &d, 0), Value::Int(_)),
                "{f:?}"
            );
        }
    }

    #[test]
    fn columns() {
        let (p, d) = sample();
        let c = Column::Custom {
            name: "c_stress[2]".into(),
            values: vec![1.5, 2.5],
        };
        assert_eq!(c.label(), "c_stress[2]");
        assert_eq!(c.value(&p, &d, 1), Value::Float(2.5));
        assert!(!c.is_integer());
        let id = Column::field("id").unwrap();
        assert_eq!(id.label(), "id");
        assert!(id.is_integer());
        assert_eq!(id.value(&p, &d, 1), Value::Int(3));
        assert!(Column::field("v_ke").is_none());
    }

    #[test]
    fn groups() {
        let (mut p, _) = sample();
        p.mask[1] |= 4;
        assert_eq!(group_selection(&p, 1), vec![0, 1]);
        assert_eq!(group_selection(&p, 4), vec![1]);
        assert_eq!(group_selection(&p, 2), Vec::<usize>::new());
    }
}

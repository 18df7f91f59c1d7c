//! An atom-style formula made ready for the engine's force pass: a fix that adds a force
//! given by `variable NAME atom FORMULA` (`fix addforce v_NAME`) evaluates it per particle
//! at the moment it acts, as LIGGGHTS does in its post-force stage, with the velocities
//! of that moment.
//!
//! [`AtomFormula::prepare`] walks the formula before each step: the per-particle fields
//! that a force fix can read in the force pass (`id`, `type`, `mass`, `x`, `vx`, `fx`,
//! `omegax`, `tqx`, `radius`, `diameter`, ...) stay as fields; atom-style variables are
//! expanded in place; every other name (numbers, thermo keywords, equal-style variables,
//! global values of computes and fixes, `x[ID]`) is evaluated then, at that step, as
//! rdem's fixes evaluate their equal-style variables. What cannot be read in the force
//! pass (per-atom computes and fixes, `density`, scaled or unwrapped coordinates, group
//! functions) is an error that names it.

use glam::DVec3;

use crate::context;
use crate::error::Error;
use crate::expr::{self, BinOp, Expr, Name};
use crate::sim::Sim;
use crate::variables::Variable;
use rdem::par::View;

/// Deepest nesting of atom-style variables.
const MAX_DEPTH: usize = 32;

/// A per-particle field a force fix reads in the force pass.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Field {
    Id,
    Type,
    Mass,
    Radius,
    Diameter,
    /// Position component.
    X(usize),
    /// Velocity component.
    V(usize),
    /// Force component (what the force pass has summed so far, as in LIGGGHTS).
    F(usize),
    /// Angular velocity component.
    Omega(usize),
    /// Torque component.
    Torque(usize),
}

impl Field {
    /// Every name, for messages.
    const NAMES: [&'static str; 20] = [
        "id", "type", "mass", "radius", "diameter", "x", "y", "z", "vx", "vy", "vz", "fx", "fy",
        "fz", "omegax", "omegay", "omegaz", "tqx", "tqy", "tqz",
    ];

    fn parse(name: &str) -> Option<Self> {
        let axis = |c: char| "xyz".find(c);
        Some(match name {
            "id" => Field::Id,
            "type" => Field::Type,
            "mass" => Field::Mass,
            "radius" => Field::Radius,
            "diameter" => Field::Diameter,
            "x" | "y" | "z" => Field::X(axis(name.chars().next()?)?),
            "vx" | "vy" | "vz" => Field::V(axis(name.chars().nth(1)?)?),
            "fx" | "fy" | "fz" => Field::F(axis(name.chars().nth(1)?)?),
            "omegax" | "omegay" | "omegaz" => Field::Omega(axis(name.chars().nth(5)?)?),
            "tqx" | "tqy" | "tqz" => Field::Torque(axis(name.chars().nth(2)?)?),
            _ => return None,
        })
    }
}

/// A one-argument math function.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Fn1 {
    Sqrt,
    Exp,
    Ln,
    Log,
    Abs,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Ceil,
    Floor,
    Round,
}

impl Fn1 {
    fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "sqrt" => Fn1::Sqrt,
            "exp" => Fn1::Exp,
            "ln" => Fn1::Ln,
            "log" => Fn1::Log,
            "abs" => Fn1::Abs,
            "sin" => Fn1::Sin,
            "cos" => Fn1::Cos,
            "tan" => Fn1::Tan,
            "asin" => Fn1::Asin,
            "acos" => Fn1::Acos,
            "atan" => Fn1::Atan,
            "ceil" => Fn1::Ceil,
            "floor" => Fn1::Floor,
            "round" => Fn1::Round,
            _ => return None,
        })
    }

    /// The value; NaN where LIGGGHTS stops with an error (sqrt of a negative value, log of
    /// a value <= 0, asin outside [-1, 1]).
    fn apply(self, x: f64) -> f64 {
        match self {
            Fn1::Sqrt if x < 0.0 => f64::NAN,
            Fn1::Ln | Fn1::Log if x <= 0.0 => f64::NAN,
            Fn1::Asin | Fn1::Acos if !(-1.0..=1.0).contains(&x) => f64::NAN,
            Fn1::Sqrt => x.sqrt(),
            Fn1::Exp => x.exp(),
            Fn1::Ln => x.ln(),
            Fn1::Log => x.log10(),
            Fn1::Abs => x.abs(),
            Fn1::Sin => x.sin(),
            Fn1::Cos => x.cos(),
            Fn1::Tan => x.tan(),
            Fn1::Asin => x.asin(),
            Fn1::Acos => x.acos(),
            Fn1::Atan => x.atan(),
            Fn1::Ceil => x.ceil(),
            Fn1::Floor => x.floor(),
            Fn1::Round => x.round(),
        }
    }
}

/// A node of a prepared formula.
#[derive(Debug, Clone, PartialEq)]
enum Node {
    Num(f64),
    Field(Field),
    Neg(Box<Node>),
    Not(Box<Node>),
    Bin(BinOp, Box<Node>, Box<Node>),
    Call(Fn1, Box<Node>),
    Atan2(Box<Node>, Box<Node>),
}

/// An atom-style formula prepared for one step: per-particle fields and the arithmetic
/// over them.
#[derive(Debug, Clone, PartialEq)]
pub struct AtomFormula(Node);

/// The particle a formula is evaluated for: the engine's view, and the force pass's chunk
/// of forces and torques that starts at particle `lo`.
pub struct At<'a, 'v> {
    /// The particles.
    pub p: &'a View<'v>,
    /// Forces of particles `lo..`.
    pub f: &'a [DVec3],
    /// Torques of particles `lo..`.
    pub torque: &'a [DVec3],
    /// The first particle of the chunk.
    pub lo: usize,
}

impl AtomFormula {
    /// The atom-style variable `name` prepared for the coming step (call it at that step:
    /// the names that are not per-particle fields are evaluated now).
    pub fn prepare(sim: &Sim, name: &str) -> Result<Self, Error> {
        prepare_variable(sim, name, 0).map(AtomFormula)
    }

    /// The value, if the formula reads no per-particle field (the same for every particle).
    pub fn value_if_constant(&self) -> Option<f64> {
        match self.0 {
            Node::Num(v) => Some(v),
            _ => None,
        }
    }

    /// The value for particle `i`; NaN or an infinity where LIGGGHTS stops with an error
    /// (a division by zero, the square root of a negative value, ...): the caller checks.
    pub fn eval(&self, at: &At, i: usize) -> f64 {
        let p = at.p;
        eval(&self.0, &|f| match f {
            Field::Id => p.tag[i] as f64,
            Field::Type => p.ty[i] as f64,
            Field::Mass => p.rmass[i],
            Field::Radius => p.radius[i],
            Field::Diameter => 2.0 * p.radius[i],
            Field::X(a) => p.x[i][a],
            Field::V(a) => p.v[i][a],
            Field::F(a) => at.f[i - at.lo][a],
            Field::Omega(a) => p.omega[i][a],
            Field::Torque(a) => at.torque[i - at.lo][a],
        })
    }
}

fn prepare_variable(sim: &Sim, name: &str, depth: usize) -> Result<Node, Error> {
    if depth > MAX_DEPTH {
        return Err(Error::Loop("variables"));
    }
    match sim.script.vars.get(name) {
        Some(Variable::Atom(f)) => {
            let e = expr::parse(f).map_err(|e| Error::InVariable {
                name: name.to_string(),
                source: e,
            })?;
            prepare(sim, &e, depth).map_err(|e| e.within(format!("variable {name}")))
        }
        Some(_) => context::eval_name_equal(sim, &Name::Variable(name.to_string())).map(Node::Num),
        None => Err(Error::undefined("variable", name)),
    }
}

fn prepare(sim: &Sim, e: &Expr, depth: usize) -> Result<Node, Error> {
    let node = |e: &Expr| prepare(sim, e, depth).map(Box::new);
    let n = match e {
        Expr::Num(v) => Node::Num(*v),
        Expr::Name(Name::Keyword(k), _) => match Field::parse(k) {
            Some(f) => Node::Field(f),
            None if crate::atom_fields::is_field(k) => {
                return Err(format!(
                    "'{k}' cannot be read while the forces are summed; a force fix's formula \
                     can read {}",
                    Field::NAMES.join(" ")
                )
                .into())
            }
            None => Node::Num(context::eval_name_equal(sim, &Name::Keyword(k.clone()))?),
        },
        Expr::Name(Name::Variable(v), _) => prepare_variable(sim, v, depth + 1)?,
        // `c_ID[I]` of a per-atom vector is one atom's value, a number.
        Expr::Name(Name::Compute(id, idx), _)
            if sim.defs.computes.iter().any(|c| {
                c.id() == id && c.is_peratom() && !(idx.is_some() && c.indexes_atoms())
            }) =>
        {
            return Err(format!(
                "c_{id} is per-atom: a force fix's formula cannot use per-atom computes yet"
            )
            .into())
        }
        Expr::Name(Name::Fix(id, idx), _)
            if crate::fixes::is_peratom(sim, id)
                && !crate::fixes::has_global(sim, id)
                && !crate::fixes::indexes_atoms(sim, id, *idx) =>
        {
            return Err(format!(
                "f_{id} is per-atom: a force fix's formula cannot use per-atom fixes yet"
            )
            .into())
        }
        Expr::Name(n, _) => Node::Num(context::eval_name_equal(sim, n)?),
        Expr::Neg(x) => Node::Neg(node(x)?),
        Expr::Not(x) => Node::Not(node(x)?),
        Expr::Bin(op, a, b, _) => Node::Bin(*op, node(a)?, node(b)?),
        Expr::Call { name, args, .. } => {
            let arg = |k: usize| -> Result<Box<Node>, Error> {
                match args.get(k).and_then(|a| a.as_ref()) {
                    Some(a) => node(a),
                    None => Err(format!("{name}(): argument {} is not a formula", k + 1).into()),
                }
            };
            let want = |n: usize| -> Result<(), Error> {
                if args.len() == n {
                    Ok(())
                } else {
                    Err(format!("{name}() takes {n} argument(s), got {}", args.len()).into())
                }
            };
            match (Fn1::parse(name), name.as_str()) {
                (Some(f), _) => {
                    want(1)?;
                    Node::Call(f, arg(0)?)
                }
                (None, "atan2") => {
                    want(2)?;
                    Node::Atan2(arg(0)?, arg(1)?)
                }
                _ => {
                    return Err(format!(
                        "{name}() cannot be used in a force fix's formula (math functions can)"
                    )
                    .into())
                }
            }
        }
    };
    Ok(fold(n))
}

/// A node whose arguments are all numbers becomes a number.
fn fold(n: Node) -> Node {
    let constant = match &n {
        Node::Neg(x) | Node::Not(x) | Node::Call(_, x) => matches!(**x, Node::Num(_)),
        Node::Bin(_, a, b) | Node::Atan2(a, b) => {
            matches!(**a, Node::Num(_)) && matches!(**b, Node::Num(_))
        }
        _ => false,
    };
    if constant {
        Node::Num(eval(&n, &|_| {
            unreachable!("a constant node reads no field")
        }))
    } else {
        n
    }
}

fn truth(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

fn eval<F: Fn(Field) -> f64>(n: &Node, field: &F) -> f64 {
    match n {
        Node::Num(v) => *v,
        Node::Field(f) => field(*f),
        Node::Neg(x) => -eval(x, field),
        Node::Not(x) => truth(eval(x, field) == 0.0),
        Node::Bin(op, a, b) => {
            expr::binary(*op, eval(a, field), eval(b, field)).unwrap_or(f64::NAN)
        }
        Node::Call(f, x) => f.apply(eval(x, field)),
        Node::Atan2(a, b) => eval(a, field).atan2(eval(b, field)),
    }
}

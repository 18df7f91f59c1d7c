//! Formulas evaluated against the simulation: thermo keywords, `v_`, `c_`, `f_`
//! references, atom values by ID (`x[12]`), group functions, and atom-style formulas
//! evaluated for every owned particle.

use crate::error::Error;
use std::collections::HashMap;

use rdem::World;

use crate::args::NumOrVar;
use crate::atom_fields;
use crate::expr::{self, Context, Name};
use crate::sim::Sim;
use crate::variables::Variable;

/// Deepest chain of variables referring to variables (a loop is an error).
const MAX_DEPTH: usize = 64;

/// Evaluation context over a [`Sim`]; with `atom` set, names are per particle.
pub struct Ctx<'a> {
    sim: &'a Sim,
    depth: usize,
    /// Particle index and per-atom cache, for atom-style evaluation.
    atom: Option<(usize, &'a mut HashMap<String, Vec<f64>>)>,
}

fn world(sim: &Sim) -> Result<&World, Error> {
    sim.world.as_ref().ok_or(Error::NoBox)
}

/// Evaluates an equal-style formula.
pub fn eval_equal(sim: &Sim, formula: &str) -> Result<f64, expr::ExprError> {
    let e = expr::parse(formula)?;
    expr::eval(
        &e,
        &mut Ctx {
            sim,
            depth: 0,
            atom: None,
        },
    )
}

/// The equal-style variables `names` (`None`: no variable, `None` back) evaluated as at
/// step `step`: the world's step is set for the evaluation and restored after it. For
/// the values a fix takes before a step (`fix gravity`, `fix move variable`), which
/// LAMMPS evaluates with the step counter already on the coming step. Errors name the
/// fix `who`; `hint` follows the message for a variable of another style. Stops at the
/// first error.
pub fn eval_equal_at(
    sim: &mut Sim,
    step: u64,
    names: &[Option<&str>],
    who: &str,
    hint: &str,
) -> Result<Vec<Option<f64>>, Error> {
    at_step(sim, step, who, |sim| {
        names
            .iter()
            .map(|name| {
                let Some(name) = name else { return Ok(None) };
                match sim.script.vars.get(name) {
                    Some(Variable::Equal(f)) => eval_equal(sim, f)
                        .map(Some)
                        .map_err(|e| Error::invalid(format!("variable {name}: {}", e.message))),
                    Some(_) => Err(Error::invalid(format!(
                        "{who}: variable '{name}' is not equal-style{hint}"
                    ))),
                    None => Err(Error::undefined("variable", *name).within(who)),
                }
            })
            .collect()
    })?
}

/// The values of a fix's `number | NULL | v_name` arguments at step `step`: numbers as
/// they are, `NULL` as `None`, variables evaluated as [`eval_equal_at`] does.
pub fn values_at(
    sim: &mut Sim,
    step: u64,
    values: &[&NumOrVar],
    who: &str,
    hint: &str,
) -> Result<Vec<Option<f64>>, Error> {
    let names: Vec<Option<&str>> = values.iter().map(|v| v.var()).collect();
    let vars = eval_equal_at(sim, step, &names, who, hint)?;
    Ok(values
        .iter()
        .zip(vars)
        .map(|(v, x)| v.num().or(x))
        .collect())
}

/// `f` run with the world's step set to `step` (restored after it), so that what reads
/// the step (variables, moving regions) sees the coming step. Errors if there is no
/// box yet (`who` names the asker).
pub fn at_step<T>(
    sim: &mut Sim,
    step: u64,
    who: &str,
    f: impl FnOnce(&mut Sim) -> T,
) -> Result<T, Error> {
    let w = sim
        .world
        .as_mut()
        .ok_or_else(|| Error::NeedsBox(who.to_string()))?;
    let now = std::mem::replace(&mut w.step, step);
    let out = f(sim);
    sim.world.as_mut().expect("checked").step = now;
    Ok(out)
}

/// The equal-style variable `name` at full precision (a moving region's displacement
/// or angle, which LAMMPS takes as a number, not as text), evaluated `depth` levels
/// down a chain of references.
pub(crate) fn equal_variable(sim: &Sim, name: &str, depth: usize) -> Result<f64, Error> {
    if depth > MAX_DEPTH {
        return Err(Error::Loop("variables and regions"));
    }
    match sim.script.vars.get(name) {
        None => Err(Error::undefined("variable", name)),
        Some(Variable::Equal(f)) => {
            let e = expr::parse(f).map_err(|e| Error::InVariable {
                name: name.to_string(),
                source: e,
            })?;
            expr::eval(
                &e,
                &mut Ctx {
                    sim,
                    depth: depth + 1,
                    atom: None,
                },
            )
            .map_err(|e| Error::InVariable {
                name: name.to_string(),
                source: e,
            })
        }
        Some(_) => Err(format!("variable '{name}' is not equal-style").into()),
    }
}

/// The value of one name as an equal-style formula would give it (a thermo keyword,
/// `PI`, an equal-style variable rounded as LIGGGHTS passes it, a global value of a
/// compute or fix, `x[ID]`).
pub fn eval_name_equal(sim: &Sim, name: &expr::Name) -> Result<f64, Error> {
    let e = expr::Expr::Name(name.clone(), 0..0);
    let mut ctx = Ctx {
        sim,
        depth: 0,
        atom: None,
    };
    expr::eval(&e, &mut ctx).map_err(|e| Error::from(e.message))
}

/// Text of `${name}` / `$x`.
pub fn variable_text(sim: &Sim, name: &str) -> Result<String, Error> {
    sim.script.vars.text(
        name,
        &mut Ctx {
            sim,
            depth: 0,
            atom: None,
        },
    )
}

/// Evaluates an atom-style formula for every owned particle.
pub fn eval_atom(sim: &Sim, formula: &str) -> Result<Vec<f64>, Error> {
    let mut cache = HashMap::new();
    eval_atom_depth(sim, formula, 0, &mut cache)
}

fn eval_atom_depth(
    sim: &Sim,
    formula: &str,
    depth: usize,
    cache: &mut HashMap<String, Vec<f64>>,
) -> Result<Vec<f64>, Error> {
    let w = world(sim)?;
    let e = expr::parse(formula).map_err(|e| e.message)?;
    let n = w.particles.nlocal();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut ctx = Ctx {
            sim,
            depth,
            atom: Some((i, &mut *cache)),
        };
        out.push(expr::eval(&e, &mut ctx).map_err(|e| e.message)?);
    }
    Ok(out)
}

fn find_compute<'s>(sim: &'s Sim, id: &str) -> Result<&'s crate::computes::Compute, Error> {
    sim.defs
        .computes
        .iter()
        .find(|c| c.id() == id)
        .ok_or_else(|| Error::undefined("compute", id))
}

/// Per-atom values of a compute (column `col`, 1-based, for array computes).
pub fn compute_peratom(sim: &Sim, id: &str, col: Option<usize>) -> Result<Vec<f64>, Error> {
    world(sim)?;
    let c = find_compute(sim, id)?;
    c.imp.peratom(sim, &c.head, col)
}

/// Global value of a compute: its scalar, or element `idx` (1-based) of its vector.
pub fn compute_global(sim: &Sim, id: &str, idx: Option<usize>) -> Result<f64, Error> {
    world(sim)?;
    let c = find_compute(sim, id)?;
    c.imp.global(sim, &c.head, idx)
}

/// The value of atom `tag` among `values` (one per owned particle), on every rank: the
/// owner's value, summed over the ranks. `what` names the reference in the error.
fn value_of_atom(sim: &Sim, values: &[f64], tag: u64, what: &str) -> Result<f64, Error> {
    let w = world(sim)?;
    let i = w.particles.find_tag(tag);
    if w.comm.sum_count(i.is_some() as u64) == 0 {
        return Err(format!("{what}: no atom with ID {tag}").into());
    }
    Ok(w.comm.sum(i.map_or(0.0, |i| values[i])))
}

impl Ctx<'_> {
    /// `random(lo, hi, seed)`: the next number of the script's RANMAR generator (seeded
    /// by the first call's seed), scaled to [lo, hi), as LIGGGHTS' equal-style formulas
    /// give it. Atom-style formulas (one number per atom) are not supported yet.
    fn random(&mut self, raw: &[String]) -> Result<f64, Error> {
        if self.atom.is_some() {
            return Err(
                "random() in an atom-style variable is not supported yet (equal-style only)".into(),
            );
        }
        let [lo, hi, seed] = raw else {
            return Err(format!(
                "random() takes 3 arguments (lower, upper, seed), not {}",
                raw.len()
            )
            .into());
        };
        let mut value = |s: &String| -> Result<f64, Error> {
            let e = expr::parse(s.trim()).map_err(|e| Error::from(e.message.clone()))?;
            expr::eval(&e, self).map_err(|e| Error::from(e.message.clone()))
        };
        let (lo, hi, seed) = (value(lo)?, value(hi)?, value(seed)?);
        let mut rng = self
            .sim
            .script
            .random_equal
            .lock()
            .map_err(|_| "random(): the generator is poisoned")?;
        if rng.is_none() {
            let s = seed as i64;
            if seed.fract() != 0.0 || s <= 0 {
                return Err(
                    format!("random(): the seed must be a positive integer, not {seed}").into(),
                );
            }
            *rng = Some(
                crate::ranmars::RanMars::new(s)
                    .ok_or_else(|| format!("random(): the seed {s} must be below 900000000"))?,
            );
        }
        let u = rng.as_mut().map_or(0.0, |r| r.uniform());
        Ok(u * (hi - lo) + lo)
    }

    fn group(&self, g: &str) -> Result<u32, Error> {
        self.sim
            .defs
            .groups
            .find(g)
            .map(|k| 1u32 << k)
            .ok_or_else(|| Error::undefined("group", g))
    }

    fn atom_vector(
        &mut self,
        key: &str,
        make: impl FnOnce(&Sim, usize) -> Result<Vec<f64>, Error>,
    ) -> Result<f64, Error> {
        let sim = self.sim;
        let depth = self.depth;
        let (i, cache) = self.atom.as_mut().expect("atom context");
        if !cache.contains_key(key) {
            let v = make(sim, depth)?;
            cache.insert(key.to_string(), v);
        }
        Ok(cache[key][*i])
    }
}

impl Context for Ctx<'_> {
    fn name(&mut self, name: &Name) -> Result<f64, Error> {
        if self.depth > MAX_DEPTH {
            return Err(Error::Loop("variables"));
        }
        let sim = self.sim;
        match name {
            Name::Keyword(k) => {
                if self.atom.is_some() && atom_fields::is_field(k) {
                    let w = world(sim)?;
                    let i = self.atom.as_ref().map(|a| a.0).unwrap_or(0);
                    return atom_fields::value(w, k, i)
                        .ok_or_else(|| Error::invalid(format!("bad field {k}")));
                }
                crate::thermo::keyword(sim, k)
            }
            Name::Variable(v) => match sim.script.vars.get(v) {
                None => Err(Error::undefined("variable", v)),
                Some(Variable::Equal(f)) => {
                    let e = expr::parse(f).map_err(|e| Error::InVariable {
                        name: v.to_string(),
                        source: e,
                    })?;
                    let depth = self.depth + 1;
                    match self.atom.as_mut() {
                        Some((i, cache)) => {
                            let mut c = Ctx {
                                sim,
                                depth,
                                atom: Some((*i, &mut **cache)),
                            };
                            expr::eval(&e, &mut c)
                        }
                        None => expr::eval(
                            &e,
                            &mut Ctx {
                                sim,
                                depth,
                                atom: None,
                            },
                        ),
                    }
                    .map_err(|e| Error::InVariable {
                        name: v.to_string(),
                        source: e,
                    })
                    // LIGGGHTS passes an equal-style variable into a formula as its text,
                    // `%.15g`: v_a with a = 1/3 is 0.333333333333333.
                    .map(|x| {
                        crate::args::parse_f64(&crate::variables::format_g(x, 15)).unwrap_or(x)
                    })
                }
                Some(Variable::Atom(f)) => {
                    if self.atom.is_none() {
                        return Err(format!(
                            "atom-style variable '{v}' used where one number is needed"
                        )
                        .into());
                    }
                    let f = f.clone();
                    self.atom_vector(&format!("v_{v}"), |s, d| {
                        let mut cache = HashMap::new();
                        eval_atom_depth(s, &f, d + 1, &mut cache)
                    })
                }
                Some(_) => {
                    let t = variable_text(sim, v)?;
                    crate::args::parse_f64(t.trim()).ok_or_else(|| {
                        Error::invalid(format!("variable '{v}' is '{t}', not a number"))
                    })
                }
            },
            Name::Compute(id, idx) => {
                let c = sim
                    .defs
                    .computes
                    .iter()
                    .find(|c| c.id() == id)
                    .ok_or_else(|| Error::undefined("compute", id))?;
                // `c_ID[I]` of a per-atom vector with no global vector: atom I's value,
                // in any formula (LAMMPS' rule).
                if let (Some(tag), true) = (idx, c.indexes_atoms()) {
                    let values = compute_peratom(sim, id, None)?;
                    return value_of_atom(sim, &values, *tag as u64, &format!("c_{id}[{tag}]"));
                }
                if c.is_peratom() {
                    if self.atom.is_none() {
                        return Err(format!(
                            "compute {id} is per-atom: use it in an atom-style variable or reduce it"
                        ).into());
                    }
                    let (id, idx) = (id.clone(), *idx);
                    let key = format!("c_{id}[{idx:?}]");
                    self.atom_vector(&key, |s, _| compute_peratom(s, &id, idx))
                } else {
                    compute_global(sim, id, *idx)
                }
            }
            Name::Fix(id, Some(tag)) if crate::fixes::indexes_atoms(sim, id, Some(*tag)) => {
                // `f_ID[I]` of a per-atom vector: atom I's value.
                let values = crate::fixes::fix_peratom(sim, id, None)?;
                value_of_atom(sim, &values, *tag as u64, &format!("f_{id}[{tag}]"))
            }
            Name::ComputeAt(id, tag, col) => {
                let c = find_compute(sim, id)?;
                if c.peratom_cols() == 0 {
                    return Err(format!(
                        "c_{id}[{tag}][{col}]: compute {id} has no per-atom array (two indices pick an atom and a column of one)"
                    )
                    .into());
                }
                let values = compute_peratom(sim, id, Some(*col))?;
                value_of_atom(sim, &values, *tag, &format!("c_{id}[{tag}][{col}]"))
            }
            Name::FixAt(id, tag, col) => {
                if !matches!(crate::fixes::peratom_cols(sim, id), Some(n) if n > 0) {
                    return Err(format!(
                        "f_{id}[{tag}][{col}]: fix {id} has no per-atom array (two indices pick an atom and a column of one)"
                    )
                    .into());
                }
                let values = crate::fixes::fix_peratom(sim, id, Some(*col))?;
                value_of_atom(sim, &values, *tag, &format!("f_{id}[{tag}][{col}]"))
            }
            Name::Fix(id, idx)
                if crate::fixes::is_peratom(sim, id) && !crate::fixes::has_global(sim, id) =>
            {
                if self.atom.is_none() {
                    return Err(format!(
                        "fix {id} is per-atom: use it in an atom-style variable or reduce it"
                    )
                    .into());
                }
                let (id, idx) = (id.clone(), *idx);
                let key = format!("f_{id}[{idx:?}]");
                self.atom_vector(&key, |s, _| crate::fixes::fix_peratom(s, &id, idx))
            }
            Name::Fix(id, idx) => crate::fixes::fix_value(sim, id, *idx),
            Name::VariableAt(v, tag) => {
                let f = match sim.script.vars.get(v) {
                    None => return Err(Error::undefined("variable", v)),
                    Some(Variable::Atom(f)) => f.clone(),
                    Some(_) => {
                        return Err(format!(
                            "v_{v}[{tag}]: '{v}' is not an atom-style variable (an index picks one atom's value of an atom-style variable)"
                        )
                        .into())
                    }
                };
                // Every rank evaluates the whole vector (its formula may sum over
                // ranks), then takes the owner's value, as LAMMPS does.
                let values = eval_atom_depth(sim, &f, self.depth + 1, &mut HashMap::new())?;
                value_of_atom(sim, &values, *tag, &format!("v_{v}[{tag}]"))
            }
            Name::Atom(field, tag) => {
                let w = world(sim)?;
                // The owner's value, on every rank.
                if !atom_fields::NAMES.contains(&field.as_str()) {
                    return Err(format!(
                        "unknown atom value '{field}' (valid: {})",
                        atom_fields::NAMES.join(" ")
                    )
                    .into());
                }
                let i = w.particles.find_tag(*tag);
                let here = i
                    .and_then(|i| atom_fields::value(w, field, i))
                    .unwrap_or(0.0);
                let found = w.comm.sum_count(i.is_some() as u64);
                if found == 0 {
                    return Err(format!("{field}[{tag}]: no atom with ID {tag}").into());
                }
                Ok(w.comm.sum(here))
            }
        }
    }

    fn function(&mut self, name: &str, raw: &[String]) -> Result<Option<f64>, Error> {
        if name == "random" {
            return self.random(raw).map(Some);
        }
        const GROUP_FNS: [&str; 6] = ["count", "mass", "xcm", "vcm", "bound", "ke"];
        if !GROUP_FNS.contains(&name) {
            return Ok(None);
        }
        let w = world(self.sim)?;
        let p = &w.particles;
        let g = self.group(raw.first().map(|s| s.trim()).unwrap_or(""))?;
        // The region form: one more argument, the region (placed at the current step if
        // it moves).
        let plain = if matches!(name, "count" | "mass" | "ke") {
            1
        } else {
            2
        };
        let region = match raw.get(plain) {
            Some(r) if raw.len() == plain + 1 => {
                let r = r.trim();
                if !self.sim.defs.regions.contains_key(r) {
                    return Err(Error::undefined("region", r).within(format!("{name}()")));
                }
                Some(crate::regions::posed(self.sim, r, self.depth + 1)?)
            }
            _ => None,
        };
        let sel: Vec<usize> = (0..p.nlocal())
            .filter(|&i| p.mask[i] & g != 0)
            .filter(|&i| region.as_ref().is_none_or(|r| r.contains(p.x[i])))
            .collect();
        let nargs = if region.is_some() {
            raw.len() - 1
        } else {
            raw.len()
        };
        let dim = |s: Option<&String>| -> Result<usize, Error> {
            match s.map(|s| s.trim()) {
                Some("x") => Ok(0),
                Some("y") => Ok(1),
                Some("z") => Ok(2),
                other => {
                    Err(format!("{name}(): dimension must be x, y or z, not {other:?}").into())
                }
            }
        };
        let mass: f64 = w.comm.sum(sel.iter().map(|&i| p.rmass[i]).sum()) + 0.0;
        let weighted = |f: &dyn Fn(usize) -> f64| -> f64 {
            let s = w.comm.sum(sel.iter().map(|&i| p.rmass[i] * f(i)).sum());
            if mass > 0.0 {
                s / mass
            } else {
                0.0
            }
        };
        Ok(Some(match (name, nargs) {
            ("count", 1) => w.comm.sum_count(sel.len() as u64) as f64,
            ("mass", 1) => mass,
            ("ke", 1) => {
                let e: f64 = sel
                    .iter()
                    .map(|&i| 0.5 * p.rmass[i] * p.v[i].length_squared())
                    .sum();
                w.comm.sum(e) + 0.0
            }
            ("xcm", 2) => {
                let a = dim(raw.get(1))?;
                let size = w.domain.boxhi - w.domain.boxlo;
                weighted(&|i| p.x[i][a] + p.image[i].get()[a] as f64 * size[a])
            }
            ("vcm", 2) => {
                let a = dim(raw.get(1))?;
                weighted(&|i| p.v[i][a])
            }
            ("bound", 2) => {
                let which = raw[1].trim();
                let (a, lo) = match which {
                    "xmin" => (0, true),
                    "xmax" => (0, false),
                    "ymin" => (1, true),
                    "ymax" => (1, false),
                    "zmin" => (2, true),
                    "zmax" => (2, false),
                    _ => {
                        return Err(
                            format!("bound(): '{which}' is not xmin, xmax, ..., zmax").into()
                        )
                    }
                };
                // An empty group gives ±1e20, as LIGGGHTS prints it (its `BIG`).
                const BIG: f64 = 1e20;
                if lo {
                    w.comm
                        .min(sel.iter().map(|&i| p.x[i][a]).fold(BIG, f64::min))
                } else {
                    w.comm
                        .max(sel.iter().map(|&i| p.x[i][a]).fold(-BIG, f64::max))
                }
            }
            _ => {
                return Err(format!(
                    "{name}() takes {} argument(s)",
                    if matches!(name, "count" | "mass" | "ke") {
                        "1 (a group) or 2 (group, region)"
                    } else {
                        "2 (group, dimension) or 3 (group, dimension, region)"
                    }
                )
                .into())
            }
        }))
    }
}

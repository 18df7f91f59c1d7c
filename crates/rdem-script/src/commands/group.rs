//! `group`: named sets of particles (at most 32, `all` included).

use crate::args::{Args, CmdResult};
use crate::sim::Sim;

pub(super) fn group(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let name = a.word("group ID")?.to_string();
    const STYLES: [&str; 8] = [
        "region",
        "type",
        "id",
        "variable",
        "union",
        "subtract",
        "intersect",
        "delete",
    ];
    let style = a.keyword("group style", &STYLES)?;
    if style == "delete" {
        a.done()?;
        let k = sim
            .defs
            .groups
            .find(&name)
            .ok_or_else(|| a.error_at(1, format!("no group '{name}'"), None))?;
        if k == 0 {
            return Err(a.error_at(1, "group all cannot be deleted", None));
        }
        if let Some(w) = &mut sim.world {
            for m in &mut w.particles.mask {
                *m &= !(1u32 << k);
            }
        }
        sim.defs.groups.delete(k);
        return Ok(());
    }
    if name == "all" {
        return Err(a.error_at(1, "group all cannot be changed", None));
    }
    let n = sim.world_ref(a)?.particles.nlocal();
    let sel: Vec<bool> = match style {
        "region" => {
            let r = sim.region(a)?;
            a.done()?;
            let p = &sim.world.as_ref().expect("checked").particles;
            (0..n).map(|i| r.contains(p.x[i])).collect()
        }
        "type" | "id" => {
            let w = sim.world.as_ref().expect("checked");
            let values: Vec<u64> = if style == "type" {
                w.particles.ty[..n].iter().map(|&t| t as u64).collect()
            } else {
                w.particles.tag[..n].to_vec()
            };
            let test = value_test(a, style)?;
            values.iter().map(|&v| test.holds(v)).collect()
        }
        "variable" => {
            let at = a.pos();
            let name = a.word("atom-style variable name")?;
            a.done()?;
            match sim.script.vars.get(name) {
                Some(crate::variables::Variable::Atom(f)) => {
                    let f = f.clone();
                    let v = crate::context::eval_atom(sim, &f)
                        .map_err(|e| a.error_at(at, e.to_string(), None))?;
                    v.iter().map(|&x| x != 0.0).collect()
                }
                Some(_) => {
                    return Err(a.error_at(
                        at,
                        format!("group variable: '{name}' is not an atom-style variable"),
                        Some("define it with 'variable NAME atom FORMULA'".into()),
                    ))
                }
                None => {
                    return Err(a.error_at(at, format!("no variable '{name}'"), None));
                }
            }
        }
        _ => {
            let mut bits = Vec::new();
            while !a.is_done() {
                bits.push(sim.group_bit(a, "group ID")?);
            }
            if bits.is_empty() {
                return Err(a.error_at(
                    a.pos(),
                    format!("group {style}: needs at least one group"),
                    None,
                ));
            }
            let p = &sim.world.as_ref().expect("checked").particles;
            (0..n)
                .map(|i| {
                    let m = p.mask[i];
                    match style {
                        "union" => bits.iter().any(|b| m & b != 0),
                        "intersect" => bits.iter().all(|b| m & b != 0),
                        _ => m & bits[0] != 0 && bits[1..].iter().all(|b| m & b == 0),
                    }
                })
                .collect()
        }
    };
    let k = sim
        .defs
        .groups
        .find_or_create(&name)
        .map_err(|m| a.error_at(1, m, None))?;
    let w = sim.world.as_mut().expect("checked");
    let mut count = 0;
    for (i, s) in sel.iter().enumerate() {
        if *s {
            w.particles.mask[i] |= 1 << k;
        }
        if w.particles.mask[i] & (1 << k) != 0 {
            count += 1;
        }
    }
    let count = w.comm.sum_count(count);
    sim.outputs
        .out
        .line(&format!("{count} atoms in group {name}"));
    Ok(())
}

/// Which values (types or IDs) a `group type|id` command selects: a list of values and
/// sequences `A:B[:C]`, or one logical (`<`, `<=`, `>`, `>=`, `==`, `!=` with a value,
/// `<>` with two, inclusive), as LIGGGHTS' group command reads them.
enum ValueTest {
    /// Inclusive ranges `(lo, hi, step)`; a single value is `(v, v, 1)`.
    List(Vec<(u64, u64, u64)>),
    /// A comparison with `value`.
    Logical(&'static str, u64, u64),
}

impl ValueTest {
    fn holds(&self, v: u64) -> bool {
        match self {
            ValueTest::List(r) => r
                .iter()
                .any(|&(lo, hi, step)| v >= lo && v <= hi && (v - lo) % step == 0),
            ValueTest::Logical(op, x, y) => match *op {
                "<" => v < *x,
                "<=" => v <= *x,
                ">" => v > *x,
                ">=" => v >= *x,
                "==" => v == *x,
                "!=" => v != *x,
                _ => v >= *x && v <= *y,
            },
        }
    }
}

/// The logicals of `group type|id`.
const LOGICALS: [&str; 7] = ["<", "<=", ">", ">=", "==", "!=", "<>"];

/// Reads the rest of a `group type|id` command.
fn value_test(a: &mut Args, style: &str) -> CmdResult<ValueTest> {
    if a.is_done() {
        return Err(a.error_at(a.pos(), format!("group {style}: missing values"), None));
    }
    let what = if style == "type" {
        "atom type"
    } else {
        "atom ID"
    };
    if let Some(op) = a.peek().and_then(|w| LOGICALS.iter().find(|&&l| l == w)) {
        a.seek(a.pos() + 1);
        let x = a.u64(what)?;
        let y = if *op == "<>" {
            let y = a.u64(what)?;
            if y < x {
                return Err(a.error_prev(
                    format!("group {style} <>: the upper value {y} is below the lower {x}"),
                    None,
                ));
            }
            y
        } else {
            x
        };
        a.done()?;
        if *op == "!=" {
            // Measured: LIGGGHTS 3.8's `!=` selects the atoms whose value *equals* x.
            a.warn_at(
                a.pos() - 2,
                "'!=' selects the values that differ, as the manual says; \
                 LIGGGHTS 3.8 selects the equal ones instead",
            );
        }
        return Ok(ValueTest::Logical(op, x, y));
    }
    let mut ranges = Vec::new();
    while let Some(spec) = a.peek() {
        let at = a.pos();
        let parts: Vec<&str> = spec.split(':').collect();
        let nums: Option<Vec<u64>> = parts.iter().map(|p| a.integer_in(at, p)).collect();
        let range = match (parts.len(), nums) {
            (1, Some(v)) => (v[0], v[0], 1),
            (2, Some(v)) => (v[0], v[1], 1),
            (3, Some(v)) if v[2] > 0 => (v[0], v[1], v[2]),
            _ => {
                let help = format!(
                    "write {what}s, sequences A:B or A:B:C (C > 0), or one logical: {}",
                    LOGICALS.join(" ")
                );
                return Err(a.error_at(
                    at,
                    format!("'{spec}' is not a number or range a:b"),
                    Some(help),
                ));
            }
        };
        ranges.push(range);
        a.seek(at + 1);
    }
    Ok(ValueTest::List(ranges))
}

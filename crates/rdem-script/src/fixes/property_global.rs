//! `fix ID all property/global NAME style values...`: a named table of material or model
//! values (`scalar`, `vector`, `peratomtype`, `peratomtypepair`, `matrix`) that the
//! contact models, bonds and wear read by name when a run starts.

use super::{count_error, plural, style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::{Property, Sim};

/// The registry row.
pub(super) const ROW: FixRow = style(
    "property/global",
    parse,
    Stages::VALUES,
    "`scalar`, `vector`, `peratomtype`, `peratomtypepair`",
);

/// A defined property: its values live in `Sim::properties` under `name`.
pub struct PropertyGlobal {
    name: String,
    parsed: Option<Property>,
}

impl ScriptFix for PropertyGlobal {
    fn install(&mut self, sim: &mut Sim, _a: &Args, _head: &FixHead) -> CmdResult<()> {
        if let Some(p) = self.parsed.take() {
            sim.defs.properties.insert(self.name.clone(), p);
        }
        Ok(())
    }

    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(sim.defs.properties[&self.name].values.clone())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        sim.defs.properties.remove(&self.name);
    }
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let id = head.id.as_str();
    let name = a.word("property name")?.to_string();
    let style = a.keyword(
        "property style",
        &[
            "scalar",
            "vector",
            "peratomtype",
            "peratomtypepair",
            "matrix",
            "atomtype",
            "atomtypepair",
        ],
    )?;
    let style = match style {
        "atomtype" => "peratomtype",
        "atomtypepair" => "peratomtypepair",
        s => s,
    };
    let mut values = Vec::new();
    if style == "peratomtypepair" || style == "matrix" {
        let n = a.count("number of atom types")? as usize;
        if style == "peratomtypepair" && sim.ntypes() > 0 && n != sim.ntypes() {
            return Err(a.error_prev(
                format!("{name}: {n} types given but the box has {}", sim.ntypes()),
                None,
            ));
        }
        let start = a.pos();
        while !a.is_done() {
            values.push(a.f64(&format!("{name} value"))?);
        }
        if style == "peratomtypepair" && values.len() != n * n {
            return Err(count_error(
                a,
                start,
                n * n,
                values.len(),
                format!(
                    "{name} peratomtypepair {n} needs {}, got {}",
                    plural(n * n, "value"),
                    values.len()
                ),
                format!(
                    "peratomtypepair N takes N*N values, one per pair of atom types ({}*{} = {})",
                    n,
                    n,
                    n * n
                ),
            ));
        }
    } else {
        let start = a.pos();
        while !a.is_done() {
            values.push(a.f64(&format!("{name} value"))?);
        }
        if values.is_empty() {
            return Err(a.error_at(a.pos(), format!("{name}: no values given"), None));
        }
        if style == "scalar" && values.len() != 1 {
            return Err(count_error(
                a,
                start,
                1,
                values.len(),
                format!("{name} scalar takes one value, got {}", values.len()),
                "use 'vector' for several values".into(),
            ));
        }
        if style == "peratomtype" && sim.ntypes() > 0 && values.len() != sim.ntypes() {
            return Err(count_error(
                a,
                start,
                sim.ntypes(),
                values.len(),
                format!(
                    "{name}: {} given but the box has {}",
                    plural(values.len(), "value"),
                    plural(sim.ntypes(), "atom type")
                ),
                "peratomtype takes one value per atom type".into(),
            ));
        }
    }
    Ok(Box::new(PropertyGlobal {
        name,
        parsed: Some(Property {
            style: style.to_string(),
            values,
            fix_id: id.to_string(),
        }),
    }))
}

//! `dump`, `dump_modify`, `undump` and `write_dump`: which particles and columns are written
//! when; the file formats themselves are in `rdem-io`.

use rdem_io::{Column, DumpFileName, Sort, TextDump, TextOptions, VtkDump};

use crate::args::{suggest, Args, CmdResult};
use crate::context;
use crate::sim::Sim;
use crate::thermo::split_reference;
use crate::variables::Variable;

/// Dump styles rdem writes.
pub const STYLES: [&str; 2] = ["custom", "custom/vtk"];

/// LIGGGHTS dump styles of later releases.
const LATER: [&str; 6] = [
    "atom/vtk",
    "euler/vtk",
    "mesh/stl",
    "mesh/gran/VTK",
    "local/gran/vtk",
    "atom",
];

/// The writer of a dump.
pub enum Writer {
    /// `dump custom`.
    Text(TextDump),
    /// `dump custom/vtk`.
    Vtk(VtkDump),
}

/// One dump.
pub struct Dump {
    /// Dump ID.
    pub id: String,
    /// Group bit mask.
    pub groupbit: u32,
    /// Every this many steps.
    pub every: u64,
    /// Column arguments as written.
    pub columns: Vec<String>,
    /// The writer.
    pub writer: Writer,
    /// Step of the last snapshot.
    pub last: Option<u64>,
}

/// Checks a column argument: a field, or `c_`/`f_`/`v_` of a per-atom quantity.
fn check_column(sim: &Sim, a: &Args, k: usize, arg: &str) -> CmdResult {
    if Column::field(arg).is_some() {
        return Ok(());
    }
    match split_reference(arg) {
        Some(('c', id, col)) => match sim.computes.iter().find(|c| c.id == id) {
            Some(c) if c.is_peratom() => {
                let n = c.peratom_cols();
                match col {
                    None if n == 0 => Ok(()),
                    Some(j) if n > 0 && j >= 1 && j <= n => Ok(()),
                    _ => Err(a.error_at(
                        k,
                        format!("'{arg}' does not match compute {id}'s columns"),
                        None,
                    )),
                }
            }
            Some(_) => Err(a.error_at(
                k,
                format!("compute {id} is not per-atom"),
                Some("a dump column needs a per-atom compute (property/atom, contact/atom)".into()),
            )),
            None => {
                let ids: Vec<&str> = sim.computes.iter().map(|c| c.id.as_str()).collect();
                Err(a.error_at(
                    k,
                    format!("no compute '{id}'"),
                    Some(crate::commands::id_help("compute", id, &ids)),
                ))
            }
        },
        Some(('v', id, None)) => match sim.vars.get(id) {
            Some(Variable::Atom(_)) => Ok(()),
            Some(_) => Err(a.error_at(
                k,
                format!("variable {id} is not atom-style"),
                Some(format!(
                    "a dump column needs a value per particle: define 'variable {id} atom FORMULA'"
                )),
            )),
            None => Err(a.error_at(
                k,
                format!("no variable '{id}'"),
                Some(crate::commands::id_help("variable", id, &sim.vars.names())),
            )),
        },
        _ => Err(a.error_at(
            k,
            format!("unknown dump column '{arg}'"),
            Some(suggest(arg, &rdem_io::Field::NAMES)),
        )),
    }
}

fn columns(sim: &Sim, args: &[String]) -> Result<Vec<Column>, String> {
    args.iter()
        .map(|arg| {
            if let Some(c) = Column::field(arg) {
                return Ok(c);
            }
            let values = match split_reference(arg) {
                Some(('c', id, col)) => context::compute_peratom(sim, id, col)?,
                Some(('v', id, None)) => match sim.vars.get(id) {
                    Some(Variable::Atom(f)) => context::eval_atom(sim, f)?,
                    _ => return Err(format!("variable {id} is not atom-style")),
                },
                _ => return Err(format!("bad dump column '{arg}'")),
            };
            Ok(Column::Custom {
                name: arg.clone(),
                values,
            })
        })
        .collect()
}

/// Writes every dump due at `step` (at set-up: also dumps that never wrote).
pub fn write_due(sim: &mut Sim, step: u64, setup: bool) -> Result<(), String> {
    for k in 0..sim.dumps.len() {
        let d = &sim.dumps[k];
        let due = (step % d.every == 0 || (setup && d.last.is_none())) && d.last != Some(step);
        if due {
            write_one(sim, k, step)?;
        }
    }
    Ok(())
}

fn write_one(sim: &mut Sim, k: usize, step: u64) -> Result<(), String> {
    let cols = columns(sim, &sim.dumps[k].columns)?;
    let Some(w) = &sim.world else {
        return Err("dump before the simulation box is defined".into());
    };
    let sel = rdem_io::fields::group_selection(&w.particles, sim.dumps[k].groupbit);
    let d = &mut sim.dumps[k];
    match &mut d.writer {
        Writer::Text(t) => t
            .write(step, &w.particles, &w.domain, &sel, &cols)
            .map(|_| ())
            .map_err(|e| format!("dump {}: {e}", d.id))?,
        Writer::Vtk(v) => v
            .write(step, &w.particles, &w.domain, &sel, &cols)
            .map(|_| ())
            .map_err(|e| format!("dump {}: {e}", d.id))?,
    }
    d.last = Some(step);
    Ok(())
}

fn dump_style(a: &mut Args) -> CmdResult<&'static str> {
    let style_word = a.word("dump style")?;
    match STYLES.iter().copied().find(|s| *s == style_word) {
        Some(s) => Ok(s),
        None if LATER.contains(&style_word) => Err(a.error_prev(
            format!("dump {style_word} is not supported by this rdem release yet"),
            Some(format!("supported: {}", STYLES.join(", "))),
        )),
        None => Err(a.error_prev(
            format!("unknown dump style '{style_word}'"),
            Some(suggest(style_word, &STYLES)),
        )),
    }
}

fn read_columns(sim: &Sim, a: &mut Args) -> CmdResult<Vec<String>> {
    let mut cols = Vec::new();
    while let Some(w) = a.peek() {
        if w == "modify" {
            break;
        }
        check_column(sim, a, a.pos(), w)?;
        cols.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    if cols.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "dump custom needs at least one column",
            Some(format!(
                "e.g. id type x y z radius; valid fields: {}",
                rdem_io::Field::NAMES.join(" ")
            )),
        ));
    }
    Ok(cols)
}

/// custom/vtk writes legacy `.vtk` files only (LIGGGHTS picks XML formats from other
/// suffixes; those come with the VTK output issue).
fn check_file_name(a: &Args, style: &str, file: &str) -> CmdResult {
    if style == "custom/vtk" && !file.ends_with(".vtk") {
        return Err(a.error_prev(
            format!("dump custom/vtk writes legacy VTK: the file name '{file}' must end in .vtk"),
            Some("XML formats (.vtp, .vtu) are not supported yet".into()),
        ));
    }
    Ok(())
}

fn writer(style: &str, file: &str) -> Writer {
    let name = DumpFileName::new(file);
    if style == "custom" {
        Writer::Text(TextDump::new(name, TextOptions::default()))
    } else {
        Writer::Vtk(VtkDump::new(name))
    }
}

/// `dump ID group style N file columns...`.
pub fn dump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("dump ID")?.to_string();
    if sim.dumps.iter().any(|d| d.id == id) {
        return Err(a.error_prev(
            format!("dump ID '{id}' is already used"),
            Some("undump it first".into()),
        ));
    }
    let groupbit = sim.group_bit(a, "group ID")?;
    let style = dump_style(a)?;
    let every = a.count("N (dump every N steps)")?;
    let file = a.word("file name")?.to_string();
    check_file_name(a, style, &file)?;
    let cols = read_columns(sim, a)?;
    a.done()?;
    sim.world_ref(a)?;
    sim.dumps.push(Dump {
        id,
        groupbit,
        every,
        columns: cols,
        writer: writer(style, &file),
        last: None,
    });
    Ok(())
}

/// `dump_modify ID keyword value ...`.
pub fn dump_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("dump ID")?;
    let Some(k) = sim.dumps.iter().position(|d| d.id == id) else {
        let names: Vec<&str> = sim.dumps.iter().map(|d| d.id.as_str()).collect();
        return Err(a.error_prev(format!("no dump '{id}'"), Some(suggest(id, &names))));
    };
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "dump_modify: missing keyword",
            Some("e.g. sort id, pad 5, every N, format \"...\"".into()),
        ));
    }
    modify(sim, a, k, &["sort", "pad", "format", "every", "first"])
}

/// Applies `dump_modify`-style keywords (those in `valid`) to dump `k`.
fn modify(sim: &mut Sim, a: &mut Args, k: usize, valid: &[&'static str]) -> CmdResult {
    while !a.is_done() {
        let kw = a.keyword("dump_modify keyword", valid)?;
        let ncols = sim.dumps[k].columns.len();
        let d = &mut sim.dumps[k];
        match kw {
            "sort" => {
                let v = a.word("sort order (id, off, N or -N)")?;
                let s = Sort::parse(v, ncols).map_err(|m| a.error_prev(m, None))?;
                match &mut d.writer {
                    Writer::Text(t) => t.options.sort = s,
                    Writer::Vtk(v) => v.sort = s,
                }
            }
            "pad" => {
                let n = a.u64("pad width")? as usize;
                match &mut d.writer {
                    Writer::Text(t) => t.name_mut().set_pad(n),
                    Writer::Vtk(v) => v.name_mut().set_pad(n),
                }
            }
            "format" => {
                let f = a.word("format string")?;
                let Writer::Text(t) = &mut d.writer else {
                    return Err(a.error_prev("format applies to dump custom only", None));
                };
                t.options.formats = rdem_io::parse_line_format(f, ncols)
                    .map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
            }
            "every" => d.every = a.count("every")?,
            _ => {
                if a.yes_no("first")? {
                    d.last = None;
                }
            }
        }
    }
    Ok(())
}

/// `undump ID`.
pub fn undump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("dump ID")?;
    a.done()?;
    let n = sim.dumps.len();
    sim.dumps.retain(|d| d.id != id);
    if n == sim.dumps.len() {
        let names: Vec<&str> = sim.dumps.iter().map(|d| d.id.as_str()).collect();
        return Err(a.error_at(1, format!("no dump '{id}'"), Some(suggest(id, &names))));
    }
    Ok(())
}

/// `write_dump group style file columns... [modify ...]`: one snapshot now.
pub fn write_dump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let groupbit = sim.group_bit(a, "group ID")?;
    let style = dump_style(a)?;
    let file = a.word("file name")?.to_string();
    check_file_name(a, style, &file)?;
    let cols = read_columns(sim, a)?;
    let step = sim.world_ref(a)?.step;
    sim.dumps.push(Dump {
        id: "__write_dump".into(),
        groupbit,
        every: 1,
        columns: cols,
        writer: writer(style, &file),
        last: None,
    });
    let k = sim.dumps.len() - 1;
    let mut result = Ok(());
    if a.peek() == Some("modify") {
        a.seek(a.pos() + 1);
        result = modify(sim, a, k, &["sort", "pad", "format"]);
    }
    if result.is_ok() {
        result = write_one(sim, k, step).map_err(|m| a.error_cmd(m, None));
    }
    sim.dumps.pop();
    result
}

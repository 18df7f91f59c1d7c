//! `dump ID group local N file c_ID[k] ...`: the rows of local (per-contact) computes as
//! text, in LIGGGHTS 3.8's layout: `ITEM: TIMESTEP`, `ITEM: NUMBER OF ENTRIES`, `ITEM: BOX
//! BOUNDS`, `ITEM: ENTRIES` and the columns as written, each value `%g` followed by a
//! space. The group is the computes' business (as in LIGGGHTS, where the dump's group is
//! not used for local data).

use crate::error::Error;
use rdem::Boundary;
use rdem_io::{write_atomic, AppendFile, DumpFileName, Printf, Sort, Value};

use super::particles::Done;
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "local",
    parse,
    "per-contact values of local computes (`c_ID[k]`) as text, LIGGGHTS' layout",
)
.notes("`dump_modify format` as for `dump custom` (a `%d` column prints the value as an integer, where LIGGGHTS 3.8 prints the bits of a double); `dump_modify label L` names the entries `L` in the header, as LIGGGHTS 3.8; `f_ID` columns are not supported yet");

/// A column: compute ID and 1-based column (`None`: a compute with one column).
#[derive(Debug, Clone)]
struct Col {
    id: String,
    k: Option<usize>,
}

/// Splits `c_ID` / `c_ID[k]`.
fn split(word: &str) -> Option<Col> {
    let rest = word.strip_prefix("c_")?;
    match rest.split_once('[') {
        None => Some(Col {
            id: rest.to_string(),
            k: None,
        }),
        Some((id, tail)) => {
            let k = tail.strip_suffix(']')?.parse::<usize>().ok()?;
            Some(Col {
                id: id.to_string(),
                k: Some(k),
            })
        }
    }
}

/// Resolves a column against the computes: the compute's index and the 0-based column.
fn resolve_col(sim: &Sim, word: &str) -> Result<(usize, usize), Error> {
    let Some(c) = split(word) else {
        return Err(format!(
            "dump local column '{word}': expected c_ID or c_ID[k] of a local compute \
             (f_ID columns are not supported yet)"
        )
        .into());
    };
    let Some(ci) = sim.compute_index(&c.id) else {
        return Err(format!("dump local: no compute '{}'", c.id).into());
    };
    let Some(n) = sim.defs.computes[ci].imp.local_cols() else {
        return Err(format!("dump local: compute {} does not compute local values", c.id).into());
    };
    let k = super::super::computes::pick_index(&c.id, c.k, n)?;
    Ok((ci, k))
}

fn parse(sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    let mut cols = Vec::new();
    while let Some(w) = a.peek() {
        if w == "modify" {
            break;
        }
        a.seek(a.pos() + 1);
        resolve_col(sim, w).map_err(|m| a.error_prev(m, None))?;
        cols.push(w.to_string());
    }
    if cols.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "dump local needs at least one column",
            Some("e.g. c_ID[1] c_ID[2] of a compute pair/gran/local".into()),
        ));
    }
    Ok((
        Box::new(Local {
            name: DumpFileName::new(file),
            single: None,
            formats: Vec::new(),
            label: "ENTRIES".into(),
        }),
        cols,
    ))
}

/// The text writer.
struct Local {
    name: DumpFileName,
    single: Option<AppendFile>,
    /// `dump_modify format`: one per column (`None`: `%g`).
    formats: Vec<Option<Printf>>,
    /// `dump_modify label`: the word of the header lines `ITEM: NUMBER OF <label>` and
    /// `ITEM: <label> ...` (default `ENTRIES`).
    label: String,
}

fn letter(b: Boundary) -> char {
    match b {
        Boundary::Periodic => 'p',
        Boundary::Fixed => 'f',
        Boundary::Shrink => 's',
        Boundary::ShrinkMin => 'm',
    }
}

/// Every rank's rows of compute `ci`, on rank 0 (`None` elsewhere), and its column count.
/// Collective.
pub(super) fn gather_local(sim: &Sim, ci: usize) -> Result<(Option<Vec<f64>>, usize), Error> {
    let c = &sim.defs.computes[ci];
    let n = c.imp.local_cols().unwrap_or(0);
    let mine = c.imp.local(sim, &c.head)?;
    let w = super::super::computes::world(sim)?;
    Ok((w.comm.gather(&mine), n))
}

impl DumpStyle for Local {
    fn write(
        &mut self,
        sim: &Sim,
        _head: &DumpHead,
        columns: &[String],
        step: u64,
        _time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let resolved = columns
            .iter()
            .map(|c| resolve_col(sim, c))
            .collect::<Result<Vec<_>, _>>()?;
        // Each compute once, in order of first use.
        let mut ids: Vec<usize> = Vec::new();
        for &(ci, _) in &resolved {
            if !ids.contains(&ci) {
                ids.push(ci);
            }
        }
        let mut data = Vec::new();
        for &ci in &ids {
            data.push(gather_local(sim, ci)?);
        }
        let Some(first) = data.first() else {
            return Ok(Vec::new());
        };
        if first.0.is_none() {
            return Ok(Vec::new());
        }
        let rows =
            |(d, n): &(Option<Vec<f64>>, usize)| d.as_ref().map_or(0, |d| d.len() / n.max(&1));
        let nrows = rows(first);
        if data.iter().any(|d| rows(d) != nrows) {
            return Err("the local computes of dump local give different numbers of rows".into());
        }
        let w = super::super::computes::world(sim)?;
        let d = &w.domain;
        let g = Printf::default_float();
        let label = &self.label;
        let mut out =
            format!("ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF {label}\n{nrows}\nITEM: BOX BOUNDS");
        for faces in d.boundary {
            out.push_str(&format!(" {}{}", letter(faces[0]), letter(faces[1])));
        }
        out.push('\n');
        for a in 0..3 {
            g.write(&mut out, Value::Float(d.boxlo[a]));
            out.push(' ');
            g.write(&mut out, Value::Float(d.boxhi[a]));
            out.push('\n');
        }
        out.push_str(&format!("ITEM: {label} "));
        for c in columns {
            out.push_str(c);
            out.push(' ');
        }
        out.push('\n');
        let pos: Vec<(usize, usize)> = resolved
            .iter()
            .map(|&(ci, k)| (ids.iter().position(|&x| x == ci).expect("listed"), k))
            .collect();
        for r in 0..nrows {
            for (col, &(m, k)) in pos.iter().enumerate() {
                let (vals, n) = &data[m];
                let v = vals.as_ref().expect("rank 0")[r * n + k];
                let f = self.formats.get(col).and_then(|f| f.as_ref()).unwrap_or(&g);
                f.write(&mut out, Value::Float(v));
                out.push(' ');
            }
            out.push('\n');
        }
        let path = self.name.path(step, 0);
        if self.name.per_step() {
            write_atomic(&path, out.as_bytes())?;
        } else {
            self.single
                .get_or_insert_with(|| AppendFile::new(&path))
                .append(out.as_bytes())?;
        }
        Ok(Vec::new())
    }

    fn resolve(&self, sim: &Sim, columns: &[String]) -> Result<(), Error> {
        columns
            .iter()
            .try_for_each(|c| resolve_col(sim, c).map(|_| ()))
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.name
    }

    fn has_collection(&self) -> bool {
        false
    }

    fn set_sort(&mut self, _s: Sort) -> Result<(), NotHere> {
        Err((
            "sort does not apply to dump local (it has no atom IDs)",
            None,
        ))
    }

    fn set_label(&mut self, label: &str) -> Result<(), NotHere> {
        self.label = label.to_string();
        Ok(())
    }

    fn set_format(&mut self, f: &str, ncols: usize) -> Result<Option<String>, NotHere> {
        Ok(super::set_line_formats(&mut self.formats, f, ncols))
    }
}

//! `dump ID group local/gran/vtk N file c_ID`: force chains for ParaView, one line cell
//! per contact of a `compute pair/gran/local` (or `wall/gran/local`) that gives `pos`
//! (or per bond of a `compute pair/gran/local/bond`, whose torque_normal and
//! torque_tangential arrays follow torque, as LIGGGHTS-INL names them), as LIGGGHTS 3.8
//! writes them ([`rdem_io::ForceChains`]): the suffix picks the format, legacy VTK 5.1
//! ASCII polydata (`.vtk`), VTK XML PolyData (`.vtp`) or UnstructuredGrid (`.vtu`),
//! ASCII unless `dump_modify binary yes` or `compressor` (XML only), as LIGGGHTS 3.8.
//! The two particle centres are the points (single precision), and per line the
//! compute's other groups are `double` arrays, named and ordered as LIGGGHTS names
//! them: vel1 vel2 id1 id2 force force_normal force_tangential torque contact_area delta
//! (the periodic flag, the history and the contact point are not written as arrays).
//! With `contactPoint`, LIGGGHTS 3.8 draws each contact as three points (centre i,
//! centre j, contact point) and three lines (i–j, i–point, j–point) carrying the same
//! values; so does rdem. The compute ID is written without `c_`, as in LIGGGHTS.

use crate::error::Error;
use std::path::PathBuf;

use rdem_io::{write_atomic, Compressor, DumpFileName, ForceChains, Sort};

use super::local::gather_local;
use super::particles::Done;
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "local/gran/vtk",
    parse,
    "force chains (lines) from a `compute pair/gran/local` with `pos`: legacy `.vtk`, XML `.vtp` (PolyData) or `.vtu` (UnstructuredGrid)",
)
.notes("parallel `.pvtp`/`.pvtu` not supported yet; `binary`/`compressor` for the XML files only; bonds through `compute pair/gran/local/bond`");

/// The compute's index, or why it cannot be dumped.
fn compute_of(sim: &Sim, id: &str) -> Result<usize, Error> {
    let Some(ci) = sim.compute_index(id) else {
        return Err(Error::undefined("compute", id).within("dump local/gran/vtk"));
    };
    let has_pos = sim.defs.computes[ci]
        .imp
        .local_groups()
        .iter()
        .any(|g| g.0 == "pos");
    if !has_pos {
        return Err(format!(
            "dump local/gran/vtk: compute {id} must be a pair/gran/local that writes the \
             positions (keyword pos)"
        )
        .into());
    }
    Ok(ci)
}

fn parse(sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    let format = if file.ends_with(".vtk") {
        Format::Legacy
    } else if file.ends_with(".vtp") {
        Format::Vtp
    } else if file.ends_with(".vtu") {
        Format::Vtu
    } else {
        return Err(a.error_prev(
            format!("dump local/gran/vtk: the file name '{file}' must end in .vtk, .vtp or .vtu"),
            Some(
                "the suffix picks the format: .vtk legacy VTK, .vtp XML PolyData, .vtu XML \
                 UnstructuredGrid (the parallel .pvtp/.pvtu are not supported yet)"
                    .into(),
            ),
        ));
    };
    let id = a.word("compute ID (of a pair/gran/local)")?;
    compute_of(sim, id).map_err(|m| a.error_prev(m, None))?;
    Ok((
        Box::new(LocalGranVtk {
            name: DumpFileName::new(file),
            format,
            binary: false,
            compressor: Compressor::None,
        }),
        vec![id.to_string()],
    ))
}

/// The file format, from the name's suffix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Legacy,
    Vtp,
    Vtu,
}

struct LocalGranVtk {
    name: DumpFileName,
    format: Format,
    /// `dump_modify binary` (XML files).
    binary: bool,
    /// `dump_modify compressor` (XML files).
    compressor: Compressor,
}

/// The lines of a snapshot from the compute's rows (`n` values each, in `groups`): the
/// two centres (and, with `contactPoint`, the contact point: three points, three lines
/// i–j, i–point, j–point, each with the contact's values, as LIGGGHTS 3.8 draws them),
/// and the arrays as LIGGGHTS splits and names them.
fn chains(groups: &[(&str, usize, usize)], data: &[f64], n: usize) -> ForceChains {
    let nrows = data.len().checked_div(n).unwrap_or(0);
    let find = |name: &str| groups.iter().find(|g| g.0 == name).map(|g| g.1);
    let pos = find("pos").expect("checked at definition");
    let cp = find("contactPoint");
    let per = if cp.is_some() { 3 } else { 1 };
    let mut c = ForceChains::default();
    for r in 0..nrows {
        let row = &data[r * n..(r + 1) * n];
        let mut pts = row[pos..pos + 6].to_vec();
        if let Some(at) = cp {
            pts.extend_from_slice(&row[at..at + 3]);
        }
        // Single precision, as the `float` points LIGGGHTS writes.
        c.points.extend(pts.iter().map(|&v| v as f32));
        let k = (r * (pts.len() / 3)) as i64;
        if cp.is_some() {
            c.lines.extend([[k, k + 1], [k, k + 2], [k + 1, k + 2]]);
        } else {
            c.lines.push([k, k + 1]);
        }
    }
    let mut arrays: Vec<(&str, usize, usize)> = Vec::new();
    for &(name, at, w) in groups {
        match name {
            "vel" => arrays.extend([("vel1", at, 3), ("vel2", at + 3, 3)]),
            "id" => arrays.extend([("id1", at, 1), ("id2", at + 1, 1)]),
            "pos" | "history" | "contactPoint" => {}
            "contactArea" => arrays.push(("contact_area", at, 1)),
            _ => arrays.push((name, at, w)),
        }
    }
    for (name, at, w) in arrays {
        let mut values = Vec::with_capacity(nrows * per * w);
        for r in 0..nrows {
            for _ in 0..per {
                values.extend_from_slice(&data[r * n + at..r * n + at + w]);
            }
        }
        c.arrays.push((name.to_string(), w, values));
    }
    c
}

impl DumpStyle for LocalGranVtk {
    fn write(
        &mut self,
        sim: &Sim,
        _head: &DumpHead,
        columns: &[String],
        step: u64,
        time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let ci = compute_of(sim, &columns[0])?;
        let groups = sim.defs.computes[ci].imp.local_groups();
        let (data, n) = gather_local(sim, ci)?;
        let Some(data) = data else {
            return Ok(Vec::new());
        };
        let c = chains(&groups, &data, n);
        let out = match self.format {
            Format::Legacy => c.format_legacy(),
            Format::Vtp => c.format_xml(self.compressor.encoding(self.binary), false),
            Format::Vtu => c.format_xml(self.compressor.encoding(self.binary), true),
        };
        let path: PathBuf = self.name.path(step, 0);
        write_atomic(&path, out.as_bytes())?;
        Ok(vec![(time, path)])
    }

    fn resolve(&self, sim: &Sim, columns: &[String]) -> Result<(), Error> {
        compute_of(sim, &columns[0]).map(|_| ())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.name
    }

    fn set_sort(&mut self, _s: Sort) -> Result<(), NotHere> {
        Err(("sort does not apply to dump local/gran/vtk", None))
    }

    fn set_binary(&mut self, yes: bool) -> Result<(), NotHere> {
        if self.format == Format::Legacy {
            return Err((
                "binary for dump local/gran/vtk is supported with .vtp or .vtu files only",
                Some("legacy .vtk force chains are written as ASCII (binary not supported yet)"),
            ));
        }
        self.binary = yes;
        Ok(())
    }

    fn set_compressor(&mut self, c: Compressor) -> Result<(), NotHere> {
        if self.format == Format::Legacy {
            return Err((
                "compressor applies to VTK XML output (.vtp or .vtu files)",
                Some("legacy .vtk files cannot be compressed"),
            ));
        }
        // As LIGGGHTS 3.8: a compressor alone makes the data binary.
        self.compressor = c;
        self.binary |= c != Compressor::None;
        Ok(())
    }
}

//! `dump`, `dump_modify`, `undump` and `write_dump`, and every dump style, one file per
//! style in this folder, all listed in one registry ([`REGISTRY`]). A style's file holds
//! its parser (the file name's rules and the columns after it) and a type implementing
//! [`DumpStyle`]: how a snapshot is written and which `dump_modify` keywords apply. The
//! file formats themselves are in `rdem-io`.

mod atom_vtk;
mod custom;
mod custom_vtk;
mod decomposition_vtk;
mod euler_vtk;
mod local;
mod local_gran_vtk;
mod mesh_stl;
mod mesh_vtk;
pub(crate) mod particles;

use crate::error::Error;
use rdem::comm::Comm;
use rdem_io::{Compressor, DumpFileName, PvdSeries, Sort};

use crate::args::{suggest, Args, CmdResult};
use crate::diagnostic::{Origin, RunError};
use crate::registry::{Registry, Row};
use crate::sim::Sim;

pub(crate) use particles::gather_owned;
use particles::Done;

/// The words every dump starts with: `dump ID group style`.
#[derive(Debug, Clone)]
pub struct DumpHead {
    /// Dump ID.
    pub id: String,
    /// Group bit mask.
    pub groupbit: u32,
    /// `dump_modify region ID`: only the particles in this region (placed at the time of
    /// each snapshot) are written.
    pub region: Option<String>,
}

/// Why a `dump_modify` keyword does not apply to a style: the message and a help line.
pub type NotHere = (&'static str, Option<&'static str>);

/// A dump style: how a snapshot is written and what `dump_modify` may change.
pub trait DumpStyle {
    /// Writes the snapshot of step `step` (collective: every rank calls it; rank 0
    /// writes). `background`: the writer may finish the file on another thread (then
    /// [`DumpStyle::finish`] reports it). Returns the files finished, with their times,
    /// for the `.pvd` collection.
    fn write(
        &mut self,
        sim: &Sim,
        head: &DumpHead,
        columns: &[String],
        step: u64,
        time: f64,
        background: bool,
    ) -> Result<Done, Error>;

    /// Evaluates the columns' references (`c_`, `f_`, `v_`) without writing anything
    /// (`rdem -check`).
    fn resolve(&self, _sim: &Sim, _columns: &[String]) -> Result<(), Error> {
        Ok(())
    }

    /// Waits for the snapshots being written in the background.
    fn finish(&mut self) -> Result<Done, Error> {
        Ok(Vec::new())
    }

    /// The file name pattern (`dump_modify pad`).
    fn name_mut(&mut self) -> &mut DumpFileName;

    /// Whether a name with `*` gets a ParaView collection (`.pvd`).
    fn has_collection(&self) -> bool {
        true
    }

    /// `dump_modify sort`.
    fn set_sort(&mut self, s: Sort) -> Result<(), NotHere>;

    /// `dump_modify binary`.
    fn set_binary(&mut self, _yes: bool) -> Result<(), NotHere> {
        Err((
            "binary applies to the particle VTK dump styles (custom/vtk, atom/vtk)",
            None,
        ))
    }

    /// `dump_modify compressor` (compression only exists for binary data: asking for it
    /// turns binary on).
    fn set_compressor(&mut self, _c: Compressor) -> Result<(), NotHere> {
        Err((
            "compressor applies to VTK XML output (atom/vtk, custom/vtk with .vtp or .vtu)",
            Some("legacy .vtk files cannot be compressed"),
        ))
    }

    /// Whether `dump_modify region` applies (LIGGGHTS 3.8: dump custom and custom/vtk;
    /// atom/vtk refuses it).
    fn takes_region(&self) -> bool {
        false
    }

    /// `dump_modify label` (LIGGGHTS 3.8: dump local only).
    fn set_label(&mut self, _label: &str) -> Result<(), NotHere> {
        Err(("label applies to dump local only, as in LIGGGHTS 3.8", None))
    }

    /// `dump_modify format`: `Ok(Some(error))` for a bad format string.
    fn set_format(&mut self, _f: &str, _ncols: usize) -> Result<Option<String>, NotHere> {
        Err(("format applies to dump custom and dump local only", None))
    }
}

/// `dump_modify format` for the text dumps: one format per column into `formats`, or the
/// error of a bad format line (`formats` unchanged then).
pub(super) fn set_line_formats(
    formats: &mut Vec<Option<rdem_io::Printf>>,
    f: &str,
    ncols: usize,
) -> Option<String> {
    match rdem_io::parse_line_format(f, ncols) {
        Ok(parsed) => {
            *formats = parsed;
            None
        }
        Err(e) => Some(e.to_string()),
    }
}

/// A dump style's parser: checks the file name (the word just read) and reads the
/// columns after it, up to `modify` or the end; returns the style and the columns.
pub type DumpParse = fn(&Sim, &mut Args, &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)>;

/// A row of the dump registry.
pub type DumpRow = Row<DumpParse>;

/// Every dump style: those rdem writes, then LIGGGHTS styles it does not write yet.
pub static REGISTRY: Registry<DumpParse> = Registry {
    family: "dump style",
    readme_prefix: "dump ",
    rows: &[
        custom::ROW,
        custom_vtk::ROW,
        atom_vtk::ROW,
        euler_vtk::ROW,
        mesh_stl::ROW,
        mesh_stl::ROW_OLD_NAME,
        decomposition_vtk::ROW,
        mesh_vtk::ROW,
        mesh_vtk::ROW_OLD_NAME,
        Row::not_yet("mesh/vtm", ""),
        local_gran_vtk::ROW,
        local::ROW,
        Row::not_yet("atom", ""),
    ],
};

/// One dump.
pub struct Dump {
    /// ID and group.
    pub head: DumpHead,
    /// Every this many steps.
    pub every: u64,
    /// Column arguments as written.
    pub columns: Vec<String>,
    /// The style.
    pub style: Box<dyn DumpStyle>,
    /// Step of the last snapshot.
    pub last: Option<u64>,
    /// `dump_modify first yes`: a snapshot at the next run's set-up even off a multiple
    /// of N, if the dump has written none yet (as LAMMPS and LIGGGHTS do).
    pub first: bool,
    /// The ParaView collection of a VTK dump whose name has `*` (see [`rdem_io::pvd`]);
    /// `None` for text dumps, `write_dump` and a VTK file overwritten at each snapshot.
    pub pvd: Option<PvdSeries>,
    /// Where its style word stands, for errors found while it writes during a run.
    pub origin: Option<Origin>,
}

impl Dump {
    /// Dump ID.
    pub fn id(&self) -> &str {
        &self.head.id
    }
}

/// Writes every dump due at `step` (a multiple of its N, at set-up too). At the last
/// step of a run, waits for the snapshots still being written in the background.
pub fn write_due(sim: &mut Sim, step: u64, setup: bool) -> Result<(), RunError> {
    for k in 0..sim.outputs.dumps.len() {
        let d = &sim.outputs.dumps[k];
        // Only on multiples of N, also at a run's set-up: LIGGGHTS 3.8 writes no first
        // snapshot for a dump defined at another step (measured: sph_2's dump, defined
        // at step 1, first writes at step 1000), unless `dump_modify first yes`.
        let first = setup && d.first && d.last.is_none();
        let due = (step % d.every == 0 || first) && d.last != Some(step);
        if due {
            write_one(sim, k, step, true).map_err(|m| {
                RunError::at(sim.outputs.dumps[k].origin.as_ref(), "rdem::run::dump", m)
            })?;
        }
    }
    if step == sim.script.run_last {
        finish_all(sim)?;
    }
    Ok(())
}

/// Waits for every snapshot being written in the background and lists it in its `.pvd`.
/// Collective (only rank 0 writes, so a failure there stops every rank).
pub fn finish_all(sim: &mut Sim) -> Result<(), Error> {
    let outcome = sim.outputs.dumps.iter_mut().try_for_each(finish);
    match &sim.world {
        Some(w) => agree(&*w.comm, "dump", outcome),
        None => outcome,
    }
}

fn finish(d: &mut Dump) -> Result<(), Error> {
    let done = d
        .style
        .finish()
        .map_err(|e| format!("dump {}: {e}", d.head.id))?;
    record(d, done)
}

/// Lists completed snapshots in the dump's `.pvd`.
fn record(d: &mut Dump, done: Done) -> Result<(), Error> {
    if let Some(pvd) = &mut d.pvd {
        for (time, path) in done {
            pvd.add(time, &path)
                .map_err(|e| format!("dump {}: {e}", d.head.id))?;
        }
    }
    Ok(())
}

/// Makes the outcome of writing a file, which only rank 0 does, the same on every rank: a
/// failure on rank 0 becomes an error everywhere, so that all ranks stop together instead
/// of the others going on to the next collective call. Collective.
pub(crate) fn agree<T>(comm: &dyn Comm, what: &str, r: Result<T, Error>) -> Result<T, Error> {
    let failed = comm.max(if r.is_err() { 1.0 } else { 0.0 }) > 0.0;
    match r {
        Ok(_) if failed => Err(Error::FailedOnRankZero(what.to_string())),
        r => r,
    }
}

/// Writes dump `k`'s snapshot of `step` and lists its files. Collective.
fn write_one(sim: &mut Sim, k: usize, step: u64, background: bool) -> Result<(), Error> {
    let time = sim.time();
    // The dump is out of `sim.outputs.dumps` while it reads the rest of the state.
    let vacant = Dump {
        head: DumpHead {
            id: String::new(),
            groupbit: 0,
            region: None,
        },
        every: 1,
        columns: Vec::new(),
        style: Box::new(Vacant),
        last: None,
        first: false,
        pvd: None,
        origin: None,
    };
    let mut d = std::mem::replace(&mut sim.outputs.dumps[k], vacant);
    let wrote = d
        .style
        .write(sim, &d.head, &d.columns, step, time, background);
    let outcome = wrote
        .map_err(|e| e.within(format!("dump {}", d.head.id)))
        .and_then(|done| record(&mut d, done));
    d.last = Some(step);
    let what = format!("dump {}", d.head.id);
    sim.outputs.dumps[k] = d;
    match &sim.world {
        Some(w) => agree(&*w.comm, &what, outcome),
        None => outcome,
    }
}

/// The stand-in of a dump whose style is writing (it is out of `Sim::dumps` meanwhile).
struct Vacant;

impl DumpStyle for Vacant {
    fn write(
        &mut self,
        _: &Sim,
        _: &DumpHead,
        _: &[String],
        _: u64,
        _: f64,
        _: bool,
    ) -> Result<Done, Error> {
        Ok(Vec::new())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        unreachable!("a vacant dump has no file")
    }

    fn set_sort(&mut self, _: Sort) -> Result<(), NotHere> {
        Ok(())
    }
}

/// The ID of the temporary dump of `write_dump`.
const WRITE_DUMP: &str = "__write_dump";

/// The IDs of the meshes (`fix mesh/surface`).
pub(crate) fn mesh_ids(sim: &Sim) -> Vec<&str> {
    sim.world
        .iter()
        .flat_map(|w| w.meshes.iter().map(|m| m.id.as_str()))
        .collect()
}

/// A dump's style, interval, file name and columns as a command gives them.
type Parsed = (Box<dyn DumpStyle>, u64, String, Vec<String>);

/// Reads `style [N] file columns...` (as `dump` and, without N, `write_dump` have them).
fn style_file_columns(sim: &Sim, a: &mut Args, every: bool) -> CmdResult<Parsed> {
    let style_word = a.word("dump style")?;
    let (_, parse) = REGISTRY.lookup(a, style_word)?;
    let n = if every {
        a.count("N (dump every N steps)")?
    } else {
        1
    };
    let file = a.word("file name")?.to_string();
    let (style, cols) = parse(sim, a, &file)?;
    Ok((style, n, file, cols))
}

/// `dump ID group style N file columns...`.
pub fn dump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("dump ID")?.to_string();
    if sim.outputs.dumps.iter().any(|d| d.id() == id) {
        return Err(a.error_prev(
            format!("dump ID '{id}' is already used"),
            Some("undump it first".into()),
        ));
    }
    let groupbit = sim.group_bit(a, "group ID")?;
    let origin = sim.origin(a, 3);
    let (style, every, file, columns) = style_file_columns(sim, a, true)?;
    a.done()?;
    sim.world_ref(a)?;
    let pvd = if style.has_collection() {
        PvdSeries::for_pattern(&file, 0)
    } else {
        None
    };
    sim.outputs.dumps.push(Dump {
        head: DumpHead {
            id,
            groupbit,
            region: None,
        },
        every,
        columns,
        style,
        last: None,
        first: false,
        pvd,
        origin,
    });
    Ok(())
}

/// `dump_modify ID keyword value ...`.
pub fn dump_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("dump ID")?;
    let Some(k) = sim.outputs.dumps.iter().position(|d| d.id() == id) else {
        let names: Vec<&str> = sim.outputs.dumps.iter().map(|d| d.id()).collect();
        return Err(a.error_prev(format!("no dump '{id}'"), Some(suggest(id, &names))));
    };
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "dump_modify: missing keyword",
            Some("e.g. sort id, pad 5, every N, format \"...\", binary yes".into()),
        ));
    }
    let regions: Vec<String> = sim.defs.regions.keys().cloned().collect();
    modify(
        &mut sim.outputs.dumps[k],
        a,
        &[
            "sort",
            "pad",
            "format",
            "every",
            "first",
            "region",
            "binary",
            "compressor",
            "label",
        ],
        &regions,
    )
}

/// Applies `dump_modify`-style keywords (those in `valid`) to dump `d`; `regions`: the
/// IDs of the regions defined.
fn modify(d: &mut Dump, a: &mut Args, valid: &[&'static str], regions: &[String]) -> CmdResult {
    let not_here = |a: &Args, (m, h): NotHere| a.error_prev(m, h.map(str::to_string));
    while !a.is_done() {
        let kw = a.keyword("dump_modify keyword", valid)?;
        let ncols = d.columns.len();
        match kw {
            "sort" => {
                let v = a.word("sort order (id, off, N or -N)")?;
                let s = Sort::parse(v, ncols).map_err(|m| a.error_prev(m.to_string(), None))?;
                d.style.set_sort(s).map_err(|e| not_here(a, e))?;
            }
            "pad" => {
                let n = a.u64("pad width")? as usize;
                d.style.name_mut().set_pad(n);
            }
            "binary" => {
                let yes = a.yes_no("binary")?;
                d.style.set_binary(yes).map_err(|e| not_here(a, e))?;
            }
            "compressor" => {
                let w = a.word("compressor (none, zlib or lz4)")?;
                let Some(c) = Compressor::parse(w) else {
                    return Err(a.error_prev(
                        format!("unknown compressor '{w}'"),
                        Some(suggest(w, &Compressor::NAMES)),
                    ));
                };
                d.style.set_compressor(c).map_err(|e| not_here(a, e))?;
            }
            "format" => {
                let f = a.word("format string")?;
                if let Some(e) = d.style.set_format(f, ncols).map_err(|e| not_here(a, e))? {
                    return Err(a.error_prev(format!("bad format: {e}"), None));
                }
            }
            "every" => d.every = a.count("every")?,
            "region" => {
                let r = a.word("region ID (or none)")?;
                if !d.style.takes_region() {
                    return Err(a.error_at(
                        a.pos() - 2,
                        "region applies to dump custom and custom/vtk only",
                        None,
                    ));
                }
                d.head.region = if r == "none" {
                    None
                } else if regions.iter().any(|x| x == r) {
                    Some(r.to_string())
                } else {
                    let names: Vec<&str> = regions.iter().map(String::as_str).collect();
                    return Err(a.error_prev(format!("no region '{r}'"), Some(suggest(r, &names))));
                };
            }
            "first" => {
                d.first = a.yes_no("first")?;
            }
            "label" => {
                let label = a.word("label")?;
                d.style.set_label(label).map_err(|e| not_here(a, e))?;
            }
            other => unreachable!("dump_modify keyword {other} is not in the valid list"),
        }
    }
    Ok(())
}

/// `undump ID`.
pub fn undump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("dump ID")?;
    a.done()?;
    if let Some(d) = sim.outputs.dumps.iter_mut().find(|d| d.id() == id) {
        finish(d).map_err(|m| a.error_cmd(m, None))?;
    }
    let n = sim.outputs.dumps.len();
    sim.outputs.dumps.retain(|d| d.id() != id);
    if n == sim.outputs.dumps.len() {
        let names: Vec<&str> = sim.outputs.dumps.iter().map(|d| d.id()).collect();
        return Err(a.error_at(1, format!("no dump '{id}'"), Some(suggest(id, &names))));
    }
    Ok(())
}

/// `write_dump group style file columns... [modify ...]`: one snapshot now.
pub fn write_dump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let groupbit = sim.group_bit(a, "group ID")?;
    let (style, _, _, columns) = style_file_columns(sim, a, false)?;
    let step = sim.world_ref(a)?.step;
    sim.outputs.dumps.push(Dump {
        head: DumpHead {
            id: WRITE_DUMP.into(),
            groupbit,
            region: None,
        },
        every: 1,
        columns,
        style,
        last: None,
        first: false,
        pvd: None,
        origin: None,
    });
    let k = sim.outputs.dumps.len() - 1;
    let mut result = Ok(());
    if a.peek() == Some("modify") {
        a.seek(a.pos() + 1);
        let regions: Vec<String> = sim.defs.regions.keys().cloned().collect();
        result = modify(
            &mut sim.outputs.dumps[k],
            a,
            &["sort", "pad", "format", "region", "binary", "compressor"],
            &regions,
        );
    }
    if result.is_ok() {
        result = if sim.script.check {
            let d = &sim.outputs.dumps[k];
            d.style.resolve(sim, &d.columns)
        } else {
            write_one(sim, k, step, false)
        }
        .map_err(|m| a.error_cmd(m, None));
    }
    sim.outputs.dumps.pop();
    result
}

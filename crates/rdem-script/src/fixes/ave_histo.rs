//! `fix ID group ave/histo Nevery Nrepeat Nfreq lo hi Nbin value ... keyword ...`: one
//! histogram of all the input values (global scalars in `mode scalar`; global vectors or
//! per-atom vectors and arrays of the group in `mode vector`), summed over `Nrepeat`
//! samples `Nevery` steps apart ending on each multiple of `Nfreq`, combined over those
//! outputs by `ave one|running|window M`, written to an optional file and given as the
//! global vector `f_ID[1..4]` (total count, missing count, min, max).
//!
//! Behaviour checked on LIGGGHTS 3.8 (tests/data/parity/item16*.in, item17.in; the
//! numbers are in tests/histo_parity.rs):
//! - the counts are sums, never averages: over the `Nrepeat` samples, and over the
//!   outputs for `ave running` (all since the fix was defined) and `ave window M`;
//! - a value on a bin boundary goes into the upper bin (the manual says the lower), and
//!   `hi` itself into the last bin (with `beyond extra`: into the extra bin above `hi`);
//! - `beyond ignore` leaves values outside `[lo, hi]` out of the total count;
//! - with `ave running` the min and max start from 0, so the min printed is never above
//!   0 and the max never below it; `ave window` takes them over the outputs in the window;
//! - with `Nrepeat` 1 a run's set-up on a multiple of `Nfreq` (step 0) gives a histogram;
//! - the file's first header line is `# Histogrammed data for fix ID` (the manual says
//!   "Histogram"), and `title1/2/3` replace the three header lines word for word (the
//!   third is written in scalar mode too).

use super::sampling::Schedule;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{id_help, Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::thermo::{column_value, split_reference};
use crate::variables::{format_g, Variable};

mod input;

use input::Input;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "ave/histo",
    parse,
    Stages::END_OF_STEP.and(Stages::VALUES),
    "`mode scalar\\|vector`: `x y z vx vy vz fx fy fz`, `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`; `file`, `ave one\\|running\\|window M`, `start`, `beyond ignore\\|end\\|extra`, `overwrite`, `title1/2/3`",
)
.notes("as LIGGGHTS 3.8: counts are sums over `Nrepeat` and over `ave running`/`window` outputs; a value on a bin boundary goes up; `ave running` min/max start from 0. The global array (bin coordinates and counts) is not given: only the vector `f_ID[1..4]`");

/// `beyond`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Beyond {
    Ignore,
    End,
    Extra,
}

/// `ave`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Ave {
    One,
    Running,
    Window(usize),
}

/// Counts and extremes of one histogram: total, missing, min, max.
type Stats = [f64; 4];

/// No value yet (LAMMPS' BIG).
const EMPTY: Stats = [0.0, 0.0, 1e20, -1e20];

/// `fix ave/histo`.
pub struct AveHisto {
    schedule: Schedule,
    lo: f64,
    hi: f64,
    /// Bins, with the two of `beyond extra`.
    nbins: usize,
    bininv: f64,
    beyond: Beyond,
    ave: Ave,
    inputs: Vec<Input>,
    /// `file F`: its name and word (none under `rdem -check`).
    path: Option<(String, usize)>,
    overwrite: bool,
    /// The three header lines, each with its newline.
    header: String,
    file: Option<rdem_io::AppendFile>,
    /// The histogram being summed over the `Nrepeat` samples.
    stats: Stats,
    hist: Vec<f64>,
    /// The combined histogram of the last output.
    stats_total: Stats,
    hist_total: Vec<f64>,
    /// `ave window`: the last M histograms, the next slot, and whether it is full.
    window: Vec<(Stats, Vec<f64>)>,
    iwindow: usize,
}

impl AveHisto {
    /// Bins one value (LAMMPS' `bin_one`).
    fn bin(&mut self, v: f64) {
        let s = &mut self.stats;
        s[2] = s[2].min(v);
        s[3] = s[3].max(v);
        let last = self.nbins - 1;
        let k = if v < self.lo || v > self.hi {
            if self.beyond == Beyond::Ignore {
                s[1] += 1.0;
                return;
            }
            if v < self.lo {
                0
            } else {
                last
            }
        } else {
            // Clamped to the last bin of all, extra ones included: with `beyond extra`
            // the value `hi` itself lands in the "above" bin (as LIGGGHTS 3.8).
            let k = (((v - self.lo) * self.bininv) as usize).min(last);
            (k + usize::from(self.beyond == Beyond::Extra)).min(last)
        };
        self.hist[k] += 1.0;
        s[0] += 1.0;
    }

    /// Bin `k`'s coordinate: its centre (`lo`, `hi` for the extra bins).
    fn coord(&self, k: usize) -> f64 {
        let width = 1.0 / self.bininv;
        match self.beyond {
            Beyond::Extra if k == 0 => self.lo,
            Beyond::Extra if k == self.nbins - 1 => self.hi,
            Beyond::Extra => self.lo + (k as f64 - 0.5) * width,
            _ => self.lo + (k as f64 + 0.5) * width,
        }
    }

    /// Combines the finished histogram into the output one, as `ave` says.
    fn combine(&mut self) {
        match self.ave {
            Ave::One => {
                self.stats_total = self.stats;
                self.hist_total.copy_from_slice(&self.hist);
            }
            Ave::Running => {
                let (t, s) = (&mut self.stats_total, &self.stats);
                t[0] += s[0];
                t[1] += s[1];
                t[2] = t[2].min(s[2]);
                t[3] = t[3].max(s[3]);
                for (t, h) in self.hist_total.iter_mut().zip(&self.hist) {
                    *t += h;
                }
            }
            Ave::Window(m) => {
                let entry = (self.stats, self.hist.clone());
                if self.window.len() < m {
                    self.window.push(entry);
                } else {
                    self.window[self.iwindow] = entry;
                }
                self.iwindow = (self.iwindow + 1) % m;
                let mut t = [0.0, 0.0, 1e20, -1e20];
                self.hist_total.iter_mut().for_each(|h| *h = 0.0);
                for (s, h) in &self.window {
                    t[0] += s[0];
                    t[1] += s[1];
                    t[2] = t[2].min(s[2]);
                    t[3] = t[3].max(s[3]);
                    for (t, h) in self.hist_total.iter_mut().zip(h) {
                        *t += h;
                    }
                }
                self.stats_total = t;
            }
        }
    }

    /// One output block of the file.
    fn block(&self, step: u64) -> String {
        let t = &self.stats_total;
        let mut s = format!(
            "{step} {} {} {} {} {}\n",
            self.nbins,
            format_g(t[0], 6),
            format_g(t[1], 6),
            format_g(t[2], 6),
            format_g(t[3], 6)
        );
        for (k, h) in self.hist_total.iter().enumerate() {
            let norm = if t[0] != 0.0 { h / t[0] } else { 0.0 };
            s += &format!(
                "{} {} {} {}\n",
                k + 1,
                format_g(self.coord(k), 6),
                format_g(*h, 6),
                format_g(norm, 6)
            );
        }
        s
    }
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let mut schedule = Schedule::parse(a)?;
    let nevery = schedule.nevery;
    let lo = a.f64("lo")?;
    let hi = a.f64("hi")?;
    if lo >= hi {
        return Err(a.error_prev(format!("hi ({hi}) must be above lo ({lo})"), None));
    }
    let nbins = a.count("Nbin")? as usize;
    let first = a.pos();
    let mut words = Vec::new();
    while let Some(w) = a.peek() {
        if !(input::ATTRIBUTES.contains(&w) || split_reference(w).is_some()) {
            break;
        }
        words.push((a.pos(), w));
        a.seek(a.pos() + 1);
    }
    if words.is_empty() {
        return Err(a.error_at(
            first,
            "ave/histo needs at least one value",
            Some(format!(
                "{}, c_ID, c_ID[i], f_ID, f_ID[i] or v_name",
                input::ATTRIBUTES.join(" ")
            )),
        ));
    }
    let (mut vector, mut ave, mut start, mut beyond, mut path, mut overwrite) =
        (false, Ave::One, 0, Beyond::Ignore, None, None);
    let mut titles = [
        format!("# Histogrammed data for fix {}", head.id),
        "# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value".to_string(),
        "# Bin Coord Count Count/Total".to_string(),
    ];
    const KEYWORDS: [&str; 9] = [
        "mode",
        "file",
        "ave",
        "start",
        "beyond",
        "overwrite",
        "title1",
        "title2",
        "title3",
    ];
    while !a.is_done() {
        match a.keyword("ave/histo keyword", &KEYWORDS)? {
            "mode" => vector = a.keyword("mode", &["scalar", "vector"])? == "vector",
            "file" => {
                let f = a.word("file name")?;
                if !sim.script.check {
                    path = Some((f.to_string(), a.pos() - 1));
                }
            }
            "ave" => {
                ave = match a.keyword("ave", &["one", "running", "window"])? {
                    "one" => Ave::One,
                    "running" => Ave::Running,
                    _ => Ave::Window(a.count("window size M")? as usize),
                }
            }
            "start" => start = a.u64("Nstart")?,
            "beyond" => {
                beyond = match a.keyword("beyond", &["ignore", "end", "extra"])? {
                    "ignore" => Beyond::Ignore,
                    "end" => Beyond::End,
                    _ => Beyond::Extra,
                }
            }
            "overwrite" => overwrite = Some(a.pos() - 1),
            t => {
                let k = usize::from(t.as_bytes()[5] - b'1');
                titles[k] = a.word("title")?.to_string();
            }
        }
    }
    if let (Some(k), false) = (overwrite, ave == Ave::Running) {
        return Err(a.error_at(k, "overwrite needs ave running", None));
    }
    let inputs = input::parse_all(sim, a, &words, vector, nevery)?;
    let width = (hi - lo) / nbins as f64;
    let nbins = nbins + if beyond == Beyond::Extra { 2 } else { 0 };
    schedule.start = start;
    schedule.begin(sim.world.as_ref().map_or(0, |w| w.step));
    let f = AveHisto {
        schedule,
        lo,
        hi,
        nbins,
        bininv: 1.0 / width,
        beyond,
        ave,
        inputs,
        path,
        overwrite: overwrite.is_some(),
        header: titles.iter().map(|t| format!("{t}\n")).collect(),
        file: None,
        stats: EMPTY,
        hist: vec![0.0; nbins],
        stats_total: [0.0; 4],
        hist_total: vec![0.0; nbins],
        window: Vec::new(),
        iwindow: 0,
    };
    Ok(Box::new(f))
}

/// An error at word `k` unless `id` names a defined compute (`kind` 'c'), fix ('f') or
/// variable ('v').
pub(super) fn unknown_id(sim: &Sim, a: &Args, k: usize, kind: char, id: &str) -> CmdResult<()> {
    let (what, known, ids): (&str, bool, Vec<&str>) = match kind {
        'c' => (
            "compute",
            sim.compute_index(id).is_some(),
            sim.defs.computes.iter().map(|c| c.id()).collect(),
        ),
        'f' => (
            "fix",
            sim.fix_index(id).is_some(),
            sim.defs.fixes.iter().map(|f| f.id()).collect(),
        ),
        _ => (
            "variable",
            sim.script.vars.get(id).is_some(),
            sim.script.vars.names(),
        ),
    };
    if known {
        return Ok(());
    }
    Err(a.error_at(
        k,
        format!("no {what} '{id}'"),
        Some(id_help(what, id, &ids)),
    ))
}

impl ScriptFix for AveHisto {
    /// Makes the `file` with its three header lines.
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let Some((path, at)) = &self.path else {
            return Ok(());
        };
        if sim.world.as_ref().is_some_and(|w| !w.comm.is_root()) {
            return Ok(());
        }
        let mut f = rdem_io::AppendFile::new(path);
        f.append(self.header.as_bytes())
            .map_err(|e| a.error_at(*at, e.to_string(), None))?;
        self.file = Some(f);
        Ok(())
    }

    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(self.stats_total.to_vec())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let Some(first) = self.schedule.due(step) else {
            return Ok(());
        };
        if first {
            self.stats = EMPTY;
            self.hist.iter_mut().for_each(|h| *h = 0.0);
        }
        let peratom = self.inputs.first().is_some_and(Input::is_peratom);
        for k in 0..self.inputs.len() {
            let values = self.inputs[k].values(ctx.view(), head.groupbit)?;
            values.into_iter().for_each(|v| self.bin(v));
        }
        if !self.schedule.sampled(step) {
            return Ok(());
        }
        if peratom {
            // Each rank binned its own particles over the samples: add the ranks' sums.
            let c = &ctx.world_ref().comm;
            if c.size() > 1 {
                c.sum_slice(&mut self.hist);
                let s = &mut self.stats;
                s[0] = c.sum(s[0]);
                s[1] = c.sum(s[1]);
                s[2] = c.min(s[2]);
                s[3] = c.max(s[3]);
            }
        }
        self.combine();
        let block = self.block(step);
        let mut wrote = Ok(());
        if let Some(f) = &mut self.file {
            if self.overwrite {
                *f = rdem_io::AppendFile::new(f.path().to_path_buf());
                wrote = f.append(self.header.as_bytes());
            }
            wrote = wrote.and_then(|()| f.append(block.as_bytes()));
        }
        ctx.agree_write("fix ave/histo", wrote.map_err(Error::from))
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

/// A global value (`c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`), read as thermo reads it.
pub(super) fn global_value(sim: &Sim, word: &str) -> Result<f64, Error> {
    column_value(sim, word).map(|v| v.0)
}

/// True if `name` is an atom-style variable.
pub(super) fn is_atom_variable(sim: &Sim, name: &str) -> bool {
    matches!(sim.script.vars.get(name), Some(Variable::Atom(_)))
}

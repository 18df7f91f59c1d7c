//! `fix ave/time Nevery Nrepeat Nfreq value ...` (scalar mode): averages of global values
//! (`c_ID`, `c_ID[i]`, `f_ID[i]`, `v_name`) over `Nrepeat` samples every `Nfreq` steps,
//! one row per average in an optional file; `f_ID[i]` is the last average.

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::thermo;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "ave/time",
    parse,
    Stages::END_OF_STEP.and(Stages::VALUES),
    "scalar mode: `c_ID`, `c_ID[i]`, `f_ID[i]`, `v_name`; `ave one\\|running`; `file`",
);

/// `fix ave/time` (scalar mode).
pub struct AveTime {
    /// Sample every.
    pub nevery: u64,
    /// Samples per average.
    pub nrepeat: u64,
    /// Output every.
    pub nfreq: u64,
    /// Inputs (`c_ID`, `c_ID[i]`, `f_ID[i]`, `v_name`).
    pub inputs: Vec<String>,
    /// `ave running`.
    pub running: bool,
    /// `file F`: its name and word (none under `rdem -check`, which writes no file).
    pub path: Option<(String, usize)>,
    /// The output file, made when the fix is installed.
    pub file: Option<rdem_io::AppendFile>,
    /// Sums of the current window.
    pub sum: Vec<f64>,
    /// Samples in the window.
    pub count: u64,
    /// Last finished averages.
    pub values: Vec<f64>,
    /// Running totals (for `ave running`).
    pub running_sum: Vec<f64>,
    /// Number of finished windows.
    pub windows: u64,
}

fn parse(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let nevery = a.count("Nevery")?;
    let nrepeat = a.count("Nrepeat")?;
    let nfreq = a.count("Nfreq")?;
    if nfreq % nevery != 0 || (nrepeat - 1) * nevery >= nfreq + nevery {
        return Err(a.error_at(
            a.pos() - 1,
            format!("Nfreq must be a multiple of Nevery and Nrepeat*Nevery <= Nfreq (got {nevery} {nrepeat} {nfreq})"),
            None,
        ));
    }
    let mut inputs = Vec::new();
    while let Some(w) = a.peek() {
        if !(w.starts_with("c_") || w.starts_with("f_") || w.starts_with("v_")) {
            break;
        }
        let Some((kind, id, _)) = crate::thermo::split_reference(w) else {
            return Err(a.error_at(a.pos(), format!("bad value '{w}'"), None));
        };
        let known = match kind {
            'c' => sim.compute_index(id).is_some(),
            'f' => sim.fix_index(id).is_some(),
            _ => sim.script.vars.get(id).is_some(),
        };
        if !known {
            let (what, ids): (&str, Vec<&str>) = match kind {
                'c' => (
                    "compute",
                    sim.defs.computes.iter().map(|c| c.id()).collect(),
                ),
                'f' => ("fix", sim.defs.fixes.iter().map(|f| f.id()).collect()),
                _ => ("variable", sim.script.vars.names()),
            };
            return Err(a.error_at(
                a.pos(),
                format!("'{w}': no {what} '{id}'"),
                Some(crate::args::id_help(what, id, &ids)),
            ));
        }
        inputs.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    if inputs.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "ave/time needs at least one value (c_ID, c_ID[i], f_ID[i], v_name)",
            None,
        ));
    }
    let (mut running, mut path) = (false, None);
    while !a.is_done() {
        match a.keyword("ave/time keyword", &["file", "ave", "mode"])? {
            "file" => {
                let f = a.word("file name")?;
                if !sim.script.check {
                    path = Some((f.to_string(), a.pos() - 1));
                }
            }
            "ave" => running = a.keyword("ave", &["one", "running"])? == "running",
            _ => {
                a.keyword("mode", &["scalar"])?;
            }
        }
    }
    let n = inputs.len();
    let ave = AveTime {
        nevery,
        nrepeat,
        nfreq,
        inputs,
        running,
        path,
        file: None,
        sum: vec![0.0; n],
        count: 0,
        values: vec![0.0; n],
        running_sum: vec![0.0; n],
        windows: 0,
    };
    Ok(Box::new(ave))
}

/// What `ave/time` keeps in restart files: the open window, the last averages and the
/// running totals.
type AveTimeState = (Vec<f64>, u64, Vec<f64>, Vec<f64>, u64);

impl ScriptFix for AveTime {
    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        let st: AveTimeState = (
            self.sum.clone(),
            self.count,
            self.values.clone(),
            self.running_sum.clone(),
            self.windows,
        );
        postcard::to_stdvec(&st).ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        let st: AveTimeState = super::decode_state(state)?;
        let n = self.inputs.len();
        if [st.0.len(), st.2.len(), st.3.len()]
            .iter()
            .any(|&l| l != n && l != 0)
        {
            return Err(format!("it averages another number of values than {n}").into());
        }
        (
            self.sum,
            self.count,
            self.values,
            self.running_sum,
            self.windows,
        ) = st;
        Ok(())
    }

    /// Makes the `file` (its folder too) with its two header lines.
    fn install(&mut self, _sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        let Some((path, at)) = &self.path else {
            return Ok(());
        };
        let mut f = rdem_io::AppendFile::new(path);
        let header = format!(
            "# Time-averaged data for fix {}\n# TimeStep {}\n",
            head.id,
            self.inputs.join(" ")
        );
        f.append(header.as_bytes())
            .map_err(|e| a.error_at(*at, e.to_string(), None))?;
        self.file = Some(f);
        Ok(())
    }

    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(self.values.clone())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let setup = ctx.setup;
        if setup {
            return Ok(());
        }
        let in_window = {
            let next = step.div_ceil(self.nfreq) * self.nfreq;
            let first = next.saturating_sub((self.nrepeat - 1) * self.nevery);
            step >= first && (next - step) % self.nevery == 0
        };
        if !in_window {
            return Ok(());
        }
        for (j, i) in self.inputs.iter().enumerate() {
            self.sum[j] += thermo::column_value(ctx.view(), i)?.0;
        }
        self.count += 1;
        if step % self.nfreq == 0 {
            self.windows += 1;
            for j in 0..self.values.len() {
                let mean = self.sum[j] / self.count as f64;
                self.running_sum[j] += mean;
                self.values[j] = if self.running {
                    self.running_sum[j] / self.windows as f64
                } else {
                    mean
                };
            }
            self.sum.iter_mut().for_each(|s| *s = 0.0);
            self.count = 0;
            let mut wrote = Ok(());
            if let Some(f) = &mut self.file {
                let row: Vec<String> = self
                    .values
                    .iter()
                    .map(|v| crate::variables::format_g(*v, 6))
                    .collect();
                wrote = f
                    .append(format!("{step} {}\n", row.join(" ")).as_bytes())
                    .map_err(Error::from);
            }
            ctx.agree_write("fix ave/time", wrote)?;
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

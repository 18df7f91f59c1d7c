//! `fix ID group ave/spatial Nevery Nrepeat Nfreq dim origin delta [dim origin delta
//! [dim origin delta]] value ... [keyword ...]` (LIGGGHTS 3.8, from LAMMPS): per-atom
//! values binned in 1d layers, 2d pencils or 3d boxes and averaged over Nrepeat samples
//! every Nfreq steps, written to a file.
//!
//! - **Bins.** Along each dim, bins of width delta start at the origin (`lower`,
//!   `center`, `upper` face of the box, or a coordinate) and extend both ways until they
//!   cover the box; a particle beyond the first or last bin counts in it. Along a
//!   periodic axis a position is first wrapped into the box. They are laid out at the
//!   first sample of each average, the first dim varying slowest.
//! - **Values.** `vx vy vz fx fy fz`, `density/number` and `density/mass` (per bin
//!   volume), `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]` (per-atom) and `v_name` (atom-style),
//!   over the group's particles (inside `region`, if given).
//! - **norm all** (default): a bin's value is the sum over the samples' particles divided
//!   by their count; **norm sample**: the mean of each sample's mean (a sample with an
//!   empty bin adds 0). Densities are sums over a sample per bin volume, averaged over
//!   the samples. The count printed is the mean count per sample.
//! - **ave one|running|window M**: each average alone, the mean of all so far, or of the
//!   last M.
//! - **units** `box` by default, as LIGGGHTS 3.8 does (its manual says `lattice`).
//! - **file**: LIGGGHTS' layout (three `#` lines, unless `title1..3` change them; then
//!   per average `step nbins` unless `write_ts no`, and `  bin coord... count values...`
//!   with `%g`); `overwrite` keeps the last average only.
//!
//! The sampling steps, the bins and the normalizations were checked on LIGGGHTS 3.8 with
//! falling spheres (tests/ave_spatial.rs of rdem-cli): the same files, but for the
//! densities under `units reduced`, which LIGGGHTS 3.8 prints as 0 (rdem computes them). Sums are per rank, then over
//! ranks. Not supported yet (errors): `units reduced` with a triclinic box (rdem's boxes
//! are orthogonal), `std`, and reading the averages back as `f_ID[i][j]`.

use glam::DVec3;

use super::peratom_ref::PerAtomRef;
use super::sampling::Schedule;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::variables::format_g;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "ave/spatial",
    parse,
    Stages::END_OF_STEP,
    "`Nevery Nrepeat Nfreq` then 1–3 × `x|y|z lower|center|upper|coord delta`, values `vx vy vz fx fy fz density/number density/mass c_ID[i] f_ID[i] v_name`; `norm all|sample`, `ave one|running|window M`, `units box|lattice|reduced`, `region`, `file`, `overwrite`, `title1..3`, `write_ts`",
)
.notes("files byte for byte LIGGGHTS 3.8's (measured over 1d–3d bins and every norm/ave setting); default units `box`, as LIGGGHTS 3.8 does (its manual says `lattice`); under `units reduced` LIGGGHTS 3.8 prints the densities as 0, rdem computes them; the averages go to the file only (`f_ID[i][j]` is not supported yet); `std` is not supported yet");

#[derive(Clone, Copy, PartialEq)]
enum Origin {
    Lower,
    Center,
    Upper,
    At(f64),
}

struct Dim {
    axis: usize,
    origin: Origin,
    delta: f64,
}

enum Value {
    Field(String),
    DensityNumber,
    DensityMass,
    Ref(PerAtomRef),
}

#[derive(Clone, Copy, PartialEq)]
enum Ave {
    One,
    Running,
    Window(usize),
}

/// The bins laid out for the current average.
#[derive(Default, Clone)]
struct Layout {
    /// Per dim: low edge, width and number of bins.
    dims: Vec<(f64, f64, usize)>,
    /// Volume of one bin.
    volume: f64,
}

impl Layout {
    fn nbins(&self) -> usize {
        self.dims.iter().map(|d| d.2).product()
    }
}

struct AveSpatial {
    schedule: Schedule,
    dims: Vec<Dim>,
    /// Names of the values (the file's header).
    names: Vec<String>,
    values: Vec<Value>,
    norm_sample: bool,
    ave: Ave,
    /// Scale of `units lattice` (1 for box); `reduced`: fractions of the box.
    scale: DVec3,
    reduced: bool,
    region: Option<String>,
    path: Option<(String, usize)>,
    overwrite: bool,
    titles: [Option<String>; 3],
    write_ts: bool,
    /// The file's `#` lines, made when the fix is installed.
    header: String,
    file: Option<rdem_io::AppendFile>,
    layout: Layout,
    /// Per bin: the count and each value, summed over this average's samples.
    count_many: Vec<f64>,
    values_many: Vec<f64>,
    /// ave running|window: the averages combined so far, and (window) the last M.
    count_total: Vec<f64>,
    values_total: Vec<f64>,
    window: std::collections::VecDeque<(Vec<f64>, Vec<f64>)>,
    norm: usize,
}

fn axis_of(a: &mut Args) -> CmdResult<usize> {
    Ok(match a.keyword("dim", &["x", "y", "z"])? {
        "x" => 0,
        "y" => 1,
        _ => 2,
    })
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let schedule = Schedule::parse(a)?;
    let mut dims = Vec::new();
    while dims.len() < 3 && matches!(a.peek(), Some("x" | "y" | "z")) {
        let axis = axis_of(a)?;
        let origin = match a.peek() {
            Some("lower") => Origin::Lower,
            Some("center") => Origin::Center,
            Some("upper") => Origin::Upper,
            _ => Origin::At(a.f64("origin (lower, center, upper or a coordinate)")?),
        };
        if !matches!(origin, Origin::At(_)) {
            a.seek(a.pos() + 1);
        }
        let delta = a.positive("delta (bin width)")?;
        if dims.iter().any(|d: &Dim| d.axis == axis) {
            return Err(a.error_at(a.pos() - 3, "each dim can be binned once", None));
        }
        dims.push(Dim {
            axis,
            origin,
            delta,
        });
    }
    if dims.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "fix ave/spatial needs 'x|y|z origin delta' after Nfreq",
            None,
        ));
    }
    let (mut names, mut values) = (Vec::new(), Vec::new());
    const FIELDS: [&str; 6] = ["vx", "vy", "vz", "fx", "fy", "fz"];
    while let Some(w) = a.peek() {
        let v = if FIELDS.contains(&w) {
            Value::Field(w.to_string())
        } else if w == "density/number" {
            Value::DensityNumber
        } else if w == "density/mass" {
            Value::DensityMass
        } else if let Some(r) = PerAtomRef::parse(sim, a, a.pos(), w)? {
            Value::Ref(r)
        } else {
            break;
        };
        names.push(w.to_string());
        values.push(v);
        a.seek(a.pos() + 1);
    }
    if values.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "fix ave/spatial needs at least one value",
            Some("vx vy vz fx fy fz density/number density/mass c_ID f_ID v_name".into()),
        ));
    }
    // LIGGGHTS 3.8's default is box (measured: delta 0.01 after `lattice sc 0.01` gave
    // bins 0.01 wide), whatever its manual says.
    let (mut norm_sample, mut ave, mut units) = (false, Ave::One, "box");
    let (mut region, mut path, mut overwrite, mut write_ts) = (None, None, false, true);
    let mut titles: [Option<String>; 3] = Default::default();
    while !a.is_done() {
        match a.keyword(
            "fix ave/spatial keyword",
            &[
                "norm",
                "ave",
                "units",
                "region",
                "file",
                "overwrite",
                "title1",
                "title2",
                "title3",
                "write_ts",
            ],
        )? {
            "norm" => norm_sample = a.keyword("norm", &["all", "sample"])? == "sample",
            "ave" => {
                ave = match a.keyword("ave", &["one", "running", "window"])? {
                    "one" => Ave::One,
                    "running" => Ave::Running,
                    _ => Ave::Window(a.count("window size M")? as usize),
                }
            }
            "units" => units = a.keyword("units", &["box", "lattice", "reduced"])?,
            "region" => region = Some(sim.region_id(a)?),
            "file" => {
                let f = a.word("file name")?;
                if !sim.script.check {
                    path = Some((f.to_string(), a.pos() - 1));
                }
            }
            "overwrite" => overwrite = true,
            "write_ts" => write_ts = a.yes_no("write_ts")?,
            t => {
                let k = (t.as_bytes()[5] - b'1') as usize;
                titles[k] = Some(a.word("title")?.to_string());
            }
        }
    }
    if overwrite && ave != Ave::Running {
        return Err(a.error_cmd(
            "fix ave/spatial: overwrite needs 'ave running' (as in LIGGGHTS)",
            None,
        ));
    }
    if units == "lattice" && sim.defs.lattice.is_none() {
        return Err(a.error_cmd(
            "fix ave/spatial units lattice: no lattice is defined",
            Some("define one with 'lattice' first, or use 'units box'".into()),
        ));
    }
    let scale = crate::commands::region::scale_of(sim, a, units == "lattice")?;
    sim.world_ref(a)?;
    let _ = head;
    Ok(Box::new(AveSpatial {
        schedule,
        dims,
        names,
        values,
        norm_sample,
        ave,
        scale,
        reduced: units == "reduced",
        region,
        path,
        overwrite,
        titles,
        write_ts,
        header: String::new(),
        file: None,
        layout: Layout::default(),
        count_many: Vec::new(),
        values_many: Vec::new(),
        count_total: Vec::new(),
        values_total: Vec::new(),
        window: Default::default(),
        norm: 0,
    }))
}

impl AveSpatial {
    /// The bins over the current box.
    fn lay_out(&self, w: &rdem::World) -> Layout {
        let (lo, hi) = (w.domain.boxlo, w.domain.boxhi);
        let mut dims = Vec::new();
        let mut volume = 1.0;
        for d in &self.dims {
            let a = d.axis;
            let prd = hi[a] - lo[a];
            // `units reduced`: fractions of the box.
            let place = |o: f64| {
                if self.reduced {
                    lo[a] + o * prd
                } else {
                    o * self.scale[a]
                }
            };
            let delta = if self.reduced {
                d.delta * prd
            } else {
                d.delta * self.scale[a]
            };
            let offset = match d.origin {
                Origin::Lower => lo[a],
                Origin::Upper => hi[a],
                Origin::Center => 0.5 * (lo[a] + hi[a]),
                Origin::At(o) => place(o),
            };
            let below = ((offset - lo[a]) / delta).ceil().max(0.0);
            let above = ((hi[a] - offset) / delta).ceil().max(0.0);
            let first = offset - below * delta;
            let n = (below + above).max(1.0) as usize;
            dims.push((first, delta, n));
        }
        for a in 0..3 {
            volume *= match dims.iter().zip(&self.dims).find(|(_, d)| d.axis == a) {
                Some((b, _)) => b.1,
                None => w.domain.boxhi[a] - w.domain.boxlo[a],
            };
        }
        Layout { dims, volume }
    }

    /// The bin of a position.
    fn bin_of(&self, w: &rdem::World, x: DVec3) -> usize {
        let mut m = 0;
        for (b, d) in self.layout.dims.iter().zip(&self.dims) {
            let a = d.axis;
            let mut c = x[a];
            if w.domain.periodic(a) {
                let (lo, hi) = (w.domain.boxlo[a], w.domain.boxhi[a]);
                if c < lo {
                    c += hi - lo;
                }
                if c >= hi {
                    c -= hi - lo;
                }
            }
            // C's cast truncates toward zero; a bin below the first clamps to it anyway.
            let k = ((c - b.0) / b.1).trunc().max(0.0) as usize;
            m = m * b.2 + k.min(b.2 - 1);
        }
        m
    }

    /// One sample: sums per bin over the group's particles (all ranks).
    fn sample(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let sim = ctx.view();
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let region = match &self.region {
            Some(r) => Some(crate::regions::region_now(sim, r)?),
            None => None,
        };
        let p = &w.particles;
        let n = p.nlocal();
        let members: Vec<usize> = (0..n)
            .filter(|&i| {
                p.mask[i] & head.groupbit != 0 && region.as_ref().is_none_or(|r| r.contains(p.x[i]))
            })
            .collect();
        let bins: Vec<usize> = members.iter().map(|&i| self.bin_of(w, p.x[i])).collect();
        let nbins = self.layout.nbins();
        let nv = self.values.len();
        let mut one = vec![0.0; nbins * (1 + nv)];
        for &b in &bins {
            one[b] += 1.0;
        }
        for (j, v) in self.values.iter().enumerate() {
            let per: Vec<f64> = match v {
                Value::DensityNumber => vec![1.0; n],
                Value::DensityMass => p.rmass[..n].to_vec(),
                Value::Field(f) => crate::computes::kernels::field_values(w, f)
                    .ok_or_else(|| format!("bad attribute {f}"))?,
                Value::Ref(r) => r.values(sim)?,
            };
            for (&i, &b) in members.iter().zip(&bins) {
                one[nbins * (1 + j) + b] += per[i];
            }
        }
        w.comm.sum_slice(&mut one);
        let (count, vals) = one.split_at(nbins);
        for (total, c) in self.count_many.iter_mut().zip(count) {
            *total += c;
        }
        for (j, v) in self.values.iter().enumerate() {
            let density = matches!(v, Value::DensityNumber | Value::DensityMass);
            for b in 0..nbins {
                let x = vals[nbins * j + b];
                self.values_many[nbins * j + b] += if self.norm_sample && !density {
                    if count[b] > 0.0 {
                        x / count[b]
                    } else {
                        0.0
                    }
                } else {
                    x
                };
            }
        }
        Ok(())
    }

    /// The average of the samples (then combined per `ave`), as LIGGGHTS normalizes it.
    fn finish(&mut self) -> (Vec<f64>, Vec<f64>) {
        let nbins = self.layout.nbins();
        let repeat = self.schedule.nrepeat as f64;
        let mut count = self.count_many.clone();
        let mut vals = self.values_many.clone();
        for (j, v) in self.values.iter().enumerate() {
            let density = matches!(v, Value::DensityNumber | Value::DensityMass);
            for b in 0..nbins {
                let x = &mut vals[nbins * j + b];
                if density {
                    *x /= repeat * self.layout.volume;
                } else if self.norm_sample {
                    *x /= repeat;
                } else if count[b] > 0.0 {
                    *x /= count[b];
                }
            }
        }
        count.iter_mut().for_each(|c| *c /= repeat);
        match self.ave {
            Ave::One => {
                self.norm = 1;
                (count, vals)
            }
            Ave::Running | Ave::Window(_) => {
                if self.count_total.len() != count.len() || self.values_total.len() != vals.len() {
                    // The bins changed with the box: start again.
                    self.count_total = vec![0.0; count.len()];
                    self.values_total = vec![0.0; vals.len()];
                    self.window.clear();
                    self.norm = 0;
                }
                for (t, c) in self.count_total.iter_mut().zip(&count) {
                    *t += c;
                }
                for (t, v) in self.values_total.iter_mut().zip(&vals) {
                    *t += v;
                }
                self.norm += 1;
                if let Ave::Window(m) = self.ave {
                    self.window.push_back((count, vals));
                    if self.window.len() > m {
                        let (c, v) = self.window.pop_front().expect("full window");
                        for (t, c) in self.count_total.iter_mut().zip(&c) {
                            *t -= c;
                        }
                        for (t, v) in self.values_total.iter_mut().zip(&v) {
                            *t -= v;
                        }
                        self.norm -= 1;
                    }
                }
                let k = self.norm as f64;
                (
                    self.count_total.iter().map(|c| c / k).collect(),
                    self.values_total.iter().map(|v| v / k).collect(),
                )
            }
        }
    }

    /// The file's block for step `step`.
    fn block(&self, step: u64, w: &rdem::World, count: &[f64], vals: &[f64]) -> String {
        let nbins = self.layout.nbins();
        let mut s = String::new();
        if self.write_ts {
            s.push_str(&format!("{step} {nbins}\n"));
        }
        for m in 0..nbins {
            s.push_str(&format!("  {}", m + 1));
            let mut rest = m;
            let mut idx = vec![0; self.layout.dims.len()];
            for (k, d) in self.layout.dims.iter().enumerate().rev() {
                idx[k] = rest % d.2;
                rest /= d.2;
            }
            for (k, (d, dim)) in self.layout.dims.iter().zip(&self.dims).enumerate() {
                let mut c = d.0 + (idx[k] as f64 + 0.5) * d.1;
                if self.reduced {
                    let a = dim.axis;
                    c = (c - w.domain.boxlo[a]) / (w.domain.boxhi[a] - w.domain.boxlo[a]);
                }
                s.push_str(&format!(" {}", format_g(c, 6)));
            }
            s.push_str(&format!(" {}", format_g(count[m], 6)));
            for j in 0..self.values.len() {
                s.push_str(&format!(" {}", format_g(vals[nbins * j + m], 6)));
            }
            s.push('\n');
        }
        s
    }

    fn make_header(&self, head: &FixHead, group: &str) -> String {
        let coords = match self.dims.len() {
            1 => "Coord".to_string(),
            n => (1..=n)
                .map(|k| format!("Coord{k}"))
                .collect::<Vec<_>>()
                .join(" "),
        };
        let defaults = [
            format!(
                "# Spatial-averaged data for fix {} and group {group}",
                head.id
            ),
            "# Timestep Number-of-bins".to_string(),
            format!("# Bin {coords} Ncount {}", self.names.join(" ")),
        ];
        let mut s = String::new();
        for (t, d) in self.titles.iter().zip(defaults) {
            let line = t.clone().unwrap_or(d);
            if !line.is_empty() {
                s.push_str(&line);
                s.push('\n');
            }
        }
        s
    }
}

impl ScriptFix for AveSpatial {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.schedule.begin(sim.world_ref(a)?.step);
        let group = sim.defs.groups.name_of_bit(head.groupbit).unwrap_or("all");
        self.header = self.make_header(head, group);
        let Some((path, at)) = &self.path else {
            return Ok(());
        };
        if sim.world.as_ref().is_some_and(|w| !w.comm.is_root()) {
            return Ok(());
        }
        let mut f = rdem_io::AppendFile::new(path);
        if !self.overwrite {
            f.append(self.header.as_bytes())
                .map_err(|e| a.error_at(*at, e.to_string(), None))?;
        }
        self.file = Some(f);
        Ok(())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let Some(first) = self.schedule.due(step) else {
            return Ok(());
        };
        if first {
            self.layout = self.lay_out(ctx.world_ref());
            let nbins = self.layout.nbins();
            self.count_many = vec![0.0; nbins];
            self.values_many = vec![0.0; nbins * self.values.len()];
        }
        self.sample(ctx, head)?;
        if !self.schedule.sampled(step) {
            return Ok(());
        }
        let (count, vals) = self.finish();
        let text = self.block(step, ctx.world_ref(), &count, &vals);
        let mut wrote = Ok(());
        if let Some((path, _)) = &self.path {
            if self.overwrite {
                let all = format!("{}{text}", self.header);
                if ctx.world_ref().comm.is_root() {
                    wrote = rdem_io::write_atomic(std::path::Path::new(path), all.as_bytes())
                        .map_err(Error::from);
                }
            } else if let Some(f) = &mut self.file {
                wrote = f.append(text.as_bytes()).map_err(Error::from);
            }
        }
        ctx.agree_write("fix ave/spatial", wrote)
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

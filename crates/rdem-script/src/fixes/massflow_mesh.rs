//! `fix massflow/mesh`: counts the particles (and their mass) that cross a mesh face
//! towards `vec_side`, optionally deleting them; `f_ID[1..6]` gives totals and rates;
//! `file`/`append` write one line per counted particle.

use crate::error::Error;
use rdem_io::AppendFile;

use super::{mesh_ref, style, FixHead, FixRow, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "massflow/mesh",
    parse,
    Stages::POST_INTEGRATE
        .and(Stages::END_OF_STEP)
        .and(Stages::VALUES),
    "`mesh ID vec_side vx vy vz`, `count once\\|multiple`, `delete_atoms yes\\|no`, `file F`, `append F`, `writeTime`; `screen` accepted",
)
.notes("`f_ID[1..6]`: mass and count through the face, mass and number rates since the previous evaluation (thermo output), deleted mass and count; a particle counts when its centre crosses the face's plane inside a triangle; `delete_atoms yes` removes it at the next re-neighboring, as LIGGGHTS does; `file`/`append`: a line per counted particle (ID, [time,] diameter, position, velocity) in LIGGGHTS 3.8's layout, counted where LIGGGHTS counts (after the initial integration: the half-step velocity); under `coarsegraining` the diameter over the factor, as LIGGGHTS-PFM; `point_at_outlet`, `inside_out` stop with an error");

/// `fix massflow/mesh`: the engine's counter and the output rates.
pub struct MassFlowFix {
    /// Totals and settings.
    pub flow: rdem::massflow::MassFlow,
    /// (step, mass, count) when the rates were last evaluated (`None`: the run start).
    pub last: std::cell::Cell<Option<(u64, f64, u64)>>,
    /// (step, mass rate, number rate) of the last evaluation.
    pub rates: std::cell::Cell<(u64, f64, f64)>,
    /// `file F` / `append F`.
    pub out: Option<FlowFile>,
}

/// `file F` / `append F`: one line per counted particle, as LIGGGHTS 3.8 writes it (checked
/// there): a header `# ID [time  ]diameter x y z u v w  (ex ey ez, color)`, then per
/// particle its ID, with `writeTime` two spaces, the time and a space, then each of
/// diameter, x, y, z, vx, vy, vz as a space and the value right-aligned in 4 columns,
/// numbers with 4 significant digits as C's `%.4g`.
pub struct FlowFile {
    /// The file name.
    pub path: String,
    /// `append` rather than `file`.
    pub append: bool,
    /// Where the name stands in the definition (for errors opening it).
    pub word: usize,
    /// `writeTime`.
    pub write_time: bool,
    /// The `coarsegraining` factor: the file gives the diameter the script describes,
    /// 2r/cg, as LIGGGHTS-PFM writes it.
    pub coarse_graining: f64,
    /// This rank's lines of the step's crossings, (ID, diameter, x, y, z, vx, vy, vz)
    /// each, from the post-integrate stage to the end of the step.
    pub pending: Vec<f64>,
    /// The file (on the rank that writes files; none under `rdem -check`).
    pub writer: Option<AppendFile>,
}

impl FlowFile {
    /// The header line.
    fn header(&self) -> &'static str {
        if self.write_time {
            "# ID time  diameter x y z u v w  (ex ey ez, color)\n"
        } else {
            "# ID diameter x y z u v w  (ex ey ez, color)\n"
        }
    }

    /// One line: `row` is (ID, diameter, x, y, z, vx, vy, vz).
    fn line(&self, time: f64, row: &[f64]) -> String {
        let g = |v: f64| crate::variables::format_g(v, 4);
        let mut s = format!("{}", row[0] as u64);
        if self.write_time {
            s.push_str(&format!("  {} ", g(time)));
        }
        for &v in &row[1..8] {
            s.push_str(&format!(" {:>4}", g(v)));
        }
        s.push('\n');
        s
    }
}

impl MassFlowFix {
    /// `f_ID[1..6]`: mass, count, mass rate and number rate since the last evaluation
    /// at an earlier step (the previous thermo output), deleted mass and count.
    fn rates(&self, step: u64, dt: f64) -> [f64; 6] {
        let f = &self.flow;
        let (s, mr, nr) = self.rates.get();
        let (mr, nr) = if s == step {
            (mr, nr)
        } else {
            let (s0, m0, c0) = self.last.get().unwrap_or((0, 0.0, 0));
            let t = step.saturating_sub(s0) as f64 * dt;
            let r = if t > 0.0 {
                ((f.mass - m0) / t, (f.count - c0) as f64 / t)
            } else {
                (0.0, 0.0)
            };
            self.last.set(Some((step, f.mass, f.count)));
            self.rates.set((step, r.0, r.1));
            r
        };
        [
            f.mass,
            f.count as f64,
            mr,
            nr,
            f.deleted_mass,
            f.deleted as f64,
        ]
    }
}

/// `fix ID group massflow/mesh mesh MESH vec_side x y z [count once|multiple]
/// [delete_atoms yes|no] [screen yes|no]`.
fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (id, groupbit) = (head.id.as_str(), head.groupbit);
    a.keyword("massflow/mesh keyword", &["mesh"])?;
    let mesh_at = a.pos();
    let mesh = mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?;
    const KEYS: [&str; 7] = [
        "vec_side",
        "count",
        "delete_atoms",
        "screen",
        "writeTime",
        "file",
        "append",
    ];
    const LATER_KEYS: [&str; 3] = ["point_at_outlet", "inside_out", "lambda"];
    let (mut side, mut once, mut delete) = (None, false, false);
    let (mut out, mut write_time) = (None, false);
    while let Some(w) = a.peek() {
        if LATER_KEYS.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("massflow/mesh keyword '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", KEYS.join(", "))),
            ));
        }
        match a.keyword("massflow/mesh keyword", &KEYS)? {
            "vec_side" => side = Some(a.vec3("vec_side")?),
            "count" => once = a.keyword("count", &["once", "multiple"])? == "once",
            "delete_atoms" => delete = a.yes_no("delete_atoms")?,
            "screen" => {
                a.yes_no("screen")?;
            }
            "writeTime" => write_time = true,
            key => {
                let word = a.pos();
                out = Some((a.word("file name")?.to_string(), key == "append", word));
            }
        }
    }
    let Some(side) = side else {
        return Err(a.error_at(
            STYLE_WORD,
            "massflow/mesh needs 'vec_side vx vy vz' (the outer side of the face)",
            None,
        ));
    };
    let w = sim.world_ref(a)?;
    let mut mf = rdem::massflow::MassFlow::new(id, mesh, &w.meshes[mesh].mesh, groupbit, side)
        .map_err(|e| a.error_at(mesh_at, e.to_string(), None))?;
    mf.once = once;
    mf.delete = delete;
    mf.record = out.is_some();
    Ok(Box::new(MassFlowFix {
        flow: mf,
        last: std::cell::Cell::new(None),
        rates: std::cell::Cell::new((u64::MAX, 0.0, 0.0)),
        out: out.map(|(path, append, word)| FlowFile {
            path,
            append,
            word,
            write_time,
            coarse_graining: sim.setup.coarse_graining.factor,
            pending: Vec::new(),
            writer: None,
        }),
    }))
}

/// What `massflow/mesh` keeps in restart files: the totals and the last rate
/// evaluation (the particles' counted flags travel with them).
type FlowState = (f64, u64, f64, u64, Option<(u64, f64, u64)>, (u64, f64, f64));

impl ScriptFix for MassFlowFix {
    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        let f = &self.flow;
        let st: FlowState = (
            f.mass,
            f.count,
            f.deleted_mass,
            f.deleted,
            self.last.get(),
            self.rates.get(),
        );
        postcard::to_stdvec(&st).ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        let st: FlowState = super::decode_state(state)?;
        let f = &mut self.flow;
        (f.mass, f.count, f.deleted_mass, f.deleted) = (st.0, st.1, st.2, st.3);
        self.last.set(st.4);
        self.rates.set(st.5);
        Ok(())
    }

    /// Opens the `file`/`append` file and writes its header (not under `rdem -check`,
    /// and only on the rank that writes files).
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let root = sim.world.as_ref().is_some_and(|w| w.comm.is_root());
        let Some(f) = self.out.as_mut().filter(|_| root && !sim.script.check) else {
            return Ok(());
        };
        // Unlike `fix print`, a missing folder is not made (the file is opened as it
        // always was here).
        let path = std::path::Path::new(&f.path);
        if path
            .parent()
            .is_some_and(|d| !d.as_os_str().is_empty() && !d.is_dir())
        {
            return Err(a.error_at(
                f.word,
                format!("cannot write {}: its folder does not exist", f.path),
                None,
            ));
        }
        let mut file = if f.append {
            AppendFile::appending(path).map_err(|e| a.error_at(f.word, e.to_string(), None))?
        } else {
            AppendFile::new(path)
        };
        file.append(f.header().as_bytes())
            .map_err(|e| a.error_at(f.word, e.to_string(), None))?;
        f.writer = Some(file);
        Ok(())
    }

    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("needs a simulation box")?;
        Ok(self.rates(w.step, w.dt).to_vec())
    }

    /// Counts the crossings where LIGGGHTS does (its `post_integrate`): with the step's
    /// new positions and the half-step velocities, which the file's lines give.
    fn post_integrate(&mut self, _head: &FixHead, w: &mut rdem::World) -> rdem::Result<()> {
        self.flow.update(w)?;
        let Some(out) = &mut self.out else {
            return Ok(());
        };
        let p = &w.particles;
        out.pending.clear();
        out.pending.extend(self.flow.crossed.iter().flat_map(|&i| {
            let (x, v) = (p.x[i], p.v[i]);
            [
                p.tag[i] as f64,
                2.0 * p.radius[i] / out.coarse_graining,
                x.x,
                x.y,
                x.z,
                v.x,
                v.y,
                v.z,
            ]
        }));
        Ok(())
    }

    /// Writes the step's lines (every rank's, in rank order, on the rank that writes).
    fn end_of_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            return Ok(());
        }
        let time = ctx.time();
        let w = ctx.world();
        let Some(out) = &mut self.out else {
            return Ok(());
        };
        let rows = std::mem::take(&mut out.pending);
        let mut wrote = Ok(());
        if let Some(all) = w.comm.gather(&rows) {
            let text: String = all.chunks_exact(8).map(|r| out.line(time, r)).collect();
            if let Some(file) = &mut out.writer {
                wrote = file.append(text.as_bytes()).map_err(Error::from);
            }
        }
        ctx.agree_write("fix massflow/mesh", wrote)
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

//! Thermo output: the keywords of `thermo_style custom`, their values, and the table in
//! LIGGGHTS' layout (a header line of the keywords, then one row per output step; integers
//! as `%8d`, floats as `%12.8g`, each followed by a space, unless `thermo_modify format`
//! says otherwise). With `thermo_modify line multi`, LIGGGHTS 3.8's multi-line layout
//! (measured): no header; per output a banner `---------------- Step %8d ----- CPU =
//! %11.4f (sec) ----------------`, then `%-8s = ` label and value (integers `%14d`,
//! floats `%14.4f`, or the `thermo_modify format`), each followed by a space, three to a
//! line.

use crate::computes;
use crate::context;
use crate::diagnostic::RunError;
use crate::error::Error;
use crate::sim::Sim;
use crate::variables::format_g;

/// Keywords with a value of their own (besides `c_`, `f_`, `v_` references).
pub const KEYWORDS: [&str; 25] = [
    "step",
    "elapsed",
    "elaplong",
    "dt",
    "time",
    "cpu",
    "atoms",
    "ke",
    "temp",
    "pe",
    "etotal",
    "vol",
    "lx",
    "ly",
    "lz",
    "xlo",
    "xhi",
    "ylo",
    "yhi",
    "zlo",
    "zhi",
    "cpuremain",
    "spcpu",
    "numbonds",
    "numbond",
];

/// Integer-valued keywords.
const INT_KEYWORDS: [&str; 6] = [
    "step", "elapsed", "elaplong", "atoms", "numbonds", "numbond",
];

/// Extensive keywords (divided by the atom count with `thermo_modify norm yes`).
const EXTENSIVE: [&str; 3] = ["ke", "pe", "etotal"];

/// Thermo settings.
#[derive(Debug, Clone)]
pub struct Thermo {
    /// Output every this many steps (0: first and last step of a run only).
    pub every: u64,
    /// Columns.
    pub columns: Vec<String>,
    /// Where each column was written (`thermo_style`), for errors found during a run.
    pub origins: Vec<Option<crate::diagnostic::Origin>>,
    /// `thermo_modify norm`.
    pub norm: bool,
    /// Per-column C formats (`thermo_modify format N "fmt"`), by 1-based column.
    pub col_format: Vec<(usize, String)>,
    /// `thermo_modify format int "fmt"`.
    pub int_format: Option<String>,
    /// `thermo_modify format float "fmt"`.
    pub float_format: Option<String>,
    /// `thermo_modify format line "fmt fmt ..."`.
    pub line_format: Option<Vec<String>>,
    /// Last step printed (no duplicate rows).
    pub last_printed: Option<u64>,
    /// `thermo_modify line multi`.
    pub multi: bool,
    /// The rows of the current (or last) run, as numbers.
    pub table: ThermoTable,
}

/// The thermo rows of one run as numbers (for host programs such as the Python module).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ThermoTable {
    /// Column keywords, as in `thermo_style`.
    pub columns: Vec<String>,
    /// One row per printed step, one value per column.
    pub rows: Vec<Vec<f64>>,
}

impl Default for Thermo {
    fn default() -> Self {
        Self {
            every: 0,
            columns: ["step", "atoms", "ke", "cpu"].map(String::from).to_vec(),
            origins: vec![None; 4],
            norm: false,
            col_format: Vec::new(),
            int_format: None,
            float_format: None,
            line_format: None,
            last_printed: None,
            multi: false,
            table: ThermoTable::default(),
        }
    }
}

/// True if `kw` is a valid column.
pub fn valid_column(kw: &str) -> bool {
    KEYWORDS.contains(&kw) || kw.starts_with("c_") || kw.starts_with("f_") || kw.starts_with("v_")
}

/// The value of thermo keyword `kw` (also used by formulas), divided by the atom count
/// for extensive keywords under `thermo_modify norm yes` (formulas see the normalised
/// value too, as in LIGGGHTS).
pub fn keyword(sim: &Sim, kw: &str) -> Result<f64, Error> {
    let v = raw_keyword(sim, kw)?;
    let n = sim.natoms();
    Ok(
        if sim.outputs.thermo.norm && EXTENSIVE.contains(&kw) && n > 0 {
            v / n as f64
        } else {
            v
        },
    )
}

fn raw_keyword(sim: &Sim, kw: &str) -> Result<f64, Error> {
    let w = sim.world.as_ref();
    let natoms = sim.natoms();
    let size = w.map(|w| w.domain.boxhi - w.domain.boxlo);
    let need_box = || format!("thermo keyword '{kw}' needs the simulation box");
    Ok(match kw {
        "step" => w.map(|w| w.step).unwrap_or(0) as f64,
        "elapsed" => w
            .map(|w| w.step)
            .unwrap_or(0)
            .saturating_sub(sim.script.run_first) as f64,
        // From `run ... start N1` when given (LAMMPS' beginstep).
        "elaplong" => w
            .map(|w| w.step)
            .unwrap_or(0)
            .saturating_sub(sim.script.run_begin) as f64,
        "dt" => sim.dt(),
        "time" => sim.time(),
        // Wall time since the run's loop started (0 at set-up), as LIGGGHTS.
        "cpu" => {
            if w.map(|w| w.step).unwrap_or(0) == sim.script.run_first {
                0.0
            } else {
                sim.script.run_started.elapsed().as_secs_f64()
            }
        }
        "cpuremain" | "spcpu" => 0.0,
        "atoms" => natoms as f64,
        // The bonds of `bond_style gran` (LIGGGHTS_Flexible_Fibers `numbonds`,
        // LIGGGHTS-PFM `numbond`), a broken one counted until the next re-neighboring.
        "numbonds" | "numbond" => {
            let w = w.ok_or_else(need_box)?;
            let n = w.bonds.as_ref().map_or(0, |b| b.count_local(&w.particles));
            w.comm.sum_count(n) as f64
        }
        // Σ ½ m v² over all particles, whatever the degrees of freedom of `thermo_temp`:
        // LIGGGHTS 3.8 prints 9.16297857297023e-05 for one particle (d = 0.01, ρ = 2500,
        // v = (0.1, 0.2, 0.3)) and the same `ke` for any `compute_modify thermo_temp
        // extra` (tests/temperature.rs).
        "ke" => computes::kinetic(w.ok_or_else(need_box)?, 1),
        // LIGGGHTS 3.8 has no `temp` keyword: rdem's is `c_thermo_temp`.
        "temp" => {
            w.ok_or_else(need_box)?;
            context::compute_global(sim, "thermo_temp", None)
                .map_err(|e| format!("thermo keyword 'temp' is c_thermo_temp: {e}"))?
        }
        "pe" => 0.0,
        "etotal" => computes::kinetic(w.ok_or_else(need_box)?, 1),
        // In 2d the area, as LAMMPS and LIGGGHTS 3.8 (sph_2 prints 0.282382 for a
        // 0.542 × 0.521 × 0.002 box).
        "vol" => {
            let s = size.ok_or_else(need_box)?;
            if sim.setup.dimension == 2 {
                s.x * s.y
            } else {
                s.x * s.y * s.z
            }
        }
        "lx" | "ly" | "lz" => size.ok_or_else(need_box)?[(kw.as_bytes()[1] - b'x') as usize],
        "xlo" | "ylo" | "zlo" => {
            w.ok_or_else(need_box)?.domain.boxlo[(kw.as_bytes()[0] - b'x') as usize]
        }
        "xhi" | "yhi" | "zhi" => {
            w.ok_or_else(need_box)?.domain.boxhi[(kw.as_bytes()[0] - b'x') as usize]
        }
        _ => {
            return Err(format!(
                "unknown thermo keyword '{kw}' (valid: {} or c_ID, f_ID, v_name)",
                KEYWORDS.join(" ")
            )
            .into())
        }
    })
}

/// Parses `c_ID`, `c_ID[2]`, `f_ID[1]`, `v_name`: (prefix, id, index).
pub fn split_reference(col: &str) -> Option<(char, &str, Option<usize>)> {
    let kind = col.chars().next()?;
    if !matches!(kind, 'c' | 'f' | 'v') || col.as_bytes().get(1) != Some(&b'_') {
        return None;
    }
    let rest = &col[2..];
    match rest.find('[') {
        Some(b) if rest.ends_with(']') => {
            let idx = rest[b + 1..rest.len() - 1].parse().ok()?;
            Some((kind, &rest[..b], Some(idx)))
        }
        Some(_) => None,
        None => Some((kind, rest, None)),
    }
}

/// Value of one column and whether it prints as an integer.
pub fn column_value(sim: &Sim, col: &str) -> Result<(f64, bool), Error> {
    if let Some((kind, id, idx)) = split_reference(col) {
        let v = match kind {
            'c' => context::compute_global(sim, id, idx)?,
            'f' => crate::fixes::fix_value(sim, id, idx)?,
            _ => {
                if idx.is_some() {
                    return Err(format!("{col}: variables have no index here").into());
                }
                match sim.script.vars.get(id) {
                    Some(crate::variables::Variable::Equal(f)) => {
                        context::eval_equal(sim, f).map_err(|e| e.message)?
                    }
                    Some(_) => {
                        let t = context::variable_text(sim, id)?;
                        crate::args::parse_f64(t.trim())
                            .ok_or_else(|| format!("variable {id} = '{t}' is not a number"))?
                    }
                    None => return Err(Error::undefined("variable", id)),
                }
            }
        };
        return Ok((v, false));
    }
    Ok((keyword(sim, col)?, INT_KEYWORDS.contains(&col)))
}

/// The header line (`None` with `thermo_modify line multi`, which prints none).
pub fn header(sim: &Sim) -> Option<String> {
    if sim.outputs.thermo.multi {
        return None;
    }
    let mut s = String::new();
    for c in &sim.outputs.thermo.columns {
        let int = INT_KEYWORDS.contains(&c.as_str());
        let label = header_label(c);
        if int {
            s.push_str(&format!("{label:>8} "));
        } else {
            s.push_str(&format!("{label:>14} "));
        }
    }
    Some(s)
}

/// LIGGGHTS' header label of a column (a few keywords print capitalised).
fn header_label(c: &str) -> String {
    match c {
        "step" => "Step".into(),
        "atoms" => "Atoms".into(),
        "ke" => "KinEng".into(),
        "vol" => "Volume".into(),
        "temp" => "Temp".into(),
        "pe" => "PotEng".into(),
        "etotal" => "TotEng".into(),
        "elapsed" => "Elapsed".into(),
        "elaplong" => "Elaplong".into(),
        "dt" => "Dt".into(),
        "time" => "Time".into(),
        "cpu" => "CPU".into(),
        "lx" => "Lx".into(),
        "ly" => "Ly".into(),
        "lz" => "Lz".into(),
        "xlo" => "Xlo".into(),
        "xhi" => "Xhi".into(),
        "ylo" => "Ylo".into(),
        "yhi" => "Yhi".into(),
        "zlo" => "Zlo".into(),
        "zhi" => "Zhi".into(),
        "cpuremain" => "CPULeft".into(),
        "spcpu" => "S/CPU".into(),
        // LIGGGHTS shows c_ID, f_ID, v_name without the prefix, cut to 8 characters.
        _ => match split_reference(c) {
            Some((_, id, None)) => id.chars().take(8).collect(),
            Some((_, id, Some(k))) => format!("{id}[{k}]").chars().take(8).collect(),
            None => c.to_string(),
        },
    }
}

/// True for a `c_`/`f_` column that thermo normalises under `thermo_modify norm yes`:
/// extensive computes, and fix check/timestep/gran, whose two fractions LIGGGHTS 3.8
/// divides by the atom count too (observed; tests/liggghts_parity.rs). Variables and
/// other fixes are printed as they are.
fn extensive_reference(sim: &Sim, col: &str) -> bool {
    match split_reference(col) {
        Some(('c', id, _)) => sim
            .defs
            .computes
            .iter()
            .any(|c| c.id() == id && c.is_extensive()),
        Some(('f', id, _)) => crate::fixes::is_extensive(sim, id),
        _ => false,
    }
}

/// One row (with `thermo_modify line multi`, the banner and the labelled lines).
pub fn row(sim: &Sim) -> Result<String, RunError> {
    row_and_values(sim).map(|(text, _)| text)
}

/// The thermo row of the current step as printed, and its values (after `norm`).
pub fn row_and_values(sim: &Sim) -> Result<(String, Vec<f64>), RunError> {
    let th = &sim.outputs.thermo;
    let mut cells = Vec::with_capacity(th.columns.len());
    let mut values = Vec::with_capacity(th.columns.len());
    for (k, c) in th.columns.iter().enumerate() {
        let (mut v, int) = column_value(sim, c).map_err(|m| {
            // A variable that fails is reported at its definition, else the column.
            let var = match split_reference(c) {
                Some(('v', id, _)) => sim.script.vars.origin(id),
                _ => None,
            };
            match var {
                Some(o) => RunError::at(Some(o), "rdem::run::variable", m),
                None => {
                    let origin = th.origins.get(k).and_then(Option::as_ref);
                    RunError::at(origin, "rdem::run::thermo", m)
                }
            }
        })?;
        let n = sim.natoms();
        if th.norm && n > 0 && extensive_reference(sim, c) {
            v /= n as f64;
        }
        values.push(v);
        let fmt = th
            .col_format
            .iter()
            .rev()
            .find(|(n, _)| *n == k + 1)
            .map(|(_, f)| f.clone())
            .or_else(|| th.line_format.as_ref().and_then(|l| l.get(k).cloned()))
            .or_else(|| {
                if int {
                    th.int_format.clone()
                } else {
                    th.float_format.clone()
                }
            });
        cells.push(match fmt {
            Some(f) => match rdem_io::Printf::parse(&f) {
                Ok(p) => p.format(if int {
                    rdem_io::Value::Int(v as i64)
                } else {
                    rdem_io::Value::Float(v)
                }),
                Err(e) => return Err(format!("thermo_modify format '{f}': {e}").into()),
            },
            None if th.multi && int => format!("{:>14}", v as i64),
            None if th.multi => format!("{v:>14.4}"),
            None if int => format!("{:>8}", v as i64),
            None => format!("{:>14}", format_g(v, 8)),
        });
    }
    if !th.multi {
        return Ok((cells.iter().map(|c| format!("{c} ")).collect(), values));
    }
    let step = sim.world.as_ref().map_or(0, |w| w.step);
    let cpu = keyword(sim, "cpu").unwrap_or(0.0);
    let mut s =
        format!("---------------- Step {step:>8} ----- CPU = {cpu:>11.4} (sec) ----------------");
    for (k, (c, cell)) in th.columns.iter().zip(&cells).enumerate() {
        if k % 3 == 0 {
            s.push('\n');
        }
        s.push_str(&format!("{:<8} = {cell} ", header_label(c)));
    }
    Ok((s, values))
}

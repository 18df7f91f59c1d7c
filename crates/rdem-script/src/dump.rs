//! `dump`, `dump_modify`, `undump` and `write_dump`: which particles and columns are written
//! when; the file formats themselves are in `rdem-io`.

use rdem_io::{
    AtomVtkDump, Column, Compressor, DumpFileName, PvdSeries, Sort, TextDump, TextOptions, VtkDump,
};

use rdem::comm::Comm;
use rdem::{DVec3, Particles};

use crate::args::{suggest, Args, CmdResult};
use crate::context;
use crate::sim::Sim;
use crate::thermo::split_reference;
use crate::variables::Variable;

/// Dump styles rdem writes.
pub const STYLES: [&str; 7] = [
    "custom",
    "custom/vtk",
    "atom/vtk",
    "euler/vtk",
    "mesh/stl",
    "mesh/vtk",
    "mesh/gran/VTK",
];

/// LIGGGHTS dump styles of later releases.
const LATER: [&str; 5] = [
    "mesh/vtk",
    "mesh/gran/VTK",
    "mesh/vtm",
    "local/gran/vtk",
    "atom",
];

/// The writer of a dump.
pub enum Writer {
    /// `dump custom`.
    Text(TextDump),
    /// `dump custom/vtk`.
    Vtk(VtkDump),
    /// `dump atom/vtk`.
    AtomVtk(AtomVtkDump),
    /// `dump euler/vtk`: the cells of the `fix ave/euler` (the dump's group and sort do
    /// not apply, as in LIGGGHTS).
    Euler(DumpFileName),
    /// `dump mesh/stl`: the triangles of the meshes named in the columns (all meshes
    /// without any) at their current positions, in one ASCII STL file per snapshot.
    MeshStl(DumpFileName),
    /// `dump mesh/vtk` (and its old name `mesh/gran/VTK`): the meshes named in `meshes`
    /// (all without any) as legacy VTK with the per-triangle values the columns name.
    MeshVtk {
        /// File name pattern.
        name: DumpFileName,
        /// Mesh IDs.
        meshes: Vec<String>,
    },
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
    /// The ParaView collection of a VTK dump whose name has `*` (see [`rdem_io::pvd`]);
    /// `None` for text dumps, `write_dump` and a VTK file overwritten at each snapshot.
    pub pvd: Option<PvdSeries>,
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

pub(crate) fn columns(sim: &Sim, args: &[String]) -> Result<Vec<Column>, String> {
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

/// Writes every dump due at `step` (at set-up: also dumps that never wrote). At the last
/// step of a run, waits for the snapshots still being written in the background.
pub fn write_due(sim: &mut Sim, step: u64, setup: bool) -> Result<(), String> {
    for k in 0..sim.dumps.len() {
        let d = &sim.dumps[k];
        let due = (step % d.every == 0 || (setup && d.last.is_none())) && d.last != Some(step);
        if due {
            write_one(sim, k, step)?;
        }
    }
    if step == sim.run_last {
        finish_all(sim)?;
    }
    Ok(())
}

/// Waits for every snapshot being written in the background and lists it in its `.pvd`.
/// Collective (only rank 0 writes, so a failure there stops every rank).
pub fn finish_all(sim: &mut Sim) -> Result<(), String> {
    let outcome = sim.dumps.iter_mut().try_for_each(finish);
    match &sim.world {
        Some(w) => agree(&*w.comm, "dump", outcome),
        None => outcome,
    }
}

fn finish(d: &mut Dump) -> Result<(), String> {
    if let Writer::AtomVtk(v) = &mut d.writer {
        let done = v.finish().map_err(|e| format!("dump {}: {e}", d.id))?;
        record(d, done.into_iter().collect())?;
    }
    Ok(())
}

/// Lists completed snapshots in the dump's `.pvd`.
fn record(d: &mut Dump, done: Vec<(f64, std::path::PathBuf)>) -> Result<(), String> {
    if let Some(pvd) = &mut d.pvd {
        for (time, path) in done {
            pvd.add(time, &path)
                .map_err(|e| format!("dump {}: {e}", d.id))?;
        }
    }
    Ok(())
}

/// The owned particles of every rank, gathered on rank 0 by [`gather_owned`].
pub(crate) struct Gathered {
    /// The particles, all owned (`nlocal` = their number), in rank order then each rank's
    /// storage order; positions, velocities, forces, torques, radii, masses, densities,
    /// types, masks and image flags (no named properties).
    pub particles: Particles,
    /// The rank that owns each gathered particle (the `proc` of `dump atom/vtk`).
    pub procs: Vec<i32>,
    /// The values of each custom column, by gathered particle index.
    pub custom: Vec<Vec<f64>>,
}

/// Gathers the owned particles `selection` of every rank, with their values of the
/// `custom` columns (`custom[k][i]` for owned particle index `i`), on rank 0: `None` on
/// the other ranks. A collective call: every rank must make it, in the same order.
pub(crate) fn gather_owned(
    comm: &dyn Comm,
    p: &Particles,
    selection: &[usize],
    custom: &[&[f64]],
) -> Option<Gathered> {
    // The fixed part of `Particles::pack` (no named properties): tag, type, mask, x, v,
    // omega, radius, mass, density, image flags; then force, torque, rank, custom values.
    let fixed = Particles::new().packed_len();
    let rec = fixed + 7 + custom.len();
    let rank = comm.rank() as f64;
    let mut buf = Vec::with_capacity(selection.len() * rec);
    let mut one = Vec::with_capacity(p.packed_len());
    for &i in selection {
        one.clear();
        p.pack(i, DVec3::ZERO, &mut one);
        // The position exactly as stored (a zero shift would turn -0.0 into +0.0).
        one[3..6].copy_from_slice(&p.x[i].to_array());
        buf.extend_from_slice(&one[..fixed]);
        buf.extend_from_slice(&p.f[i].to_array());
        buf.extend_from_slice(&p.torque[i].to_array());
        buf.push(rank);
        buf.extend(custom.iter().map(|c| c[i]));
    }
    let all = comm.gather(&buf)?;
    let n = all.len() / rec;
    let mut g = Gathered {
        particles: Particles::new(),
        procs: Vec::with_capacity(n),
        custom: vec![Vec::with_capacity(n); custom.len()],
    };
    for r in all.chunks_exact(rec) {
        let q = &mut g.particles;
        q.unpack(&r[..fixed], None);
        let k = q.nlocal() - 1;
        q.f[k] = DVec3::from_slice(&r[fixed..fixed + 3]);
        q.torque[k] = DVec3::from_slice(&r[fixed + 3..fixed + 6]);
        g.procs.push(r[fixed + 6] as i32);
        for (c, &v) in g.custom.iter_mut().zip(&r[fixed + 7..]) {
            c.push(v);
        }
    }
    Some(g)
}

/// Makes the outcome of writing a file, which only rank 0 does, the same on every rank: a
/// failure on rank 0 becomes an error everywhere, so that all ranks stop together instead
/// of the others going on to the next collective call. Collective.
fn agree<T>(comm: &dyn Comm, what: &str, r: Result<T, String>) -> Result<T, String> {
    let failed = comm.max(if r.is_err() { 1.0 } else { 0.0 }) > 0.0;
    match r {
        Ok(_) if failed => Err(format!("{what}: writing failed on rank 0")),
        r => r,
    }
}

fn write_one(sim: &mut Sim, k: usize, step: u64) -> Result<(), String> {
    let time = sim.time();
    if let Writer::Euler(name) = &sim.dumps[k].writer {
        // The cells are global (summed over the ranks); rank 0 writes them.
        let path = name.path(step, 0);
        let id = sim.dumps[k].id.clone();
        let wrote = crate::euler::write_euler_snapshot(sim, None, &path)
            .map_err(|e| format!("dump {id}: {e}"));
        let d = &mut sim.dumps[k];
        let outcome = match wrote {
            Ok(true) => record(d, vec![(time, path)]),
            Ok(false) => Ok(()),
            Err(e) => Err(e),
        };
        if let Some(w) = &sim.world {
            agree(&*w.comm, &format!("dump {id}"), outcome)?;
        } else {
            outcome?;
        }
        sim.dumps[k].last = Some(step);
        return Ok(());
    }
    if let Writer::MeshVtk { name, meshes } = &sim.dumps[k].writer {
        let Some(w) = &sim.world else {
            return Err("dump before the simulation box is defined".into());
        };
        let path = name.path(step, 0);
        let d = &sim.dumps[k];
        let outcome = if w.comm.rank() == 0 {
            let (tris, arrays) = mesh_arrays(w, meshes, &d.columns);
            rdem_io::mesh_vtk::write_mesh_vtk(&path, &tris, &arrays)
                .map_err(|e| format!("dump {}: {e}", d.id))
        } else {
            Ok(())
        };
        let outcome = outcome.and_then(|_| {
            if w.comm.rank() == 0 {
                record(&mut sim.dumps[k], vec![(time, path)])
            } else {
                Ok(())
            }
        });
        if let Some(w) = &sim.world {
            agree(&*w.comm, &format!("dump {}", sim.dumps[k].id), outcome)?;
        }
        sim.dumps[k].last = Some(step);
        return Ok(());
    }
    if let Writer::MeshStl(name) = &sim.dumps[k].writer {
        let Some(w) = &sim.world else {
            return Err("dump before the simulation box is defined".into());
        };
        // Every rank holds every mesh: rank 0 writes.
        let path = name.path(step, 0);
        let d = &sim.dumps[k];
        let outcome = if w.comm.rank() == 0 {
            let (mut tris, mut normals) = (Vec::new(), Vec::new());
            for m in w
                .meshes
                .iter()
                .filter(|m| d.columns.is_empty() || d.columns.contains(&m.id))
            {
                for t in 0..m.mesh.tris.len() {
                    tris.push(m.mesh.corners(t as u32));
                    normals.push(m.mesh.normals[t]);
                }
            }
            rdem_io::stl::write_ascii_stl(&path, &tris, &normals)
                .map_err(|e| format!("dump {}: {e}", d.id))
        } else {
            Ok(())
        };
        agree(&*w.comm, &format!("dump {}", d.id), outcome)?;
        sim.dumps[k].last = Some(step);
        return Ok(());
    }
    let cols = columns(sim, &sim.dumps[k].columns)?;
    let Some(w) = &sim.world else {
        return Err("dump before the simulation box is defined".into());
    };
    let sel = rdem_io::fields::group_selection(&w.particles, sim.dumps[k].groupbit);
    let custom: Vec<&[f64]> = cols
        .iter()
        .filter_map(|c| match c {
            Column::Custom { values, .. } => Some(values.as_slice()),
            Column::Field(_) => None,
        })
        .collect();
    // Every rank sends its particles; rank 0 writes them all (also for a name with `%`,
    // which becomes 0: one file, not one per rank).
    let gathered = gather_owned(&*w.comm, &w.particles, &sel, &custom);
    let background = sim.dumps[k].id != WRITE_DUMP;
    let d = &mut sim.dumps[k];
    let outcome = match gathered {
        None => Ok(()),
        Some(g) => write_gathered(d, g, cols, &w.domain, step, time, background),
    };
    agree(&*w.comm, &format!("dump {}", d.id), outcome)?;
    d.last = Some(step);
    Ok(())
}

/// The triangles of the meshes `ids` (all without any) of `w` and the cell arrays
/// `fields` asks for (`stress`: normal_stress_average and shear_stress_average, `wear`,
/// `vel`: the velocity of each triangle's centroid, `id`, `area`).
fn mesh_arrays(
    w: &rdem::World,
    ids: &[String],
    fields: &[String],
) -> (Vec<[DVec3; 3]>, Vec<rdem_io::mesh_vtk::CellArray>) {
    use rdem_io::mesh_vtk::CellArray;
    let mut tris = Vec::new();
    let mut arrays: Vec<CellArray> = Vec::new();
    let mut push = |name: &str, components: usize, values: &[f64]| match arrays
        .iter_mut()
        .find(|a| a.name == name)
    {
        Some(a) => a.values.extend_from_slice(values),
        None => arrays.push(CellArray {
            name: name.to_string(),
            components,
            values: values.to_vec(),
        }),
    };
    for m in w
        .meshes
        .iter()
        .filter(|m| ids.is_empty() || ids.contains(&m.id))
    {
        let n = m.mesh.tris.len();
        for t in 0..n {
            tris.push(m.mesh.corners(t as u32));
        }
        for f in fields {
            match f.as_str() {
                "stress" => {
                    let (mut sn, mut ss) = rdem::wall::mesh_stress::stresses(m);
                    sn.resize(n, 0.0);
                    ss.resize(n, 0.0);
                    push("normal_stress_average", 1, &sn);
                    push("shear_stress_average", 1, &ss);
                }
                "wear" => {
                    let wear = m
                        .stress
                        .as_ref()
                        .map(|s| s.wear.clone())
                        .unwrap_or_else(|| vec![0.0; n]);
                    push("wear", 1, &wear);
                }
                "vel" => {
                    let v: Vec<f64> = (0..n as u32)
                        .flat_map(|t| {
                            let [a, b, c] = m.mesh.corners(t);
                            m.wall_velocity(t, (a + b + c) / 3.0).to_array()
                        })
                        .collect();
                    push("v", 3, &v);
                }
                "id" => {
                    let ids: Vec<f64> = (0..n).map(|t| t as f64).collect();
                    push("id", 1, &ids);
                }
                _ => {
                    let area: Vec<f64> = (0..n as u32)
                        .map(|t| {
                            let [a, b, c] = m.mesh.corners(t);
                            0.5 * (b - a).cross(c - a).length()
                        })
                        .collect();
                    push("area", 1, &area);
                }
            }
        }
    }
    (tris, arrays)
}

/// Rank 0's part of [`write_one`]: writes the gathered particles `g` with the columns
/// `cols` (whose custom values are replaced by the gathered ones) and lists the files in
/// the dump's `.pvd`.
fn write_gathered(
    d: &mut Dump,
    g: Gathered,
    cols: Vec<Column>,
    domain: &rdem::Domain,
    step: u64,
    time: f64,
    background: bool,
) -> Result<(), String> {
    let mut values = g.custom.into_iter();
    let cols: Vec<Column> = cols
        .into_iter()
        .map(|c| match c {
            Column::Custom { name, .. } => Column::Custom {
                name,
                values: values.next().unwrap_or_default(),
            },
            field => field,
        })
        .collect();
    let p = &g.particles;
    let sel: Vec<usize> = (0..p.nlocal()).collect();
    let procs = Some(g.procs.as_slice());
    let done = match &mut d.writer {
        Writer::Text(t) => t.write(step, p, domain, &sel, &cols).map(|_| vec![]),
        Writer::Vtk(v) => v
            .write(step, p, domain, &sel, &cols)
            .map(|[main, _]| vec![(time, main)]),
        Writer::AtomVtk(v) if background => v.start(step, time, p, &sel, procs),
        Writer::AtomVtk(v) => v.write(step, p, &sel, procs).map(|path| vec![(time, path)]),
        Writer::Euler(_) | Writer::MeshStl(_) | Writer::MeshVtk { .. } => {
            unreachable!("euler/vtk and the mesh dumps are written by write_one")
        }
    }
    .map_err(|e| format!("dump {}: {e}", d.id))?;
    record(d, done)
}

/// The ID of the temporary dump of `write_dump`.
const WRITE_DUMP: &str = "__write_dump";

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

/// custom/vtk picks the format from the suffix, as LIGGGHTS does: `.vtk` legacy VTK,
/// `.vtp` XML PolyData, `.vtu` XML UnstructuredGrid (the parallel `.pvtp`/`.pvtu` and
/// anything else are refused). atom/vtk writes XML UnstructuredGrid whatever the name.
fn check_file_name(a: &Args, style: &str, file: &str) -> CmdResult {
    if style == "euler/vtk" {
        return crate::euler::check_euler_dump_name(file).map_err(|m| {
            a.error_prev(
                m,
                Some("e.g. post/euler_*.vtk: one legacy VTK file per snapshot".into()),
            )
        });
    }
    if style == "custom/vtk" && ![".vtk", ".vtp", ".vtu"].iter().any(|s| file.ends_with(s)) {
        return Err(a.error_prev(
            format!("dump custom/vtk: the file name '{file}' must end in .vtk, .vtp or .vtu"),
            Some(
                "the suffix picks the format: .vtk legacy VTK, .vtp XML PolyData, .vtu XML \
                 UnstructuredGrid"
                    .into(),
            ),
        ));
    }
    Ok(())
}

fn writer(style: &str, file: &str) -> Writer {
    let name = DumpFileName::new(file);
    match style {
        "custom" => Writer::Text(TextDump::new(name, TextOptions::default())),
        "atom/vtk" => Writer::AtomVtk(AtomVtkDump::new(name)),
        "euler/vtk" => Writer::Euler(name),
        "mesh/stl" => Writer::MeshStl(name),
        "mesh/vtk" | "mesh/gran/VTK" => Writer::MeshVtk {
            name,
            meshes: Vec::new(),
        },
        _ => Writer::Vtk(VtkDump::new(name)),
    }
}

/// The `.pvd` collection of a VTK dump series (a name with `*`).
fn collection(style: &str, file: &str) -> Option<PvdSeries> {
    if style == "custom" || style == "mesh/stl" {
        return None;
    }
    PvdSeries::for_pattern(file, 0)
}

/// The IDs of the meshes (`fix mesh/surface`).
fn mesh_ids(sim: &Sim) -> Vec<&str> {
    sim.world
        .iter()
        .flat_map(|w| w.meshes.iter().map(|m| m.id.as_str()))
        .collect()
}

/// The columns of a style: atom/vtk has none.
fn style_columns(sim: &Sim, a: &mut Args, style: &str) -> CmdResult<Vec<String>> {
    if style == "euler/vtk" {
        if let Some(w) = a.peek() {
            if w != "modify" {
                return Err(a.error_at(
                    a.pos(),
                    "dump euler/vtk takes no columns",
                    Some(
                        "it writes the cells of fix ave/euler: v_avg, volumefraction, radius \
                         and pressure"
                            .into(),
                    ),
                ));
            }
        }
        return Ok(Vec::new());
    }
    if style == "mesh/vtk" || style == "mesh/gran/VTK" {
        // [output face|interpolate|original] fields... mesh IDs...; the mesh IDs are
        // kept after a "|" marker in the columns.
        const FIELDS: [&str; 5] = ["stress", "wear", "vel", "id", "area"];
        const LATER_FIELDS: [&str; 5] =
            ["stresscomponents", "owner", "aedges", "acorners", "nneighs"];
        let mut cols = Vec::new();
        let mut ids = Vec::new();
        while let Some(w) = a.peek() {
            if w == "modify" {
                break;
            }
            if w == "output" {
                a.seek(a.pos() + 1);
                a.keyword("output", &["face", "interpolate", "original"])?;
                continue;
            }
            if FIELDS.contains(&w) {
                cols.push(w.to_string());
            } else if LATER_FIELDS.contains(&w) {
                return Err(a.error_at(
                    a.pos(),
                    format!("dump {style} value '{w}' is not supported by this rdem release yet"),
                    Some(format!("supported: {}", FIELDS.join(", "))),
                ));
            } else {
                let known = mesh_ids(sim);
                if !known.contains(&w) {
                    return Err(a.error_at(
                        a.pos(),
                        format!(
                            "dump {style}: '{w}' is neither a value ({}) nor a mesh ID",
                            FIELDS.join(", ")
                        ),
                        Some(suggest(w, &known)),
                    ));
                }
                ids.push(w.to_string());
            }
            a.seek(a.pos() + 1);
        }
        cols.push("|".into());
        cols.extend(ids);
        return Ok(cols);
    }
    if style == "mesh/stl" {
        // Mesh IDs (none: every mesh); LIGGGHTS' parallel selectors mean the whole mesh
        // with one process, which is what rdem writes.
        let mut ids = Vec::new();
        while let Some(w) = a.peek() {
            if w == "modify" {
                break;
            }
            if matches!(w, "local" | "ghost" | "all") {
                a.seek(a.pos() + 1);
                continue;
            }
            let known = mesh_ids(sim);
            if !known.contains(&w) {
                return Err(a.error_at(
                    a.pos(),
                    format!("dump mesh/stl: no mesh '{w}' (a fix mesh/surface ID)"),
                    Some(suggest(w, &known)),
                ));
            }
            ids.push(w.to_string());
            a.seek(a.pos() + 1);
        }
        return Ok(ids);
    }
    if style == "atom/vtk" {
        if let Some(w) = a.peek() {
            if w != "modify" {
                return Err(a.error_at(
                    a.pos(),
                    "dump atom/vtk takes no columns",
                    Some(
                        "it always writes radii, id, type, proc, mass, velocity_lin, \
                         velocity_ang and force; use custom/vtk to choose columns"
                            .into(),
                    ),
                ));
            }
        }
        return Ok(Vec::new());
    }
    read_columns(sim, a)
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
    let cols = style_columns(sim, a, style)?;
    a.done()?;
    sim.world_ref(a)?;
    let mut writer = writer(style, &file);
    let mut cols = cols;
    if let Writer::MeshVtk { meshes, .. } = &mut writer {
        if let Some(k) = cols.iter().position(|c| c == "|") {
            *meshes = cols.split_off(k + 1);
            cols.pop();
        }
    }
    sim.dumps.push(Dump {
        id,
        groupbit,
        every,
        columns: cols,
        writer,
        last: None,
        pvd: collection(style, &file),
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
            Some("e.g. sort id, pad 5, every N, format \"...\", binary yes".into()),
        ));
    }
    modify(
        sim,
        a,
        k,
        &[
            "sort",
            "pad",
            "format",
            "every",
            "first",
            "binary",
            "compressor",
        ],
    )
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
                    Writer::AtomVtk(_) if s == Sort::Id => {}
                    Writer::AtomVtk(_) => {
                        return Err(a.error_prev(
                            "dump atom/vtk always sorts by id",
                            Some("use custom/vtk for another order".into()),
                        ))
                    }
                    Writer::Euler(_) => {
                        return Err(
                            a.error_prev("dump euler/vtk writes cells: sort does not apply", None)
                        )
                    }
                    Writer::MeshStl(_) | Writer::MeshVtk { .. } => {
                        return Err(
                            a.error_prev("mesh dumps write triangles: sort does not apply", None)
                        )
                    }
                }
            }
            "pad" => {
                let n = a.u64("pad width")? as usize;
                match &mut d.writer {
                    Writer::Text(t) => t.name_mut().set_pad(n),
                    Writer::Vtk(v) => v.name_mut().set_pad(n),
                    Writer::AtomVtk(v) => v.name_mut().set_pad(n),
                    Writer::Euler(name) | Writer::MeshStl(name) | Writer::MeshVtk { name, .. } => {
                        name.set_pad(n)
                    }
                }
            }
            "binary" => {
                let yes = a.yes_no("binary")?;
                match &mut d.writer {
                    Writer::Vtk(v) => v.binary = yes,
                    Writer::AtomVtk(v) => v.binary = yes,
                    Writer::Text(_)
                    | Writer::Euler(_)
                    | Writer::MeshStl(_)
                    | Writer::MeshVtk { .. } => {
                        return Err(a.error_prev(
                            "binary applies to the particle VTK dump styles (custom/vtk, atom/vtk)",
                            None,
                        ))
                    }
                }
            }
            "compressor" => {
                let w = a.word("compressor (none, zlib or lz4)")?;
                let Some(c) = Compressor::parse(w) else {
                    return Err(a.error_prev(
                        format!("unknown compressor '{w}'"),
                        Some(suggest(w, &Compressor::NAMES)),
                    ));
                };
                // Compression only exists for binary data: asking for it turns binary on.
                let on = c != Compressor::None;
                match &mut d.writer {
                    Writer::Vtk(v) if v.is_xml() => {
                        v.compressor = c;
                        v.binary |= on;
                    }
                    Writer::AtomVtk(v) => {
                        v.compressor = c;
                        v.binary |= on;
                    }
                    _ => {
                        return Err(a.error_prev(
                            "compressor applies to VTK XML output (atom/vtk, custom/vtk with \
                             .vtp or .vtu)",
                            Some("legacy .vtk files cannot be compressed".into()),
                        ))
                    }
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
    if let Some(d) = sim.dumps.iter_mut().find(|d| d.id == id) {
        finish(d).map_err(|m| a.error_cmd(m, None))?;
    }
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
    let cols = style_columns(sim, a, style)?;
    let step = sim.world_ref(a)?.step;
    sim.dumps.push(Dump {
        id: WRITE_DUMP.into(),
        groupbit,
        every: 1,
        columns: cols,
        writer: writer(style, &file),
        last: None,
        pvd: None,
    });
    let k = sim.dumps.len() - 1;
    let mut result = Ok(());
    if a.peek() == Some("modify") {
        a.seek(a.pos() + 1);
        result = modify(
            sim,
            a,
            k,
            &["sort", "pad", "format", "binary", "compressor"],
        );
    }
    if result.is_ok() {
        result = if sim.check {
            crate::check::dump_columns(sim, k)
        } else {
            write_one(sim, k, step)
        }
        .map_err(|m| a.error_cmd(m, None));
    }
    sim.dumps.pop();
    result
}

//! `dump ID group mesh/vtk N file [output ...] values... [mesh IDs]` (and its old name
//! `mesh/gran/VTK`): the meshes as legacy VTK polydata as LIGGGHTS writes them (three
//! points per triangle) with the per-triangle values asked for, and a `.pvd` series.

use crate::error::Error;
use rdem::DVec3;
use rdem_io::{DumpFileName, Sort};

use super::particles::Done;
use super::{mesh_ids, DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "mesh/vtk",
    parse,
    "`stress` (normal_stress_average, shear_stress_average), `stresscomponents` (stress: force on the triangle / its area, 3 components), `id` (meshid), `wear`, `owner` (the rank whose subdomain holds the triangle's centroid), `area`, `aedges` (active_edges), `acorners` (active_corners), `nneighs`, `vel` (v), then mesh IDs; `output` accepted",
)
.notes("legacy VTK polydata as LIGGGHTS writes it (three points per triangle, cell arrays in LIGGGHTS' fixed order, whatever the order of the values), with a `.pvd` series; `aedges`, `acorners` and `nneighs` count as LIGGGHTS 3.8 does (checked on small meshes and on two tutorials' meshes)");

/// The registry row of the old name.
pub(super) const ROW_OLD_NAME: DumpRow =
    DumpRow::runs("mesh/gran/VTK", parse, "the old name of `mesh/vtk`");

/// The values rdem writes, in the order LIGGGHTS 3.8 writes their arrays (measured: the
/// order of the values in the command does not matter).
const FIELDS: [&str; 10] = [
    "stress",
    "stresscomponents",
    "id",
    "wear",
    "owner",
    "area",
    "aedges",
    "acorners",
    "nneighs",
    "vel",
];

/// The cell arrays LIGGGHTS writes as integers.
const INT_ARRAYS: [&str; 5] = [
    "meshid",
    "owner",
    "active_edges",
    "active_corners",
    "nneighs",
];

fn parse(sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    // [output face|interpolate|original] fields... mesh IDs...
    // The style word as written (`dump` has it at word 3, `write_dump` at word 2).
    let style = a
        .words()
        .iter()
        .map(|w| w.text.as_str())
        .find(|t| matches!(*t, "mesh/vtk" | "mesh/gran/VTK"))
        .unwrap_or("mesh/vtk");
    let mut cols = Vec::new();
    let mut meshes = Vec::new();
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
            if !cols.iter().any(|c| c == w) {
                cols.push(w.to_string());
            }
        } else {
            let known = mesh_ids(sim);
            if !known.contains(&w) {
                return Err(a.error_at(
                    a.pos(),
                    format!(
                        "dump {style}: no mesh '{w}', and '{w}' is not a value ({})",
                        FIELDS.join(", ")
                    ),
                    Some(if known.is_empty() {
                        "no mesh is defined yet: define one with fix mesh/surface first".into()
                    } else {
                        let all: Vec<&str> = FIELDS.iter().copied().chain(known).collect();
                        suggest(w, &all)
                    }),
                ));
            }
            meshes.push(w.to_string());
        }
        a.seek(a.pos() + 1);
    }
    cols.sort_by_key(|c| FIELDS.iter().position(|f| f == c));
    let name = DumpFileName::new(file);
    Ok((Box::new(MeshVtk { name, meshes }), cols))
}

/// The file name pattern and the meshes (all without any); the values are the dump's
/// columns.
struct MeshVtk {
    name: DumpFileName,
    meshes: Vec<String>,
}

impl DumpStyle for MeshVtk {
    fn write(
        &mut self,
        sim: &Sim,
        _head: &DumpHead,
        columns: &[String],
        step: u64,
        time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let w = sim
            .world
            .as_ref()
            .ok_or("dump before the simulation box is defined")?;
        if w.comm.rank() != 0 {
            return Ok(Vec::new());
        }
        let path = self.name.path(step, 0);
        let (tris, arrays) = mesh_arrays(w, &self.meshes, columns);
        rdem_io::mesh_vtk::write_mesh_vtk(&path, &tris, &arrays)?;
        Ok(vec![(time, path)])
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.name
    }

    fn set_sort(&mut self, _: Sort) -> Result<(), NotHere> {
        Err(("mesh dumps write triangles: sort does not apply", None))
    }
}

/// The triangles of the meshes `ids` (all without any) of `w` and the cell arrays
/// `fields` asks for (`stress`: normal_stress_average and shear_stress_average,
/// `stresscomponents`: stress, the force of the particles on the triangle over its area,
/// `id`: meshid, the triangle's index (integers), `wear`, `owner`: the rank of the
/// triangle's centroid, `area`, `aedges`: active_edges, `acorners`: active_corners, `nneighs`, `vel`: v, the velocity
/// of each triangle's centroid).
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
            // LIGGGHTS writes indices and counts as integers.
            int: INT_ARRAYS.contains(&name),
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
                "stresscomponents" => {
                    let mut s: Vec<f64> = match &m.stress {
                        Some(st) => st
                            .force
                            .iter()
                            .enumerate()
                            .flat_map(|(t, f)| {
                                let [a, b, c] = m.mesh.corners(t as u32);
                                let area = 0.5 * (b - a).cross(c - a).length();
                                let s = if area > 0.0 { *f / area } else { DVec3::ZERO };
                                s.to_array()
                            })
                            .collect(),
                        None => Vec::new(),
                    };
                    s.resize(3 * n, 0.0);
                    push("stress", 3, &s);
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
                    push("meshid", 1, &ids);
                }
                "owner" => {
                    let d = &w.domain;
                    let owner: Vec<f64> = (0..n as u32)
                        .map(|t| {
                            let [a, b, c] = m.mesh.corners(t);
                            d.rank_of(d.owner_loc((a + b + c) / 3.0)) as f64
                        })
                        .collect();
                    push("owner", 1, &owner);
                }
                "aedges" => {
                    let count = m.mesh.active_edge_counts(m.coplanar_cos);
                    let count: Vec<f64> = count.into_iter().map(f64::from).collect();
                    push("active_edges", 1, &count);
                }
                "acorners" => {
                    let count = m.mesh.active_corner_counts(m.coplanar_cos);
                    let count: Vec<f64> = count.into_iter().map(f64::from).collect();
                    push("active_corners", 1, &count);
                }
                "nneighs" => {
                    let count: Vec<f64> = m
                        .mesh
                        .neighbour_counts()
                        .into_iter()
                        .map(f64::from)
                        .collect();
                    push("nneighs", 1, &count);
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

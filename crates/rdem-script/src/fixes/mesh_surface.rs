//! `fix mesh/surface`, `mesh/surface/planar` and `mesh/surface/stress`: a triangle mesh
//! from an STL file, kept in the engine's `World::meshes` under the fix ID, which walls
//! (`wall/gran ... mesh`), motions, insertion faces and mesh dumps use. The `/stress`
//! form sums the force on each triangle (and wears it): `f_ID[1..9]`.

use super::{style, FixHead, FixRow, Notes, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row of `mesh/surface`.
pub(super) const ROW: FixRow = style(
    "mesh/surface",
    parse,
    Stages::NONE,
    "`file F` (ASCII or binary STL), `type T`, `scale`, `move`, `rotate axis ax ay az angle deg` (in the order given), `surface_vel vx vy vz`, `surface_ang_vel origin .. axis .. omega w`, `precision`, `heal auto_remove_duplicates`, `element_exclusion_list read\\|write F` (a list of triangles, by the line number of their `facet normal` line in an ASCII STL, by their position in a binary one), `temperature T` (a wall at fixed temperature for `fix heat/gran`); `curvature`, `curvature_tolerant`, `verbose` accepted; `/stress`: `stress on\\|off`, `wear finnie\\|off` (with `property/global k_finnie peratomtypepair`), `reference_point`",
)
.notes("`precision` (default 1e-8) merges corners closer than it and widens each face by it for contacts (a point over the face within −precision/(2 r_b) in barycentric terms, r_b the triangle's bounding radius, is a face contact), as LIGGGHTS 3.8 does; `curvature` sets the angle below which neighbouring triangles are one flat surface (their shared edge and corners inactive), as in LIGGGHTS; `/planar` refuses a mesh that is not planar; `/stress`: per-triangle force summed in particle order (the same on any thread count), `f_ID[1..9]` total force, torque about the reference point, the point; `surface_vel` is used as given (LIGGGHTS projects it onto each face); `element_exclusion_list read` stops on a blank line, a line that is not one integer, and a number that is no triangle's (LIGGGHTS 3.8 would then exclude nothing, stop, or ignore that number and every larger one); `write` lists, once each and in increasing order, triangles with an angle below 1e-3 rad (LIGGGHTS 3.8 measured; its manual says 0.0181185 degrees) or two corners within `precision` (LIGGGHTS 3.8 leaves out those with two equal corners), all copies but the last of a repeated triangle (none with `heal`), and triangles with more than 5 edge neighbours, then imports the mesh as without the keyword (LIGGGHTS 3.8 may list a line twice, and stops on slivers and crowded edges); `mass_temperature`, `extrude_planar` stop with an error; a negative `temperature` is an error (LIGGGHTS 3.8 silently conducts no heat)");

/// The registry row of `mesh/surface/planar`.
pub(super) const ROW_PLANAR: FixRow = style(
    "mesh/surface/planar",
    parse,
    Stages::NONE,
    "as `mesh/surface`, for a planar mesh",
);

/// The registry row of `mesh/surface/stress`.
pub(super) const ROW_STRESS: FixRow = style(
    "mesh/surface/stress",
    parse,
    Stages::VALUES,
    "as `mesh/surface`, and `stress on\\|off`, `wear finnie\\|off`, `reference_point`",
);

pub(super) fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    sim.world_ref(a)?;
    let mut notes = Notes::default();
    let mesh = mesh_surface(sim, a, &head.id, head.style, &mut notes)?;
    Ok(Box::new(Mesh {
        parsed: Some((mesh, notes)),
    }))
}

/// A mesh in `World::meshes` under the fix ID.
pub struct Mesh {
    /// The mesh read from its file and what to print about it, until installed.
    parsed: Option<(rdem::wall::MeshSurface, Notes)>,
}

impl ScriptFix for Mesh {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        if let Some((mesh, notes)) = self.parsed.take() {
            sim.world_mut(a)?.add_mesh(mesh);
            notes.print(&mut sim.outputs.out);
        }
        Ok(())
    }

    /// `f_ID[1..9]` of a `/stress` mesh: total force, torque about the reference point,
    /// the point.
    fn values(&self, sim: &Sim, head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("needs a simulation box")?;
        let st = w
            .mesh_index(&head.id)
            .and_then(|k| w.meshes[k].stress.as_ref())
            .ok_or("computes no global values")?;
        let (fo, to, r) = (st.total_force, st.total_torque, st.reference_point);
        Ok(vec![fo.x, fo.y, fo.z, to.x, to.y, to.z, r.x, r.y, r.z])
    }

    /// `fix_modify` of a servo mesh ([`super::mesh_servo::modify`]).
    fn modify(
        &mut self,
        sim: &mut Sim,
        head: &FixHead,
        keyword: &str,
        a: &mut Args,
    ) -> CmdResult<bool> {
        if head.style == "mesh/surface/stress/servo" {
            super::mesh_servo::modify(sim, head, keyword, a)
        } else {
            Ok(false)
        }
    }

    /// Vertex positions and velocities, stress tallies, servo state.
    fn save_state(&self, sim: &Sim, head: &FixHead) -> Option<Vec<u8>> {
        let w = sim.world.as_ref()?;
        let k = w.mesh_index(&head.id)?;
        postcard::to_stdvec(&w.meshes[k].state()).ok()
    }

    fn restore_state(&mut self, sim: &mut Sim, head: &FixHead, state: &[u8]) -> Result<(), Error> {
        let st: rdem::restart::MeshState = super::decode_state(state)?;
        let w = sim.world.as_mut().ok_or("no simulation box")?;
        let k = w.mesh_index(&head.id).ok_or("the mesh is missing")?;
        w.meshes[k]
            .set_state(&st)
            .map_err(|e| Error::Invalid(e.to_string()))
    }

    // The mesh stays in the world (LIGGGHTS keeps a mesh that walls may still use).
    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

/// `fix ID group mesh/surface file F type T [keywords]`: the STL file's triangles with
/// `scale`, `move` and `rotate` applied in the order given, vertices closer than
/// `precision` merged, `heal auto_remove_duplicates` dropping degenerate and repeated
/// triangles, `element_exclusion_list read` leaving out listed triangles (`write` lists
/// the bad ones), and `surface_vel` for a conveyor belt.
fn mesh_surface(
    sim: &Sim,
    a: &mut Args,
    id: &str,
    style: &str,
    notes: &mut Notes,
) -> CmdResult<rdem::wall::MeshSurface> {
    let servo_style = style == "mesh/surface/stress/servo";
    let stress_style = style == "mesh/surface/stress" || servo_style;
    let mut servo = super::mesh_servo::ServoWords::default();
    let (mut stress_on, mut finnie, mut reference_point) = (true, false, rdem::DVec3::ZERO);
    a.keyword("mesh/surface keyword", &["file"])?;
    let file_at = a.pos();
    let file = a.word("STL file name")?.to_string();
    let rdem_io::stl::NumberedStl {
        tris: mut soup,
        mut numbers,
        binary,
    } = rdem_io::stl::read_stl_numbered(std::path::Path::new(&file))
        .map_err(|e| a.error_at(file_at, e.to_string(), None))?;
    let stl = StlNumbering {
        file: &file,
        binary,
        numbers: numbers.clone(),
    };
    let mut exclusion_write: Option<(String, usize)> = None;
    let mut wall_type = None;
    let mut precision = 1e-8;
    let mut heal = false;
    let mut surface_vel = rdem::DVec3::ZERO;
    let mut surface_ang_vel = None;
    let mut coplanar_cos = rdem::wall::mesh::COPLANAR_COS;
    let mut temperature = None;
    const KEYS: [&str; 13] = [
        "surface_ang_vel",
        "type",
        "precision",
        "heal",
        "verbose",
        "scale",
        "move",
        "rotate",
        "surface_vel",
        "curvature",
        "curvature_tolerant",
        "temperature",
        "element_exclusion_list",
    ];
    const LATER_KEYS: [&str; 3] = ["min_feature_length", "mass_temperature", "extrude_planar"];
    const STRESS_KEYS: [&str; 3] = ["stress", "wear", "reference_point"];
    while let Some(w) = a.peek() {
        if LATER_KEYS.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("mesh/surface keyword '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", KEYS.join(", "))),
            ));
        }
        if super::mesh_servo::KEYS.contains(&w) {
            if !servo_style {
                return Err(a.error_at(
                    a.pos(),
                    format!("'{w}' is a keyword of fix mesh/surface/stress/servo"),
                    Some(format!(
                        "use fix {id} all mesh/surface/stress/servo ... {w} ..."
                    )),
                ));
            }
            servo.read(a, w)?;
            continue;
        }
        if STRESS_KEYS.contains(&w) {
            if !stress_style {
                return Err(a.error_at(
                    a.pos(),
                    format!("'{w}' is a keyword of fix mesh/surface/stress"),
                    Some(format!("use fix {id} all mesh/surface/stress ... {w} ...")),
                ));
            }
            a.seek(a.pos() + 1);
            match w {
                "stress" => stress_on = a.keyword("stress", &["on", "off"])? == "on",
                "wear" => finnie = a.keyword("wear", &["finnie", "off", "none"])? == "finnie",
                _ => reference_point = a.vec3("reference point")?,
            }
            continue;
        }
        match a.keyword("mesh/surface keyword", &KEYS)? {
            "type" => wall_type = Some(a.count("wall atom type")? as u32),
            "surface_ang_vel" => {
                a.keyword("surface_ang_vel keyword", &["origin"])?;
                let o = a.vec3("origin")?;
                a.keyword("surface_ang_vel keyword", &["axis"])?;
                let at = a.pos();
                let ax = a.vec3("axis")?;
                if !ax.is_finite() || ax.length() <= 0.0 {
                    return Err(a.error_at(at, "the axis has no direction", None));
                }
                a.keyword("surface_ang_vel keyword", &["omega"])?;
                let w = a.f64("omega (rad per time unit)")?;
                surface_ang_vel = Some((o, ax.normalize() * w));
            }
            "precision" => precision = a.positive("precision")?,
            "heal" => {
                heal = a.keyword("heal", &["auto_remove_duplicates", "no"])? != "no";
            }
            "verbose" => {
                a.yes_no("verbose")?;
            }
            "curvature" => {
                let at = a.pos();
                let deg = a.positive("curvature (degrees)")?;
                if deg >= 90.0 {
                    return Err(a.error_at(
                        at,
                        "curvature is the largest angle (degrees) between two triangles of one flat surface: below 90",
                        None,
                    ));
                }
                coplanar_cos = deg.to_radians().cos();
            }
            "curvature_tolerant" => {
                a.yes_no("curvature_tolerant")?;
            }
            "temperature" => temperature = Some(wall_temperature(a)?),
            "element_exclusion_list" => {
                let mode = a.keyword("element_exclusion_list mode", &["read", "write"])?;
                let at = a.pos();
                let list = a.word("element exclusion file name")?.to_string();
                if mode == "write" {
                    exclusion_write = Some((list, at));
                } else {
                    let excluded = read_exclusion_list(&list, &stl)
                        .map_err(|(message, help)| a.error_at(at, message, help))?;
                    let before = soup.len();
                    let mut k = 0;
                    soup.retain(|_| {
                        k += 1;
                        !excluded.contains(&numbers[k - 1])
                    });
                    numbers.retain(|n| !excluded.contains(n));
                    notes.line(format!(
                        "  mesh {id}: {} triangle(s) of {file} excluded by {list}",
                        before - soup.len()
                    ));
                }
            }
            "scale" => {
                let f = a.positive("scale factor")?;
                for t in &mut soup {
                    *t = t.map(|p| p * f);
                }
            }
            "move" => {
                let d = rdem::DVec3::new(a.f64("mx")?, a.f64("my")?, a.f64("mz")?);
                for t in &mut soup {
                    *t = t.map(|p| p + d);
                }
            }
            "rotate" => {
                a.keyword("rotate keyword", &["axis"])?;
                let axis_at = a.pos();
                let axis = rdem::DVec3::new(a.f64("ax")?, a.f64("ay")?, a.f64("az")?);
                a.keyword("rotate keyword", &["angle"])?;
                let deg = a.f64("angle (degrees)")?;
                if axis.length().is_nan() || axis.length() <= 0.0 || !axis.is_finite() {
                    return Err(a.error_at(axis_at, "the rotation axis has no direction", None));
                }
                let q = glam::DQuat::from_axis_angle(axis.normalize(), deg.to_radians());
                for t in &mut soup {
                    *t = t.map(|p| q * p);
                }
            }
            _ => {
                surface_vel = rdem::DVec3::new(a.f64("vx")?, a.f64("vy")?, a.f64("vz")?);
            }
        }
    }
    let Some(wall_type) = wall_type else {
        return Err(a.error_at(
            STYLE_WORD,
            "mesh/surface needs 'type T' (the wall's material type)",
            None,
        ));
    };
    let mut bad_help = None;
    if let Some((list, at)) = &exclusion_write {
        let bad = bad_triangles(&soup, &numbers, precision, heal);
        let rank0 = rdem::comm::process_rank_size().0 == 0;
        if rank0 && !sim.script.check {
            let text: String = bad.iter().map(|n| format!("{n}\n")).collect();
            rdem_io::write_atomic(std::path::Path::new(list), text.as_bytes())
                .map_err(|e| a.error_at(*at, format!("element exclusion list: {e}"), None))?;
        }
        notes.line(format!(
            "  mesh {id}: {} bad triangle(s) of {file} listed in {list}",
            bad.len()
        ));
        bad_help = Some(format!(
            "the bad triangles are listed in {list}: 'element_exclusion_list read {list}' leaves them out"
        ));
    }
    let (mesh, report) = rdem::mesh::TriMesh::from_triangles(&soup, precision, heal)
        .map_err(|e| a.error_at(file_at, format!("{file}: {e}"), bad_help.clone()))?;
    if !report.degenerate.is_empty() || !report.duplicates.is_empty() {
        notes.warning(format!(
            "mesh/surface {id}: dropped {} degenerate and {} repeated triangle(s) of {file}",
            report.degenerate.len(),
            report.duplicates.len()
        ));
    }
    notes.line(format!(
        "  mesh {id}: {} triangles, {} vertices",
        mesh.tris.len(),
        mesh.verts.len()
    ));
    if style == "mesh/surface/planar" {
        let n = mesh.normals.first().copied().unwrap_or(rdem::DVec3::Z);
        let p0 = mesh.verts.first().copied().unwrap_or_default();
        let (lo, hi) = mesh.bounds();
        let tol = 1e-6 * (hi - lo).length();
        if mesh.verts.iter().any(|&v| (v - p0).dot(n).abs() > tol) {
            return Err(a.error_at(
                file_at,
                format!("{file}: mesh/surface/planar needs a planar mesh, and this one is not"),
                Some("use fix mesh/surface".into()),
            ));
        }
    }
    let servo = if servo_style {
        if !stress_on {
            return Err(a.error_at(
                STYLE_WORD,
                "mesh/surface/stress/servo measures its force with the stress: 'stress off' does not apply",
                None,
            ));
        }
        Some(servo.finish(sim, a, &mesh.verts)?)
    } else {
        None
    };
    let ntri = mesh.tris.len();
    let mut surface = rdem::wall::MeshSurface::new(id, mesh, wall_type);
    if stress_style && (stress_on || finnie) {
        let mut st = rdem::wall::mesh_stress::MeshStress::new(ntri, finnie);
        st.reference_point = reference_point;
        if let Some(servo) = &servo {
            // LIGGGHTS 3.8 reports the centre of mass as the servo's reference point.
            st.reference_point = servo.com;
        }
        surface.stress = Some(st);
    }
    surface.servo = servo;
    surface.surface_vel = surface_vel;
    surface.temperature = temperature;
    surface.surface_ang_vel = surface_ang_vel;
    surface.coplanar_cos = coplanar_cos;
    Ok(surface)
}

/// The value of a wall's `temperature` keyword (`fix mesh/surface`, `fix wall/gran`): a
/// temperature ≥ 0. LIGGGHTS 3.8 takes a negative one as "no temperature" and conducts no
/// heat, silently; rdem stops instead.
pub(super) fn wall_temperature(a: &mut Args) -> CmdResult<f64> {
    let at = a.pos();
    let t = a.f64("wall temperature")?;
    if t < 0.0 {
        return Err(a.error_at(
            at,
            format!("wall temperature {t} is negative"),
            Some(
                "give an absolute temperature >= 0 (LIGGGHTS 3.8 would silently conduct no heat)"
                    .into(),
            ),
        ));
    }
    Ok(t)
}

/// How an STL file numbers its triangles for `element_exclusion_list`.
struct StlNumbering<'f> {
    /// The STL file's name.
    file: &'f str,
    /// Binary (triangles numbered by position) or ASCII (by the line of `facet`).
    binary: bool,
    /// The number of each triangle of the file.
    numbers: Vec<usize>,
}

/// The numbers of `element_exclusion_list read FILE`: one integer per line, each the
/// number of a triangle of the STL file, in any order, repeats allowed. As measured on
/// LIGGGHTS 3.8, a number that names no triangle is silently ignored there together
/// with every larger number in the list, a blank line anywhere (even last) makes it
/// exclude nothing, and a line of two numbers or a non-integer stops it. Here each of
/// those is an error (message and help), so a list rdem accepts leaves out what LIGGGHTS
/// leaves out.
fn read_exclusion_list(
    list: &str,
    stl: &StlNumbering,
) -> Result<std::collections::BTreeSet<usize>, (String, Option<String>)> {
    let what = if stl.binary {
        format!(
            "the number (1 to {}) of a triangle of the binary STL file {}",
            stl.numbers.len(),
            stl.file
        )
    } else {
        format!(
            "the line number of a 'facet normal' line of the ASCII STL file {}",
            stl.file
        )
    };
    let form = format!("one number per line, each {what}");
    let text = std::fs::read_to_string(list).map_err(|e| {
        (
            format!("cannot read element exclusion list {list}: {e}"),
            Some(form.clone()),
        )
    })?;
    let known: std::collections::HashSet<usize> = stl.numbers.iter().copied().collect();
    let mut out = std::collections::BTreeSet::new();
    for (k, line) in text.lines().enumerate() {
        let at = format!("element exclusion list {list}, line {}", k + 1);
        let mut words = line.split_whitespace();
        let Some(word) = words.next() else {
            return Err((
                format!("{at} is blank"),
                Some(format!(
                    "{form}, and no blank line (LIGGGHTS 3.8 would exclude nothing)"
                )),
            ));
        };
        if words.next().is_some() {
            return Err((format!("{at} holds more than one word"), Some(form.clone())));
        }
        let n: i64 = word.parse().map_err(|_| {
            (
                format!("{at}: '{word}' is not an integer"),
                Some(form.clone()),
            )
        })?;
        match usize::try_from(n).ok().filter(|n| known.contains(n)) {
            Some(n) => {
                out.insert(n);
            }
            None => {
                return Err((
                    format!("{at}: {n} is not {what}"),
                    Some(format!(
                        "{form} (LIGGGHTS 3.8 would silently ignore {n} and every larger number)"
                    )),
                ))
            }
        }
    }
    Ok(out)
}

/// The smallest angle of a triangle below which `element_exclusion_list write` lists it
/// (radians). Measured on LIGGGHTS 3.8 (2026-12-04): it lists a right-angled sliver
/// whose smallest angle is 0.05729 degrees and not one of 0.057296 (1e-3 rad =
/// 0.0572958 degrees), and isosceles slivers of 0.057 but not 0.058 degrees whatever
/// their size; its manual says 0.0181185 degrees.
const SLIVER_ANGLE: f64 = 1e-3;

/// The numbers (`numbers[k]` of `soup[k]`) that `element_exclusion_list write` lists,
/// increasing, each once: slivers (an angle below [`SLIVER_ANGLE`], or two corners within
/// `precision` or degenerate as the engine judges), every copy but the last of a repeated
/// triangle unless `heal` drops the copies anyway, and triangles with more than 5
/// neighbours across their edges. On the meshes measured LIGGGHTS 3.8 lists the same set,
/// but it may write a number twice and out of order, and it does not list a triangle
/// with two equal corners (which the engine refuses without `heal`).
fn bad_triangles(
    soup: &[[rdem::DVec3; 3]],
    numbers: &[usize],
    precision: f64,
    heal: bool,
) -> Vec<usize> {
    use rdem::mesh::TriMesh;
    let n = soup.len();
    let mut bad = vec![false; n];
    for (k, t) in soup.iter().enumerate() {
        // Each corner's angle; an edge within `precision` joins two corners.
        bad[k] = (0..3).any(|c| {
            let (u, v) = (t[(c + 1) % 3] - t[c], t[(c + 2) % 3] - t[c]);
            u.length() <= precision || u.cross(v).length().atan2(u.dot(v)) < SLIVER_ANGLE
        });
    }
    // The engine drops a repeated triangle's later copies: built back to front, the
    // copies it drops are all but the last.
    if !heal {
        let back: Vec<[rdem::DVec3; 3]> = soup.iter().rev().copied().collect();
        if let Ok((_, report)) = TriMesh::from_triangles(&back, precision, true) {
            for k in &report.duplicates {
                bad[n - 1 - k] = true;
            }
        }
    }
    if let Ok((mesh, report)) = TriMesh::from_triangles(soup, precision, true) {
        let mut dropped = vec![false; n];
        for &k in &report.degenerate {
            (dropped[k], bad[k]) = (true, true);
        }
        for &k in &report.duplicates {
            dropped[k] = true;
        }
        let kept = (0..n).filter(|&k| !dropped[k]);
        for (t, k) in kept.enumerate() {
            let neighbours: u32 = mesh.tri_edges[t]
                .iter()
                .map(|&e| mesh.edge_first[e as usize + 1] - mesh.edge_first[e as usize] - 1)
                .sum();
            bad[k] |= neighbours > 5;
        }
    }
    // The numbers increase along the file.
    (0..n).filter(|&k| bad[k]).map(|k| numbers[k]).collect()
}

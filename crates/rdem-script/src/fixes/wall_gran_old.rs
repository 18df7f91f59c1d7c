//! `fix wall/gran/hertz/history`, `wall/gran/hooke/history`, `wall/gran/hooke`: the
//! granular walls in the syntax of LIGGGHTS 1.x and 2.x (LIGGGHTS 3.8 refuses them), run
//! as the `fix wall/gran` walls they mean, with a note line giving the 3.x command.
//!
//! - 1.x: `dampflag cohesionflag wallstyle args [shear dim v]`, wallstyle one of
//!   `xplane|yplane|zplane lo hi type` (either of lo, hi may be NULL: one wall per
//!   number), `zcylinder radius type` (axis x = y = 0), `mesh/gran n ID...`;
//! - 2.x: `primitive type T style args` or `mesh n_meshes N meshes ID...`, `shear dim v`,
//!   `store_force no`, and the 2.x model keywords ([`old_gran::KEYWORDS`]) before or
//!   after the wall.
//!
//! A 1.x plane pair `lo hi` becomes two 3.x walls, `ID` (at lo) and `ID_hi` (at hi), in
//! that order; `unfix ID` removes both.

use glam::DVec3;
use rdem::wall::MeshWall;
use rdem::{ContactModel, Fix, FixKind, PrimitiveWall, WallShape};

use super::{mesh_ref, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Accept, Args, CmdResult};
use crate::old_gran::{self, Form};
use crate::sim::Sim;

const HELP: &str = "LIGGGHTS 1.x `dampflag cohesionflag` then `xplane\\|yplane\\|zplane lo hi type` (NULL for no wall), `zcylinder R type`, `mesh/gran N ID...`, `shear dim v`; LIGGGHTS 2.x `primitive type T ...`, `mesh n_meshes N meshes ID...`, `shear`, `store_force yes|no`, with `tangential_damping on\\|off`, `cohesion off\\|sjkr`, `rolling_friction off\\|cdt`, `viscous off`: run as `fix wall/gran` (a note line gives the 3.x command)";
const NOTES: &str = "pre-3.0 syntax, which LIGGGHTS 3.8 refuses; `gran/hooke` is `model hooke tangential no_history`; the contact physics are LIGGGHTS 3.x's (with `cohesion sjkr` the Coulomb limit uses the contact force without cohesion, where 2.x subtracted it); `wiggle`, `temperature`, `viscous on` and cylinder `shear` around the axis stop with an error";

/// The registry row of `wall/gran/hertz/history`.
pub(super) const ROW_HERTZ: FixRow =
    super::style("wall/gran/hertz/history", parse, Stages::ENGINE, HELP).notes(NOTES);
/// The registry row of `wall/gran/hooke/history`.
pub(super) const ROW_HOOKE_HISTORY: FixRow = super::style(
    "wall/gran/hooke/history",
    parse,
    Stages::ENGINE,
    "as `wall/gran/hertz/history`, with `model hooke`",
)
.notes(NOTES);
/// The registry row of `wall/gran/hooke`.
pub(super) const ROW_HOOKE: FixRow = super::style(
    "wall/gran/hooke",
    parse,
    Stages::ENGINE,
    "as `wall/gran/hertz/history`, with `model hooke tangential no_history`",
)
.notes(NOTES);

/// The walls of one old-syntax fix, until they are installed in the world.
struct OldWall {
    /// The engine fixes (one per wall), in the order LIGGGHTS applies them.
    fixes: Vec<Fix>,
    /// Their IDs, for `unfix`.
    ids: Vec<String>,
    /// The note line: what the command became.
    note: String,
    /// With `store_force yes`: the `force_ID` property/atom.
    store: Option<String>,
}

impl ScriptFix for OldWall {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let w = sim.world_mut(a)?;
        for fix in self.fixes.drain(..) {
            w.add_fix(fix)
                .map_err(|e| a.error_cmd(e.to_string(), None))?;
        }
        if let Some(name) = &self.store {
            super::wall_gran::define_store(sim, a, name)?;
        }
        sim.outputs.out.line(&self.note);
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            for id in &self.ids {
                w.remove_fix(id);
            }
        }
        if let Some(name) = &self.store {
            super::unfix_id(sim, name);
        }
    }
}

/// One wall as read: the engine wall and its 3.x words after the model.
enum Wall {
    Primitive {
        ty: u32,
        shape: WallShape,
        words: String,
    },
    Mesh {
        meshes: Vec<usize>,
        words: String,
    },
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    sim.world_ref(a)?;
    let name = &head.style["wall/gran/".len()..];
    let mut m = old_gran::base_model(name).expect("registry names are old model names");
    let mut store = false;
    let (form, walls, shear) = if old_gran::at_flags(a) {
        old_gran::read_flags(a, &mut m)?;
        let (walls, shear) = v1_walls(sim, a)?;
        (Form::V1, walls, shear)
    } else {
        let (wall, shear) = v2_wall(sim, a, &mut m, &head.id, &mut store)?;
        (Form::V2, vec![wall], shear)
    };
    crate::coarse_graining::check_model(sim, a, super::STYLE_WORD, &m)?;
    // `store_force` is a 2.x keyword: one wall.
    let store_name = store.then(|| format!("force_{}", head.id));
    let mut fixes = Vec::new();
    let mut ids = Vec::new();
    let mut new_words = Vec::new();
    for (k, wall) in walls.into_iter().enumerate() {
        let id = if k == 0 {
            head.id.clone()
        } else {
            format!("{}_hi", head.id)
        };
        let (kind, words) = match wall {
            Wall::Primitive { ty, shape, words } => {
                let mut w = PrimitiveWall::new(&id, m, ty, shape)
                    .map_err(|e| a.error_cmd(e.to_string(), None))?;
                w.store_force = store_name.clone();
                let mut words = words;
                if let Some((d, v)) = shear {
                    w.velocity = DVec3::ZERO;
                    w.velocity[d] = v;
                    words.push_str(&format!(" shear {} {}", ["x", "y", "z"][d], v));
                }
                (FixKind::WallGran(Box::new(w)), words)
            }
            Wall::Mesh { meshes, words } => {
                let mut w =
                    MeshWall::new(&id, m, meshes).map_err(|e| a.error_cmd(e.to_string(), None))?;
                w.store_force = store_name.clone();
                (FixKind::MeshWall(Box::new(w)), words)
            }
        };
        let words = if store {
            format!("{words} store_force yes")
        } else {
            words
        };
        let group = &a.words()[2].text;
        new_words.push(format!(
            "fix {id} {group} wall/gran {} {words}",
            old_gran::model_words(&m)
        ));
        fixes.push(
            Fix::new(&id, head.groupbit, kind).map_err(|e| a.error_cmd(e.to_string(), None))?,
        );
        ids.push(id);
    }
    let note = format!(
        "fix {} ({} syntax) runs as: {}",
        old_gran::text_from(a, 1),
        form.label(),
        new_words.join(" and ")
    );
    Ok(Box::new(OldWall {
        fixes,
        ids,
        note,
        store: store_name,
    }))
}

/// A wall type (an integer ≥ 1).
fn wall_type(a: &mut Args) -> CmdResult<u32> {
    let t = a.count("wall atom type")?;
    if t == 0 {
        return Err(a.error_prev("wall atom types start at 1", None));
    }
    Ok(t as u32)
}

/// The 1.x wall styles and the `shear` keyword.
type Shear = Option<(usize, f64)>;

fn v1_walls(sim: &Sim, a: &mut Args) -> CmdResult<(Vec<Wall>, Shear)> {
    let style_at = a.pos();
    let style = a.keyword(
        "LIGGGHTS 1.x wall style",
        &["xplane", "yplane", "zplane", "zcylinder", "mesh/gran"],
    )?;
    let mut walls = Vec::new();
    match style {
        "zcylinder" => {
            let r = a.positive("cylinder radius")?;
            let ty = wall_type(a)?;
            walls.push(Wall::Primitive {
                ty,
                shape: WallShape::Cylinder {
                    axis: 2,
                    radius: r,
                    c1: 0.0,
                    c2: 0.0,
                },
                words: format!("primitive type {ty} zcylinder {r} 0 0"),
            });
        }
        "mesh/gran" => {
            let n = a.count("number of meshes")?;
            let mut meshes = Vec::new();
            let mut names = Vec::new();
            for _ in 0..n {
                meshes.push(mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?);
                names.push(a.words()[a.pos() - 1].text.clone());
            }
            walls.push(Wall::Mesh {
                meshes,
                words: format!("mesh n_meshes {n} meshes {}", names.join(" ")),
            });
        }
        plane => {
            let axis = (plane.as_bytes()[0] - b'x') as usize;
            let mut pos = [None, None];
            for (k, what) in ["lo", "hi"].into_iter().enumerate() {
                let what = format!("{what} plane position (or NULL)");
                pos[k] = a.num_or_var(&what, Accept::Null)?.num();
            }
            let ty = wall_type(a)?;
            if pos == [None, None] {
                return Err(a.error_at(
                    style_at,
                    format!("{plane}: both lo and hi are NULL, so there is no wall"),
                    None,
                ));
            }
            for p in pos.into_iter().flatten() {
                walls.push(Wall::Primitive {
                    ty,
                    shape: WallShape::Plane { axis, pos: p },
                    words: format!("primitive type {ty} {plane} {p}"),
                });
            }
        }
    }
    let mut shear = None;
    while let Some(w) = a.peek() {
        match w {
            "shear" => {
                a.seek(a.pos() + 1);
                shear = Some(read_shear(a, &walls)?);
            }
            "wiggle" => {
                return Err(a.error_at(
                    a.pos(),
                    "wiggle (a wall oscillating in place, LIGGGHTS 1.x) is not supported: LIGGGHTS 3.x has no wall wiggle",
                    Some("use a mesh wall with 'fix move/mesh mesh ID wiggle ...'".into()),
                ))
            }
            "temperature" => {
                return Err(a.error_at(
                    a.pos(),
                    "temperature (a wall's temperature for fix heat/gran) is not supported yet",
                    None,
                ))
            }
            _ => {
                return Err(a.error_at(
                    a.pos(),
                    format!("unknown keyword '{w}' of the LIGGGHTS 1.x wall"),
                    Some(crate::args::suggest(w, &["shear", "wiggle", "temperature"])),
                ))
            }
        }
    }
    Ok((walls, shear))
}

/// `shear dim v` (the keyword read): a plane may move in its own plane, a cylinder along
/// its axis.
fn read_shear(a: &mut Args, walls: &[Wall]) -> CmdResult<(usize, f64)> {
    let d = a.keyword("shear direction", &["x", "y", "z"])?;
    let d = (d.as_bytes()[0] - b'x') as usize;
    let at = a.pos() - 1;
    let v = a.f64("shear velocity")?;
    let Some(Wall::Primitive { shape, .. }) = walls.first() else {
        return Err(a.error_at(
            at - 1,
            "shear moves a primitive wall: for a mesh wall use fix move/mesh",
            None,
        ));
    };
    let why = match shape {
        WallShape::Plane { axis, .. } if d == *axis => {
            Some("a plane wall can only shear in its own plane")
        }
        WallShape::Cylinder { axis, .. } if d != *axis => Some(
            "a cylinder spinning about its axis (shear across the axis) is not supported: only shear along the axis",
        ),
        WallShape::Plane { .. } | WallShape::Cylinder { .. } => None,
        WallShape::GeneralPlane { .. }
        | WallShape::GeneralCylinder { .. }
        | WallShape::GeneralCone { .. } => Some(
            "shear moves xplane, yplane, zplane and the axis-aligned cylinders, not a general_plane, general_cylinder or general_cone wall",
        ),
    };
    if let Some(why) = why {
        return Err(a.error_at(at, why, None));
    }
    Ok((d, v))
}

/// The 2.x wall: model keywords, one `primitive` or `mesh` wall, `shear`, `store_force`.
fn v2_wall(
    sim: &Sim,
    a: &mut Args,
    m: &mut ContactModel,
    id: &str,
    store: &mut bool,
) -> CmdResult<(Wall, Shear)> {
    let mut wall: Option<Wall> = None;
    let mut shear_at = None;
    let mut shear = None;
    while let Some(w) = a.peek() {
        if old_gran::at_keyword(a) {
            old_gran::read_keyword(a, m)?;
            continue;
        }
        let at = a.pos();
        a.seek(at + 1);
        match w {
            "primitive" | "mesh" if wall.is_some() => {
                return Err(a.error_prev(
                    "one wall per fix: 'primitive' or 'mesh' is given twice",
                    None,
                ))
            }
            "primitive" => {
                a.keyword("primitive keyword", &["type"])?;
                let ty = wall_type(a)?;
                let (shape, args) = super::wall_gran::primitive_shape(a)?;
                let words = format!("primitive type {ty} {args}");
                wall = Some(Wall::Primitive { ty, shape, words });
            }
            "mesh" => {
                a.keyword("mesh keyword", &["n_meshes"])?;
                let n = a.count("n_meshes")?;
                a.keyword("mesh keyword", &["meshes"])?;
                let mut meshes = Vec::new();
                let mut names = Vec::new();
                for _ in 0..n {
                    meshes.push(mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?);
                    names.push(a.words()[a.pos() - 1].text.clone());
                }
                wall = Some(Wall::Mesh {
                    meshes,
                    words: format!("mesh n_meshes {n} meshes {}", names.join(" ")),
                });
            }
            "shear" => shear_at = Some(at),
            "store_force" => {
                a.seek(at);
                *store = super::wall_gran::store_force_keyword(a, id)?.is_some();
            }
            _ => {
                let mut valid = vec!["primitive", "mesh", "shear", "store_force"];
                valid.extend_from_slice(&old_gran::KEYWORDS);
                return Err(a.error_at(
                    at,
                    format!("unknown keyword '{w}' of the LIGGGHTS 2.x wall"),
                    Some(crate::args::suggest(w, &valid)),
                ));
            }
        }
        if shear_at == Some(at) {
            // `shear` needs the wall, which LIGGGHTS 2.x wants first too.
            let Some(wall) = &wall else {
                return Err(a.error_at(
                    at,
                    "shear before the wall: define 'primitive type T ...' first",
                    None,
                ));
            };
            shear = Some(read_shear(a, std::slice::from_ref(wall))?);
        }
    }
    let Some(wall) = wall else {
        return Err(a.error_at(
            a.words().len(),
            format!("{}: missing wall", a.context()),
            Some("add 'primitive type T zplane POS' or 'mesh n_meshes N meshes ID...'".into()),
        ));
    };
    Ok((wall, shear))
}

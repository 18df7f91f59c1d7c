//! `fix wall/gran`: a primitive wall (plane, cylinder) or the meshes named after `mesh`,
//! with the contact model words of `pair_style gran`. The wall lives in the engine's
//! `World::fixes`, which computes its contacts in the post-force stage.

use glam::DVec3;
use rdem::{FixKind, PrimitiveWall, WallShape};

use super::engine::engine_fix;
use super::{style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::models;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "wall/gran",
    parse,
    Stages::ENGINE,
    "`primitive type T xplane\\|yplane\\|zplane POS`, `xcylinder\\|ycylinder\\|zcylinder R C1 C2`; `shear DIM V`; `temperature T` (a wall at fixed temperature for `fix heat/gran`); `mesh n_meshes k meshes ID...`; the model words of `pair_style gran` (switches before or after the wall)",
)
.notes("with `cohesion bond`, particle–wall bonds (on mesh walls anchored to a triangle, so they go with `fix move/mesh` and `surface_vel`); mesh walls: one contact per shared edge or corner and per flat surface (`curvature`), history that follows a sphere to the next triangle; the wall's velocity at the contact point (`surface_vel`, `surface_ang_vel`, `fix move/mesh`) enters the contact");

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let kind = match wall_gran(sim, a, &head.id)? {
        Wall::Primitive(wall) => FixKind::WallGran(Box::new(wall)),
        Wall::Mesh(wall) => FixKind::MeshWall(Box::new(wall)),
    };
    engine_fix(sim, a, head, kind)
}

/// A `wall/gran` wall.
enum Wall {
    Primitive(PrimitiveWall),
    Mesh(rdem::wall::MeshWall),
}

fn wall_gran(sim: &Sim, a: &mut Args, id: &str) -> CmdResult<Wall> {
    let start = a.pos();
    let mut model = models::parse_types(a)?;
    if model.cohesion == rdem::CohesionKind::Easo {
        let k = (start..a.pos())
            .find(|&k| a.words()[k].text == "easo/capillary/viscous")
            .unwrap_or(start);
        // LIGGGHTS 3.8 runs it with a warning ("only supports dry walls").
        return Err(a.error_at(
            k,
            "cohesion easo/capillary/viscous is not supported for walls: its manual allows it in pair_style gran only",
            Some("leave the cohesion model out of fix wall/gran".into()),
        ));
    }
    models::parse_leading_switches(a, &mut model)?;
    let style_at = a.pos();
    match a.peek() {
        Some("primitive") => a.seek(a.pos() + 1),
        Some("mesh") => {
            a.seek(a.pos() + 1);
            a.keyword("mesh keyword", &["n_meshes"])?;
            let n = a.count("n_meshes")?;
            a.keyword("mesh keyword", &["meshes"])?;
            let mut meshes = Vec::with_capacity(n as usize);
            for _ in 0..n {
                let at = a.pos();
                let mid = a.word("mesh ID (a fix mesh/surface)")?;
                let found = sim.world.as_ref().and_then(|w| w.mesh_index(mid));
                let Some(m) = found else {
                    let ids: Vec<&str> = sim
                        .world
                        .iter()
                        .flat_map(|w| w.meshes.iter().map(|m| m.id.as_str()))
                        .collect();
                    return Err(a.error_at(
                        at,
                        format!("no fix mesh/surface '{mid}'"),
                        Some(crate::args::id_help("fix mesh/surface", mid, &ids)),
                    ));
                };
                meshes.push(m);
            }
            if a.peek() == Some("temperature") {
                return Err(a.error_at(
                    a.pos(),
                    "wall/gran: a mesh wall takes its temperature from its fix mesh/surface",
                    Some("write 'temperature T' in the fix mesh/surface line (LIGGGHTS 3.8 ignores it here)".into()),
                ));
            }
            if models::at_switch(a) {
                models::parse_switches(a, &mut model)?;
            } else if !a.is_done() {
                return Err(models::unknown(a, a.pos(), &[]));
            }
            let wall = rdem::wall::MeshWall::new(id, model, meshes)
                .map_err(|e| a.error_cmd(e.to_string(), None))?;
            return Ok(Wall::Mesh(wall));
        }
        Some(
            w @ ("type" | "xplane" | "yplane" | "zplane" | "xcylinder" | "ycylinder" | "zcylinder"),
        ) => {
            return Err(a.error_at(
                style_at,
                format!("wall/gran: missing 'primitive' before '{w}'"),
                Some("write 'primitive type T zplane POS' (or another primitive)".into()),
            ))
        }
        Some(_) => return Err(models::unknown(a, style_at, &["primitive", "mesh"])),
        None => {
            return Err(a.error_at(
                a.pos(),
                "wall/gran: missing wall style",
                Some("add 'primitive type T zplane POS' (or another primitive)".into()),
            ))
        }
    }
    a.keyword("primitive keyword", &["type"])?;
    let wall_type = a.count("wall atom type")? as u32;
    let shape = primitive_shape(a)?.0;
    let mut velocity = DVec3::ZERO;
    let mut temperature = None;
    while let Some(w) = a.peek() {
        if models::at_switch(a) {
            models::parse_switches(a, &mut model)?;
            break;
        }
        match w {
            "shear" => {
                a.seek(a.pos() + 1);
                let d = a.keyword("shear direction", &["x", "y", "z"])?;
                let v = a.f64("shear velocity")?;
                velocity[(d.as_bytes()[0] - b'x') as usize] = v;
            }
            "temperature" => {
                a.seek(a.pos() + 1);
                temperature = Some(super::mesh_surface::wall_temperature(a)?);
            }
            "store_force" | "store_force_contact" => {
                a.seek(a.pos() + 1);
                if a.yes_no(w)? {
                    return Err(a.error_prev(format!("{w} yes is not supported yet"), None));
                }
            }
            _ => {
                return Err(models::unknown(
                    a,
                    a.pos(),
                    &["shear", "temperature", "store_force"],
                ))
            }
        }
    }
    let mut wall = PrimitiveWall::new(id, model, wall_type, shape)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    wall.velocity = velocity;
    wall.temperature = temperature;
    Ok(Wall::Primitive(wall))
}

/// A primitive wall's shape, `xplane|yplane|zplane POS` or `xcylinder|ycylinder|zcylinder
/// R C1 C2`, and its words as a 3.x script writes them (for the note line of the pre-3.0
/// walls).
pub(super) fn primitive_shape(a: &mut Args) -> CmdResult<(WallShape, String)> {
    let style = a.keyword(
        "primitive wall",
        &[
            "xplane",
            "yplane",
            "zplane",
            "xcylinder",
            "ycylinder",
            "zcylinder",
        ],
    )?;
    let axis = (style.as_bytes()[0] - b'x') as usize;
    Ok(if style.ends_with("plane") {
        let pos = a.f64("plane position")?;
        (WallShape::Plane { axis, pos }, format!("{style} {pos}"))
    } else {
        let radius = a.positive("cylinder radius")?;
        let c1 = a.f64("axis coordinate c1")?;
        let c2 = a.f64("axis coordinate c2")?;
        (
            WallShape::Cylinder {
                axis,
                radius,
                c1,
                c2,
            },
            format!("{style} {radius} {c1} {c2}"),
        )
    })
}

//! `fix wall/gran`: a primitive wall (plane, cylinder) or the meshes named after `mesh`,
//! with the contact model words of `pair_style gran`. The wall lives in the engine's
//! `World::fixes`, which computes its contacts in the post-force stage.

use glam::DVec3;
use rdem::{FixKind, PrimitiveWall, WallShape};

use super::engine::engine_fix;
use super::property_atom::{self, PropertyAtom};
use super::{style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::models;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "wall/gran",
    parse,
    Stages::ENGINE,
    "`primitive type T xplane\\|yplane\\|zplane POS`, `xcylinder\\|ycylinder\\|zcylinder R C1 C2`, `general_plane PX PY PZ NX NY NZ`, `general_cylinder R PX PY PZ AX AY AZ`, `general_cone R1 X1 Y1 Z1 X2 Y2 Z2 R2` (LIGGGHTS-PFM); `shear DIM V`; `store_force yes` (the wall's force on each particle as `f_force_ID[1..3]`); `temperature T` (a wall at fixed temperature for `fix heat/gran`); `mesh n_meshes k meshes ID...`; the model words of `pair_style gran` (switches before or after the wall)",
)
.notes("with `cohesion bond`, particle–wall bonds (on mesh walls anchored to a triangle, so they go with `fix move/mesh` and `surface_vel`); mesh walls: contacts counted as LIGGGHTS 3.8 counts them (a face always; an active edge or corner once, through the last of its triangles, so a sphere on a face next to a convex edge may touch the edge too; one contact per flat surface, `curvature`), history that follows a sphere to the next triangle; the wall's velocity at the contact point (`surface_vel`, `surface_ang_vel`, `fix move/mesh`) enters the contact");

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (kind, store) = match wall_gran(sim, a, &head.id)? {
        Wall::Primitive(wall) => {
            let store = wall.store_force.clone();
            (FixKind::WallGran(Box::new(wall)), store)
        }
        Wall::Mesh(wall) => {
            let store = wall.store_force.clone();
            (FixKind::MeshWall(Box::new(wall)), store)
        }
    };
    let engine = engine_fix(sim, a, head, kind)?;
    Ok(match store {
        Some(name) => Box::new(StoringWall { engine, name }),
        None => engine,
    })
}

/// A wall with `store_force yes`: the engine wall, and the `fix property/atom` (ID and
/// name `force_ID`, 3 values per particle) that holds the wall's force on each particle,
/// defined when the wall is (`f_force_ID[1..3]` in dumps and variables).
pub(super) struct StoringWall {
    /// The wall's own entry (the engine fix).
    pub(super) engine: Box<dyn ScriptFix>,
    /// `force_ID`.
    pub(super) name: String,
}

impl std::fmt::Debug for StoringWall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "StoringWall({})", self.name)
    }
}

impl ScriptFix for StoringWall {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.engine.install(sim, a, head)?;
        define_store(sim, a, &self.name)
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.engine.unfix(sim, head);
        super::unfix_id(sim, &self.name);
    }
}

/// Defines `fix NAME all property/atom NAME vector no no no 0 0 0` for a wall's
/// `store_force` (replacing an earlier one of that ID, as a redefined wall does).
pub(super) fn define_store(sim: &mut Sim, a: &Args, name: &str) -> CmdResult<()> {
    super::unfix_id(sim, name);
    property_atom::define(
        sim,
        a,
        PropertyAtom {
            name: name.to_string(),
            vector: true,
            defaults: vec![0.0; 3],
            forward: false,
            restart: true,
        },
    )
}

/// Reads `store_force yes|no` or `store_force_contact no` at the current word (which is
/// one of them): the name of the stored-force property for `yes`.
pub(super) fn store_force_keyword(a: &mut Args, id: &str) -> CmdResult<Option<String>> {
    let w = a.word("keyword")?.to_string();
    let yes = a.yes_no(&w)?;
    if w == "store_force_contact" && yes {
        return Err(a.error_prev(
            "store_force_contact yes is not supported (LIGGGHTS 3.8 has it in selected versions only, not in the public one)",
            Some("use 'store_force yes' for the total wall force per particle".into()),
        ));
    }
    Ok(yes.then(|| format!("force_{id}")))
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
                // LIGGGHTS 3.8 reads it and ignores it (measured: 500 K and 900 K here
                // gave the same heat flow from a 500 K mesh). rdem does too, and says so
                // where it differs from a mesh's own temperature.
                let at = a.pos();
                a.word("temperature")?;
                let t = a.f64("wall temperature")?;
                let w = sim.world.as_ref();
                let differs = meshes.iter().any(|&m| {
                    w.and_then(|w| w.meshes.get(m))
                        .is_some_and(|mesh| mesh.temperature != Some(t))
                });
                if differs {
                    a.warn_at(
                        at,
                        "wall/gran: 'temperature' on a mesh wall is ignored, as in LIGGGHTS 3.8: \
                         each mesh has the temperature of its fix mesh/surface",
                    );
                }
            }
            let mut store = None;
            while matches!(a.peek(), Some("store_force" | "store_force_contact")) {
                if let Some(name) = store_force_keyword(a, id)? {
                    store = Some(name);
                }
            }
            if models::at_switch(a) {
                models::parse_switches(a, &mut model)?;
            } else if !a.is_done() {
                return Err(models::unknown(a, a.pos(), &["store_force"]));
            }
            crate::coarse_graining::check_model(sim, a, start, &model)?;
            let mut wall = rdem::wall::MeshWall::new(id, model, meshes)
                .map_err(|e| a.error_cmd(e.to_string(), None))?;
            wall.store_force = store;
            return Ok(Wall::Mesh(wall));
        }
        Some(
            w @ ("type" | "xplane" | "yplane" | "zplane" | "xcylinder" | "ycylinder" | "zcylinder"
            | "general_plane" | "general_cylinder" | "general_cone"),
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
    let mut store = None;
    while let Some(w) = a.peek() {
        if models::at_switch(a) {
            models::parse_switches(a, &mut model)?;
            break;
        }
        match w {
            "shear" => {
                if matches!(
                    shape,
                    WallShape::GeneralPlane { .. }
                        | WallShape::GeneralCylinder { .. }
                        | WallShape::GeneralCone { .. }
                ) {
                    return Err(a.error_at(
                        a.pos(),
                        "wall/gran: 'shear' with a general_plane, general_cylinder or general_cone wall is not supported",
                        Some("shear moves xplane, yplane, zplane and the axis-aligned cylinders; a moving wall of another shape can be a mesh with fix move/mesh".into()),
                    ));
                }
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
                if let Some(name) = store_force_keyword(a, id)? {
                    store = Some(name);
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
    crate::coarse_graining::check_model(sim, a, start, &model)?;
    let mut wall = PrimitiveWall::new(id, model, wall_type, shape)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    wall.velocity = velocity;
    wall.temperature = temperature;
    wall.store_force = store;
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
            "general_plane",
            "general_cylinder",
            "general_cone",
        ],
    )?;
    let vector = |a: &mut Args, what: &str| -> CmdResult<DVec3> {
        Ok(DVec3::new(
            a.f64(&format!("{what} x"))?,
            a.f64(&format!("{what} y"))?,
            a.f64(&format!("{what} z"))?,
        ))
    };
    let direction = |a: &mut Args, what: &str| -> CmdResult<DVec3> {
        let at = a.pos();
        let v = vector(a, what)?;
        let n = v.length();
        if !(n > 0.0 && n.is_finite()) {
            return Err(a.error_at(
                at,
                format!(
                    "{style}: the {what} ({}, {}, {}) has no direction",
                    v.x, v.y, v.z
                ),
                Some("give a vector of non-zero length (it need not be a unit vector)".into()),
            ));
        }
        Ok(v / n)
    };
    match style {
        "general_plane" => {
            let point = vector(a, "point")?;
            let normal = direction(a, "normal")?;
            let words = format!(
                "{style} {} {} {} {} {} {}",
                point.x, point.y, point.z, normal.x, normal.y, normal.z
            );
            return Ok((WallShape::GeneralPlane { point, normal }, words));
        }
        "general_cylinder" => {
            let radius = a.positive("cylinder radius")?;
            let point = vector(a, "axis point")?;
            let axis = direction(a, "axis")?;
            let words = format!("{style} {radius}");
            return Ok((
                WallShape::GeneralCylinder {
                    radius,
                    point,
                    axis,
                },
                words,
            ));
        }
        "general_cone" => {
            let r1 = a.non_negative("cone radius 1")?;
            let p1 = vector(a, "first rim centre")?;
            let at = a.pos();
            let p2 = vector(a, "second rim centre")?;
            let r2 = a.non_negative("cone radius 2")?;
            if p1 == p2 || r1 + r2 == 0.0 {
                return Err(a.error_at(
                    at,
                    "general_cone: the two rim centres must differ and the radii must not both be 0",
                    Some("general_cone R1 X1 Y1 Z1 X2 Y2 Z2 R2: the circles of radius R1 about (X1, Y1, Z1) and R2 about (X2, Y2, Z2)".into()),
                ));
            }
            let words = format!("{style} {r1} {r2}");
            return Ok((WallShape::GeneralCone { r1, p1, p2, r2 }, words));
        }
        _ => {}
    }
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

//! `region` and `lattice`: the geometric regions insertion, groups and walls use, and the
//! lattice that `units lattice` and `create_atoms` refer to.

use glam::DVec3;
use rdem::region::{Region, Shape};

use crate::args::{Args, CmdResult};
use crate::lattice::{self, Lattice};
use crate::regions::{Motion, RegionDef};
use crate::registry::{Registry, Row};
use crate::sim::Sim;

/// `units lattice` scale; without a `lattice` command it is LIGGGHTS' default `none 1.0`.
pub(crate) fn scale_of(sim: &Sim, _a: &Args, units_lattice: bool) -> CmdResult<DVec3> {
    Ok(sim
        .defs
        .lattice
        .as_ref()
        .filter(|_| units_lattice)
        .map_or(DVec3::ONE, |l| l.spacing()))
}

/// Every region style, with the names of its geometry arguments (`union` and
/// `intersect` take a count and region IDs instead).
pub static STYLES: Registry<&'static [&'static str]> = Registry {
    family: "region style",
    readme_prefix: "region ",
    rows: &[
        Row::runs(
            "block",
            &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi"],
            "`xlo xhi ylo yhi zlo zhi` (`INF`, `-INF`, `EDGE` allowed)",
        ),
        Row::runs("sphere", &["x", "y", "z", "radius"], "`x y z radius`"),
        Row::runs(
            "cylinder",
            &["dim", "c1", "c2", "radius", "lo", "hi"],
            "`dim c1 c2 radius lo hi` (`INF`, `-INF`, `EDGE` allowed for lo, hi)",
        ),
        Row::runs(
            "cone",
            &["dim", "c1", "c2", "radlo", "radhi", "lo", "hi"],
            "`dim c1 c2 radlo radhi lo hi` (`INF`, `-INF`, `EDGE` allowed for lo, hi)",
        ),
        Row::runs(
            "plane",
            &["px", "py", "pz", "nx", "ny", "nz"],
            "`px py pz nx ny nz`: the half-space behind the normal",
        ),
        Row::<&'static [&'static str]>::runs(
            "mesh/tet",
            &[],
            "`file F scale s move dx dy dz rotate ax ay az`: the tetrahedra of an ASCII legacy VTK file, moved, then scaled, then turned about x, y, z (degrees)",
        )
        .notes("inside = strictly inside one tetrahedron: points exactly on a face, outer or shared, are out, as LIGGGHTS 3.8 decides (measured); insertion samples by volume; `all_in yes` keeps whole spheres inside (distance to the surface faces; LIGGGHTS lets them poke out); either orientation of a tetrahedron (LIGGGHTS fails an assertion on inverted ones); binary VTK, VTK 5 cell arrays and `units lattice` are errors, other cell types are skipped with a warning"),
        Row::runs("union", &[], "`N ID1 ID2 ...`"),
        Row::runs("intersect", &[], "`N ID1 ID2 ...`"),
        Row::<&'static [&'static str]>::runs(
            "prism",
            &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "xy", "xz", "yz"],
            "`xlo xhi ylo yhi zlo zhi xy xz yz`: the parallelepiped from (xlo, ylo, zlo) along (xhi−xlo, 0, 0), (xy, yhi−ylo, 0), (xz, yz, zhi−zlo) (`INF`, `-INF`, `EDGE` allowed for the bounds)",
        )
        .notes("inside as LAMMPS' prism decides (boundary included); `all_in yes` keeps whole spheres inside (distance to each face); `create_box` with a tilted prism (a triclinic box) is refused; not usable as a `fix wall/region` surface"),
        Row::<&'static [&'static str]>::runs(
            "wedge",
            &[
                "axis", "dim", "center", "c1", "c2", "radius", "r", "bounds", "lo", "hi",
                "angle0", "alpha0", "angle", "alpha",
            ],
            "`axis dim center c1 c2 radius r bounds lo hi angle0 alpha0 angle alpha` (LIGGGHTS-INL): the sector of a cylinder along dim through (c1, c2) in the cyclically next coordinates (y z, z x or x y), from alpha0 over alpha degrees counterclockwise, measured from the first of them",
        )
        .notes("inside as LIGGGHTS-INL decides (boundary included); `all_in yes` keeps whole spheres inside the sector; not usable as a `fix wall/region` surface"),
    ],
};

/// "region block takes xlo xhi ylo yhi zlo zhi ..." for help texts.
fn region_usage(style: &str, names: &[&str]) -> String {
    format!(
        "region ID {style} {} [side in|out] [units box|lattice]",
        names.join(" ")
    )
}

pub(super) fn region(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("region ID")?.to_string();
    if sim.defs.regions.contains_key(&id) {
        return Err(a.error_prev(format!("region ID '{id}' is already used"), None));
    }
    let w = a.word("region style")?;
    let (style, arg_names) = STYLES.lookup(a, w)?;
    let arg_names: &[&str] = arg_names;
    let args_start = a.pos();
    // Geometry words first (numbers may be INF/EDGE); keywords after.
    let mut geo: Vec<String> = Vec::new();
    let mut parts: Vec<Region> = Vec::new();
    let mut part_ids: Vec<String> = Vec::new();
    let mut tet_mesh = None;
    match style {
        "mesh/tet" => tet_mesh = Some(read_tet_mesh(sim, a)?),
        "union" | "intersect" => {
            let n = a.count("number of regions")?;
            for _ in 0..n {
                let id = sim.region_id(a)?;
                parts.push(sim.defs.regions[&id].region.clone());
                part_ids.push(id);
            }
        }
        _ => {
            for name in arg_names {
                let w = a.word(name).map_err(|mut e| {
                    e.help = Some(region_usage(style, arg_names));
                    e
                })?;
                geo.push(w.to_string());
            }
        }
    }
    let (mut outside, mut lattice_units) = (false, false); // LIGGGHTS 3.8: units box
    let mut motion: Option<Motion> = None;
    while !a.is_done() {
        match a.keyword(
            "region keyword",
            &["side", "units", "move", "rotate", "volume_limit"],
        )? {
            "side" => outside = a.keyword("side", &["in", "out"])? == "out",
            "volume_limit" => {
                // LIGGGHTS 3.8 (undocumented) stops with "Unable to calculate region
                // volume" below this limit, whose default is too large for a box of
                // micrometre particles (measured: a 3.7e-11 m³ block needs it); rdem's
                // volumes need no such limit, so the value is checked and has no other
                // effect.
                a.positive("volume_limit")?;
            }
            "units" => lattice_units = a.keyword("units", &["box", "lattice"])? == "lattice",
            k => {
                if matches!(style, "union" | "intersect") {
                    return Err(a.error_prev(
                        format!("region {style} cannot {k}: give move/rotate to its parts"),
                        None,
                    ));
                }
                let m = motion.get_or_insert_with(Motion::default);
                if k == "move" {
                    for c in 0..3 {
                        m.shift[c] = motion_variable(a, "x, y or z displacement", true)?;
                    }
                } else {
                    let theta = motion_variable(a, "rotation angle", false)?.expect("required");
                    let point = a.vec3("rotation point Px Py Pz")?;
                    let axis = a.vec3("rotation axis Rx Ry Rz")?;
                    if axis.length_squared() == 0.0 {
                        return Err(a.error_prev("rotation axis must not be 0 0 0", None));
                    }
                    m.rotate = Some((theta, point, axis));
                }
            }
        }
    }
    if style == "mesh/tet" && lattice_units {
        // As LIGGGHTS 3.8, which has no lattice scaling for this style.
        return Err(a.error_cmd(
            "region mesh/tet: units lattice is not supported; use units box (the mesh's own scale keyword scales it)",
            None,
        ));
    }
    let needs_scale = !matches!(style, "union" | "intersect" | "mesh/tet");
    let s = if needs_scale {
        scale_of(sim, a, lattice_units)?
    } else {
        DVec3::ONE
    };
    let bounds = sim.world.as_ref().map(|w| (w.domain.boxlo, w.domain.boxhi));
    let axis0 = match geo.first().map(|s| s.as_str()) {
        Some("x") => 0,
        Some("y") => 1,
        _ => 2,
    };
    // Which bounds may be INF, -INF or EDGE: (axis, lower bound?).
    let bound = |k: usize| -> Option<(usize, bool)> {
        match style {
            "block" => Some((k / 2, k % 2 == 0)),
            "prism" if k < 6 => Some((k / 2, k % 2 == 0)),
            "cylinder" if k >= 4 => Some((axis0, k == 4)),
            "cone" if k >= 5 => Some((axis0, k == 5)),
            _ => None,
        }
    };
    let num = |k: usize, scale: f64| -> CmdResult<f64> {
        let w = &geo[k];
        let word = args_start + k;
        if matches!(w.as_str(), "INF" | "-INF" | "EDGE") {
            let Some((axis, lo)) = bound(k) else {
                return Err(a.error_at(
                    word,
                    format!(
                        "'{w}' is only valid for the bounds of block, cylinder, cone and prism"
                    ),
                    None,
                ));
            };
            return match (w.as_str(), bounds) {
                ("EDGE", Some((blo, bhi))) => Ok(if lo { blo[axis] } else { bhi[axis] }),
                ("EDGE", None) => Err(a.error_at(word, "EDGE needs the simulation box", None)),
                ("-INF", _) => Ok(-1e300),
                _ => Ok(if lo { -1e300 } else { 1e300 }),
            };
        }
        a.f64_at(word).map(|v| v * scale).ok_or_else(|| {
            a.error_at(
                word,
                format!(
                    "region {style}: {} must be a number, not '{w}'",
                    arg_names[k]
                ),
                Some(region_usage(style, arg_names)),
            )
        })
    };
    let axis_of = |k: usize| -> CmdResult<usize> {
        match geo[k].as_str() {
            "x" => Ok(0),
            "y" => Ok(1),
            "z" => Ok(2),
            w => Err(a.error_at(
                args_start + k,
                format!("region {style}: axis must be x, y or z, not '{w}'"),
                Some(region_usage(style, arg_names)),
            )),
        }
    };
    let shape = match style {
        "block" => Shape::Block {
            lo: DVec3::new(num(0, s.x)?, num(2, s.y)?, num(4, s.z)?),
            hi: DVec3::new(num(1, s.x)?, num(3, s.y)?, num(5, s.z)?),
        },
        "sphere" => Shape::Sphere {
            centre: DVec3::new(num(0, s.x)?, num(1, s.y)?, num(2, s.z)?),
            radius: num(3, s.x)?,
        },
        "cylinder" | "cone" => {
            let axis = axis_of(0)?;
            let (o1, o2) = match axis {
                0 => (1, 2),
                1 => (0, 2),
                _ => (0, 1),
            };
            let c1 = num(1, s[o1])?;
            let c2 = num(2, s[o2])?;
            if style == "cylinder" {
                Shape::Cylinder {
                    axis,
                    c1,
                    c2,
                    radius: num(3, s[o1])?,
                    lo: num(4, s[axis])?,
                    hi: num(5, s[axis])?,
                }
            } else {
                Shape::Cone {
                    axis,
                    c1,
                    c2,
                    rlo: num(3, s[o1])?,
                    rhi: num(4, s[o1])?,
                    lo: num(5, s[axis])?,
                    hi: num(6, s[axis])?,
                }
            }
        }
        "wedge" => {
            for (k, want) in [
                (0, "axis"),
                (2, "center"),
                (5, "radius"),
                (7, "bounds"),
                (10, "angle0"),
                (12, "angle"),
            ] {
                if geo[k] != want {
                    return Err(a.error_at(
                        args_start + k,
                        format!(
                            "region wedge: expected the keyword '{want}', not '{}'",
                            geo[k]
                        ),
                        Some(region_usage(style, arg_names)),
                    ));
                }
            }
            let axis = axis_of(1)?;
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            Shape::Wedge {
                axis,
                cu: num(3, s[u])?,
                cv: num(4, s[v])?,
                radius: num(6, s[u])?,
                lo: num(8, s[axis])?,
                hi: num(9, s[axis])?,
                start: num(11, 1.0)?.to_radians(),
                span: num(13, 1.0)?.to_radians(),
            }
        }
        "prism" => {
            let lo = DVec3::new(num(0, s.x)?, num(2, s.y)?, num(4, s.z)?);
            let hi = DVec3::new(num(1, s.x)?, num(3, s.y)?, num(5, s.z)?);
            let tilt = DVec3::new(num(6, s.x)?, num(7, s.x)?, num(8, s.y)?);
            // As LAMMPS: a tilt may not pair with a dimension infinite at both ends.
            let infinite = |d: usize| lo[d] <= -1e299 && hi[d] >= 1e299;
            for (k, (d1, d2)) in [(6, (0, 1)), (7, (0, 2)), (8, (1, 2))] {
                if tilt[k - 6] != 0.0 && (infinite(d1) || infinite(d2)) {
                    return Err(a.error_at(
                        args_start + k,
                        format!(
                            "region prism: the tilt {} is not 0, and {} is INF at both ends",
                            arg_names[k],
                            if infinite(d1) {
                                ["x", "y", "z"][d1]
                            } else {
                                ["x", "y", "z"][d2]
                            }
                        ),
                        None,
                    ));
                }
            }
            Shape::Prism { lo, hi, tilt }
        }
        "plane" => Shape::Plane {
            point: DVec3::new(num(0, s.x)?, num(1, s.y)?, num(2, s.z)?),
            normal: DVec3::new(num(3, 1.0)?, num(4, 1.0)?, num(5, 1.0)?),
        },
        "union" => Shape::Union(parts),
        "mesh/tet" => Shape::TetMesh(std::sync::Arc::new(tet_mesh.expect("read above"))),
        _ => Shape::Intersect(parts),
    };
    let mut r = Region::new(shape).map_err(|e| a.error_at(args_start, e.to_string(), None))?;
    if outside {
        r = r.side_out();
    }
    // LAMMPS scales the rotation point with `units lattice`, not the axis.
    if let Some((_, p, _)) = motion.as_mut().and_then(|m| m.rotate.as_mut()) {
        *p *= s;
    }
    sim.defs.regions.insert(
        id,
        RegionDef {
            region: r,
            motion,
            parts: part_ids,
        },
    );
    Ok(())
}

/// `file F scale s move dx dy dz rotate ax ay az` of `region mesh/tet` (the three keywords
/// are required, in this order, as LIGGGHTS reads them): the tetrahedra of the VTK file,
/// each node moved by (dx, dy, dz), then scaled by s about the origin, then turned by ax
/// about x, then ay about y, then az about z (degrees, right-handed, about the origin).
/// As LIGGGHTS, a node outside the simulation box is an error.
fn read_tet_mesh(sim: &Sim, a: &mut Args) -> CmdResult<rdem::region::TetMesh> {
    const USAGE: &str =
        "region ID mesh/tet file F scale s move dx dy dz rotate ax ay az [side in|out] [units box]";
    let usage = || Some(USAGE.to_string());
    let required = |a: &mut Args, name: &'static str| -> CmdResult<()> {
        a.keyword("region mesh/tet keyword", &[name])
            .map(|_| ())
            .map_err(|mut e| {
                e.help = usage();
                e
            })
    };
    required(a, "file")?;
    let file_at = a.pos();
    let file = a.word("VTK file name")?.to_string();
    required(a, "scale")?;
    let scale = a.positive("scale factor")?;
    required(a, "move")?;
    let offset = a.vec3("offset dx dy dz")?;
    required(a, "rotate")?;
    let angles = a.vec3("rotation angles about x, y, z (degrees)")?;
    let tf = rdem_io::vtk_tets::read_tet_vtk(std::path::Path::new(&file))
        .map_err(|e| a.error_at(file_at, e.to_string(), None))?;
    if tf.skipped > 0 {
        a.warn_at(
            file_at,
            &format!(
                "{file}: {} cells that are not tetrahedra (vertices, lines, triangles, ...) are left out of the region",
                tf.skipped
            ),
        );
    }
    let nodes: Vec<DVec3> = tf
        .points
        .iter()
        .map(|p| turn_xyz((*p + offset) * scale, angles))
        .collect();
    if let Some(w) = sim.world.as_ref() {
        let (lo, hi) = (w.domain.boxlo, w.domain.boxhi);
        let used = tf.tets.iter().flatten().copied();
        if let Some(i) = used
            .into_iter()
            .find(|&i| (0..3).any(|d| !(lo[d] <= nodes[i][d] && nodes[i][d] <= hi[d])))
        {
            let x = nodes[i];
            return Err(a.error_at(
                file_at,
                format!(
                    "region mesh/tet: node {i} of {file} is at ({}, {}, {}) after scale/move/rotate, outside the simulation box {lo} .. {hi}",
                    x.x, x.y, x.z
                ),
                Some("LIGGGHTS refuses a mesh that sticks out of the box too; check scale, move and rotate".into()),
            ));
        }
    }
    rdem::region::TetMesh::new(nodes, tf.tets)
        .map_err(|e| a.error_at(file_at, format!("{file}: {e}"), None))
}

/// `x` turned right-handedly about the x axis by `deg.x` degrees, then about y by `deg.y`,
/// then about z by `deg.z` (LIGGGHTS `mesh/tet rotate`); a zero angle leaves `x` as it is.
fn turn_xyz(mut x: DVec3, deg: DVec3) -> DVec3 {
    for axis in 0..3 {
        if deg[axis] == 0.0 {
            continue;
        }
        let (s, c) = deg[axis].to_radians().sin_cos();
        let (i, j) = match axis {
            0 => (1, 2),
            1 => (2, 0),
            _ => (0, 1),
        };
        let (u, v) = (x[i], x[j]);
        x[i] = c * u - s * v;
        x[j] = s * u + c * v;
    }
    x
}

/// Reads `v_name` (or `NULL` if `null_ok`) for a region's motion; the variable is looked
/// up when the region is used, as LAMMPS does at run set-up.
fn motion_variable(a: &mut Args, what: &str, null_ok: bool) -> CmdResult<Option<String>> {
    let w = a.word(what)?;
    if null_ok && w == "NULL" {
        return Ok(None);
    }
    match w.strip_prefix("v_").filter(|n| !n.is_empty()) {
        Some(n) => Ok(Some(n.to_string())),
        None => Err(a.error_prev(
            format!(
                "region {what} must be an equal-style variable v_name{}, not '{w}'",
                if null_ok { " or NULL" } else { "" }
            ),
            Some("e.g. 'variable dx equal 0.1*time' then 'move v_dx NULL NULL'".into()),
        )),
    }
}

pub(super) fn lattice_cmd(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("lattice style", &lattice::STYLES)?;
    if style == "none" {
        let scale = a.f64("scale")?;
        a.done()?;
        sim.defs.lattice = Lattice::new(style, scale);
        return Ok(());
    }
    let is_2d = lattice::STYLES_2D.contains(&style);
    if style != "custom" && is_2d != (sim.setup.dimension == 2) {
        return Err(a.error_prev(
            format!(
                "lattice style {style} does not fit a {}d simulation",
                sim.setup.dimension
            ),
            Some(if is_2d {
                "sq, sq2 and hex are 2d lattices: give 'dimension 2' first".into()
            } else {
                "in 2d use sq, sq2, hex or custom".into()
            }),
        ));
    }
    let scale = a.positive("lattice constant (m)")?;
    let mut l = Lattice::new(style, scale).expect("valid style");
    let custom = style == "custom";
    let mut axes = [None; 3];
    let mut keywords = vec!["origin", "orient", "spacing"];
    if custom {
        keywords.extend(["a1", "a2", "a3", "basis"]);
    }
    while !a.is_done() {
        match a.keyword("lattice keyword", &keywords)? {
            "origin" => {
                let o = a.vec3("origin")?;
                if (0..3).any(|d| !(0.0..1.0).contains(&o[d])) {
                    return Err(a.error_prev("origin values must be in [0, 1)", None));
                }
                l.origin = o;
            }
            k @ ("a1" | "a2" | "a3") => {
                let d = (k.as_bytes()[1] - b'1') as usize;
                let v = a.vec3(k)?;
                // Axis-aligned cells only: a1 along x, a2 along y, a3 along z.
                if (0..3).any(|e| e != d && v[e] != 0.0) || v[d] <= 0.0 {
                    return Err(a.error_prev(
                        format!(
                            "lattice custom: {k} must lie along +{} (other cell vectors are not supported yet)",
                            ["x", "y", "z"][d]
                        ),
                        None,
                    ));
                }
                axes[d] = Some(v[d]);
            }
            "basis" => {
                let b = a.vec3("basis atom")?;
                if (0..3).any(|d| !(0.0..1.0).contains(&b[d])) {
                    return Err(a.error_prev("basis values must be in [0, 1)", None));
                }
                l.basis.push(b);
            }
            k => {
                return Err(a.error_prev(
                    format!("lattice {k} is not supported yet (only unrotated lattices)"),
                    None,
                ))
            }
        }
    }
    if custom {
        l.cell = DVec3::new(
            axes[0].unwrap_or(1.0),
            axes[1].unwrap_or(1.0),
            axes[2].unwrap_or(1.0),
        );
        if l.basis.is_empty() {
            return Err(a.error_at(1, "lattice custom needs at least one 'basis x y z'", None));
        }
    }
    let s = l.spacing();
    sim.outputs.out.line(&format!(
        "Lattice spacing in x,y,z = {} {} {}",
        crate::variables::g(s.x),
        crate::variables::g(s.y),
        crate::variables::g(s.z)
    ));
    sim.defs.lattice = Some(l);
    Ok(())
}

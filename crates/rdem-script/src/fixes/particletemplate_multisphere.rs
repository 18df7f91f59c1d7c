//! `fix ID group particletemplate/multisphere seed atom_type T density constant RHO
//! nspheres N ntry M spheres ... type MT [mass M inertia_tensor ... use_volume|use_density]
//! [fflag ...] [tflag ...]`: a rigid clump of overlapping spheres that distributions and
//! insertion fixes draw from, as LIGGGHTS 3.8 defines it.
//!
//! The spheres come inline (`spheres x1 y1 z1 r1 x2 ...`) or from a file (`spheres file F`,
//! a line `x y z r` per sphere, `#` starting a comment; LIGGGHTS-INL's
//! `spheres_different_types file F`, a line `x y z r type`); `scale s` multiplies
//! positions and radii (after either form). The clump's volume, centre of mass and inertia tensor come
//! from `ntry` Monte Carlo points (`rdem::multisphere::ClumpTemplate`), and its mass is the
//! density times that volume. With `mass` and `inertia_tensor` (about the centre of mass,
//! in the frame the spheres are given in) the mass and inertia are taken as given, and the
//! density is the mass over the Monte Carlo volume (`use_volume`) or the given density
//! (`use_density`, the volume then the mass over it).

use crate::error::Error;
use rdem::insert::{ClumpShape, ParticleTemplate};
use rdem::multisphere::{ClumpTemplate, MassSource, Sphere};

use super::{style, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "particletemplate/multisphere",
    parse,
    Stages::NONE,
    "`atom_type`, `density constant`, `nspheres`, `ntry`, `spheres x y z r ...\\|file F`, `scale`, `type`, `mass` with `inertia_tensor` and `use_volume\\|use_density`, `fflag`, `tflag`; `volume_limit` accepted",
)
.notes("the Monte Carlo mass properties use rdem's own generator: they differ from LIGGGHTS' within the stated standard errors, which the verbose output prints")
.atoi();

/// The registry row of `particletemplate/multiplespheres` (stock LIGGGHTS 3.8, without
/// bonds): the same sphere list, inserted as separate spheres.
pub(super) const ROW_MULTIPLE: FixRow = style(
    "particletemplate/multiplespheres",
    parse,
    Stages::NONE,
    "`atom_type`, `density constant`, `nspheres`, `ntry`, `spheres x y z r ...\\|file F`, `scale`, `bonded no`: the spheres are placed as a clump would be (about the Monte Carlo centre of mass, turned by the insertion's `orientation`) and inserted as separate particles, as LIGGGHTS 3.8 does",
)
.notes("`bonded yes\\|yes/implicit` (spheres closer than r_i + r_j + skin bonded) and `bonded yes/explicit nbond_pairs N i1 j1 ... [bond_type T]` (the pairs given): the forks' bonded templates, with `bond_style gran`; the bonds are made at insertion, their length L0 at their first evaluation. Without bond atoms, `bonded yes` is LIGGGHTS-INL's: each copy's spheres share a `bond_random_id` (fix `bond_random_id`, `f_bond_random_id`), by which `cohesion bond` bonds those closer than createDistanceBond at the step they appear. `relative yes` (LIGGGHTS-INL): sizes in bounding radii, for `fix insert/fragments` only. `spheres_different_types file F [scale s]` (LIGGGHTS-INL): a line `x y z r type` per sphere, each sphere of its own atom type (a file only, as the fork). `create_particles` puts the spheres about their bounding sphere's centre, as given (LIGGGHTS-INL). Inserted spheres join the template's and the distribution's groups, as in LIGGGHTS 3.8")
.atoi();

/// A defined clump template: it lives in `Sim::templates` under the fix ID.
pub struct MultisphereTemplate {
    parsed: Option<ParticleTemplate>,
    /// What the definition prints (the mass properties).
    report: String,
}

impl ScriptFix for MultisphereTemplate {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        if let Some(t) = self.parsed.take() {
            sim.outputs.out.line(&self.report);
            if t.clump.as_ref().is_some_and(|c| c.random_bond_id)
                && sim.fix_index(rdem::bond::RANDOM_ID).is_none()
            {
                // As LIGGGHTS-INL: the fix `bond_random_id` (property/atom), dumped as
                // `f_bond_random_id`.
                super::property_atom::define(
                    sim,
                    a,
                    super::property_atom::PropertyAtom {
                        name: rdem::bond::RANDOM_ID.to_string(),
                        vector: false,
                        defaults: vec![-1.0],
                        forward: false,
                        restart: true,
                    },
                )?;
            }
            sim.defs.templates.insert(head.id.clone(), t);
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        sim.defs.templates.remove(&head.id);
    }
}

/// Where the spheres come from.
enum Source {
    Inline(Vec<Sphere>),
    /// `typed`: each line ends with the sphere's atom type (`spheres_different_types`).
    File {
        path: String,
        at: usize,
        typed: bool,
    },
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let rigid = head.style == "particletemplate/multisphere";
    let style_name = head.style;
    if sim.setup.dimension == 2 {
        return Err(a.error_at(
            STYLE_WORD,
            format!("{style_name} is for 3d simulations only"),
            None,
        ));
    }
    let id = head.id.as_str();
    let seed = a.seed()?;
    let (mut ty, mut density, mut nspheres, mut ntry) = (1u32, None, None, None);
    let (mut source, mut scale, mut ms_type) = (None, 1.0, None);
    let (mut mass, mut inertia, mut use_volume, mut use_density) = (None, None, false, false);
    let (mut fflag, mut tflag) = ([true; 3], [true; 3]);
    // `bonded yes|yes/implicit|yes/explicit` (the forks' bonded templates): implicit
    // (None) or explicit (the pairs given, 1-based, with where they stand); bond type.
    let (mut bonded, mut pairs, mut bond_type): (Option<bool>, Vec<(u64, u64, usize)>, u64) =
        (None, Vec::new(), 1);
    // LIGGGHTS-INL's `bonded yes` without bond atoms (see `ClumpShape::random_bond_id`);
    // `relative yes` (for `fix insert/fragments`).
    let (mut random_bond_id, mut relative) = (false, false);
    const KEYS: [&str; 15] = [
        "atom_type",
        "density",
        "volume_limit",
        "nspheres",
        "ntry",
        "spheres",
        "scale",
        "type",
        "mass",
        "inertia_tensor",
        "use_volume",
        "use_density",
        "fflag",
        "tflag",
        "relative",
    ];
    const KEYS_MULTIPLE: [&str; 12] = [
        "atom_type",
        "density",
        "volume_limit",
        "nspheres",
        "ntry",
        "spheres",
        "spheres_different_types",
        "scale",
        "relative",
        "bonded",
        "nbond_pairs",
        "bond_type",
    ];
    let keys: &[&'static str] = if rigid { &KEYS } else { &KEYS_MULTIPLE };
    while !a.is_done() {
        match a.keyword(&format!("{style_name} keyword"), keys)? {
            "bonded" => {
                let word = a.keyword("bonded", &["no", "yes", "yes/implicit", "yes/explicit"])?;
                bonded = match word {
                    "no" => None,
                    "yes/explicit" => Some(true),
                    _ => Some(false),
                };
                random_bond_id = false;
                if word == "yes" && sim.setup.bond_gran.is_none() {
                    // LIGGGHTS-INL: each copy's spheres share a random ID, which
                    // `cohesion bond` bonds them by.
                    bonded = None;
                    random_bond_id = true;
                } else if bonded.is_some() && sim.setup.bond_gran.is_none() {
                    return Err(a.error_prev(
                        "bonded templates need an atom style with bonds",
                        Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M (or leave 'bonded' out for separate spheres)".into()),
                    ));
                }
            }
            "nbond_pairs" => {
                let n = a.u64("number of bonded pairs")?;
                for k in 1..=n {
                    let at = a.pos();
                    let i = a.count(&format!("first sphere of bonded pair {k}"))?;
                    let j = a.count(&format!("second sphere of bonded pair {k}"))?;
                    pairs.push((i, j, at));
                }
            }
            "bond_type" => bond_type = a.count("bond type")?,
            "atom_type" => ty = super::particletemplate_sphere::atom_type(sim, a)?,
            "density" => {
                a.keyword("density distribution", &["constant"])?;
                density = Some(a.positive("density")?);
            }
            "volume_limit" => {
                a.positive("volume limit")?;
            }
            "nspheres" => nspheres = Some(a.count("number of spheres")? as usize),
            "ntry" => ntry = Some(a.count("number of Monte Carlo points")?),
            key @ ("spheres" | "spheres_different_types") => {
                let typed = key == "spheres_different_types";
                let Some(n) = nspheres else {
                    return Err(a.error_prev(
                        format!("'{key}' must come after 'nspheres N'"),
                        Some(format!("LIGGGHTS reads nspheres first: '... nspheres 3 ntry 1000000 {key} ...'")),
                    ));
                };
                if a.peek() == Some("file") {
                    a.seek(a.pos() + 1);
                    let at = a.pos();
                    let path = a.word("sphere file name")?.to_string();
                    source = Some(Source::File { path, at, typed });
                } else if typed {
                    // As LIGGGHTS-INL: the types come from a file only.
                    a.keyword("spheres_different_types source", &["file"])?;
                } else {
                    let mut v = Vec::with_capacity(n);
                    for k in 1..=n {
                        let x = a.vec3(&format!("sphere {k} centre"))?;
                        let r = a.positive(&format!("sphere {k} radius"))?;
                        v.push(Sphere { x, r });
                    }
                    source = Some(Source::Inline(v));
                }
            }
            "scale" => scale = a.positive("scale factor")?,
            "type" => ms_type = Some(a.count("multisphere type")?),
            "mass" => mass = Some(a.positive("mass")?),
            "inertia_tensor" => {
                let mut t = [0.0; 6];
                for (k, name) in ["Ixx", "Ixy", "Ixz", "Iyy", "Iyz", "Izz"]
                    .iter()
                    .enumerate()
                {
                    t[k] = a.f64(name)?;
                }
                inertia = Some(t);
            }
            "use_volume" => use_volume = true,
            "use_density" => use_density = true,
            "fflag" | "tflag" => {
                let key = a.words()[a.pos() - 1].text.clone();
                let mut f = [true; 3];
                for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                    f[k] = a.yes_no(&format!("{key} {axis} (on or off)"))?;
                }
                if key == "fflag" {
                    fflag = f;
                } else {
                    tflag = f;
                }
            }
            _ => {
                relative = a.yes_no("relative")?;
                if relative && rigid {
                    return Err(a.error_prev(
                        "a rigid template cannot be relative",
                        Some("relative templates are the fragments of fix insert/fragments: define them with particletemplate/multiplespheres".into()),
                    ));
                }
            }
        }
    }
    let need = |what: &str, help: &str| {
        a.error_at(
            STYLE_WORD,
            format!("{style_name} needs {what}"),
            Some(help.into()),
        )
    };
    let nspheres = nspheres.ok_or_else(|| need("'nspheres N'", "the number of spheres"))?;
    let ntry = ntry.ok_or_else(|| {
        need(
            "'ntry N'",
            "the number of Monte Carlo points for the mass properties, e.g. 'ntry 1000000'",
        )
    })?;
    let source = source.ok_or_else(|| {
        need(
            "'spheres'",
            "'spheres x1 y1 z1 r1 ...' or 'spheres file F [scale s]'",
        )
    })?;
    let clump_type = match ms_type {
        Some(t) => t,
        None if !rigid => 0,
        None => {
            return Err(need(
                "'type MT'",
                "the multisphere type of the template, from 1",
            ))
        }
    };
    let mut sphere_types = Vec::new();
    let mut spheres = match source {
        Source::Inline(v) => v,
        Source::File { path, at, typed } => {
            let text =
                std::fs::read(&path).map_err(|e| a.error_at(at, format!("{path}: {e}"), None))?;
            let rows = parse_rows(&text, nspheres, typed)
                .map_err(|e| a.error_at(at, format!("{path}: {e}"), None))?;
            let ntypes = sim.ntypes();
            let mut v = Vec::with_capacity(rows.len());
            for (k, (sphere, t)) in rows.into_iter().enumerate() {
                if let Some(t) = t {
                    if t as usize > ntypes {
                        return Err(a.error_at(
                            at,
                            format!(
                                "{path}: sphere {} has atom type {t}, more than the box's {ntypes}",
                                k + 1
                            ),
                            None,
                        ));
                    }
                    sphere_types.push(t);
                }
                v.push(sphere);
            }
            v
        }
    };
    // LIGGGHTS-PFM's coarse graining scales the spheres too.
    let scale = scale * sim.setup.coarse_graining.factor;
    for s in &mut spheres {
        s.x *= scale;
        s.r *= scale;
    }
    let bonds = template_bonds(sim, a, &spheres, bonded, &pairs, bond_type)?;
    let bound_offsets = if rigid {
        Vec::new()
    } else {
        let (c, _) = rdem::multisphere::template::enclosing_sphere(&spheres);
        spheres.iter().map(|s| s.x - c).collect()
    };
    let source = match (mass, inertia) {
        (None, None) => {
            let rho = density.ok_or_else(|| {
                need(
                    "a density",
                    "add 'density constant RHO' (kg/m^3), or 'mass M inertia_tensor ...'",
                )
            })?;
            MassSource::Density(rho)
        }
        (Some(mass), Some(inertia)) => MassSource::Given { mass, inertia },
        _ => return Err(need(
            "'mass' and 'inertia_tensor' together",
            "give both, or neither (then they come from the density and the Monte Carlo volume)",
        )),
    };
    if let MassSource::Given { .. } = source {
        if use_volume == use_density {
            return Err(need(
                "one of 'use_volume' and 'use_density' with 'mass'",
                "use_volume: density = mass / Monte Carlo volume; use_density: volume = mass / density",
            ));
        }
    }
    let template = ClumpTemplate::new(&spheres, ntry, seed, source)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    let p = &template.props;
    let density = match source {
        MassSource::Given { mass, .. } if use_volume => mass / p.volume,
        MassSource::Given { .. } => density.ok_or_else(|| {
            need(
                "a density with 'use_density'",
                "add 'density constant RHO' (kg/m^3)",
            )
        })?,
        MassSource::Density(rho) => rho,
    };
    let m = template.moments;
    let what = if rigid {
        "Multisphere"
    } else {
        "Multiplespheres"
    };
    let report = format!(
        "{what} template {id}: {nspheres} spheres, Monte Carlo volume {:e} (± {:e}), mass {:e}, \
         centre of mass ({:e}, {:e}, {:e}) (± {:e}), principal moments of inertia ({:e}, {:e}, {:e}), \
         bounding radius {:e}",
        p.volume,
        p.volume_err,
        p.mass,
        p.com.x,
        p.com.y,
        p.com.z,
        p.com_err.max_element(),
        m.x,
        m.y,
        m.z,
        template.bound_radius
    );
    let shape = ClumpShape {
        template,
        fflag,
        tflag,
        clump_type: u32::try_from(clump_type).unwrap_or(u32::MAX),
        rigid,
        bonds,
        random_bond_id,
        relative,
        sphere_types,
        bound_offsets,
    };
    let mut t = ParticleTemplate::clump(id, seed, ty, density, shape)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    // Inserted spheres join the template's group too, as in LIGGGHTS 3.8.
    t.groupbit = head.groupbit;
    Ok(Box::new(MultisphereTemplate {
        parsed: Some(t),
        report,
    }))
}

/// The bonds of a bonded template (`bonded yes/explicit`: the pairs given; `bonded yes`:
/// the spheres closer than r_i + r_j + the neighbor skin), as 0-based sphere pairs with
/// the bond type.
fn template_bonds(
    sim: &Sim,
    a: &Args,
    spheres: &[Sphere],
    bonded: Option<bool>,
    pairs: &[(u64, u64, usize)],
    bond_type: u64,
) -> CmdResult<Vec<(u32, u32, u32)>> {
    let Some(explicit) = bonded else {
        if let Some(&(_, _, at)) = pairs.first() {
            return Err(a.error_at(at, "nbond_pairs without 'bonded yes/explicit'", None));
        }
        return Ok(Vec::new());
    };
    let ntypes = sim.setup.bond_gran.map_or(0, |b| b.0) as u64;
    if bond_type > ntypes {
        return Err(a.error_cmd(
            format!("bond_type {bond_type} > the atom style's n_bondtypes {ntypes}"),
            None,
        ));
    }
    let t = bond_type as u32;
    if explicit {
        if pairs.is_empty() {
            return Err(a.error_cmd(
                "bonded yes/explicit needs 'nbond_pairs N i1 j1 ...'",
                Some("e.g. 'bonded yes/explicit nbond_pairs 2 1 2 2 3 bond_type 1'".into()),
            ));
        }
        let n = spheres.len() as u64;
        let mut out = Vec::with_capacity(pairs.len());
        for &(i, j, at) in pairs {
            if i > n || j > n || i == j {
                return Err(a.error_at(
                    at,
                    format!("bonded pair {i} {j}: spheres are 1..={n}, two different ones"),
                    None,
                ));
            }
            out.push(((i - 1) as u32, (j - 1) as u32, t));
        }
        Ok(out)
    } else {
        let skin = sim.neighbor_settings().skin;
        let mut out = Vec::new();
        for i in 0..spheres.len() {
            for j in i + 1..spheres.len() {
                let (si, sj) = (&spheres[i], &spheres[j]);
                if (si.x - sj.x).length() < si.r + sj.r + skin {
                    out.push((i as u32, j as u32, t));
                }
            }
        }
        Ok(out)
    }
}

/// The spheres of the bytes of a template file: a line `x y z r` per sphere, `#`
/// starting a comment, blank lines skipped; exactly `n` spheres. Any bytes give the
/// spheres or an error.
pub fn parse_spheres(bytes: &[u8], n: usize) -> Result<Vec<Sphere>, Error> {
    Ok(parse_rows(bytes, n, false)?
        .into_iter()
        .map(|(s, _)| s)
        .collect())
}

/// The spheres of a `spheres_different_types` file (LIGGGHTS-INL): a line `x y z r type`
/// per sphere, otherwise as [`parse_spheres`].
pub fn parse_typed_spheres(bytes: &[u8], n: usize) -> Result<Vec<(Sphere, u32)>, Error> {
    Ok(parse_rows(bytes, n, true)?
        .into_iter()
        .map(|(s, t)| (s, t.unwrap_or(1)))
        .collect())
}

/// The rows of a template file, each with its atom type when `typed`.
fn parse_rows(bytes: &[u8], n: usize, typed: bool) -> Result<Vec<(Sphere, Option<u32>)>, Error> {
    let text = String::from_utf8_lossy(bytes);
    let cols = if typed { 5 } else { 4 };
    let mut out = Vec::with_capacity(n.min(bytes.len() / 8 + 1));
    for (k, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let v: Vec<&str> = line.split_whitespace().collect();
        let nums: Option<Vec<f64>> = v.iter().map(|w| crate::args::parse_f64(w)).collect();
        match nums {
            Some(x) if x.len() == cols => {
                if x[3].is_nan() || x[3] <= 0.0 {
                    return Err(format!("line {}: radius {} must be > 0", k + 1, x[3]).into());
                }
                let ty = if typed {
                    let t = x[4];
                    if !(t >= 1.0 && t.fract() == 0.0 && t <= u32::MAX as f64) {
                        return Err(format!(
                            "line {}: atom type {} must be a whole number from 1",
                            k + 1,
                            v[4]
                        )
                        .into());
                    }
                    Some(t as u32)
                } else {
                    None
                };
                out.push((
                    Sphere {
                        x: glam::DVec3::new(x[0], x[1], x[2]),
                        r: x[3],
                    },
                    ty,
                ));
            }
            _ => {
                let want = if typed {
                    "five numbers 'x y z r type'"
                } else {
                    "four numbers 'x y z r'"
                };
                return Err(format!("line {}: expected {want}, got '{line}'", k + 1).into());
            }
        }
    }
    if out.len() != n {
        return Err(format!("holds {} sphere(s), but nspheres says {n}", out.len()).into());
    }
    Ok(out)
}

//! The command table: every command rdem runs, mapped to its handler. Flow-control
//! commands (`include`, `label`, `jump`, `next`, `if`, `print`, `variable`, `log`, `echo`)
//! are handled by [`crate::input`], which owns the file stack.

use glam::DVec3;
use rdem::region::{Region, Shape};
use rdem::{Boundary, ContactModel, Domain, LostPolicy, NewParticle, PairGran, World};

use crate::args::{nearest, suggest, Args, CmdResult};
use crate::computes::{self, Compute, ComputeKind, ReduceInput};
use crate::lattice::{self, Lattice};
use crate::sim::Sim;
use crate::{dump, fixes, models, run, thermo};

/// Commands handled here.
pub const SIM_COMMANDS: [&str; 41] = [
    "atom_style",
    "atom_modify",
    "boundary",
    "units",
    "newton",
    "communicate",
    "processors",
    "hard_particles",
    "region",
    "lattice",
    "create_box",
    "create_atoms",
    "read_data",
    "delete_atoms",
    "set",
    "velocity",
    "group",
    "neighbor",
    "neigh_modify",
    "pair_style",
    "pair_coeff",
    "timestep",
    "fix",
    "unfix",
    "compute",
    "uncompute",
    "thermo",
    "thermo_style",
    "thermo_modify",
    "run",
    "reset_timestep",
    "dump",
    "dump_modify",
    "undump",
    "write_dump",
    "write_data",
    "write_restart",
    "read_restart",
    "soft_particles",
    "modify_timing",
    "atom_modify_sort",
];

/// LIGGGHTS commands outside this release.
const LATER: [(&str, &str); 6] = [
    ("bond_style", "bonds"),
    ("bond_coeff", "bonds"),
    ("create_bonds", "bonds"),
    ("run_style", "run styles other than verlet"),
    ("minimize", "energy minimisation"),
    ("displace_atoms", "displace_atoms"),
];

/// Runs a simulation command. `Ok(false)` if `name` is not one.
pub fn execute(sim: &mut Sim, a: &mut Args) -> CmdResult<bool> {
    match a.name() {
        "atom_style" => atom_style(a)?,
        "atom_modify" => atom_modify(sim, a)?,
        "boundary" => boundary(sim, a)?,
        "units" => {
            let u = a.word("unit style")?;
            if u != "si" {
                return Err(a.error_prev(
                    format!("units {u} is not supported: rdem works in SI units"),
                    Some("use 'units si' (metres, kilograms, seconds)".into()),
                ));
            }
            a.done()?;
            sim.units_set = true;
        }
        "newton" => {
            a.keyword("newton setting", &["on", "off"])?;
            if !a.is_done() {
                a.keyword("newton bond setting", &["on", "off"])?;
            }
            a.done()?;
        }
        "communicate" => {
            a.keyword("communicate style", &["single", "multi"])?;
            while !a.is_done() {
                match a.keyword("communicate keyword", &["vel", "cutoff", "group"])? {
                    "vel" => {
                        a.yes_no("vel")?;
                    }
                    "cutoff" => {
                        a.non_negative("cutoff")?;
                    }
                    _ => {
                        sim.group_bit(a, "group ID")?;
                    }
                }
            }
        }
        "processors" => {
            if sim.world.is_some() {
                return Err(a.error_cmd(
                    "processors must come before the box is defined (create_box, read_data)",
                    None,
                ));
            }
            let mut procs = [0; 3];
            for (k, d) in ["Px", "Py", "Pz"].into_iter().enumerate() {
                if a.peek() == Some("*") {
                    a.word(d)?;
                } else {
                    procs[k] = a.count(d)? as usize;
                }
            }
            if !a.is_done() {
                return Err(a.error_at(
                    a.pos(),
                    "processors keywords (grid, map, part, file) are not supported",
                    Some("give only 'processors Px Py Pz' (each a count or *)".into()),
                ));
            }
            let nprocs = rdem::comm::process_rank_size().1;
            if rdem::domain::least_surface_grid(nprocs, DVec3::ONE, procs).is_none() {
                let shown: Vec<String> = procs
                    .iter()
                    .map(|&n| if n == 0 { "*".into() } else { n.to_string() })
                    .collect();
                return Err(a.error_at(
                    1,
                    format!(
                        "no {} grid has {nprocs} process{} (the number this run was started with)",
                        shown.join(" x "),
                        if nprocs == 1 { "" } else { "es" }
                    ),
                    Some(
                        "use 'processors * * *', or start rdem (built with --features mpi) \
                         with mpirun -np N where N is the product of the counts"
                            .into(),
                    ),
                ));
            }
            sim.pending.procs = procs;
        }
        "hard_particles" | "soft_particles" => {
            a.yes_no(a.name())?;
            a.done()?;
        }
        "region" => region(sim, a)?,
        "lattice" => lattice_cmd(sim, a)?,
        "create_box" => create_box(sim, a)?,
        "create_atoms" => create_atoms(sim, a)?,
        "read_data" | "read_restart" => read_data(sim, a)?,
        "delete_atoms" => delete_atoms(sim, a)?,
        "set" => set(sim, a)?,
        "velocity" => velocity(sim, a)?,
        "group" => group(sim, a)?,
        "neighbor" => {
            let skin = a.non_negative("skin distance")?;
            a.keyword("neighbor style", &["bin", "nsq"])?;
            a.done()?;
            sim.pending.neighbor.skin = skin;
        }
        "neigh_modify" => neigh_modify(sim, a)?,
        "pair_style" => pair_style(sim, a)?,
        "pair_coeff" => {
            let t1 = a.word("type I")?;
            let t2 = a.word("type J")?;
            for (t, k) in [(t1, 1), (t2, 2)] {
                if t != "*"
                    && t.parse::<usize>()
                        .map_or(true, |v| v == 0 || v > sim.ntypes.max(1))
                {
                    return Err(a.error_at(
                        k,
                        format!("bad atom type '{t}'"),
                        Some(format!("use * or 1..{}", sim.ntypes)),
                    ));
                }
            }
            if !a.is_done() {
                return Err(a.error_at(
                    a.pos(),
                    "granular pair styles take no coefficients: write 'pair_coeff * *'",
                    None,
                ));
            }
            if sim.world.as_ref().and_then(|w| w.pair.as_ref()).is_none() {
                return Err(a.error_cmd(
                    "pair_coeff before pair_style",
                    Some("define 'pair_style gran ...' first".into()),
                ));
            }
            sim.pair_coeff_set = true;
        }
        "timestep" => {
            let dt = a.positive("timestep")?;
            a.done()?;
            let now = (sim.world.as_ref().map(|w| w.step).unwrap_or(0), sim.time());
            sim.time_origin = now;
            sim.pending.dt = dt;
            if let Some(w) = &mut sim.world {
                w.dt = dt;
            }
        }
        "fix" => fixes::fix(sim, a)?,
        "unfix" => {
            let id = a.word("fix ID")?;
            a.done()?;
            fixes::check_unfix(sim, id).map_err(|m| a.error_prev(m, None))?;
            if !fixes::unfix_id(sim, id) {
                let names: Vec<&str> = sim.fixes.iter().map(|f| f.id.as_str()).collect();
                return Err(a.error_prev(format!("no fix '{id}'"), Some(suggest(id, &names))));
            }
        }
        "compute" => compute(sim, a)?,
        "uncompute" => {
            let id = a.word("compute ID")?;
            a.done()?;
            match sim.compute_index(id) {
                Some(k) => {
                    sim.computes.remove(k);
                }
                None => {
                    let names: Vec<&str> = sim.computes.iter().map(|c| c.id.as_str()).collect();
                    return Err(
                        a.error_prev(format!("no compute '{id}'"), Some(suggest(id, &names)))
                    );
                }
            }
        }
        "thermo" => {
            sim.thermo.every = a.u64("thermo output interval")?;
            a.done()?;
        }
        "thermo_style" => thermo_style(sim, a)?,
        "thermo_modify" => thermo_modify(sim, a)?,
        "run" => run::run(sim, a)?,
        "reset_timestep" => {
            let n = a.u64("timestep")?;
            a.done()?;
            sim.world_mut(a)?.step = n;
        }
        "dump" => dump::dump(sim, a)?,
        "dump_modify" => dump::dump_modify(sim, a)?,
        "undump" => dump::undump(sim, a)?,
        "write_dump" => dump::write_dump(sim, a)?,
        // rdem's restart files are portable data files (particles, box, step); the
        // LIGGGHTS binary restart format is not written or read.
        "write_data" | "write_restart" => {
            let restart = a.name() == "write_restart";
            let f = a.word("file name")?;
            while !a.is_done() {
                if restart {
                    a.keyword("write_restart keyword", &[])?;
                } else {
                    a.keyword("write_data keyword", &["nocoeff", "nofix"])?;
                }
            }
            let ntypes = sim.ntypes as u32;
            let w = sim.world_ref(a)?;
            let f = f.replace('*', &w.step.to_string());
            if sim.check {
                return Ok(true); // rdem -check writes no file
            }
            // Every rank sends its owned particles; rank 0 writes them all, sorted by tag.
            let all: Vec<usize> = (0..w.particles.nlocal()).collect();
            if let Some(g) = dump::gather_owned(&*w.comm, &w.particles, &all, &[]) {
                rdem_io::write_data(
                    std::path::Path::new(&f),
                    &g.particles,
                    &w.domain,
                    ntypes,
                    w.step,
                )
                .map_err(|e| a.error_at(1, e.to_string(), None))?;
            }
        }
        name => {
            if let Some((_, what)) = LATER.iter().find(|(c, _)| *c == name) {
                return Err(a.error_cmd(
                    format!("{name} ({what}) is not supported by this rdem release yet"),
                    None,
                ));
            }
            return Ok(false);
        }
    }
    Ok(true)
}

/// Help for an unknown command: the nearest known command.
pub fn unknown_command_help(name: &str, all: &[&str]) -> String {
    match nearest(name, all) {
        Some(n) => {
            format!("did you mean '{n}'? (rdem runs the LIGGGHTS commands listed in its README)")
        }
        None => "rdem runs the LIGGGHTS commands listed in its README".into(),
    }
}

/// Help for an unknown compute/fix/dump ID: the nearest defined one, or how to define it.
pub fn id_help(what: &str, id: &str, ids: &[&str]) -> String {
    if ids.is_empty() {
        format!("no {what} is defined yet; define '{id}' with '{what} {id} ...' first")
    } else {
        suggest(id, ids)
    }
}

fn atom_style(a: &mut Args) -> CmdResult {
    let s = a.word("atom style")?;
    if s != "granular" && s != "sphere" {
        let later = [
            "hybrid",
            "superquadric",
            "bond/gran",
            "granular/multisphere",
        ];
        let help = if later.contains(&s) {
            format!("atom_style {s} is not supported by this rdem release yet; use granular")
        } else {
            suggest(s, &["granular", "sphere"])
        };
        return Err(a.error_prev(format!("unsupported atom style '{s}'"), Some(help)));
    }
    a.done()
}

fn atom_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "atom_modify: missing keyword",
            Some("map, sort".into()),
        ));
    }
    while !a.is_done() {
        match a.keyword("atom_modify keyword", &["map", "sort", "id"])? {
            "map" => {
                a.keyword("map style", &["array", "hash"])?;
            }
            "id" => {
                a.yes_no("id")?;
            }
            _ => {
                let every = a.u64("sort interval (0 = off)")?;
                let bin = a.non_negative("sort bin size (0 = half the neighbor cutoff)")?;
                sim.pending.sort = rdem::SortSettings {
                    every,
                    binsize: bin,
                };
            }
        }
    }
    Ok(())
}

fn boundary(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if sim.world.is_some() {
        return Err(a.error_cmd(
            "boundary after the simulation box is defined",
            Some("give boundary before create_box or read_data".into()),
        ));
    }
    let mut b = [[Boundary::Periodic; 2]; 3];
    for (axis, slot) in b.iter_mut().enumerate() {
        let w = a.word(&format!("{} boundary", ["x", "y", "z"][axis]))?;
        let letters: Vec<char> = w.chars().collect();
        let faces = match letters.as_slice() {
            [c] => [*c, *c],
            [c, d] => [*c, *d],
            _ => {
                return Err(a.error_prev(
                    format!("bad boundary '{w}'"),
                    Some("one or two of p f s m per axis, e.g. 'm m m' or 'p p fm'".into()),
                ))
            }
        };
        for (k, c) in faces.iter().enumerate() {
            slot[k] = Boundary::from_letter(*c).ok_or_else(|| {
                a.error_prev(
                    if letters.len() == 1 {
                        format!("unknown boundary '{c}'")
                    } else {
                        format!("unknown boundary '{c}' in '{w}'")
                    },
                    Some(
                        "use p (periodic), f (fixed), s (shrink-wrapped) or m (shrink-wrapped with a minimum)"
                            .into(),
                    ),
                )
            })?;
        }
        if (slot[0] == Boundary::Periodic) != (slot[1] == Boundary::Periodic) {
            return Err(a.error_prev(
                format!("'{w}': both faces must be periodic, or neither"),
                Some("write 'p' for a periodic axis, or two of f s m such as 'fm'".into()),
            ));
        }
    }
    a.done()?;
    sim.pending.boundary = b;
    Ok(())
}

fn scale_of(sim: &Sim, a: &Args, units_lattice: bool) -> CmdResult<DVec3> {
    if !units_lattice {
        return Ok(DVec3::ONE);
    }
    sim.lattice.as_ref().map(|l| l.spacing()).ok_or_else(|| {
        a.error_cmd(
            "units lattice (the default) needs a lattice",
            Some("add 'units box' to use box coordinates, or define a 'lattice' first".into()),
        )
    })
}

/// "region block takes xlo xhi ylo yhi zlo zhi ..." for help texts.
fn region_usage(style: &str, names: &[&str]) -> String {
    format!(
        "region ID {style} {} [side in|out] [units box|lattice]",
        names.join(" ")
    )
}

fn region(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("region ID")?.to_string();
    if sim.regions.contains_key(&id) {
        return Err(a.error_prev(format!("region ID '{id}' is already used"), None));
    }
    const STYLES: [&str; 7] = [
        "block",
        "sphere",
        "cylinder",
        "cone",
        "plane",
        "union",
        "intersect",
    ];
    let style = a.keyword("region style", &STYLES)?;
    let args_start = a.pos();
    let arg_names: &[&str] = match style {
        "block" => &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi"],
        "sphere" => &["x", "y", "z", "radius"],
        "cylinder" => &["dim", "c1", "c2", "radius", "lo", "hi"],
        "cone" => &["dim", "c1", "c2", "radlo", "radhi", "lo", "hi"],
        "plane" => &["px", "py", "pz", "nx", "ny", "nz"],
        _ => &[],
    };
    // Geometry words first (numbers may be INF/EDGE); keywords after.
    let mut geo: Vec<String> = Vec::new();
    let mut parts: Vec<Region> = Vec::new();
    match style {
        "union" | "intersect" => {
            let n = a.count("number of regions")?;
            for _ in 0..n {
                parts.push(sim.region(a)?);
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
    let (mut outside, mut lattice_units) = (false, true);
    while !a.is_done() {
        match a.keyword(
            "region keyword",
            &["side", "units", "move", "rotate", "open"],
        )? {
            "side" => outside = a.keyword("side", &["in", "out"])? == "out",
            "units" => lattice_units = a.keyword("units", &["box", "lattice"])? == "lattice",
            k => {
                return Err(a.error_prev(format!("region keyword '{k}' is not supported yet"), None))
            }
        }
    }
    let needs_scale = !matches!(style, "union" | "intersect");
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
                    format!("'{w}' is only valid for the bounds of block, cylinder and cone"),
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
        crate::args::parse_f64(w).map(|v| v * scale).ok_or_else(|| {
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
        "plane" => Shape::Plane {
            point: DVec3::new(num(0, s.x)?, num(1, s.y)?, num(2, s.z)?),
            normal: DVec3::new(num(3, 1.0)?, num(4, 1.0)?, num(5, 1.0)?),
        },
        "union" => Shape::Union(parts),
        _ => Shape::Intersect(parts),
    };
    let mut r = Region::new(shape).map_err(|e| a.error_at(args_start, e.to_string(), None))?;
    if outside {
        r = r.side_out();
    }
    sim.regions.insert(id, r);
    Ok(())
}

fn lattice_cmd(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("lattice style", &lattice::STYLES)?;
    if style == "none" {
        a.f64("scale")?;
        a.done()?;
        sim.lattice = None;
        return Ok(());
    }
    let scale = a.positive("lattice constant (m)")?;
    let mut l = Lattice::new(style, scale).expect("valid style");
    while !a.is_done() {
        match a.keyword("lattice keyword", &["origin", "orient", "spacing"])? {
            "origin" => {
                let o = a.vec3("origin")?;
                if (0..3).any(|d| !(0.0..1.0).contains(&o[d])) {
                    return Err(a.error_prev("origin values must be in [0, 1)", None));
                }
                l.origin = o;
            }
            k => {
                return Err(a.error_prev(
                    format!("lattice {k} is not supported yet (only unrotated cubic lattices)"),
                    None,
                ))
            }
        }
    }
    sim.out.line(&format!(
        "Lattice spacing in x,y,z = {} {} {}",
        fixes::g(scale),
        fixes::g(scale),
        fixes::g(scale)
    ));
    sim.lattice = Some(l);
    Ok(())
}

fn create_box(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if sim.world.is_some() {
        return Err(a.error_cmd("create_box: the simulation box is already defined", None));
    }
    let n = a.count("number of atom types")?;
    if a.is_done() {
        let names: Vec<&str> = sim.regions.keys().map(|s| s.as_str()).collect();
        return Err(a.error_at(
            a.pos(),
            "create_box: missing region ID",
            Some(if names.is_empty() {
                "create_box N REGION-ID: define the box region first, e.g. 'region reg block -1 1 -1 1 0 2 units box'".into()
            } else {
                format!("create_box N REGION-ID with a defined region: {}", crate::diagnostic::one_of(&names))
            }),
        ));
    }
    let r = sim.region(a)?;
    if !a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "create_box: bonds and extra keywords are not supported",
            None,
        ));
    }
    let (lo, hi) = r
        .bounding_box()
        .ok_or_else(|| a.error_at(2, "create_box needs a bounded region (e.g. a block)", None))?;
    if (0..3).any(|d| lo[d] <= -1e299 || hi[d] >= 1e299) {
        return Err(a.error_at(2, "create_box needs a region with finite bounds", None));
    }
    let domain = Domain::with_faces(lo, hi, sim.pending.boundary)
        .map_err(|e| a.error_at(2, e.to_string(), None))?;
    sim.out.line(&format!(
        "Created orthogonal box = ({} {} {}) to ({} {} {})",
        fixes::g(lo.x),
        fixes::g(lo.y),
        fixes::g(lo.z),
        fixes::g(hi.x),
        fixes::g(hi.y),
        fixes::g(hi.z)
    ));
    let mut w = World::new(domain);
    decompose(sim, &mut w, a, 0)?;
    w.dt = sim.pending.dt;
    sim.ntypes = n as usize;
    sim.world = Some(w);
    Ok(())
}

/// Splits the new box between the ranks (`processors`) and reports the grid as LIGGGHTS.
fn decompose(sim: &mut Sim, w: &mut World, a: &Args, word: usize) -> CmdResult {
    w.decompose(sim.pending.procs)
        .map_err(|e| a.error_at(word, e.to_string(), None))?;
    let g = w.domain.procgrid;
    sim.out.line(&format!(
        "  {} by {} by {} MPI processor grid",
        g[0], g[1], g[2]
    ));
    Ok(())
}

fn new_default(x: DVec3, ty: u32) -> NewParticle {
    // LIGGGHTS' granular defaults for created atoms: diameter 1, density 1.
    NewParticle::at(x, 0.5, 1.0).with_type(ty)
}

fn create_atoms(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let ty = a.count("atom type")? as u32;
    if ty as usize > sim.ntypes {
        return Err(a.error_prev(
            format!("atom type {ty} > the box's {} type(s)", sim.ntypes),
            None,
        ));
    }
    let style = a.keyword("create_atoms style", &["single", "region", "box", "random"])?;
    let mut points = Vec::new();
    let mut reg = None;
    let mut single = None;
    match style {
        "single" => single = Some(a.vec3("position")?),
        "region" => reg = Some(sim.region(a)?),
        "box" => {}
        _ => {
            return Err(a.error_prev(
                "create_atoms random is not supported; use fix insert/pack",
                None,
            ))
        }
    }
    let mut lattice_units = true;
    while !a.is_done() {
        a.keyword("create_atoms keyword", &["units"])?;
        lattice_units = a.keyword("units", &["box", "lattice"])? == "lattice";
    }
    let w = sim
        .world
        .as_ref()
        .ok_or_else(|| a.error_cmd("create_atoms before the simulation box is defined", None))?;
    let (lo, hi) = (w.domain.boxlo, w.domain.boxhi);
    if let Some(x) = single {
        let s = scale_of(sim, a, lattice_units)?;
        points.push(x * s);
    } else {
        let l = sim.lattice.as_ref().ok_or_else(|| {
            a.error_cmd(
                "create_atoms box/region needs a lattice",
                Some("define one with 'lattice sc|bcc|fcc a'".into()),
            )
        })?;
        points = l.points(lo, hi);
        if let Some(r) = &reg {
            points.retain(|x| r.contains(*x));
        }
    }
    let w = sim.world.as_mut().expect("checked");
    let mut n = 0;
    for x in points {
        let mut p = new_default(x, ty);
        p.mask = 1;
        // Every rank sees every point; the one whose subdomain holds it creates it.
        w.domain
            .check_inside_fixed(x)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
        n += 1;
        if !w.owns_point(x) {
            continue;
        }
        w.add_particle(&p)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
    }
    w.extend_tags();
    sim.out.line(&format!("Created {n} atoms"));
    Ok(())
}

fn read_data(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let file = a.word("data file")?;
    if !a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "read_data keywords (add, offset, ...) are not supported yet",
            None,
        ));
    }
    if sim.world.is_some() {
        return Err(a.error_cmd("read_data: the simulation box is already defined", None));
    }
    let data = rdem_io::read_data(std::path::Path::new(file))
        .map_err(|e| a.error_at(1, e.to_string(), None))?;
    let domain = Domain::with_faces(data.lo, data.hi, sim.pending.boundary)
        .map_err(|e| a.error_at(1, format!("{file}: {e}"), None))?;
    sim.out.line(&format!(
        "Created orthogonal box = ({} {} {}) to ({} {} {})",
        fixes::g(data.lo.x),
        fixes::g(data.lo.y),
        fixes::g(data.lo.z),
        fixes::g(data.hi.x),
        fixes::g(data.hi.y),
        fixes::g(data.hi.z)
    ));
    let mut w = World::new(domain);
    decompose(sim, &mut w, a, 1)?;
    w.dt = sim.pending.dt;
    for (mut p, image) in data.new_particles() {
        p.mask = 1;
        if !w.owns_point(p.x) {
            continue;
        }
        let i = w
            .add_particle(&p)
            .map_err(|e| a.error_at(1, format!("{file}: {e}"), None))?;
        w.particles.image[i] = image;
    }
    sim.out.line(&format!("  {} atoms", data.atoms.len()));
    if a.name() == "read_restart" {
        // The step written by write_restart (or write_data) into the title line.
        w.step = data
            .title
            .rsplit_once("timestep = ")
            .and_then(|(_, n)| n.trim().parse().ok())
            .ok_or_else(|| {
                a.error_at(
                    1,
                    format!("{file}: not an rdem restart file (no 'timestep = N' in its title)"),
                    None,
                )
            })?;
    }
    sim.ntypes = data.ntypes as usize;
    sim.world = Some(w);
    Ok(())
}

fn select(sim: &Sim, a: &mut Args, style: &str) -> CmdResult<Vec<bool>> {
    let w = sim.world_ref(a)?;
    let p = &w.particles;
    let n = p.nlocal();
    Ok(match style {
        "group" => {
            let bit = sim.group_bit(a, "group ID")?;
            (0..n).map(|i| p.mask[i] & bit != 0).collect()
        }
        "region" => {
            let r = sim.region(a)?;
            (0..n).map(|i| r.contains(p.x[i])).collect()
        }
        "type" | "atom" => {
            let spec = a.word(if style == "type" {
                "type or range"
            } else {
                "atom ID or range"
            })?;
            let (lo, hi) = range(spec).ok_or_else(|| {
                a.error_prev(
                    format!("bad {style} range '{spec}'"),
                    Some("N, N*, *N, N*M or *".into()),
                )
            })?;
            (0..n)
                .map(|i| {
                    let v = if style == "type" {
                        p.ty[i] as u64
                    } else {
                        p.tag[i]
                    };
                    v >= lo && v <= hi
                })
                .collect()
        }
        _ => unreachable!(),
    })
}

/// LAMMPS ranges: `N`, `*`, `N*`, `*N`, `N*M`.
fn range(s: &str) -> Option<(u64, u64)> {
    match s.split_once('*') {
        None => s.parse().ok().map(|v| (v, v)),
        Some((l, h)) => {
            let lo = if l.is_empty() { 1 } else { l.parse().ok()? };
            let hi = if h.is_empty() {
                u64::MAX
            } else {
                h.parse().ok()?
            };
            Some((lo, hi))
        }
    }
}

fn delete_atoms(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("delete_atoms style", &["group", "region"])?;
    let remove = select(sim, a, style)?;
    let mut compress = true;
    while !a.is_done() {
        a.keyword("delete_atoms keyword", &["compress"])?;
        compress = a.yes_no("compress")?;
    }
    let settings = sim.pending.neighbor;
    let w = sim.world_mut(a)?;
    w.neighbor.save_history(&w.particles);
    w.particles.clear_ghosts();
    let n = w.comm.sum_count(w.particles.remove_locals(&remove) as u64);
    let mut renumbered = false;
    if compress {
        // Renumber tags 1..N keeping their order (LIGGGHTS' compress yes): a tag's new
        // value is its rank among the tags of all ranks.
        let p = &mut w.particles;
        let mine: Vec<f64> = p.tag[..p.nlocal()].iter().map(|&t| t as f64).collect();
        let mut all = w.comm.all_gather(&mine);
        all.sort_by(f64::total_cmp);
        let nlocal = p.nlocal();
        for t in &mut p.tag[..nlocal] {
            let new = all.partition_point(|&x| x < *t as f64) as u64 + 1;
            renumbered |= *t != new;
            *t = new;
        }
        renumbered = w.comm.any(renumbered);
    }
    let total = w.natoms();
    if renumbered {
        // Saved contact history is keyed by the old tags: start it afresh. Without
        // renumbering it carries over to the next run's set-up.
        w.neighbor = rdem::neighbor::Neighbor::new(settings);
    }
    sim.out
        .line(&format!("Deleted {n} atoms, new total = {total}"));
    Ok(())
}

fn set(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("set style", &["atom", "type", "group", "region"])?;
    let sel = select(sim, a, style)?;
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "set: missing keyword",
            Some("type, diameter, density, mass, vx, vy, vz, omega, property/atom".into()),
        ));
    }
    sim.out.line("Setting atom values ...");
    while !a.is_done() {
        let kw = a.keyword(
            "set keyword",
            &[
                "type",
                "diameter",
                "density",
                "mass",
                "vx",
                "vy",
                "vz",
                "omega",
                "property/atom",
            ],
        )?;
        let ntypes = sim.ntypes;
        let w = sim.world.as_mut().expect("select checked");
        w.neighbor.save_history(&w.particles);
        w.particles.clear_ghosts();
        let p = &mut w.particles;
        let mut count = 0;
        match kw {
            "type" => {
                let t = a.count("type")?;
                if t as usize > ntypes {
                    return Err(
                        a.error_prev(format!("type {t} > the box's {ntypes} type(s)"), None)
                    );
                }
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.ty[i] = t as u32;
                    count += 1;
                }
            }
            "diameter" => {
                let d = a.positive("diameter")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.set_radius(i, 0.5 * d)
                        .map_err(|e| a.error_prev(e.to_string(), None))?;
                    count += 1;
                }
            }
            "density" => {
                let rho = a.positive("density")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.density[i] = rho;
                    let r = p.radius[i];
                    p.set_radius(i, r)
                        .map_err(|e| a.error_prev(e.to_string(), None))?;
                    count += 1;
                }
            }
            "mass" => {
                let m = a.positive("mass")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.rmass[i] = m;
                    p.density[i] = m / (4.0 / 3.0 * std::f64::consts::PI * p.radius[i].powi(3));
                    count += 1;
                }
            }
            "vx" | "vy" | "vz" => {
                let v = a.f64(kw)?;
                let d = (kw.as_bytes()[1] - b'x') as usize;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.v[i][d] = v;
                    count += 1;
                }
            }
            "omega" => {
                let o = a.vec3("omega")?;
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.omega[i] = o;
                    count += 1;
                }
            }
            _ => {
                let name = a.word("property name")?;
                let Some(id) = p.property(name) else {
                    let names: Vec<&str> = p.props.iter().map(|q| q.name.as_str()).collect();
                    return Err(a.error_prev(
                        format!("no per-atom property '{name}'"),
                        Some(suggest(name, &names)),
                    ));
                };
                let width = p.props[id.0].width;
                let mut vals = Vec::new();
                for _ in 0..width {
                    vals.push(a.f64("property value")?);
                }
                for i in (0..p.nlocal()).filter(|&i| sel[i]) {
                    p.props[id.0].get_mut(i).copy_from_slice(&vals);
                    count += 1;
                }
            }
        }
        let count = sim.world_ref(a)?.comm.sum_count(count as u64);
        sim.out.line(&format!("  {count} settings made for {kw}"));
    }
    Ok(())
}

fn velocity(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let bit = sim.group_bit(a, "group ID")?;
    let style = a.keyword("velocity style", &["set", "zero", "ramp", "create"])?;
    enum Op {
        Set([Option<f64>; 3]),
        Zero(bool),
        Ramp(usize, f64, f64, usize, f64, f64),
        Create(f64, u64),
    }
    let opt = |a: &mut Args, what: &str| -> CmdResult<Option<f64>> {
        if a.peek() == Some("NULL") {
            a.seek(a.pos() + 1);
            Ok(None)
        } else {
            Ok(Some(a.f64(what)?))
        }
    };
    let op = match style {
        "set" => Op::Set([opt(a, "vx")?, opt(a, "vy")?, opt(a, "vz")?]),
        "zero" => Op::Zero(a.keyword("zero what", &["linear", "angular"])? == "angular"),
        "ramp" => {
            let vd = a.keyword("velocity component", &["vx", "vy", "vz"])?;
            let (vlo, vhi) = (a.f64("vlo")?, a.f64("vhi")?);
            let d = a.keyword("coordinate", &["x", "y", "z"])?;
            let (clo, chi) = (a.f64("coordinate lo")?, a.f64("coordinate hi")?);
            Op::Ramp(
                (vd.as_bytes()[1] - b'x') as usize,
                vlo,
                vhi,
                (d.as_bytes()[0] - b'x') as usize,
                clo,
                chi,
            )
        }
        _ => Op::Create(a.non_negative("temperature")?, a.count("seed")?),
    };
    let mut sum = false;
    while !a.is_done() {
        match a.keyword(
            "velocity keyword",
            &["sum", "units", "dist", "mom", "rot", "loop"],
        )? {
            "sum" => sum = a.yes_no("sum")?,
            "units" => {
                if a.keyword("units", &["box", "lattice"])? == "lattice" {
                    return Err(a.error_prev(
                        "velocity units lattice is not supported: give box units",
                        None,
                    ));
                }
            }
            "dist" => {
                a.keyword("dist", &["uniform", "gaussian"])?;
            }
            "mom" | "rot" => {
                a.yes_no("mom/rot")?;
            }
            _ => {
                a.keyword("loop", &["all", "local", "geom"])?;
            }
        }
    }
    let w = sim.world_mut(a)?;
    let p = &mut w.particles;
    let sel: Vec<usize> = (0..p.nlocal()).filter(|&i| p.mask[i] & bit != 0).collect();
    match op {
        Op::Set(v) => {
            for &i in &sel {
                for (d, vd) in v.iter().enumerate() {
                    if let Some(x) = *vd {
                        p.v[i][d] = if sum { p.v[i][d] + x } else { x };
                    }
                }
            }
        }
        Op::Zero(angular) => {
            if angular {
                for &i in &sel {
                    p.omega[i] = DVec3::ZERO;
                }
            } else {
                let vcm = group_vcm(&*w.comm, p, &sel);
                for &i in &sel {
                    p.v[i] -= vcm;
                }
            }
        }
        Op::Ramp(vd, vlo, vhi, d, clo, chi) => {
            for &i in &sel {
                let f = ((p.x[i][d] - clo) / (chi - clo)).clamp(0.0, 1.0);
                let v = vlo + f * (vhi - vlo);
                p.v[i][vd] = if sum { p.v[i][vd] + v } else { v };
            }
        }
        Op::Create(t, seed) => {
            use rand::SeedableRng;
            use rand_distr::Distribution;
            let normal = rand_distr::StandardNormal;
            for &i in &sel {
                // One stream per particle tag, so the velocities do not depend on how the
                // particles are stored or split between ranks.
                let mut rng = rand_pcg::Pcg64::seed_from_u64(
                    seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ p.tag[i],
                );
                let s = (1.3806504e-23 * t / p.rmass[i]).sqrt();
                let g: [f64; 3] = [
                    normal.sample(&mut rng),
                    normal.sample(&mut rng),
                    normal.sample(&mut rng),
                ];
                p.v[i] = DVec3::from_array(g) * s;
            }
            let vcm = group_vcm(&*w.comm, p, &sel);
            for &i in &sel {
                p.v[i] -= vcm;
            }
        }
    }
    Ok(())
}

/// Mass-weighted mean velocity of the particles `sel` over all ranks (zero for no mass).
fn group_vcm(comm: &dyn rdem::comm::Comm, p: &rdem::Particles, sel: &[usize]) -> DVec3 {
    let m = comm.sum(sel.iter().map(|&i| p.rmass[i]).sum());
    let mv = sel.iter().map(|&i| p.v[i] * p.rmass[i]).sum::<DVec3>();
    let mut mv = mv.to_array();
    comm.sum_slice(&mut mv);
    if m > 0.0 {
        DVec3::from_array(mv) / m
    } else {
        DVec3::ZERO
    }
}

fn group(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let name = a.word("group ID")?.to_string();
    const STYLES: [&str; 7] = [
        "region",
        "type",
        "id",
        "union",
        "subtract",
        "intersect",
        "delete",
    ];
    let style = a.keyword("group style", &STYLES)?;
    if style == "delete" {
        a.done()?;
        let k = sim
            .groups
            .find(&name)
            .ok_or_else(|| a.error_at(1, format!("no group '{name}'"), None))?;
        if k == 0 {
            return Err(a.error_at(1, "group all cannot be deleted", None));
        }
        if let Some(w) = &mut sim.world {
            for m in &mut w.particles.mask {
                *m &= !(1u32 << k);
            }
        }
        sim.groups.delete(k);
        return Ok(());
    }
    if name == "all" {
        return Err(a.error_at(1, "group all cannot be changed", None));
    }
    let n = sim.world_ref(a)?.particles.nlocal();
    let sel: Vec<bool> = match style {
        "region" => {
            let r = sim.region(a)?;
            a.done()?;
            let p = &sim.world.as_ref().expect("checked").particles;
            (0..n).map(|i| r.contains(p.x[i])).collect()
        }
        "type" | "id" => {
            let mut sel = vec![false; n];
            if a.is_done() {
                return Err(a.error_at(a.pos(), format!("group {style}: missing values"), None));
            }
            while let Some(spec) = a.peek() {
                let (lo, hi) = match spec.split_once(':') {
                    Some((l, h)) => match (l.parse::<u64>(), h.parse::<u64>()) {
                        (Ok(l), Ok(h)) => (l, h),
                        _ => return Err(a.error_at(a.pos(), format!("bad range '{spec}'"), None)),
                    },
                    None => match spec.parse::<u64>() {
                        Ok(v) => (v, v),
                        Err(_) => {
                            return Err(a.error_at(
                                a.pos(),
                                format!("'{spec}' is not a number or range a:b"),
                                None,
                            ))
                        }
                    },
                };
                a.seek(a.pos() + 1);
                let p = &sim.world.as_ref().expect("checked").particles;
                for (i, s) in sel.iter_mut().enumerate() {
                    let v = if style == "type" {
                        p.ty[i] as u64
                    } else {
                        p.tag[i]
                    };
                    if v >= lo && v <= hi {
                        *s = true;
                    }
                }
            }
            sel
        }
        _ => {
            let mut bits = Vec::new();
            while !a.is_done() {
                bits.push(sim.group_bit(a, "group ID")?);
            }
            if bits.is_empty() {
                return Err(a.error_at(
                    a.pos(),
                    format!("group {style}: needs at least one group"),
                    None,
                ));
            }
            let p = &sim.world.as_ref().expect("checked").particles;
            (0..n)
                .map(|i| {
                    let m = p.mask[i];
                    match style {
                        "union" => bits.iter().any(|b| m & b != 0),
                        "intersect" => bits.iter().all(|b| m & b != 0),
                        _ => m & bits[0] != 0 && bits[1..].iter().all(|b| m & b == 0),
                    }
                })
                .collect()
        }
    };
    let k = sim
        .groups
        .find_or_create(&name)
        .map_err(|m| a.error_at(1, m, None))?;
    let w = sim.world.as_mut().expect("checked");
    let mut count = 0;
    for (i, s) in sel.iter().enumerate() {
        if *s {
            w.particles.mask[i] |= 1 << k;
        }
        if w.particles.mask[i] & (1 << k) != 0 {
            count += 1;
        }
    }
    let count = w.comm.sum_count(count);
    sim.out.line(&format!("{count} atoms in group {name}"));
    Ok(())
}

fn neigh_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "neigh_modify: missing keyword",
            Some("delay, every, check".into()),
        ));
    }
    let s = &mut sim.pending.neighbor;
    while !a.is_done() {
        match a.keyword(
            "neigh_modify keyword",
            &[
                "delay",
                "every",
                "check",
                "one",
                "page",
                "binsize",
                "contact_distance_factor",
                "exclude",
                "include",
            ],
        )? {
            "delay" => s.delay = a.u64("delay")?,
            "every" => s.every = a.count("every")?,
            "check" => s.check = a.yes_no("check")?,
            "one" | "page" => {
                a.count("size")?;
            }
            "binsize" | "contact_distance_factor" => {
                a.non_negative("value")?;
            }
            k => return Err(a.error_prev(format!("neigh_modify {k} is not supported yet"), None)),
        }
    }
    s.validate().map_err(|e| a.error_cmd(e.to_string(), None))
}

fn pair_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.word("pair style")?;
    match style {
        "gran" => {}
        "none" => {
            a.done()?;
            sim.world_mut(a)?.pair = None;
            return Ok(());
        }
        s if s.starts_with("gran/") => {
            return Err(a.error_prev(
                format!("pair_style {s} is the pre-3.0 syntax, which rdem does not take"),
                Some(
                    "write 'pair_style gran model hertz tangential history' (LIGGGHTS 3.x syntax)"
                        .into(),
                ),
            ))
        }
        s => {
            return Err(a.error_prev(
                format!("unknown pair style '{s}'"),
                Some(suggest(s, &["gran", "none"])),
            ))
        }
    }
    let mut m: ContactModel = models::parse_types(a)?;
    if !a.is_done() && !models::at_switch(a) {
        return Err(models::unknown(a, a.pos(), &[]));
    }
    models::parse_switches(a, &mut m)?;
    sim.world_mut(a)?.pair = Some(PairGran::new(m));
    sim.pair_coeff_set = false;
    Ok(())
}

fn compute(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("compute ID")?.to_string();
    if sim.compute_index(&id).is_some() {
        return Err(a.error_prev(
            format!("compute ID '{id}' is already used"),
            Some("uncompute it first".into()),
        ));
    }
    let groupbit = sim.group_bit(a, "group ID")?;
    let style_word = a.word("compute style")?;
    let Some(style) = computes::STYLES.iter().copied().find(|s| *s == style_word) else {
        let later = [
            "pair/gran/local",
            "wall/gran/local",
            "bond/counter",
            "com",
            "msd",
            "rdf",
        ];
        if later.contains(&style_word) {
            return Err(a.error_prev(
                format!("compute {style_word} is not supported by this rdem release yet"),
                Some(format!("supported: {}", computes::STYLES.join(", "))),
            ));
        }
        return Err(a.error_prev(
            format!("unknown compute style '{style_word}'"),
            Some(suggest(style_word, &computes::STYLES)),
        ));
    };
    let kind = match style {
        "erotate/sphere" => ComputeKind::ERotateSphere,
        "ke" => ComputeKind::Ke,
        "contact/atom" => ComputeKind::ContactAtom,
        "nbond/atom" => ComputeKind::NBondAtom,
        "bond/counter" => {
            if let Some(other) = sim
                .computes
                .iter()
                .find(|c| matches!(c.kind, ComputeKind::BondCounter(_)))
            {
                return Err(a.error_at(
                    3,
                    format!(
                        "only one compute bond/counter is allowed (compute {} is one)",
                        other.id
                    ),
                    Some(format!("use c_{}[1..6]", other.id)),
                ));
            }
            ComputeKind::BondCounter(Default::default())
        }
        "stress/atom" => {
            // No keyword: every term; otherwise only the listed ones (`virial`: all but ke).
            let (mut ke, mut pair, mut any) = (false, false, false);
            while !a.is_done() {
                match a.keyword("stress/atom keyword", &computes::STRESS_KEYWORDS)? {
                    "ke" => ke = true,
                    "pair" | "virial" => pair = true,
                    _ => {}
                }
                any = true;
            }
            if !any {
                (ke, pair) = (true, true);
            }
            ComputeKind::StressAtom { ke, pair }
        }
        "property/atom" => {
            let mut f = Vec::new();
            while let Some(w) = a.peek() {
                if !crate::atom_fields::is_field(w) {
                    return Err(a.error_at(
                        a.pos(),
                        format!("unknown per-atom property '{w}'"),
                        Some(suggest(w, &crate::atom_fields::NAMES)),
                    ));
                }
                f.push(w.to_string());
                a.seek(a.pos() + 1);
            }
            if f.is_empty() {
                return Err(a.error_at(
                    a.pos(),
                    "compute property/atom needs at least one property",
                    Some(format!(
                        "e.g. radius; valid: {}",
                        crate::atom_fields::NAMES.join(" ")
                    )),
                ));
            }
            ComputeKind::PropertyAtom(f)
        }
        _ => {
            let mode = a
                .keyword("reduce mode", &computes::REDUCE_MODES)?
                .to_string();
            let mut inputs = Vec::new();
            while let Some(w) = a.peek() {
                if w == "replace" {
                    return Err(a.error_at(
                        a.pos(),
                        "compute reduce replace is not supported",
                        None,
                    ));
                }
                let input = if crate::atom_fields::is_field(w) {
                    ReduceInput::Field(w.to_string())
                } else {
                    match thermo::split_reference(w) {
                        Some(('c', cid, col)) => match sim.computes.iter().find(|c| c.id == cid) {
                            Some(c) if c.is_peratom() => ReduceInput::Compute(cid.to_string(), col),
                            Some(_) => {
                                return Err(a.error_at(
                                    a.pos(),
                                    format!("compute {cid} is not per-atom"),
                                    None,
                                ))
                            }
                            None => {
                                let ids: Vec<&str> =
                                    sim.computes.iter().map(|c| c.id.as_str()).collect();
                                return Err(a.error_at(
                                    a.pos(),
                                    format!("no compute '{cid}'"),
                                    Some(id_help("compute", cid, &ids)),
                                ));
                            }
                        },
                        Some(('v', v, None)) => ReduceInput::Variable(v.to_string()),
                        _ => {
                            return Err(a.error_at(
                                a.pos(),
                                format!("unknown reduce input '{w}'"),
                                Some(format!(
                                    "a per-atom property ({}), c_ID, c_ID[N] or v_name",
                                    crate::atom_fields::NAMES.join(" ")
                                )),
                            ))
                        }
                    }
                };
                inputs.push(input);
                a.seek(a.pos() + 1);
            }
            if inputs.is_empty() {
                return Err(a.error_at(a.pos(), "compute reduce needs at least one input", None));
            }
            ComputeKind::Reduce { mode, inputs }
        }
    };
    if !matches!(
        kind,
        ComputeKind::PropertyAtom(_) | ComputeKind::Reduce { .. }
    ) {
        a.done()?;
    }
    sim.computes.push(Compute { id, groupbit, kind });
    Ok(())
}

fn thermo_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("thermo style", &["custom", "one", "multi"])?;
    let cols: Vec<String> = match style {
        "custom" => {
            let mut c = Vec::new();
            while let Some(w) = a.peek() {
                if !thermo::valid_column(w) {
                    return Err(a.error_at(
                        a.pos(),
                        format!("unknown thermo keyword '{w}'"),
                        Some(suggest(w, &thermo::KEYWORDS)),
                    ));
                }
                if let Some((kind, id, _)) = thermo::split_reference(w) {
                    let ok = match kind {
                        'c' => sim.compute_index(id).is_some(),
                        'f' => sim.fix_index(id).is_some(),
                        _ => true,
                    };
                    if !ok {
                        let what = if kind == 'c' { "compute" } else { "fix" };
                        let ids: Vec<&str> = if kind == 'c' {
                            sim.computes.iter().map(|c| c.id.as_str()).collect()
                        } else {
                            sim.fixes.iter().map(|f| f.id.as_str()).collect()
                        };
                        return Err(a.error_at(
                            a.pos(),
                            format!("'{w}': no {what} '{id}'"),
                            Some(id_help(what, id, &ids)),
                        ));
                    }
                }
                c.push(w.to_string());
                a.seek(a.pos() + 1);
            }
            if c.is_empty() {
                return Err(a.error_at(
                    a.pos(),
                    "thermo_style custom needs at least one keyword",
                    Some(format!(
                        "e.g. step atoms ke; valid: {}",
                        thermo::KEYWORDS.join(" ")
                    )),
                ));
            }
            c
        }
        "one" => ["step", "atoms", "ke", "cpu"].map(String::from).to_vec(),
        _ => return Err(a.error_prev("thermo_style multi is not supported; use custom", None)),
    };
    if sim.thermo.norm
        || !sim.thermo.col_format.is_empty()
        || sim.thermo.float_format.is_some()
        || sim.thermo.int_format.is_some()
    {
        sim.out
            .warning("New thermo_style command, previous thermo_modify settings will be lost");
    }
    sim.thermo.columns = cols;
    sim.thermo.norm = false;
    sim.thermo.col_format.clear();
    sim.thermo.int_format = None;
    sim.thermo.float_format = None;
    sim.thermo.line_format = None;
    Ok(())
}

fn thermo_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "thermo_modify: missing keyword",
            Some("lost, norm, format, flush".into()),
        ));
    }
    while !a.is_done() {
        match a.keyword(
            "thermo_modify keyword",
            &["lost", "norm", "format", "flush", "every"],
        )? {
            "lost" => {
                let p = match a.keyword("lost setting", &["error", "warn", "ignore"])? {
                    "error" => LostPolicy::Error,
                    "warn" => LostPolicy::Warn,
                    _ => LostPolicy::Ignore,
                };
                sim.pending.lost = p;
                if let Some(w) = &mut sim.world {
                    w.lost_policy = p;
                }
            }
            "norm" => sim.thermo.norm = a.yes_no("norm")?,
            "flush" => {
                a.yes_no("flush")?;
            }
            "every" => sim.thermo.every = a.u64("every")?,
            _ => {
                let which = a.word("format target (int, float, line or a column number)")?;
                let f = a.word("format string")?.to_string();
                let check = |s: &str| rdem_io::Printf::parse(s).map(|_| ());
                match which {
                    "int" => {
                        check(&f).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        sim.thermo.int_format = Some(f);
                    }
                    "float" => {
                        check(&f).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        sim.thermo.float_format = Some(f);
                    }
                    "line" => {
                        let parts: Vec<String> = f.split_whitespace().map(String::from).collect();
                        for p in &parts {
                            check(p).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        }
                        sim.thermo.line_format = Some(parts);
                    }
                    n => {
                        let k: usize = n
                            .parse()
                            .ok()
                            .filter(|&k| k >= 1 && k <= sim.thermo.columns.len())
                            .ok_or_else(|| {
                                a.error_at(
                                    a.pos() - 2,
                                    format!(
                                        "'{n}' is not int, float, line or a column number 1..{}",
                                        sim.thermo.columns.len()
                                    ),
                                    None,
                                )
                            })?;
                        check(&f).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        sim.thermo.col_format.push((k, f));
                    }
                }
            }
        }
    }
    Ok(())
}

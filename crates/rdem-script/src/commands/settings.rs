//! The commands that set the simulation up before (or around) the box: atom style and
//! map, boundary, units, processor grid, neighbor settings, time step.

use glam::DVec3;
use rdem::Boundary;

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;
use crate::units::Units;

pub(super) fn atom_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let s = a.word("atom style")?;
    if sim.world.is_some() {
        return Err(a.error_cmd("atom_style after the simulation box is defined", None));
    }
    sim.setup.sph = s == "sph";
    sim.setup.bond_gran = None;
    sim.setup.data_layout = Some(rdem_io::AtomLayout::Granular);
    match s {
        // `granular/omp`: LIGGGHTS-PFM's OpenMP variant of `granular`.
        "granular" | "granular/omp" | "sphere" | "sph" => a.done(),
        "bond/gran" => {
            sim.setup.data_layout = None;
            bond_gran_style(sim, a)
        }
        "hybrid" => {
            // `hybrid granular bond/gran ...` (LIGGGHTS_Flexible_Fibers, LIGGGHTS-PFM).
            let mut spheres = false;
            let mut subs = Vec::new();
            while !a.is_done() {
                match a.keyword(
                    "atom_style hybrid sub-style",
                    &["granular", "sphere", "bond/gran"],
                )? {
                    "bond/gran" => {
                        bond_gran_style(sim, a)?;
                        subs.push(rdem_io::SubStyle::BondGran);
                    }
                    s => {
                        if spheres {
                            return Err(a.error_prev(
                                format!("atom_style hybrid: a second sphere sub-style '{s}'"),
                                Some("granular and sphere are one style; name it once".into()),
                            ));
                        }
                        spheres = true;
                        subs.push(rdem_io::SubStyle::Sphere);
                    }
                }
            }
            sim.setup.data_layout = Some(rdem_io::AtomLayout::Hybrid(subs));
            if !spheres || sim.setup.bond_gran.is_none() {
                return Err(a.error_cmd(
                    "atom_style hybrid: rdem supports the hybrid of granular (or sphere) and bond/gran",
                    Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M".into()),
                ));
            }
            Ok(())
        }
        _ => {
            let later = ["superquadric", "granular/multisphere"];
            let help = if later.contains(&s) {
                format!("atom_style {s} is not supported by this rdem release yet; use granular")
            } else {
                suggest(s, &["granular", "sphere", "sph", "bond/gran", "hybrid"])
            };
            Err(a.error_prev(format!("unsupported atom style '{s}'"), Some(help)))
        }
    }
}

/// The arguments of the `bond/gran` atom style: `n_bondtypes N bonds_per_atom M
/// [disableNormalContact 0|1]`.
fn bond_gran_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let (mut ntypes, mut per_atom, mut disable) = (None, None, false);
    while let Some(w) = a.peek() {
        match w {
            "n_bondtypes" => {
                a.word("keyword")?;
                ntypes = Some(a.count("number of bond types")? as usize);
            }
            "bonds_per_atom" => {
                a.word("keyword")?;
                per_atom = Some(a.count("bonds per atom")? as usize);
            }
            "disableNormalContact" => {
                a.word("keyword")?;
                let k = a.pos();
                disable = match a.u64("disableNormalContact (0 or 1)")? {
                    0 => false,
                    1 => true,
                    v => {
                        return Err(a.error_at(
                            k,
                            format!("disableNormalContact {v}: 0 or 1"),
                            Some("1: bonded spheres have no pair contact".into()),
                        ))
                    }
                };
            }
            _ => break,
        }
    }
    let (Some(ntypes), Some(per_atom)) = (ntypes, per_atom) else {
        return Err(a.error_cmd(
            "atom style bond/gran needs n_bondtypes and bonds_per_atom",
            Some("bond/gran n_bondtypes N bonds_per_atom M [disableNormalContact 0]".into()),
        ));
    };
    rdem::bond_gran::GranBonds::new(ntypes, per_atom)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    sim.setup.bond_gran = Some((ntypes, per_atom, disable));
    Ok(())
}

pub(super) fn atom_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
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
                sim.set_sort(rdem::SortSettings {
                    every,
                    binsize: bin,
                });
            }
        }
    }
    Ok(())
}

pub(super) fn boundary(sim: &mut Sim, a: &mut Args) -> CmdResult {
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
    sim.setup.boundary = b;
    Ok(())
}

/// `units si|cgs|micro` (before the box, as LIGGGHTS): sets the unit system and, as
/// LIGGGHTS 3.8 does, the default time step and neighbor skin of that system (see
/// [`crate::units`]).
pub(super) fn units(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if sim.world.is_some() {
        return Err(a.error_cmd(
            "units after the simulation box is defined",
            Some("give units before create_box or read_data".into()),
        ));
    }
    let u = a.word("unit style")?;
    let Some(units) = Units::from_name(u) else {
        let help = format!("rdem supports {}", crate::diagnostic::one_of(&Units::NAMES));
        let msg = if ["lj", "real", "metal", "electron", "nano"].contains(&u) {
            format!("units {u} is not supported by rdem yet")
        } else {
            format!("unknown unit style '{u}'")
        };
        return Err(a.error_prev(msg, Some(help)));
    };
    a.done()?;
    sim.setup.units = units;
    sim.setup.dt = units.default_timestep();
    sim.setup.neighbor.skin = units.default_skin();
    Ok(())
}

/// `dimension 2|3` (before the box, as LIGGGHTS). In 2d the box must be periodic in z
/// (checked when it is made), z velocities must stay 0, the temperature counts 2 degrees
/// of freedom per particle and `fix enforce2d` keeps the particles in their plane.
pub(super) fn dimension(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if sim.world.is_some() {
        return Err(a.error_cmd(
            "dimension after the simulation box is defined",
            Some("give dimension before create_box or read_data".into()),
        ));
    }
    let d = match a.word("dimension")? {
        "3" => 3,
        "2" => 2,
        d => {
            return Err(a.error_prev(
                format!("dimension must be 2 or 3, not '{d}'"),
                Some("'dimension 3' (the default) or 'dimension 2'".into()),
            ))
        }
    };
    a.done()?;
    sim.setup.dimension = d;
    Ok(())
}

/// In 2d, LIGGGHTS 3.8 gives a particle of density ρ the mass of a disc, π r² ρ (density
/// is mass per area, "ρ σ^dim" in the `units` manual; checked there: after
/// `set atom 1 diameter 0.01 density 2500` the mass is 0.196349540849362, and a new atom
/// of diameter 1 and density 1 has 0.785398163397448), while the moment of inertia stays
/// a sphere's, 2/5 m r². The engine makes sphere masses: this sets the disc masses of
/// the owned particles after the commands that make particles or change their size or
/// density (`create_atoms`, `read_data`, `set`). Nothing in 3d.
pub(crate) fn disc_masses(sim: &mut Sim) {
    if sim.setup.sph {
        crate::sph::apply_type_masses(sim);
        return;
    }
    if sim.setup.dimension != 2 {
        return;
    }
    if let Some(w) = &mut sim.world {
        let p = &mut w.particles;
        for i in 0..p.nlocal() {
            p.rmass[i] = std::f64::consts::PI * p.radius[i] * p.radius[i] * p.density[i];
        }
    }
}

/// The boundaries the engine's box gets, after LIGGGHTS 3.8's check of a 2d box: it must
/// be periodic in z (its error "Cannot run 2d simulation with nonperiodic Z dimension";
/// errors point at word `k`). LAMMPS makes no ghost images along z in 2d, so the z slab
/// may be thinner than the contact distance; rdem's engine gives the 2d box fixed z faces,
/// which make no images either (the particles, kept at their z by `fix enforce2d`, never
/// reach them; one that leaves the slab without enforce2d is lost instead of wrapped).
pub(super) fn box_boundary(sim: &Sim, a: &Args, k: usize) -> CmdResult<[[Boundary; 2]; 3]> {
    let mut b = sim.setup.boundary;
    if sim.setup.dimension == 2 {
        if b[2][0] != Boundary::Periodic {
            return Err(a.error_at(
                k,
                "a 2d simulation needs a periodic z boundary",
                Some("dimension 2: give 'boundary x y p'".into()),
            ));
        }
        b[2] = [Boundary::Fixed; 2];
    }
    Ok(b)
}

/// `clear`: everything back to the state after start-up (box, particles, fixes,
/// computes, groups, regions, dumps, thermo settings, units, time step) except what
/// LIGGGHTS 3.8 keeps: the variables, the screen and log, and the `thermo_log` file
/// (checked there: after `clear`, `print ${a}` shows a variable defined before, and the
/// next run's thermo lines go on into the same thermo log).
pub(super) fn clear(sim: &mut Sim, a: &mut Args) -> CmdResult {
    a.done()?;
    let out = std::mem::replace(&mut sim.outputs.out, crate::output::Output::captured());
    let mut fresh = Sim::new(out);
    fresh.outputs.progress = sim.outputs.progress.take();
    fresh.outputs.step_hook = sim.outputs.step_hook.take();
    fresh.outputs.warned = std::mem::take(&mut sim.outputs.warned);
    let s = &mut sim.script;
    let f = &mut fresh.script;
    std::mem::swap(&mut f.vars, &mut s.vars);
    f.here = s.here.take();
    f.check = s.check;
    f.threads = s.threads;
    f.started = s.started;
    *sim = fresh;
    Ok(())
}

/// `newton on|off [on|off]` (accepted: rdem computes each pair once).
pub(super) fn newton(_sim: &mut Sim, a: &mut Args) -> CmdResult {
    a.keyword("newton setting", &["on", "off"])?;
    if !a.is_done() {
        a.keyword("newton bond setting", &["on", "off"])?;
    }
    a.done()?;
    Ok(())
}

/// `communicate single|multi [vel yes|no] [cutoff C] [group G]` (accepted).
pub(super) fn communicate(sim: &mut Sim, a: &mut Args) -> CmdResult {
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
    Ok(())
}

/// `grid twolevel Nc Cx Cy Cz` (after the style word): the cores of a node and their
/// grid, each a count or `*`. They only say how ranks group onto nodes, which changes the
/// speed, not the outcome: rdem reads them, checks them as LAMMPS does where that needs
/// no machine (the core grid must fit Nc), and lays the ranks out as `onelevel`; a
/// count of processes that is not a multiple of Nc is a warning (LAMMPS stops).
fn twolevel(a: &mut Args) -> CmdResult {
    let nc = a.count("cores per node")? as usize;
    let mut grid = [0usize; 3];
    for (k, d) in ["Cx", "Cy", "Cz"].into_iter().enumerate() {
        if a.peek() == Some("*") {
            a.word(d)?;
        } else {
            grid[k] = a.count(d)? as usize;
        }
    }
    let given: usize = grid.iter().filter(|&&c| c != 0).product();
    let full = grid.iter().all(|&c| c != 0);
    if (full && given != nc) || (!full && nc % given != 0) {
        return Err(a.error_prev(
            format!(
                "processors grid twolevel: the core grid {} does not fit {nc} cores per node",
                grid.map(|c| if c == 0 {
                    "*".to_string()
                } else {
                    c.to_string()
                })
                .join(" x ")
            ),
            Some("Cx x Cy x Cz must be Nc (or divide it where one is '*')".into()),
        ));
    }
    let nprocs = rdem::comm::process_rank_size().1;
    if nprocs % nc != 0 {
        a.warn_at(
            0,
            &format!(
                "processors grid twolevel: {nprocs} {} not a multiple of {nc} cores per node (LAMMPS stops here): rdem lays the ranks out as grid onelevel",
                if nprocs == 1 { "process is" } else { "processes are" }
            ),
        );
    }
    Ok(())
}

/// `processors Px Py Pz [grid onelevel] [map cart|cart/reorder|xyz]`: the MPI processor
/// grid (each a count or `*`). A grid whose product does not fit the number of processes
/// stops LIGGGHTS; rdem warns and keeps the counts that still fit (in x, y, z order),
/// choosing the others, so a script written for 8 ranks runs on 1 (see [`fit_grid`]).
pub(super) fn processors(sim: &mut Sim, a: &mut Args) -> CmdResult {
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
    while !a.is_done() {
        match a.keyword("processors keyword", &["grid", "map", "part", "file"])? {
            "grid" => {
                let g = a.keyword("grid style", &["onelevel", "twolevel", "numa", "custom"])?;
                match g {
                    "twolevel" => twolevel(a)?,
                    "custom" => {
                        return Err(a.error_prev(
                            "processors grid custom is not supported yet",
                            Some("use 'grid onelevel' (the default), 'twolevel' or 'numa', or leave the keyword out".into()),
                        ))
                    }
                    _ => {}
                }
            }
            "map" => {
                let m = a.keyword(
                    "map style",
                    &["cart", "cart/reorder", "xyz", "xzy", "yxz", "yzx", "zxy", "zyx"],
                )?;
                if !matches!(m, "cart" | "cart/reorder" | "xyz") {
                    return Err(a.error_prev(
                        format!("processors map {m} is not supported yet"),
                        Some("rdem places ranks in xyz order (x fastest); 'map xyz', 'cart' and 'cart/reorder' are accepted".into()),
                    ));
                }
            }
            k => {
                return Err(a.error_prev(
                    format!("processors {k} is not supported yet"),
                    Some("rdem runs one partition and writes no grid file; give 'processors Px Py Pz' with grid/map only".into()),
                ))
            }
        }
    }
    let nprocs = rdem::comm::process_rank_size().1;
    let kept = fit_grid(nprocs, procs);
    if kept != procs {
        let show = |g: [usize; 3]| {
            g.map(|n| {
                if n == 0 {
                    "*".to_string()
                } else {
                    n.to_string()
                }
            })
            .join(" x ")
        };
        let used = if nprocs == 1 {
            "1 x 1 x 1".to_string()
        } else if kept.iter().all(|&n| n != 0) {
            show(kept)
        } else {
            format!("{} (the * counts chosen when the box is made)", show(kept))
        };
        a.warn_at(
            0,
            &format!(
                "processors {} does not fit the {nprocs} process{} of this run (LIGGGHTS stops here): rdem uses {used}",
                show(procs),
                if nprocs == 1 { "" } else { "es" }
            ),
        );
    }
    sim.setup.procs = kept;
    Ok(())
}

/// The processor grid constraint rdem uses for the counts asked for (`0` = free) on
/// `nprocs` processes: the counts as given if a grid fits them, else each given count
/// in x, y, z order is kept while a grid with `nprocs` processes still fits it, and the
/// others are freed.
pub(crate) fn fit_grid(nprocs: usize, asked: [usize; 3]) -> [usize; 3] {
    let fits = |g: [usize; 3]| rdem::domain::least_surface_grid(nprocs, DVec3::ONE, g).is_some();
    if fits(asked) {
        return asked;
    }
    let mut kept = [0; 3];
    for k in 0..3 {
        if asked[k] == 0 {
            continue;
        }
        let mut g = kept;
        g[k] = asked[k];
        if fits(g) {
            kept = g;
        }
    }
    kept
}

/// `hard_particles yes|no`, `soft_particles yes|no` (accepted).
pub(super) fn hard_particles(_sim: &mut Sim, a: &mut Args) -> CmdResult {
    a.yes_no(a.name())?;
    a.done()?;
    Ok(())
}

/// `neighbor skin bin|nsq`.
pub(super) fn neighbor(sim: &mut Sim, a: &mut Args) -> CmdResult {
    // LIGGGHTS-PFM's coarse graining scales the skin too.
    let skin = a.non_negative("skin distance")? * sim.setup.coarse_graining.factor;
    a.keyword("neighbor style", &["bin", "nsq"])?;
    a.done()?;
    sim.setup.skin_given = true;
    let mut s = sim.neighbor_settings();
    s.skin = skin;
    sim.set_neighbor(s);
    Ok(())
}

pub(super) fn neigh_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "neigh_modify: missing keyword",
            Some("delay, every, check".into()),
        ));
    }
    // Read everything first: a wrong word changes nothing.
    let mut s = sim.neighbor_settings();
    let mut exclude = sim.exclusions().clone();
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
            "binsize" => {
                a.non_negative("value")?;
            }
            "contact_distance_factor" => {
                let f = a.f64("contact distance factor")?;
                if f.is_nan() || f < 1.0 {
                    return Err(a.error_prev(
                        format!("contact_distance_factor must be >= 1, not {f}"),
                        Some("LIGGGHTS 3.8 refuses a factor below 1 too".into()),
                    ));
                }
                s.contact_distance_factor = f;
            }
            "exclude" => exclude_pairs(sim, a, &mut exclude)?,
            k => return Err(a.error_prev(format!("neigh_modify {k} is not supported yet"), None)),
        }
    }
    s.validate().map_err(|e| a.error_cmd(e.to_string(), None))?;
    sim.set_neighbor(s);
    sim.set_exclusions(exclude);
    Ok(())
}

/// `exclude type M N | group G1 G2 | molecule G | none` (`molecule` needs the molecule
/// IDs of atom style bond/gran: granular atoms have none, an error).
fn exclude_pairs(sim: &Sim, a: &mut Args, ex: &mut rdem::Exclusions) -> CmdResult {
    match a.keyword("exclude style", &["type", "group", "none", "molecule"])? {
        "type" => {
            let mut t = [0u32; 2];
            for (k, tk) in t.iter_mut().enumerate() {
                let v = a.count(["type M", "type N"][k])?;
                let n = sim.ntypes();
                if sim.world.is_some() && v as usize > n {
                    return Err(a.error_prev(
                        format!("atom type {v} is out of range: the box has {n} type(s)"),
                        None,
                    ));
                }
                *tk = v as u32;
            }
            ex.types.push((t[0], t[1]));
        }
        "group" => {
            let g1 = sim.group_bit(a, "group ID")?;
            let g2 = sim.group_bit(a, "group ID")?;
            ex.groups.push((g1, g2));
        }
        "none" => *ex = rdem::Exclusions::default(),
        _ => {
            if sim.setup.bond_gran.is_none() {
                return Err(a.error_prev(
                    "neigh_modify exclude molecule needs molecule IDs, which granular atoms do not have",
                    Some("exclude pairs by 'type M N' or 'group G1 G2', or use atom_style hybrid granular bond/gran ...".into()),
                ));
            }
            ex.molecule_groups.push(sim.group_bit(a, "group ID")?);
        }
    }
    Ok(())
}

/// `timestep dt`.
pub(super) fn timestep(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let dt = a.positive("timestep")?;
    a.done()?;
    sim.set_timestep(dt).map_err(|m| a.error_at(1, m, None))
}

/// `modify_timing on|off|verbose` (LIGGGHTS 3.8): each fix's time, printed after every
/// run (`verbose`: on each MPI rank too). While it is on, the post-force fixes act one
/// at a time instead of in one fused pass over the particles, each timed (the same
/// forces; the run is a little slower, as in LIGGGHTS, whose timers cost too).
pub(super) fn modify_timing(sim: &mut Sim, a: &mut Args) -> CmdResult {
    sim.script.modify_timing = match a.keyword("modify_timing", &["on", "off", "verbose"])? {
        "on" => crate::sim::ModifyTiming::On,
        "verbose" => crate::sim::ModifyTiming::Verbose,
        _ => crate::sim::ModifyTiming::Off,
    };
    a.done()
}

/// `reset_timestep N`.
pub(super) fn reset_timestep(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let n = a.u64("timestep")?;
    a.done()?;
    sim.world_mut(a)?.step = n;
    Ok(())
}

/// `package omp N|* [force/neigh|force] [thread-binding] [verbose]` (LIGGGHTS-PFM's hybrid
/// parallelization, which its `/omp` styles need): rdem runs every style on its own
/// threads (`--threads`, `RDEM_THREADS`), whose count does not change the results; a
/// count N other than rdem's is a warning saying so. Other packages (`gpu`, `cuda`,
/// `kokkos`) are LAMMPS accelerators that granular LIGGGHTS has not: an error.
pub(super) fn package(sim: &mut Sim, a: &mut Args) -> CmdResult {
    a.keyword("package", &["omp"])?;
    let at = a.pos();
    // `*`: the OpenMP default, which rdem's own count stands for.
    let n = if a.peek() == Some("*") {
        a.seek(at + 1);
        None
    } else {
        Some(a.u64("number of OpenMP threads (or *)")?)
    };
    while !a.is_done() {
        a.keyword(
            "package omp keyword",
            &["force/neigh", "force", "thread-binding", "verbose"],
        )?;
    }
    let threads = sim.script.threads;
    if let Some(n) = n.filter(|&n| n as usize != threads) {
        a.warn_at(
            at,
            &format!(
                "package omp {n}: rdem runs on its {threads} thread(s) (set with --threads or RDEM_THREADS); the count does not change the results"
            ),
        );
    }
    Ok(())
}

/// `partitioner_style zoltan [KEY VALUE ...]` (LIGGGHTS-PFM): how the fork shares the
/// particles of a process between its OpenMP threads (the Zoltan library's options).
/// rdem shares the work between its threads itself, so the options have nothing to set:
/// a warning says so once.
pub(super) fn partitioner_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    a.keyword("partitioner style", &["zoltan"])?;
    while !a.is_done() {
        a.word("Zoltan option name")?;
        if a.is_done() {
            return Err(a.error_prev(
                "partitioner_style zoltan: an option without its value",
                Some("Zoltan options come in pairs, e.g. RCB_REUSE 1".into()),
            ));
        }
        a.word("Zoltan option value")?;
    }
    sim.outputs.warn_once(
        "partitioner_style zoltan: rdem shares the particles between its threads itself; the Zoltan options are not used",
    );
    Ok(())
}

#[cfg(test)]
mod grid_tests {
    use super::fit_grid;

    #[test]
    fn counts_that_fit_are_kept_the_others_freed() {
        assert_eq!(fit_grid(8, [2, 2, 2]), [2, 2, 2]);
        assert_eq!(fit_grid(1, [2, 2, 2]), [0, 0, 0]);
        assert_eq!(fit_grid(4, [2, 2, 2]), [2, 2, 0]);
        assert_eq!(fit_grid(4, [3, 2, 0]), [0, 2, 0]);
        assert_eq!(fit_grid(6, [4, 3, 1]), [0, 3, 1]);
        assert_eq!(fit_grid(2, [1, 1, 4]), [1, 1, 0]);
        assert_eq!(fit_grid(1, [1, 1, 1]), [1, 1, 1]);
    }
}

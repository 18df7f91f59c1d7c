//! The commands that set the simulation up before (or around) the box: atom style and
//! map, boundary, units, processor grid, neighbor settings, time step.

use glam::DVec3;
use rdem::Boundary;

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

pub(super) fn atom_style(_sim: &mut Sim, a: &mut Args) -> CmdResult {
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
                sim.setup.sort = rdem::SortSettings {
                    every,
                    binsize: bin,
                };
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

/// `units si`.
pub(super) fn units(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let u = a.word("unit style")?;
    if u != "si" {
        return Err(a.error_prev(
            format!("units {u} is not supported: rdem works in SI units"),
            Some("use 'units si' (metres, kilograms, seconds)".into()),
        ));
    }
    a.done()?;
    sim.script.units_set = true;
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

/// `processors Px Py Pz`: the MPI processor grid (each a count or `*`).
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
    sim.setup.procs = procs;
    Ok(())
}

/// `hard_particles yes|no`, `soft_particles yes|no` (accepted).
pub(super) fn hard_particles(_sim: &mut Sim, a: &mut Args) -> CmdResult {
    a.yes_no(a.name())?;
    a.done()?;
    Ok(())
}

/// `neighbor skin bin|nsq`.
pub(super) fn neighbor(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let skin = a.non_negative("skin distance")?;
    a.keyword("neighbor style", &["bin", "nsq"])?;
    a.done()?;
    sim.setup.neighbor.skin = skin;
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
    let s = &mut sim.setup.neighbor;
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

/// `timestep dt`.
pub(super) fn timestep(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let dt = a.positive("timestep")?;
    a.done()?;
    sim.set_timestep(dt).map_err(|m| a.error_at(1, m, None))
}

/// `reset_timestep N`.
pub(super) fn reset_timestep(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let n = a.u64("timestep")?;
    a.done()?;
    sim.world_mut(a)?.step = n;
    Ok(())
}

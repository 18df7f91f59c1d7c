//! `fix ID group bond/create/gran Nevery itype jtype cutoff btype newperts`
//! (LIGGGHTS_Flexible_Fibers): every `Nevery` steps, bonds of type `btype` between the
//! spheres of the group of types `itype` and `jtype` whose centres are closer than
//! `cutoff` (r² < cutoff², strictly) and not bonded yet. A sphere takes at most
//! `newperts` new bonds at one step and holds at most the atom style's
//! `bonds_per_atom`; the candidate pairs are taken in the order of their tags (lower tag,
//! then higher), each where both spheres have room. That order gives the fork's bonds:
//! on a 3 × 3 square of spheres with `newperts` 1, 2 and 3 it makes the same 4, 8 and 11
//! bonds at the first step. `doNorm yes` makes the cutoff relative: a pair bonds when
//! r²/(R_a + R_b)² < cutoff² (the fork's test). `iparam maxbond newtype` (spheres of
//! `itype`) and `jparam maxbond newtype` (the others): a sphere holding `maxbond` bonds
//! of type `btype` takes no more (0: no limit), and turns into atom type `newtype` when
//! a new bond brings it to `maxbond`; with itype = jtype both must agree. The count is
//! of the bonds the sphere holds at the step (the fork's, from the run's start on, keeps
//! bonds broken during the run). `prob fraction seed`: each sphere draws u in [0, 1)
//! per creation step and a pair bonds only when (u_a + u_b)/2 < fraction, as the fork
//! decides; the draws come from a hash of (seed, tag, step), the same on any number of
//! ranks and threads (the fork's depend on the rank), so the same fraction bonds but
//! not the same pairs. `fix_modify ID every N` changes `Nevery`; `every 0` stops
//! the creation. Bonds are made after the neighbor decision of a step, before its
//! forces, never at a run's set-up (the fork's "Created N bonds at timestep 1" of a
//! `run 1`); their length L₀ is the one of that step.
//!
//! The creation is part of the engine's step ([`rdem::bond_gran::GranBonds::create`]);
//! this entry holds its ID and prints the fork's line for each step that made bonds.

use crate::error::Error;

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "bond/create/gran",
    parse,
    Stages::END_OF_STEP,
    "`Nevery itype jtype cutoff btype newperts [doNorm yes|no] [iparam maxbond newtype] [jparam maxbond newtype] [prob fraction seed]` (LIGGGHTS_Flexible_Fibers): bonds between spheres closer than cutoff (`doNorm yes`: closer than cutoff × (R₁ + R₂)); `iparam`/`jparam` limit the bonds per sphere and change its type at the limit; `prob` bonds a pair when the mean of two per-sphere draws is below fraction (rdem's own random numbers); `fix_modify ID every N` (0 stops it)",
);

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let every = a.u64("Nevery")?;
    let ntypes = sim.ntypes() as u64;
    let itype = atom_type(a, "itype", ntypes)?;
    let jtype = atom_type(a, "jtype", ntypes)?;
    let cutoff = a.positive("cutoff")?;
    let bk = a.pos();
    let btype = a.count("bond type")? as u32;
    let per_step = a.count("newperts (new bonds per sphere and step)")? as usize;
    let mut creator = rdem::bond_gran::Creator::new(
        &head.id,
        head.groupbit,
        every,
        itype,
        jtype,
        cutoff,
        btype,
        per_step,
    );
    while !a.is_done() {
        match a.keyword("keyword", &["doNorm", "iparam", "jparam", "prob"])? {
            "doNorm" => creator.relative = a.yes_no("doNorm")?,
            "prob" => {
                let k = a.pos();
                let f = a.f64("fraction")?;
                if !(0.0..=1.0).contains(&f) {
                    return Err(a.error_at(k, format!("fraction {f} is not within [0, 1]"), None));
                }
                creator.fraction = f;
                creator.seed = a.count("seed")?;
            }
            w => {
                let max = a.u64("maxbond (0: no limit)")? as usize;
                let new_type = atom_type(a, "newtype", ntypes)?;
                creator.limits[usize::from(w == "jparam")] =
                    rdem::bond_gran::Limit { max, new_type };
            }
        }
    }
    if itype == jtype && creator.limits[0] != creator.limits[1] {
        return Err(a.error_cmd(
            "inconsistent iparam and jparam: with itype = jtype they must be equal",
            Some("give both the same maxbond and newtype, or one of them only".into()),
        ));
    }
    let w = sim.world_ref(a)?;
    let Some(bonds) = &w.bonds else {
        return Err(a.error_cmd(
            "fix bond/create/gran needs an atom style with bonds",
            Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M".into()),
        ));
    };
    if btype as usize > bonds.ntypes {
        return Err(a.error_at(
            bk,
            format!(
                "bond type {btype} > the atom style's n_bondtypes {}",
                bonds.ntypes
            ),
            None,
        ));
    }
    Ok(Box::new(BondCreate(Some(creator))))
}

/// An atom type within the box's `ntypes`.
fn atom_type(a: &mut Args, what: &str, ntypes: u64) -> CmdResult<u32> {
    let k = a.pos();
    let t = a.count(what)?;
    if t > ntypes {
        return Err(a.error_at(
            k,
            format!("{what} {t} > the box's {ntypes} atom type(s)"),
            None,
        ));
    }
    Ok(t as u32)
}

/// The script's entry: the creator, until `install` hands it to the world's bonds.
struct BondCreate(Option<rdem::bond_gran::Creator>);

/// This fix's creator in the world.
fn creator<'w>(w: &'w mut rdem::World, head: &FixHead) -> Option<&'w mut rdem::bond_gran::Creator> {
    w.bonds
        .as_mut()
        .and_then(|b| b.creators.iter_mut().find(|c| c.id == head.id))
}

impl ScriptFix for BondCreate {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        let w = sim.world_mut(a)?;
        let bonds = w.bonds.as_mut().expect("checked by the parser");
        let c = self.0.take().expect("installed once");
        bonds.creators.retain(|o| o.id != head.id);
        bonds.creators.push(c);
        Ok(())
    }

    fn modify(
        &mut self,
        sim: &mut Sim,
        head: &FixHead,
        keyword: &str,
        a: &mut Args,
    ) -> CmdResult<bool> {
        if keyword != "every" {
            return Ok(false);
        }
        let every = a.u64("every (0 stops the creation)")?;
        if let Some(c) = creator(sim.world_mut(a)?, head) {
            c.every = every;
        }
        Ok(true)
    }

    /// The fork's line for each step that made bonds (counted over all ranks).
    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let made = match creator(ctx.world(), head) {
            Some(c) if !c.made.is_empty() => std::mem::take(&mut c.made),
            _ => return Ok(()),
        };
        for (step, n) in made {
            let n = ctx.world().comm.sum_count(n);
            if n > 0 {
                ctx.line(&format!("Created {n} bonds at timestep {step}"));
            }
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        if let Some(b) = sim.world.as_mut().and_then(|w| w.bonds.as_mut()) {
            b.creators.retain(|c| c.id != head.id);
        }
    }
}

//! `bond_style gran` and `bond_coeff`: the flexible-fiber bonds of
//! LIGGGHTS_Flexible_Fibers (see [`rdem::bond_gran`]).

use rdem::bond_gran::{BondCoeff, Breaking, Damping, Push};

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

/// The bonds of the world, or a located error when the atom style has none.
fn bonds_of<'s>(sim: &'s mut Sim, a: &Args) -> CmdResult<&'s mut rdem::bond_gran::GranBonds> {
    if sim.setup.bond_gran.is_none() {
        return Err(a.error_cmd(
            format!("{} needs an atom style with bonds", a.name()),
            Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M".into()),
        ));
    }
    let Some(w) = sim.world.as_mut() else {
        return Err(a.error_cmd(
            format!("{} before the simulation box is defined", a.name()),
            None,
        ));
    };
    Ok(w.bonds
        .as_mut()
        .expect("the world of a bond/gran atom style has bonds"))
}

pub(super) fn bond_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let s = a.word("bond style")?;
    if s != "gran" {
        return Err(a.error_prev(
            format!("unsupported bond style '{s}'"),
            Some(suggest(s, &["gran"])),
        ));
    }
    if sim.setup.bond_gran.is_none() {
        return Err(a.error_cmd(
            "bond_style gran needs an atom style with bonds",
            Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M".into()),
        ));
    }
    a.done()
}

/// `bond_coeff T ro ri Y G dstyle d... bstyle b...` (Flexible_Fibers' form): damping
/// style 0 (one value, unused), 1 (β) or 2 (β₀ β₁ β₂); break style 0 to 5 ([`breaking`]); or `bond_coeff T ro ri lb Sn St Sben Stor damp bn bt bstyle b...`
/// (LIGGGHTS-PFM's form, [`BondCoeff::pfm`]).
pub(super) fn bond_coeff(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let ntypes = sim.setup.bond_gran.map_or(0, |b| b.0);
    bonds_of(sim, a)?;
    let tk = a.pos();
    let t = a.word("bond type")?;
    let types: Vec<usize> = if t == "*" {
        (1..=ntypes).collect()
    } else {
        match t.parse::<usize>() {
            Ok(n) if n >= 1 && n <= ntypes => vec![n],
            _ => {
                return Err(a.error_at(
                    tk,
                    format!("bond type '{t}' is not within 1..={ntypes}"),
                    Some("a bond type of atom_style's n_bondtypes, or *".into()),
                ))
            }
        }
    };
    // Two dialects: Flexible_Fibers' (8 to 12 values, the fifth a damping style 0, 1 or
    // 2) and LIGGGHTS-PFM's (12 to 13 values, the fifth its shear modulus).
    let pfm = a.remaining() >= 13
        || (a.remaining() == 12
            && a.words()
                .get(a.pos() + 4)
                .is_some_and(|w| !matches!(w.text.as_str(), "0" | "1" | "2")));
    let c = if pfm { pfm_coeff(a)? } else { fibers_coeff(a)? };
    a.done()?;
    let bonds = bonds_of(sim, a)?;
    for t in types {
        bonds
            .set_coeff(t, c)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
    }
    Ok(())
}

/// The break style and its values: 0 r_b (apart beyond 2 r_b), 1 σ_c τ_c (by
/// stress), 2 σ_c τ_c T_break (by stress or the pair's mean temperature); in
/// Flexible_Fibers' form (`fibers`) also 3, 4 and 5 σ_c τ_c (by stress, a bond broken
/// while its spheres overlap pushing them apart until they separate).
fn breaking(a: &mut Args, fibers: bool) -> CmdResult<Breaking> {
    let bk = a.pos();
    let styles = if fibers {
        "0 r_b (apart beyond 2 r_b), 1 sigma_c tau_c (by stress), 2 sigma_c tau_c T_break (by stress or temperature), \
         3, 4 or 5 sigma_c tau_c (by stress; a bond broken while its spheres overlap pushes them apart)"
    } else {
        "0 r_b (apart beyond 2 r_b), 1 sigma_c tau_c (by stress) or 2 sigma_c tau_c T_break (by stress or temperature)"
    };
    let style = a.u64("break style")?;
    if style > 5 || (!fibers && style > 2) {
        let form = if fibers {
            ""
        } else {
            " in LIGGGHTS-PFM's form of bond_coeff"
        };
        return Err(a.error_at(
            bk,
            format!("unknown break style {style}{form}"),
            Some(styles.into()),
        ));
    }
    if style == 0 {
        return Ok(Breaking::Distance {
            rb: a.positive("bond break radius r_b")?,
        });
    }
    let sigma = a.positive("bond normal strength sigma_c")?;
    let tau = a.positive("bond shear strength tau_c")?;
    Ok(match style {
        1 => Breaking::Stress { sigma, tau },
        2 => Breaking::Hot {
            sigma,
            tau,
            temp: a.f64("bond break temperature T_break")?,
        },
        3 => Breaking::Separating {
            sigma,
            tau,
            push: Push::Weak,
        },
        4 => Breaking::Separating {
            sigma,
            tau,
            push: Push::Linear,
        },
        _ => Breaking::Separating {
            sigma,
            tau,
            push: Push::Hertz,
        },
    })
}

/// LIGGGHTS-PFM's form: `ro ri lb Sn St Sben Stor damp bn bt bstyle b...`.
fn pfm_coeff(a: &mut Args) -> CmdResult<BondCoeff> {
    let ro = a.positive("bond outer radius multiplier ro")?;
    let ri = a.non_negative("bond inner radius multiplier ri")?;
    let lb = a.positive("bond length multiplier lb")?;
    let sn = a.positive("bond normal modulus Sn")?;
    let st = a.positive("bond shear modulus St")?;
    let sben = a.positive("bond bending modulus Sben")?;
    let stor = a.positive("bond twisting modulus Stor")?;
    let damp = a.non_negative("bond damping ratio damp")?;
    let bn = a.positive("bond maximum length bn")?;
    a.f64("bt (read; it has no effect in LIGGGHTS-PFM)")?;
    let breaking = breaking(a, false)?;
    BondCoeff::pfm(ro, ri, lb, sn, st, sben, stor, damp, bn, breaking)
        .map_err(|e| a.error_cmd(e.to_string(), None))
}

/// Flexible_Fibers' form: `ro ri Y G dstyle d... bstyle b...`.
fn fibers_coeff(a: &mut Args) -> CmdResult<BondCoeff> {
    let ro = a.positive("bond outer radius multiplier ro")?;
    let ri = a.non_negative("bond inner radius multiplier ri")?;
    let youngs = a.positive("bond Young's modulus Y")?;
    let shear = a.positive("bond shear modulus G")?;
    let dk = a.pos();
    let damping = match a.u64("damping style (0, 1 or 2)")? {
        0 => {
            a.f64("damping style 0 value")?;
            Damping::None
        }
        1 => Damping::Critical {
            beta: a.non_negative("damping ratio beta")?,
        },
        2 => Damping::Dry {
            b0: a.non_negative("damping beta0")?,
            b1: a.non_negative("damping beta1")?,
            b2: a.non_negative("damping beta2")?,
        },
        d => {
            return Err(a.error_at(
                dk,
                format!("unknown damping style {d}"),
                Some("0 (none), 1 (beta), 2 (beta0 beta1 beta2)".into()),
            ))
        }
    };
    let breaking = breaking(a, true)?;
    BondCoeff::new(ro, ri, youngs, shear, damping, breaking)
        .map_err(|e| a.error_cmd(e.to_string(), None))
}

/// `delete_bonds group-ID multi|atom T|bond T|stats [any] [undo] [remove] [special]`:
/// bonds turned off (their type negated: no force), on again (`undo`) or removed
/// (`remove`, every turned-off bond), as LAMMPS' command does ([`rdem::bond_gran::DeleteBonds`]).
/// `special` asks LAMMPS to rebuild its 1-2 neighbor list; rdem keeps none (its pair
/// rules read the bonds as they are), so it changes nothing more.
pub(super) fn delete_bonds(sim: &mut Sim, a: &mut Args) -> CmdResult {
    use rdem::bond_gran::{BondSelect, DeleteBonds};
    bonds_of(sim, a)?;
    let groupbit = sim.group_bit(a, "group ID")?;
    let select = match a.keyword("delete_bonds style", &["multi", "atom", "bond", "stats"])? {
        "multi" => BondSelect::Multi,
        "atom" => {
            let k = a.pos();
            let t = a.u64("atom type")?;
            let n = sim.ntypes() as u64;
            if t == 0 || t > n {
                return Err(a.error_at(k, format!("atom type {t} is not within 1..={n}"), None));
            }
            BondSelect::AtomType(t as u32)
        }
        "bond" => {
            let k = a.pos();
            let t = a.u64("bond type (0: the broken bonds)")?;
            let n = sim.setup.bond_gran.map_or(0, |b| b.0) as u64;
            if t > n {
                return Err(a.error_at(k, format!("bond type {t} is not within 0..={n}"), None));
            }
            BondSelect::BondType(t as u32)
        }
        _ => BondSelect::Stats,
    };
    let mut d = DeleteBonds {
        select,
        groupbit,
        any: false,
        undo: false,
        remove: false,
    };
    while !a.is_done() {
        match a.keyword(
            "delete_bonds keyword",
            &["any", "undo", "remove", "special"],
        )? {
            "any" => d.any = true,
            "undo" => d.undo = true,
            "remove" => d.remove = true,
            _ => {}
        }
    }
    let w = sim.world.as_mut().expect("checked by bonds_of");
    let bonds = w.bonds.as_mut().expect("checked by bonds_of");
    let tally = bonds
        .delete(&mut w.particles, &*w.comm, &d)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    sim.outputs.out.line(&format!(
        "Deleting bonds ...\n  {} total bonds, {} turned on, {} turned off",
        tally.total, tally.on, tally.off
    ));
    Ok(())
}

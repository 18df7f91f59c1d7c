//! `bond_style gran` and `bond_coeff`: the flexible-fiber bonds of
//! LIGGGHTS_Flexible_Fibers (see [`rdem::bond_gran`]).

use rdem::bond_gran::{BondCoeff, Breaking, Damping};

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
/// style 0 (one value, unused), 1 (β) or 2 (β₀ β₁ β₂); break style 1 (σ_c τ_c).
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
    if a.remaining() == 13 {
        if let Some(w) = a.words().get(a.pos() + 4) {
            if !matches!(w.text.as_str(), "0" | "1" | "2") {
                return Err(a.error_cmd(
                    "the LIGGGHTS-PFM form of bond_coeff (ro ri lb Sn St Sben Stor damp bn bt break ...) is not supported yet",
                    Some("Flexible_Fibers' form: bond_coeff T ro ri Y G dstyle d... bstyle b...".into()),
                ));
            }
        }
    }
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
    let bk = a.pos();
    let breaking =
        match a.u64("break style")? {
            1 => Breaking::Stress {
                sigma: a.positive("bond normal strength sigma_c")?,
                tau: a.positive("bond shear strength tau_c")?,
            },
            b @ (0 | 2..=5) => return Err(a.error_at(
                bk,
                format!("break style {b} is not supported yet"),
                Some(
                    "1 sigma_c tau_c (breaking by stress); a very large strength keeps the bond"
                        .into(),
                ),
            )),
            b => {
                return Err(a.error_at(
                    bk,
                    format!("unknown break style {b}"),
                    Some("1 sigma_c tau_c".into()),
                ))
            }
        };
    a.done()?;
    let c = BondCoeff::new(ro, ri, youngs, shear, damping, breaking)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    let bonds = bonds_of(sim, a)?;
    for t in types {
        bonds
            .set_coeff(t, c)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
    }
    Ok(())
}

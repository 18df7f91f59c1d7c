//! The script side of SPH ([`rdem::sph`]): the `mass` command (per-type masses of
//! `atom_style sph`), `pair_style sph/artVisc/tensCorr`, the per-type tables it reads
//! from `fix property/global` at each run, and the `set` keywords `meso_rho` and
//! `sphkernel`. The SPH fix styles are in `fixes/sph.rs`.

use crate::error::Error;
use rdem::sph::{KernelKind, SphPair};

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

/// The kernel names, for help texts.
pub fn kernel_names() -> Vec<&'static str> {
    KernelKind::ALL.iter().map(|(n, _)| *n).collect()
}

/// Reads a kernel name.
pub fn kernel(a: &mut Args) -> CmdResult<KernelKind> {
    let w = a.word("SPH kernel")?;
    KernelKind::from_name(w).ok_or_else(|| {
        a.error_prev(
            format!("unknown SPH kernel '{w}'"),
            Some(suggest(w, &kernel_names())),
        )
    })
}

/// Gives every owned particle its type's mass (`atom_style sph`; types without a mass
/// keep theirs until `mass` gives one).
pub fn apply_type_masses(sim: &mut Sim) {
    let masses = &sim.defs.type_mass;
    if let Some(w) = &mut sim.world {
        let p = &mut w.particles;
        for i in 0..p.nlocal() {
            if let Some(Some(m)) = masses.get(p.ty[i] as usize) {
                p.rmass[i] = *m;
            }
        }
    }
}

/// `mass I value`: I a type, `*`, `*n`, `n*` or `m*n` (LAMMPS' type ranges).
pub fn mass(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let n = sim.ntypes();
    sim.world_ref(a)?;
    if !sim.setup.sph {
        return Err(a.error_cmd(
            "mass: this atom style has per-particle masses",
            Some("the per-type mass is for atom_style sph; use 'set ... mass' or density".into()),
        ));
    }
    let t = a.word("atom type")?;
    let bad = || {
        a.error_prev(
            format!("bad atom type or range '{t}'"),
            Some(format!("a type 1..{n}, *, *n, n* or m*n")),
        )
    };
    let parse = |s: &str, dflt: usize| -> Option<usize> {
        if s.is_empty() {
            Some(dflt)
        } else {
            s.parse::<usize>().ok()
        }
    };
    let (lo, hi) = match t.split_once('*') {
        Some((l, h)) => (parse(l, 1).ok_or_else(bad)?, parse(h, n).ok_or_else(bad)?),
        None => {
            let v = t.parse::<usize>().map_err(|_| bad())?;
            (v, v)
        }
    };
    if lo < 1 || hi > n || lo > hi {
        return Err(bad());
    }
    let m = a.positive("mass")?;
    a.done()?;
    let tm = &mut sim.defs.type_mass;
    if tm.len() < n + 1 {
        tm.resize(n + 1, None);
    }
    for slot in &mut tm[lo..=hi] {
        *slot = Some(m);
    }
    apply_type_masses(sim);
    Ok(())
}

/// The switches of `pair_style sph/artVisc/tensCorr`.
const SWITCHES: [&str; 2] = ["artVisc", "tensCorr"];

/// `pair_style sph/artVisc/tensCorr kernel h [artVisc] [tensCorr]` (LIGGGHTS 3.8 reads
/// the switches without values, and their parameters from `fix property/global`; the
/// `h` is read and not used: atom_style sph takes the per-type `sl`).
pub fn pair_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if !sim.setup.sph {
        return Err(a.error_prev("pair_style sph/artVisc/tensCorr needs atom_style sph", None));
    }
    let k = kernel(a)?;
    a.positive("smoothing length h")?;
    let (mut visc, mut tens) = (false, false);
    while !a.is_done() {
        match a.keyword("pair_style sph keyword", &SWITCHES)? {
            "artVisc" => visc = true,
            _ => tens = true,
        }
        if let Some(w) = a.peek() {
            if crate::args::parse_f64(w).is_some() {
                return Err(a.error_at(
                    a.pos(),
                    "artVisc and tensCorr take no values in LIGGGHTS 3.8",
                    Some("give them with fix property/global: artViscAlpha, artViscBeta (peratomtype), artViscEta (scalar), tensCorrEpsilon (scalar), tensCorrDeltaP (peratomtype)".into()),
                ));
            }
        }
    }
    let w = sim.world_mut(a)?;
    w.pair = None;
    w.sph = Some(SphPair::new(k, visc, tens));
    sim.defs.pair_coeff_set = false;
    Ok(())
}

/// Fills the SPH pair style's per-type tables from `fix property/global` (at each run).
pub fn tables(sim: &mut Sim) -> Result<(), Error> {
    let n = sim.ntypes();
    let props = &sim.defs.properties;
    let Some(w) = &mut sim.world else {
        return Ok(());
    };
    let Some(pair) = &mut w.sph else {
        return Ok(());
    };
    let pertype = |name: &str| -> Result<Vec<f64>, Error> {
        let p = props.get(name).ok_or_else(|| {
            format!("pair_style sph/artVisc/tensCorr needs fix property/global {name} peratomtype ({n} value(s))")
        })?;
        if p.style != "peratomtype" || p.values.len() != n {
            return Err(format!(
                "property {name} (fix {}) must be peratomtype with {n} value(s)",
                p.fix_id
            )
            .into());
        }
        let mut v = vec![0.0];
        v.extend_from_slice(&p.values);
        Ok(v)
    };
    let scalar = |name: &str| -> Result<f64, Error> {
        let p = props.get(name).ok_or_else(|| {
            format!("pair_style sph/artVisc/tensCorr needs fix property/global {name} scalar")
        })?;
        match (p.style.as_str(), p.values.as_slice()) {
            ("scalar", [v]) => Ok(*v),
            _ => Err(format!("property {name} (fix {}) must be scalar", p.fix_id).into()),
        }
    };
    pair.sl = pertype("sl")?;
    if pair.art_visc {
        pair.c = pertype("speedOfSound")?;
        pair.alpha = pertype("artViscAlpha")?;
        pair.beta = pertype("artViscBeta")?;
        pair.eta2 = scalar("artViscEta")?;
    }
    if pair.tens_corr {
        pair.eps = scalar("tensCorrEpsilon")?;
        pair.deltap = pertype("tensCorrDeltaP")?;
    }
    pair.check(n)?;
    if sim.setup.sph {
        let tm = &sim.defs.type_mass;
        if let Some(t) = (1..=n).find(|&t| tm.get(t).copied().flatten().is_none()) {
            return Err(format!(
                "not all per-type masses are set: type {t} has none (use the mass command)"
            )
            .into());
        }
    }
    Ok(())
}

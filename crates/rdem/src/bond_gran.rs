//! `bond_style gran`: the flexible-fiber bonds of LIGGGHTS_Flexible_Fibers (also in
//! LIGGGHTS_SEAICE), a beam between two spheres in the manner of Potyondy & Cundall
//! (2004) with the damping of Guo et al. (2013) and Schramm et al. (2019).
//!
//! A bond between spheres a and b (radii R_a, R_b) is a tube of outer and inner radii
//! r_o = `ro`·min(R_a, R_b), r_i = `ri`·min(R_a, R_b), with A = π(r_o² − r_i²),
//! I_p = π/2 (r_o⁴ − r_i⁴), I = I_p/2 and the length L₀ that the pair has at the bond's
//! first evaluation. Its stiffnesses are K_n = Y A/L₀, K_t = G A/L₀, K_tor = G I_p/L₀,
//! K_ben = Y I/L₀. With n the unit vector from a to b, v = v_a − v_b,
//! v_n = (v·n)n, v_t = v − v_n + (R_a ω_a + R_b ω_b) × n, ω = ω_a − ω_b split into
//! ω_n and ω_t, each step
//!
//! - the normal force on a is K_n (r − L₀) n (explicit);
//! - the shear force F_t, the twisting torque T_n and the bending torque T_t grow by
//!   −K_t v_t dt, −K_tor ω_n dt, −K_ben ω_t dt, after the stored F_t and T_t are turned
//!   into the plane normal to the new n at constant length and T_n is projected on n;
//! - a gets the force F_n + F_t (+ damping) and the torque R_a n × F_t + T_n + T_t
//!   (+ damping), b the opposite force and R_b n × F_t − (T_n + T_t) (− damping). The
//!   damping forces act on the centres only, without a lever arm.
//!
//! Damping (global, as in the fork: the last `bond_coeff` sets it):
//! - style 0: none;
//! - style 1: −2β√(m* K) times the matching relative velocity for each of the four
//!   loads (m* the reduced mass for the forces, I* = I_aI_b/(I_a + I_b) of the spheres'
//!   moments of inertia for the torques);
//! - style 2: for each Cartesian component c of each load L with stiffness K,
//!   −sgn(w_c)(K β₀ + β₁|L_c| + β₂ L_c²/K), w the load's relative velocity (for the shear
//!   force the translational part only).
//!
//! Breaking: style 1, σ = |F_n|/A + 2|T_t|(r_o − r_i)/I_p above σ_c or
//! τ = |F_t|/A + |T_n|(r_o − r_i)/I_p above τ_c; style 0, the centres farther apart
//! than 2 r_b; style 2, as style 1 or the pair's mean temperature (`Temp`) above
//! T_break. A bond that breaks still acts at that step, no more from the next, and is
//! removed at the next re-neighboring (`numbonds` counts it until then).
//!
//! Styles 3 to 5 break as style 1, and a bond that breaks while its spheres overlap
//! (r < R_a + R_b) turns into a *separating* bond: its loads are cleared, it no longer
//! counts in `numbonds`, and until the spheres separate it pushes them apart along n
//! with (no torque, no damping)
//! - style 3: 0.001 K_n (R_a + R_b − r);
//! - style 4: K_n (L₀ − r) while r < L₀, L₀ reset to r at the break;
//! - style 5: (4/3) Y* √(r* (L₀ − r)) (L₀ − r) while r < L₀, L₀ reset to r at the
//!   break, r* = r_o/2, Y* = Y/(2(1 − ν²)), ν = Y/(2G) − 1.
//!
//! A bond of styles 3 to 5 that breaks without overlap, or a separating bond whose
//! spheres no longer overlap, leaves `numbonds` at once.
//!
//! Whatever the style, a bond breaks without acting when the centre of one of its
//! spheres comes near a box face that is not periodic, as the forks do before computing
//! any bond force: within 0.75 of that sphere's radius in Flexible_Fibers' form, within
//! the neighbor skin in LIGGGHTS-PFM's (d075b97's `bond_gran.cpp` takes the skin).
//!
//! LIGGGHTS-PFM's form of `bond_coeff` (see [`BondCoeff::pfm`]) is the same beam with a
//! prescribed length L₀ = lb (R_a + R_b), moduli of its own for bending and twisting,
//! damping style 1, and the normal force multiplied by (1 − L₀/bn)/(1 − r/bn).
//!
//! Each figure above was measured against the fork (LIGGGHTS_Flexible_Fibers 0fc7c5b,
//! built here): three bonded pairs in general motion follow it to 1e-10 over 1000 steps
//! for each damping style; a pair broken while overlapping follows it to 1e-14 over 2000
//! steps for break styles 3, 4 and 5, and a pair heated past T_break (style 2) breaks at
//! its step (`crates/rdem-cli/tests/bond_gran.rs`).
//!
//! **Where the bonds live.** Each sphere holds its bonds in the dense per-particle
//! property [`PROP`], [`SLOT`] values per bond: partner tag, bond type, broken flag, L₀,
//! F_t, T_n, T_t, and the last elastic force and torque on the bond's first sphere (for
//! output, without damping, as the fork reports them).
//! A bond is held by both spheres, each in the orientation of the pair's lower tag, so
//! the two copies evolve alike bit for bit and each sphere's force is computed from its
//! own copy: no force is written to another particle, so the pass runs on any number of
//! threads with the same result, and across MPI ranks without reverse communication. The
//! property follows its particle through sorting, migration and restart files like any
//! other. At each re-neighboring the broken bonds are dropped and each bond's partner is
//! looked up among the owned particles and ghosts (the nearest image).

use glam::DVec3;
use rayon::prelude::*;

use crate::bond::turn_tangent;
use crate::error::{Error, Result};
use crate::particles::{Particles, PropId, Tag, REMOTE_GHOST};

mod delete;
pub use delete::{BondSelect, BondTally, DeleteBonds};

/// Name of the per-particle property holding the bonds.
pub const PROP: &str = "bond/gran";

/// Name of the per-particle molecule ID of atom style bond/gran (`mol` in dumps): each
/// inserted bonded template gets the next ID (1, 2, …, in insertion order), other
/// particles 0. `neigh_modify exclude molecule` reads it.
pub const MOLECULE: &str = "molecule";

/// Values per bond in [`PROP`].
pub const SLOT: usize = 19;

const TAG: usize = 0;
const TYPE: usize = 1;
const BROKEN: usize = 2;
const LEN0: usize = 3;
const FT: usize = 4;
const TN: usize = 7;
const TT: usize = 10;
const FORCE: usize = 13;
const TORQUE: usize = 16;

/// Marks a bond slot whose partner is not resolved.
const NONE: u32 = u32::MAX;

/// Values of a slot's `BROKEN`: the bond holds; it broke (dropped at the next
/// re-neighboring, counted in `numbonds` until then); it broke while its spheres
/// overlapped and pushes them apart (break styles 3 to 5); it broke and left `numbonds`
/// at once (break styles 3 to 5).
const INTACT: f64 = 0.0;
const BROKE: f64 = 1.0;
const SEPARATING: f64 = 2.0;
const GONE: f64 = 3.0;

/// A `BROKEN` value of a broken bond.
#[inline(always)]
fn broken(v: f64) -> bool {
    v == BROKE || v == GONE
}

/// The damping of a bond type (`bond_coeff`'s damping style and values).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    /// Style 0: none.
    None,
    /// Style 1: −2β√(m*K) v per load.
    Critical {
        /// β.
        beta: f64,
    },
    /// Style 2: −sgn(w_c)(Kβ₀ + β₁|L_c| + β₂L_c²/K) per component.
    Dry {
        /// β₀ (a length).
        b0: f64,
        /// β₁.
        b1: f64,
        /// β₂ (an inverse length).
        b2: f64,
    },
}

impl Damping {
    /// The style number of the fork.
    pub fn style(&self) -> u32 {
        match self {
            Damping::None => 0,
            Damping::Critical { .. } => 1,
            Damping::Dry { .. } => 2,
        }
    }
}

/// When a bond type breaks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Breaking {
    /// Style 0: when the centres are farther apart than 2 `rb` (measured in
    /// LIGGGHTS-PFM; Flexible_Fibers' manual says the same, but its build stops with
    /// "ERROR: broken" instead).
    Distance {
        /// The break radius r_b.
        rb: f64,
    },
    /// Style 1: by the normal stress σ_c or the shear stress τ_c.
    Stress {
        /// σ_c.
        sigma: f64,
        /// τ_c.
        tau: f64,
    },
    /// Style 2: as style 1, or when the mean temperature of the pair exceeds T_break.
    Hot {
        /// σ_c.
        sigma: f64,
        /// τ_c.
        tau: f64,
        /// T_break.
        temp: f64,
    },
    /// Styles 3 to 5: as style 1; a bond that breaks while its spheres overlap pushes
    /// them apart until they separate.
    Separating {
        /// σ_c.
        sigma: f64,
        /// τ_c.
        tau: f64,
        /// How the broken bond pushes.
        push: Push,
    },
}

/// How a bond of break styles 3 to 5 that broke while its spheres overlap pushes them
/// apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Push {
    /// Style 3: 0.001 K_n times the overlap.
    Weak,
    /// Style 4: K_n times the shortening from the length at the break.
    Linear,
    /// Style 5: a Hertz force on the shortening from the length at the break.
    Hertz,
}

impl Breaking {
    /// The style number of the fork.
    pub fn style(&self) -> u32 {
        match self {
            Breaking::Distance { .. } => 0,
            Breaking::Stress { .. } => 1,
            Breaking::Hot { .. } => 2,
            Breaking::Separating { push, .. } => match push {
                Push::Weak => 3,
                Push::Linear => 4,
                Push::Hertz => 5,
            },
        }
    }

    /// σ_c and τ_c of the styles that break by stress.
    fn strength(&self) -> Option<(f64, f64)> {
        match *self {
            Breaking::Distance { .. } => None,
            Breaking::Stress { sigma, tau }
            | Breaking::Hot { sigma, tau, .. }
            | Breaking::Separating { sigma, tau, .. } => Some((sigma, tau)),
        }
    }

    /// Styles 3 to 5: a bond broken without overlap leaves at once.
    fn leaves_at_once(&self) -> bool {
        matches!(self, Breaking::Separating { .. })
    }
}

/// The coefficients of one bond type (`bond_coeff`, Flexible_Fibers' form).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BondCoeff {
    /// Outer radius over the smaller sphere's radius.
    pub ro: f64,
    /// Inner radius over the smaller sphere's radius.
    pub ri: f64,
    /// Young's modulus Y of the bond.
    pub youngs: f64,
    /// Shear modulus G of the bond.
    pub shear: f64,
    /// Modulus of the bending stiffness K_ben = E_ben I/L₀: Y in Flexible_Fibers' form,
    /// its own value (`Sben`) in LIGGGHTS-PFM's.
    pub bend_modulus: f64,
    /// Modulus of the twisting stiffness K_tor = G_tor I_p/L₀: G in Flexible_Fibers'
    /// form, its own value (`Stor`) in LIGGGHTS-PFM's.
    pub twist_modulus: f64,
    /// LIGGGHTS-PFM's prescribed length L₀ = `lb`(R_a + R_b); `None` (Flexible_Fibers):
    /// L₀ is the length at the bond's first evaluation.
    pub length_ratio: Option<f64>,
    /// LIGGGHTS-PFM's `bn`: the normal force is multiplied by (1 − L₀/bn)/(1 − r/bn)
    /// (lengths in the script's units, as the fork computes it); `None`: by 1.
    pub fene: Option<f64>,
    /// Damping.
    pub damping: Damping,
    /// Breaking.
    pub breaking: Breaking,
}

/// `Ok` when `v` is finite and above 0, else the error that says so for `what`.
fn positive(what: &'static str, v: f64) -> Result<()> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(Error::Invalid {
            what,
            reason: format!("{v} must be > 0"),
        })
    }
}

impl BondCoeff {
    /// Checks the ranges.
    pub fn new(
        ro: f64,
        ri: f64,
        youngs: f64,
        shear: f64,
        damping: Damping,
        breaking: Breaking,
    ) -> Result<Self> {
        let bad = |what: &'static str, reason: String| Err(Error::Invalid { what, reason });
        positive("bond outer radius", ro)?;
        if !(ri >= 0.0 && ri < ro) {
            return bad(
                "bond inner radius",
                format!("{ri} must be >= 0 and below the outer radius {ro}"),
            );
        }
        positive("bond Young's modulus", youngs)?;
        positive("bond shear modulus", shear)?;
        let damping_ok = match damping {
            Damping::None => true,
            Damping::Critical { beta } => beta >= 0.0 && beta.is_finite(),
            Damping::Dry { b0, b1, b2 } => [b0, b1, b2].iter().all(|b| *b >= 0.0 && b.is_finite()),
        };
        if !damping_ok {
            return bad("bond damping", format!("{damping:?}: values must be >= 0"));
        }
        if let Breaking::Distance { rb } = breaking {
            positive("bond break radius", rb)?;
        }
        if let Some((sigma, tau)) = breaking.strength() {
            if !(sigma > 0.0 && tau > 0.0) {
                return bad(
                    "bond strength",
                    format!("sigma {sigma} and tau {tau} must be > 0"),
                );
            }
        }
        if let Breaking::Hot { temp, .. } = breaking {
            if !temp.is_finite() {
                return bad("bond break temperature", format!("{temp} is not finite"));
            }
        }
        let nu = youngs / (2.0 * shear) - 1.0;
        if matches!(
            breaking,
            Breaking::Separating {
                push: Push::Hertz,
                ..
            }
        ) && nu.abs() >= 1.0
        {
            return bad(
                "break style 5",
                format!(
                    "its Poisson's ratio Y/(2G) - 1 = {nu} from Y {youngs} and G {shear} must lie within (-1, 1)"
                ),
            );
        }
        Ok(Self {
            ro,
            ri,
            youngs,
            shear,
            bend_modulus: youngs,
            twist_modulus: shear,
            length_ratio: None,
            fene: None,
            damping,
            breaking,
        })
    }

    /// LIGGGHTS-PFM's form (`bond_coeff T ro ri lb Sn St Sben Stor damp bn bt …`): the
    /// same beam with L₀ = `lb`(R_a + R_b) prescribed, bending and twisting moduli of
    /// their own, damping style 1 with β = `damp`, and the normal force multiplied by
    /// (1 − L₀/bn)/(1 − r/bn). Measured against LIGGGHTS-PFM 24.01 (built here): `bt`
    /// changes nothing in it (a spinning, stretched three-pair probe gives the same
    /// bytes for bt 0, 1e-4 and 1.5), so it is read and not used.
    #[allow(clippy::too_many_arguments)]
    pub fn pfm(
        ro: f64,
        ri: f64,
        lb: f64,
        sn: f64,
        st: f64,
        sben: f64,
        stor: f64,
        damp: f64,
        bn: f64,
        breaking: Breaking,
    ) -> Result<Self> {
        positive("bond length multiplier lb", lb)?;
        positive("bond bending modulus Sben", sben)?;
        positive("bond twisting modulus Stor", stor)?;
        // The fork divides by it.
        positive("bond maximum length bn", bn)?;
        let mut c = Self::new(ro, ri, sn, st, Damping::Critical { beta: damp }, breaking)?;
        c.bend_modulus = sben;
        c.twist_modulus = stor;
        c.length_ratio = Some(lb);
        c.fene = Some(bn);
        Ok(c)
    }
}

/// `fix bond/create/gran`: bonds between spheres closer than `cutoff`.
#[derive(Debug, Clone, PartialEq)]
pub struct Creator {
    /// Fix ID.
    pub id: String,
    /// Group bit mask (both spheres in the group).
    pub groupbit: u32,
    /// Create every this many steps; 0: never (`fix_modify ID every 0`).
    pub every: u64,
    /// Atom types of the two spheres (either order).
    pub itype: u32,
    /// See `itype`.
    pub jtype: u32,
    /// Centre distance below which a pair bonds; with `relative`, over the sum of the
    /// two radii.
    pub cutoff: f64,
    /// `doNorm yes`: `cutoff` is relative to R_a + R_b (a pair bonds when
    /// r²/(R_a + R_b)² < cutoff²).
    pub relative: bool,
    /// Bond type of the new bonds (1-based).
    pub btype: u32,
    /// Most new bonds per sphere at one step.
    pub per_step: usize,
    /// `iparam` and `jparam`: for spheres of `itype` and of `jtype`, the bonds of type
    /// `btype` a sphere may hold before it takes no more from this fix (0: no limit),
    /// and the atom type it turns into on reaching that count.
    pub limits: [Limit; 2],
    /// `prob fraction seed`: each sphere with a candidate draws u in [0, 1) at each
    /// creation step, and a pair bonds only when (u_a + u_b)/2 < fraction (1: always).
    pub fraction: f64,
    /// The seed of `prob`.
    pub seed: u64,
    /// (step, bonds made on this rank) of each creation step, for the front end's log,
    /// which sums them over the ranks and drains it; a bond is counted by the rank that
    /// owns its lower tag.
    pub made: Vec<(u64, u64)>,
}

/// One of `fix bond/create/gran`'s `iparam` and `jparam`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limit {
    /// Most bonds of the creator's type; 0: no limit.
    pub max: usize,
    /// The atom type a sphere turns into when it reaches `max`.
    pub new_type: u32,
}

impl Creator {
    /// A creator without `iparam`, `jparam` or `prob`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        id: &str,
        groupbit: u32,
        every: u64,
        itype: u32,
        jtype: u32,
        cutoff: f64,
        btype: u32,
        per_step: usize,
    ) -> Self {
        Self {
            id: id.to_string(),
            groupbit,
            every,
            itype,
            jtype,
            cutoff,
            relative: false,
            btype,
            per_step,
            limits: [
                Limit {
                    max: 0,
                    new_type: itype,
                },
                Limit {
                    max: 0,
                    new_type: jtype,
                },
            ],
            fraction: 1.0,
            seed: 0,
            made: Vec::new(),
        }
    }

    /// The limit of a sphere of type `ty` (`iparam` for `itype`, else `jparam`, as the
    /// fork tells them apart).
    fn limit(&self, ty: u32) -> Limit {
        self.limits[usize::from(ty != self.itype)]
    }

    /// Whether a sphere of type `ty` holding `held` bonds of the creator's type may take
    /// another.
    fn room(&self, ty: u32, held: usize) -> bool {
        let l = self.limit(ty);
        l.max == 0 || held < l.max
    }

    /// The draw of `prob` for the sphere of tag `tag` at `step`: uniform in [0, 1), the
    /// same on every rank and thread.
    fn draw(&self, tag: Tag, step: u64) -> f64 {
        let mut z = self
            .seed
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(tag.wrapping_mul(0xD1B5_4A32_D192_ED03))
            .wrapping_add(step.wrapping_mul(0xBF58_476D_1CE4_E5B9));
        // splitmix64's finalizer.
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Whether this creator makes bonds at `step`.
    pub fn due(&self, step: u64) -> bool {
        self.every > 0 && step % self.every == 0
    }

    /// The bonds of this creator's type among a sphere's bond slots `slots`.
    fn typed(&self, slots: &[f64]) -> usize {
        slots
            .chunks_exact(SLOT)
            .filter(|s| s[TYPE] == self.btype as f64)
            .count()
    }

    /// The largest centre distance that bonds, for spheres of radius at most `rmax`.
    pub fn distance(&self, rmax: f64) -> f64 {
        if self.relative {
            self.cutoff * 2.0 * rmax
        } else {
            self.cutoff
        }
    }

    /// Whether a pair of radii `ra`, `rb` at squared distance `rsq` is close enough.
    fn close(&self, rsq: f64, ra: f64, rb: f64) -> bool {
        if self.relative {
            rsq / ((ra + rb) * (ra + rb)) < self.cutoff * self.cutoff
        } else {
            rsq < self.cutoff * self.cutoff
        }
    }
}

/// The bonds of a run: settings, coefficients, creators and the resolved partners.
#[derive(Debug, Clone)]
pub struct GranBonds {
    /// Bond types (`n_bondtypes`).
    pub ntypes: usize,
    /// Bonds per sphere (`bonds_per_atom`).
    pub per_atom: usize,
    /// Coefficients per bond type (index type − 1).
    pub coeffs: Vec<Option<BondCoeff>>,
    /// Bond creation fixes, in definition order.
    pub creators: Vec<Creator>,
    /// `disableNormalContact 1`: bonded spheres have no pair contact, from the step the
    /// bond is made to the re-neighboring after it breaks (or the step after it leaves,
    /// break styles 3 to 5), as in the fork (see `pair::BondRules`).
    pub disable_contact: bool,
    prop: Option<PropId>,
    molecule: Option<PropId>,
    /// The temperature `Temp` (break style 2).
    temp: Option<PropId>,
    /// The last molecule ID given.
    last_molecule: u64,
    /// Partner index per bond slot of each owned particle (`NONE`: none).
    links: Vec<u32>,
    /// Sides of the bonds of inserted templates (local index, partner's tag, bond type),
    /// made by [`GranBonds::make_pending`].
    pending: Vec<(usize, Tag, u32)>,
}

/// One sphere of a bond, as the force reads it.
#[derive(Debug, Clone, Copy)]
struct Side {
    x: DVec3,
    v: DVec3,
    w: DVec3,
    r: f64,
    m: f64,
    /// Temperature (break style 2; 0 otherwise).
    t: f64,
}

/// What became of a bond at a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// It holds.
    Holds,
    /// It broke.
    Breaks,
    /// It broke while its spheres overlap (break styles 3 to 5): it pushes them apart
    /// from the next step.
    Separates,
}

/// What a bond gives its lower-tag sphere a: force, torque; and b's torque.
#[derive(Debug, Clone, Copy, Default)]
struct Load {
    f: DVec3,
    ta: DVec3,
    tb: DVec3,
    /// The elastic force and torque on a (without damping), for output.
    fe: DVec3,
    me: DVec3,
}

#[inline(always)]
fn get3(h: &[f64], k: usize) -> DVec3 {
    DVec3::new(h[k], h[k + 1], h[k + 2])
}

#[inline(always)]
fn put3(h: &mut [f64], k: usize, v: DVec3) {
    h[k] = v.x;
    h[k + 1] = v.y;
    h[k + 2] = v.z;
}

/// sgn per component (0 at 0).
#[inline(always)]
fn sgn(v: DVec3) -> DVec3 {
    let s = |x: f64| {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    };
    DVec3::new(s(v.x), s(v.y), s(v.z))
}

/// Style-2 damping of a load `l` with stiffness `k` against the velocity `w`.
#[inline(always)]
fn dry(l: DVec3, w: DVec3, k: f64, b0: f64, b1: f64, b2: f64) -> DVec3 {
    let a = l.abs();
    -sgn(w) * (DVec3::splat(k * b0) + b1 * a + (b2 / k) * a * a)
}

/// The bond between a (the lower tag) and b, history `h` (one slot) advanced, and
/// whether it breaks: a bond whose stress exceeds its strength still acts at this step
/// and acts no more from the next (the fork's order: a pair pulled apart by a constant
/// force moves as the fork's to the digit and goes free at the same step). A bond of
/// break styles 3 to 5 that breaks while its spheres overlap has its loads cleared (and
/// its length set to r for styles 4 and 5) for its separating phase ([`push`]).
#[inline(always)]
fn bond(a: &Side, b: &Side, c: &BondCoeff, h: &mut [f64], dt: f64) -> (Load, Outcome) {
    let d = b.x - a.x;
    let r = d.length();
    // Coincident centres (or a NaN): no direction, no force.
    if r.is_nan() || r <= 0.0 {
        return (Load::default(), Outcome::Holds);
    }
    let n = d / r;
    if h[LEN0] == 0.0 {
        h[LEN0] = c.length_ratio.map_or(r, |lb| lb * (a.r + b.r));
    }
    let l0 = h[LEN0];
    let rmin = a.r.min(b.r);
    let (ro, ri) = (c.ro * rmin, c.ri * rmin);
    let area = std::f64::consts::PI * (ro * ro - ri * ri);
    let ip = std::f64::consts::FRAC_PI_2 * (ro.powi(4) - ri.powi(4));
    let ib = 0.5 * ip;
    let kn = c.youngs * area / l0;
    let kt = c.shear * area / l0;
    let ktor = c.twist_modulus * ip / l0;
    let kben = c.bend_modulus * ib / l0;

    let vr = a.v - b.v;
    let vn = vr.dot(n) * n;
    let vtt = vr - vn;
    let vt = vtt + (a.r * a.w + b.r * b.w).cross(n);
    let dw = a.w - b.w;
    let wn = dw.dot(n) * n;
    let wt = dw - wn;

    let ft = turn_tangent(get3(h, FT), n) - kt * dt * vt;
    let tn = get3(h, TN).dot(n) * n - ktor * dt * wn;
    let tt = turn_tangent(get3(h, TT), n) - kben * dt * wt;
    put3(h, FT, ft);
    put3(h, TN, tn);
    put3(h, TT, tt);
    let fene = c.fene.map_or(1.0, |bn| (1.0 - l0 / bn) / (1.0 - r / bn));
    let fnorm = kn * (r - l0) * fene * n;

    let stressed = |sigma: f64, tau: f64| {
        let arm = ro - ri;
        let s = fnorm.length() / area + 2.0 * tt.length() * arm / ip;
        let t = ft.length() / area + tn.length() * arm / ip;
        s > sigma || t > tau
    };
    let broke = match c.breaking {
        Breaking::Distance { rb } => r > 2.0 * rb,
        Breaking::Stress { sigma, tau } | Breaking::Separating { sigma, tau, .. } => {
            stressed(sigma, tau)
        }
        Breaking::Hot { sigma, tau, temp } => stressed(sigma, tau) || 0.5 * (a.t + b.t) > temp,
    };

    let fe = fnorm + ft;
    let me = tn + tt;
    let (mut f, mut m) = (fe, me);
    match c.damping {
        Damping::None => {}
        Damping::Critical { beta } => {
            let ms = a.m * b.m / (a.m + b.m);
            let (ia, ibb) = (0.4 * a.m * a.r * a.r, 0.4 * b.m * b.r * b.r);
            let is = ia * ibb / (ia + ibb);
            f -= 2.0 * beta * ((ms * kn).sqrt() * vn + (ms * kt).sqrt() * vt);
            m -= 2.0 * beta * ((is * ktor).sqrt() * wn + (is * kben).sqrt() * wt);
        }
        Damping::Dry { b0, b1, b2 } => {
            f += dry(fnorm, vn, kn, b0, b1, b2) + dry(ft, vtt, kt, b0, b1, b2);
            m += dry(tn, wn, ktor, b0, b1, b2) + dry(tt, wt, kben, b0, b1, b2);
        }
    }
    let lever = n.cross(ft);
    let mut load = Load {
        f,
        ta: a.r * lever + m,
        tb: b.r * lever - m,
        fe,
        me,
    };
    let outcome = match c.breaking {
        _ if !broke => Outcome::Holds,
        Breaking::Separating { push, .. } if r < a.r + b.r => {
            h[FT..TT + 3].fill(0.0);
            if push != Push::Weak {
                h[LEN0] = r;
            }
            load.fe = DVec3::ZERO;
            load.me = DVec3::ZERO;
            Outcome::Separates
        }
        _ => Outcome::Breaks,
    };
    (load, outcome)
}

/// The force on a (the lower tag) of a separating bond (history `h`) of break style 3,
/// 4 or 5 while its spheres a and b overlap (see the module's doc), or `None` once they
/// no longer do: the bond is then broken.
#[inline(always)]
fn push(a: &Side, b: &Side, c: &BondCoeff, h: &[f64]) -> Option<DVec3> {
    let Breaking::Separating { push, .. } = c.breaking else {
        return None;
    };
    let d = b.x - a.x;
    let r = d.length();
    let gap = r - (a.r + b.r);
    if gap > 0.0 {
        return None;
    }
    if r.is_nan() || r <= 0.0 {
        return Some(DVec3::ZERO);
    }
    let l0 = h[LEN0];
    let rmin = a.r.min(b.r);
    let (ro, ri) = (c.ro * rmin, c.ri * rmin);
    let kn = c.youngs * std::f64::consts::PI * (ro * ro - ri * ri) / l0;
    let short = l0 - r;
    let f = match push {
        Push::Weak => -0.001 * kn * gap,
        Push::Linear => (kn * short).max(0.0),
        Push::Hertz if short > 0.0 => {
            let nu = c.youngs / (2.0 * c.shear) - 1.0;
            let y = 0.5 * c.youngs / (1.0 - nu * nu);
            4.0 / 3.0 * y * (0.5 * ro * short).sqrt() * short
        }
        Push::Hertz => 0.0,
    };
    Some(-f / r * d)
}

impl GranBonds {
    /// Bonds of `ntypes` types, at most `per_atom` per sphere.
    pub fn new(ntypes: usize, per_atom: usize) -> Result<Self> {
        if ntypes == 0 || per_atom == 0 {
            return Err(Error::Invalid {
                what: "atom_style bond/gran",
                reason: format!(
                    "n_bondtypes ({ntypes}) and bonds_per_atom ({per_atom}) must be >= 1"
                ),
            });
        }
        Ok(Self {
            ntypes,
            per_atom,
            coeffs: vec![None; ntypes],
            creators: Vec::new(),
            disable_contact: false,
            temp: None,
            prop: None,
            molecule: None,
            last_molecule: 0,
            links: Vec::new(),
            pending: Vec::new(),
        })
    }

    /// The handle of [`PROP`] once attached.
    pub fn prop_id(&self) -> Option<PropId> {
        self.prop
    }

    /// Values per sphere in [`PROP`].
    pub fn width(&self) -> usize {
        self.per_atom * SLOT
    }

    /// Adds [`PROP`] to `p` (idempotent).
    /// Adds the per-particle properties of the bonds; with break style 2, finds the
    /// temperature `Temp` (forwarded to the ghosts every step from now on), which must
    /// exist (`fix property/atom Temp` or `fix heat/gran`).
    pub fn attach(&mut self, p: &mut Particles) -> Result<()> {
        let w = self.width();
        self.prop = Some(p.add_property(PROP, w, &vec![0.0; w])?);
        self.molecule = Some(p.add_property(MOLECULE, 1, &[0.0])?);
        let hot = self
            .coeffs
            .iter()
            .flatten()
            .any(|c| matches!(c.breaking, Breaking::Hot { .. }));
        self.temp = None;
        if hot {
            let id = p.property(crate::heat::TEMP).ok_or_else(|| Error::Invalid {
                what: "bond_coeff",
                reason: format!(
                    "break style 2 breaks by the temperature, and there is no per-particle temperature '{}': \
                     define it with `fix ID all property/atom {} scalar yes no no T0` or `fix heat/gran`",
                    crate::heat::TEMP,
                    crate::heat::TEMP
                ),
            })?;
            p.set_forward(id);
            self.temp = Some(id);
        }
        Ok(())
    }

    /// True when a bond type has Flexible_Fibers' form of `bond_coeff` (not
    /// LIGGGHTS-PFM's).
    pub fn fibers_form(&self) -> bool {
        self.coeffs
            .iter()
            .flatten()
            .any(|c| c.length_ratio.is_none())
    }

    /// The handle of [`MOLECULE`] once attached.
    pub fn molecule_id(&self) -> Option<PropId> {
        self.molecule
    }

    /// The molecule ID of the next inserted bonded template (every rank draws every
    /// template, so the IDs agree across ranks).
    pub fn next_molecule(&mut self) -> f64 {
        self.last_molecule += 1;
        self.last_molecule as f64
    }

    /// Raises the molecule counter to `max_seen`, the largest ID held by any particle
    /// (after a restart file or a data file).
    pub fn seen_molecules(&mut self, max_seen: f64) {
        if max_seen.is_finite() && max_seen > self.last_molecule as f64 {
            self.last_molecule = max_seen as u64;
        }
    }

    /// Sets the coefficients of bond type `t` (1-based); the damping and breaking styles
    /// must agree with those of the types set before (the fork keeps one of each).
    pub fn set_coeff(&mut self, t: usize, c: BondCoeff) -> Result<()> {
        if t == 0 || t > self.ntypes {
            return Err(Error::Invalid {
                what: "bond type",
                reason: format!("{t} is not within 1..={}", self.ntypes),
            });
        }
        for (k, o) in self.coeffs.iter().enumerate() {
            if let Some(o) = o {
                if k + 1 != t
                    && (o.damping.style() != c.damping.style()
                        || o.breaking.style() != c.breaking.style())
                {
                    return Err(Error::Invalid {
                        what: "bond_coeff",
                        reason: format!(
                            "type {t} has damping style {} and break style {}, type {} has {} and {}; \
                             LIGGGHTS_Flexible_Fibers applies one damping and one break style to all bond types",
                            c.damping.style(),
                            c.breaking.style(),
                            k + 1,
                            o.damping.style(),
                            o.breaking.style()
                        ),
                    });
                }
            }
        }
        self.coeffs[t - 1] = Some(c);
        Ok(())
    }

    /// Checks before a run: every bond type has coefficients, every creator's bond type
    /// exists and its cutoff (a relative one times twice the largest radius `rmax`) lies
    /// within the neighbor cutoff `reach` (the ghosts' reach: a pair across two ranks
    /// must be seen by both).
    pub fn check(&self, reach: f64, rmax: f64) -> Result<()> {
        if let Some(t) = self.coeffs.iter().position(Option::is_none) {
            return Err(Error::Invalid {
                what: "bond_coeff",
                reason: format!("bond type {} has no coefficients", t + 1),
            });
        }
        for c in &self.creators {
            if c.btype == 0 || c.btype as usize > self.ntypes {
                return Err(Error::Invalid {
                    what: "fix bond/create/gran",
                    reason: format!(
                        "{}: bond type {} is not within 1..={}",
                        c.id, c.btype, self.ntypes
                    ),
                });
            }
            let cut = c.distance(rmax);
            if c.every > 0 && cut > reach {
                return Err(Error::Invalid {
                    what: "fix bond/create/gran",
                    reason: format!(
                        "{}: the cutoff {cut} exceeds the neighbor cutoff {reach} (twice the largest radius plus the skin), \
                         the reach of the ghost particles; raise the skin with `neighbor`",
                        c.id
                    ),
                });
            }
        }
        Ok(())
    }

    /// The side of owned particle `i` of a bond of type `t` to the particle tagged
    /// `partner` (owned here, or on another rank, which adds the other side), just
    /// inserted: made by [`GranBonds::make_pending`].
    pub fn add_pending(&mut self, i: usize, partner: Tag, t: u32) {
        self.pending.push((i, partner, t));
    }

    /// Makes the pending bonds of inserted templates (their particles have tags now);
    /// a particle with more bonds than `bonds_per_atom` is an error.
    pub fn make_pending(&mut self, p: &mut Particles) -> Result<()> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let Some(id) = self.prop else { return Ok(()) };
        let (m, w) = (self.per_atom, self.width());
        for (me, tag, t) in std::mem::take(&mut self.pending) {
            if t == 0 || t as usize > self.ntypes {
                return Err(Error::Invalid {
                    what: "bonded template",
                    reason: format!("bond type {t} is not within 1..={}", self.ntypes),
                });
            }
            let row = &mut p.props[id.0].data[me * w..(me + 1) * w];
            let s = Self::count(row);
            if s >= m {
                return Err(Error::Invalid {
                    what: "bonded template",
                    reason: format!(
                        "particle {} would get more than bonds_per_atom = {m} bonds",
                        p.tag[me]
                    ),
                });
            }
            let h = &mut row[s * SLOT..(s + 1) * SLOT];
            h.fill(0.0);
            h[TAG] = tag as f64;
            h[TYPE] = t as f64;
        }
        Ok(())
    }

    /// The intact bonds of particle `i` that are turned on, as (partner's tag, type), in
    /// slot order (for data files).
    pub fn intact(&self, p: &Particles, i: usize) -> Vec<(Tag, u32)> {
        let Some(id) = self.prop else {
            return Vec::new();
        };
        p.props[id.0]
            .get(i)
            .chunks_exact(SLOT)
            .filter(|s| s[TYPE] > 0.0 && s[BROKEN] == INTACT)
            .map(|s| (s[TAG] as Tag, s[TYPE] as u32))
            .collect()
    }

    /// Bonds held by owned particle `i`: its slots with a partner.
    fn count(slots: &[f64]) -> usize {
        slots.chunks_exact(SLOT).filter(|s| s[TYPE] != 0.0).count()
    }

    /// Bonds counted once each (by the sphere of the lower tag), broken ones included
    /// until the next re-neighboring except those of break styles 3 to 5 broken by
    /// stress (and separating ones): thermo `numbonds` on this rank.
    pub fn count_local(&self, p: &Particles) -> u64 {
        let Some(id) = self.prop else { return 0 };
        let data = &p.props[id.0];
        let counts = |s: &[f64]| s[TYPE] != 0.0 && (s[BROKEN] == INTACT || s[BROKEN] == BROKE);
        (0..p.nlocal())
            .map(|i| {
                data.get(i)
                    .chunks_exact(SLOT)
                    .filter(|s| counts(s) && p.tag[i] < s[TAG] as Tag)
                    .count() as u64
            })
            .sum()
    }

    /// Drops the broken bonds (at a re-neighboring) and finds each bond's partner.
    pub fn link(&mut self, p: &mut Particles) -> Result<()> {
        let Some(id) = self.prop else { return Ok(()) };
        let w = self.width();
        for i in 0..p.nlocal() {
            let row = &mut p.props[id.0].data[i * w..(i + 1) * w];
            keep_slots(row, |h| h[TYPE] != 0.0 && !broken(h[BROKEN]));
        }
        self.resolve(p)
    }

    /// Finds each bond's partner among the owned particles and ghosts (the image nearest
    /// to the sphere). A partner that is not there is an error.
    fn resolve(&mut self, p: &Particles) -> Result<()> {
        let Some(id) = self.prop else { return Ok(()) };
        let (m, n, nl) = (self.per_atom, p.len(), p.nlocal());
        let mut by_tag: Vec<(Tag, u32)> = (0..n).map(|i| (p.tag[i], i as u32)).collect();
        by_tag.sort_unstable();
        self.links.clear();
        self.links.resize(nl * m, NONE);
        for i in 0..nl {
            for (s, h) in p.props[id.0].get(i).chunks_exact(SLOT).enumerate() {
                if h[TYPE] == 0.0 {
                    continue;
                }
                let t = h[TAG] as Tag;
                let lo = by_tag.partition_point(|e| e.0 < t);
                let hi = by_tag.partition_point(|e| e.0 <= t);
                let best = by_tag[lo..hi].iter().map(|e| e.1).min_by(|&u, &v| {
                    let du = (p.x[u as usize] - p.x[i]).length_squared();
                    let dv = (p.x[v as usize] - p.x[i]).length_squared();
                    du.total_cmp(&dv)
                });
                match best {
                    Some(j) => self.links[i * m + s] = j,
                    // A turned-off bond (`delete_bonds`) needs no partner.
                    None if broken(h[BROKEN]) || h[TYPE] < 0.0 => {}
                    None => {
                        return Err(Error::Invalid {
                            what: "bond/gran",
                            reason: format!(
                                "particle {} is bonded to particle {t}, which is neither on this rank nor one of its ghosts \
                                 (a bond longer than the ghost cutoff, or a bonded particle lost)",
                                p.tag[i]
                            ),
                        });
                    }
                }
            }
        }
        Ok(())
    }

    /// The bond forces and torques added to the owned particles' `f` and `torque`; each
    /// bond's history advances (at a run's set-up too, as in the fork). A bond one of
    /// whose spheres has its centre near a face of the box `domain` that is not periodic
    /// breaks, without acting (the forks' rule, before any force: a fibre hitting a floor
    /// on the box's face loses its bonds there): within 0.75 of the sphere's radius in
    /// Flexible_Fibers' form, within the neighbor `skin` in LIGGGHTS-PFM's.
    pub fn forces(
        &mut self,
        p: &mut Particles,
        dt: f64,
        domain: &crate::domain::Domain,
        skin: f64,
    ) {
        let (lo, hi, periodic) = (domain.boxlo, domain.boxhi, domain.periodicity());
        let near_face = move |x: DVec3, m: f64| {
            (0..3).any(|k| !periodic[k] && (x[k] < lo[k] + m || x[k] > hi[k] - m))
        };
        let Some(id) = self.prop else { return };
        let (m, nl, w) = (self.per_atom, p.nlocal(), self.width());
        if nl == 0 {
            return;
        }
        let coeffs = &self.coeffs;
        let links = &self.links;
        let (view, f, torque, props, _) = crate::par::View::split(p);
        let (data, temp) = match self.temp {
            // Two distinct properties: the bonds written, the temperature read.
            Some(t) => {
                let (lo, hi) = props.split_at_mut(id.0.max(t.0));
                let (b, t) = if id.0 < t.0 {
                    (&mut lo[id.0], &hi[0])
                } else {
                    (&mut hi[0], &lo[t.0])
                };
                (&mut b.data[..nl * w], Some(&t.data[..]))
            }
            None => (&mut props[id.0].data[..nl * w], None),
        };
        let one = |i: usize, fi: &mut DVec3, ti: &mut DVec3, row: &mut [f64]| {
            for s in 0..m {
                let h = &mut row[s * SLOT..(s + 1) * SLOT];
                // Empty, turned off (`delete_bonds`) or broken.
                if h[TYPE] <= 0.0 || broken(h[BROKEN]) {
                    continue;
                }
                let j = links.get(i * m + s).copied().unwrap_or(NONE);
                if j == NONE {
                    continue;
                }
                let j = j as usize;
                let side = |k: usize| Side {
                    x: view.x[k],
                    v: view.v[k],
                    w: view.omega[k],
                    r: view.radius[k],
                    m: view.rmass[k],
                    t: temp.map_or(0.0, |t| t[k]),
                };
                let first = view.tag[i] < view.tag[j];
                let (a, b) = if first {
                    (side(i), side(j))
                } else {
                    (side(j), side(i))
                };
                let Some(c) = coeffs[h[TYPE] as usize - 1].as_ref() else {
                    continue;
                };
                let margin = |k: usize| match c.length_ratio {
                    None => 0.75 * view.radius[k],
                    Some(_) => skin,
                };
                if near_face(view.x[i], margin(i)) || near_face(view.x[j], margin(j)) {
                    h[BROKEN] = BROKE;
                    continue;
                }
                if h[BROKEN] == SEPARATING {
                    match push(&a, &b, c, h) {
                        Some(fa) if first => *fi += fa,
                        Some(fa) => *fi -= fa,
                        None => h[BROKEN] = GONE,
                    }
                    continue;
                }
                let (l, outcome) = bond(&a, &b, c, h, dt);
                put3(h, FORCE, l.fe);
                put3(h, TORQUE, l.me);
                if first {
                    *fi += l.f;
                    *ti += l.ta;
                } else {
                    *fi -= l.f;
                    *ti += l.tb;
                }
                match outcome {
                    Outcome::Holds => {}
                    Outcome::Breaks if c.breaking.leaves_at_once() => h[BROKEN] = GONE,
                    Outcome::Breaks => h[BROKEN] = BROKE,
                    Outcome::Separates => h[BROKEN] = SEPARATING,
                }
            }
        };
        let (f, t) = (&mut f[..nl], &mut torque[..nl]);
        if crate::par::parallel(nl) {
            let chunk = crate::par::CHUNK;
            f.par_chunks_mut(chunk)
                .zip(t.par_chunks_mut(chunk))
                .zip(data.par_chunks_mut(chunk * w))
                .enumerate()
                .for_each(|(c, ((fc, tc), dc))| {
                    for k in 0..fc.len() {
                        one(
                            c * chunk + k,
                            &mut fc[k],
                            &mut tc[k],
                            &mut dc[k * w..(k + 1) * w],
                        );
                    }
                });
        } else {
            for i in 0..nl {
                one(i, &mut f[i], &mut t[i], &mut data[i * w..(i + 1) * w]);
            }
        }
    }

    /// Creates the bonds of the creators due at `step` between the owned particles and
    /// their partners (owned or ghosts) closer than a creator's cutoff; returns how many.
    /// Each rank finds the pairs of its owned particles itself (the neighbor list holds a
    /// pair across two ranks on one of them only), so both spheres of a bond across
    /// ranks get it.
    pub fn create(
        &mut self,
        p: &mut Particles,
        step: u64,
        exclude: &crate::neighbor::Exclusions,
    ) -> Result<u64> {
        let Some(id) = self.prop else { return Ok(0) };
        let due: Vec<usize> = (0..self.creators.len())
            .filter(|&k| self.creators[k].due(step))
            .collect();
        if due.is_empty() {
            return Ok(0);
        }
        let (m, nl, w) = (self.per_atom, p.nlocal(), self.width());
        let mut total = 0;
        let mut wrote = false;
        for k in due {
            let c = self.creators[k].clone();
            let mut made = 0;
            // Candidates (lower tag, higher tag, index of lower, index of higher).
            let mut cand: Vec<(Tag, Tag, usize, usize)> = Vec::new();
            let rmax = p.radius.iter().copied().fold(0.0, f64::max);
            for (i, j) in near_pairs(p, c.distance(rmax)) {
                let (i, j) = (i as usize, j as usize);
                let rsq = (p.x[j] - p.x[i]).length_squared();
                if !c.close(rsq, p.radius[i], p.radius[j]) {
                    continue;
                }
                let (ti, tj) = (p.ty[i], p.ty[j]);
                let types = (ti == c.itype && tj == c.jtype) || (ti == c.jtype && tj == c.itype);
                if !types || p.mask[i] & c.groupbit == 0 || p.mask[j] & c.groupbit == 0 {
                    continue;
                }
                // The forks create bonds from the neighbor list: a pair that
                // `neigh_modify exclude` leaves out never bonds (measured in LIGGGHTS-PFM).
                if exclude.excludes(p, i, j) {
                    continue;
                }
                let (a, b) = if p.tag[i] < p.tag[j] { (i, j) } else { (j, i) };
                cand.push((p.tag[a], p.tag[b], a, b));
            }
            cand.sort_unstable();
            cand.dedup_by(|x, y| x.0 == y.0 && x.1 == y.1);
            // New bonds per particle at this step, by the owned particle (or remote ghost)
            // they belong to.
            let mut fresh = vec![0usize; p.len()];
            let owner = |k: usize| {
                let o = p.origin(k);
                if o >= REMOTE_GHOST {
                    k
                } else {
                    o
                }
            };
            let data = &p.props[id.0].data;
            let row = |k: usize| &data[k * w..(k + 1) * w];
            let bonded = |k: usize, t: Tag| {
                row(k)
                    .chunks_exact(SLOT)
                    .any(|s| s[TYPE] != 0.0 && s[TAG] as Tag == t)
            };
            let mut plan: Vec<(usize, usize)> = Vec::new();
            let mut held: Vec<usize> = (0..p.len()).map(|k| Self::count(row(k))).collect();
            // Bonds of the creator's type at the step's start, for `iparam`/`jparam`.
            let typed = |k: usize| c.typed(row(k));
            for &(_, _, a, b) in &cand {
                let (oa, ob) = (owner(a), owner(b));
                if oa == ob || bonded(a, p.tag[b]) {
                    continue;
                }
                if fresh[oa] >= c.per_step || fresh[ob] >= c.per_step {
                    continue;
                }
                if held[oa] >= m || held[ob] >= m {
                    continue;
                }
                if !c.room(p.ty[oa], typed(oa)) || !c.room(p.ty[ob], typed(ob)) {
                    continue;
                }
                if c.fraction < 1.0 {
                    let (ua, ub) = (c.draw(p.tag[oa], step), c.draw(p.tag[ob], step));
                    if 0.5 * (ua + ub) >= c.fraction {
                        continue;
                    }
                }
                fresh[oa] += 1;
                fresh[ob] += 1;
                held[oa] += 1;
                held[ob] += 1;
                plan.push((oa, ob));
                // Each bond counted once over the ranks: by the owner of its lower tag.
                if oa < nl {
                    made += 1;
                }
            }
            let limited = c.limits.iter().any(|l| l.max > 0);
            wrote |= !plan.is_empty();
            for (oa, ob) in plan {
                let (ta, tb) = (p.tag[oa], p.tag[ob]);
                for (me, other) in [(oa, tb), (ob, ta)] {
                    if me >= nl {
                        continue;
                    }
                    let r = &mut p.props[id.0].data[me * w..(me + 1) * w];
                    let s = Self::count(r);
                    let h = &mut r[s * SLOT..(s + 1) * SLOT];
                    h.fill(0.0);
                    h[TAG] = other as f64;
                    h[TYPE] = c.btype as f64;
                    if limited {
                        // As the fork: after each new bond, a sphere whose count of the
                        // creator's bonds reaches its limit (by its type at that moment)
                        // turns into the limit's new type.
                        let l = c.limit(p.ty[me]);
                        if c.typed(r) == l.max {
                            p.ty[me] = l.new_type;
                        }
                    }
                }
            }
            // Every rank records every creation step, so that the front end can sum
            // the counts over the ranks.
            self.creators[k].made.push((step, made));
            total += made;
        }
        if wrote {
            self.resolve(p)?;
        }
        Ok(total)
    }

    /// The shortest bond time on this rank, √(m*/K_n) over the unbroken bonds (m* the
    /// pair's reduced mass; L₀, or the current length before the first evaluation):
    /// `fix check/timestep/bond` compares the time step with it, as the fork (its
    /// warning for two spheres of 7.147e6 kg on a bond of K_n = 7.854e9 N/m gives the
    /// time 0.021331 s). `None` without bonds.
    pub fn shortest_time(&self, p: &Particles) -> Option<f64> {
        let id = self.prop?;
        let m = self.per_atom;
        let mut t = f64::INFINITY;
        for i in 0..p.nlocal() {
            for (s, h) in p.props[id.0].get(i).chunks_exact(SLOT).enumerate() {
                let j = self.links.get(i * m + s).copied().unwrap_or(NONE);
                if h[TYPE] <= 0.0 || h[BROKEN] != INTACT || j == NONE {
                    continue;
                }
                let Some(c) = self.coeffs[h[TYPE] as usize - 1].as_ref() else {
                    continue;
                };
                let j = j as usize;
                let l0 = if h[LEN0] > 0.0 {
                    h[LEN0]
                } else if let Some(lb) = c.length_ratio {
                    lb * (p.radius[i] + p.radius[j])
                } else {
                    (p.x[j] - p.x[i]).length()
                };
                let rmin = p.radius[i].min(p.radius[j]);
                let (ro, ri) = (c.ro * rmin, c.ri * rmin);
                let kn = c.youngs * std::f64::consts::PI * (ro * ro - ri * ri) / l0;
                let ms = p.rmass[i] * p.rmass[j] / (p.rmass[i] + p.rmass[j]);
                t = t.min((ms / kn).sqrt());
            }
        }
        t.is_finite().then_some(t)
    }

    /// The bonds for output, each once (held by the lower tag), without those turned off
    /// by `delete_bonds`: (tag a, tag b, type,
    /// position of a, position of b, force on a, bending and twisting torque on a, L₀,
    /// broken).
    pub fn local_rows(&self, p: &Particles) -> Vec<BondRow> {
        let Some(id) = self.prop else {
            return Vec::new();
        };
        let m = self.per_atom;
        let data = &p.props[id.0];
        let mut out = Vec::new();
        for i in 0..p.nlocal() {
            for (s, h) in data.get(i).chunks_exact(SLOT).enumerate() {
                // Empty, turned off (`delete_bonds`), or held by the lower tag.
                if h[TYPE] <= 0.0 || (h[TAG] as Tag) < p.tag[i] {
                    continue;
                }
                let j = self.links.get(i * m + s).copied().unwrap_or(NONE);
                let xb = if j == NONE { p.x[i] } else { p.x[j as usize] };
                out.push(BondRow {
                    mask1: p.mask[i],
                    mask2: if j == NONE { 0 } else { p.mask[j as usize] },
                    atom1: p.tag[i],
                    atom2: h[TAG] as Tag,
                    btype: h[TYPE] as u32,
                    x1: p.x[i],
                    x2: xb,
                    force: get3(h, FORCE),
                    torque: get3(h, TORQUE),
                    len0: h[LEN0],
                    broken: broken(h[BROKEN]),
                    separating: h[BROKEN] == SEPARATING,
                });
            }
        }
        out
    }
}

/// Keeps the bond slots of a sphere's `row` for which `keep` holds, in order, at the
/// front; the slots after them are emptied.
fn keep_slots(row: &mut [f64], keep: impl Fn(&[f64]) -> bool) {
    let mut k = 0;
    for s in 0..row.len() / SLOT {
        let slot = s * SLOT;
        if keep(&row[slot..slot + SLOT]) {
            if k != s {
                row.copy_within(slot..slot + SLOT, k * SLOT);
            }
            k += 1;
        }
    }
    row[k * SLOT..].fill(0.0);
}

/// The pairs (i, j) of an owned particle i and an owned (j > i) or ghost particle j
/// closer than `cut`, found in cells of side `cut`.
fn near_pairs(p: &Particles, cut: f64) -> Vec<(u32, u32)> {
    use std::collections::HashMap;
    let (n, nl) = (p.len(), p.nlocal());
    let cell = |x: DVec3| {
        let c = (x / cut).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    };
    let mut cells: HashMap<(i64, i64, i64), Vec<u32>> = HashMap::new();
    for k in 0..n {
        cells.entry(cell(p.x[k])).or_default().push(k as u32);
    }
    let cut2 = cut * cut;
    let mut out = Vec::new();
    for i in 0..nl {
        let (cx, cy, cz) = cell(p.x[i]);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(v) = cells.get(&(cx + dx, cy + dy, cz + dz)) else {
                        continue;
                    };
                    for &j in v {
                        let ju = j as usize;
                        if (ju < nl && ju <= i) || (p.x[ju] - p.x[i]).length_squared() >= cut2 {
                            continue;
                        }
                        out.push((i as u32, j));
                    }
                }
            }
        }
    }
    out
}

/// True when the bonds `row` of a sphere (its values of [`PROP`]) hold a bond to the
/// sphere of tag `tag` that keeps their contact off under `disableNormalContact 1`: one
/// that has not left (intact, separating, or broken and not yet dropped at a
/// re-neighboring), as the fork's pair style tests the bond's type.
#[inline]
pub fn keeps_apart(row: &[f64], tag: Tag) -> bool {
    row.chunks_exact(SLOT)
        .any(|s| s[TYPE] != 0.0 && s[BROKEN] != GONE && s[TAG] as Tag == tag)
}

/// True when a sphere's bond slots `row` (its [`PROP`] values) hold a bond, broken or
/// not, until it is dropped at a re-neighboring.
pub fn holds_any(row: &[f64]) -> bool {
    row.chunks_exact(SLOT).any(|s| s[TYPE] != 0.0)
}

/// One bond as `compute property/local` reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BondRow {
    /// Group mask of the first sphere.
    pub mask1: u32,
    /// Group mask of the second sphere (0 when it is not found).
    pub mask2: u32,
    /// Tag of the first sphere (the lower tag).
    pub atom1: Tag,
    /// Tag of the second sphere.
    pub atom2: Tag,
    /// Bond type.
    pub btype: u32,
    /// Position of the first sphere.
    pub x1: DVec3,
    /// Position of the second sphere (the image bonded).
    pub x2: DVec3,
    /// Force of the bond on the first sphere.
    pub force: DVec3,
    /// Twisting and bending torque of the bond on the first sphere (without the lever
    /// arm of the shear force).
    pub torque: DVec3,
    /// Length at the first evaluation (0 before it).
    pub len0: f64,
    /// Broken since the last re-neighboring.
    pub broken: bool,
    /// Broken while its spheres overlap, pushing them apart (break styles 3 to 5; the
    /// fork reports its type negative).
    pub separating: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn coeff(damping: Damping) -> BondCoeff {
        BondCoeff::new(
            0.8,
            0.2,
            1e7,
            4e6,
            damping,
            Breaking::Stress {
                sigma: 1e32,
                tau: 1e32,
            },
        )
        .unwrap()
    }

    fn side(x: DVec3, v: DVec3, w: DVec3) -> Side {
        Side {
            x,
            v,
            w,
            r: 1e-3,
            m: 4.18879e-6,
            t: 0.0,
        }
    }

    /// A bond at rest at its length gives nothing; stretched by u it pulls with
    /// K_n u = Y A u / L₀; the shear increment is −K_t v_t dt with the rotation's
    /// R_a ω_a + R_b ω_b in v_t; equal and opposite twisting torques.
    #[test]
    fn the_first_increments_follow_the_formulas() {
        let c = coeff(Damping::None);
        let mut h = [0.0; SLOT];
        let a = side(DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        let b = side(DVec3::new(2e-3, 0.0, 0.0), DVec3::ZERO, DVec3::ZERO);
        let (l, _) = bond(&a, &b, &c, &mut h, 1e-7);
        assert_eq!(h[LEN0], 2e-3);
        assert_eq!(l.f, DVec3::ZERO);
        let area = std::f64::consts::PI * (0.64e-6 - 0.04e-6);
        let u = 1e-6;
        let b2 = side(DVec3::new(2e-3 + u, 0.0, 0.0), DVec3::ZERO, DVec3::ZERO);
        let mut h2 = h;
        let (l, _) = bond(&a, &b2, &c, &mut h2, 1e-7);
        let kn = 1e7 * area / 2e-3;
        assert!((l.f.x - kn * u).abs() < 1e-12 * kn * u, "{:?}", l.f);
        let a3 = side(
            DVec3::ZERO,
            DVec3::new(0.0, 0.02, 0.0),
            DVec3::new(0.0, 0.0, 3.0),
        );
        let mut h3 = h;
        let (l, _) = bond(&a3, &b, &c, &mut h3, 1e-7);
        let kt = 4e6 * area / 2e-3;
        // v_t = v + R ω × n = 0.02 + 1e-3·3·(z × x = y) = 0.023 along y.
        assert!((l.f.y + kt * 0.023 * 1e-7).abs() < 1e-12, "{:?}", l.f);
        let a4 = side(DVec3::ZERO, DVec3::ZERO, DVec3::new(5.0, 0.0, 0.0));
        let mut h4 = h;
        let (l, _) = bond(&a4, &b, &c, &mut h4, 1e-7);
        assert!((l.ta.x + l.tb.x).abs() < 1e-25 && l.ta.x < 0.0, "{l:?}");
    }

    /// Style-1 damping adds −2β√(m*K_n) v_n to the normal force.
    #[test]
    fn critical_damping_of_the_normal_force() {
        let beta = 0.5;
        let c = coeff(Damping::Critical { beta });
        let mut h = [0.0; SLOT];
        let a = side(DVec3::ZERO, DVec3::new(0.01, 0.0, 0.0), DVec3::ZERO);
        let b = side(DVec3::new(2e-3, 0.0, 0.0), DVec3::ZERO, DVec3::ZERO);
        let (l, _) = bond(&a, &b, &c, &mut h, 1e-7);
        let area = std::f64::consts::PI * (0.64e-6 - 0.04e-6);
        let kn = 1e7 * area / 2e-3;
        let want = -2.0 * beta * (0.5 * a.m * kn).sqrt() * 0.01;
        assert!(
            (l.f.x - want).abs() < 1e-12 * want.abs(),
            "{} {want}",
            l.f.x
        );
    }

    /// A stress above σ_c breaks the bond.
    #[test]
    fn stress_breaks() {
        let mut c = coeff(Damping::None);
        c.breaking = Breaking::Stress {
            sigma: 1.0,
            tau: 1e32,
        };
        let mut h = [0.0; SLOT];
        h[LEN0] = 2e-3;
        let a = side(DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        let b = side(DVec3::new(2.001e-3, 0.0, 0.0), DVec3::ZERO, DVec3::ZERO);
        assert_eq!(bond(&a, &b, &c, &mut h, 1e-7).1, Outcome::Breaks);
    }
}

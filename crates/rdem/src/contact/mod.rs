//! Granular contact law (SPEC §3), composed from sub-models: normal (hertz, hooke,
//! hooke/hysteresis, hertz/stiffness, hooke/stiffness, jkr, hysteretic/nonlinear1 and 2),
//! tangential (off, history, no_history,
//! incremental_history),
//! rolling friction (off, cdt, cdtnonlinear2, epsd, epsd2, epsd3) and cohesion (off, sjkr, sjkr2,
//! easo/capillary/viscous liquid bridges). Each sub-model is a zero-sized type; a
//! [`ContactModel`] value picks one of each and [`ContactModel::dispatch`] turns that
//! choice into one monomorphized kernel per pass, so the per-contact code has no dynamic
//! dispatch. Particle–particle and particle–wall contacts share [`contact`].

pub mod cohesion;
pub mod hysteretic;
pub mod jkr;
pub mod jkr_pfm;
pub mod liquid;
pub mod materials;
pub mod names;
pub mod normal;
pub mod rolling;
pub mod tangential;

use crate::error::{Error, Result};
use glam::DVec3;

pub use materials::{
    CoeffTable, HystereticProperties, LiquidProperties, Materials, Needs, PairCoeff,
};

/// The normal force laws, one row each: the kind, the law's type (a
/// [`normal::Normal`]), the type its kernels are compiled with, and its script name. The
/// kind enum, the names the script reads ([`names::NORMAL_MODELS`]) and the kernel
/// dispatch all come from this table. Laws that keep the same history and are seldom
/// used share a kernel type that picks the law per contact from [`Flags::normal`] (a
/// branch that goes the same way all run), so that rdem is compiled for fewer kernels.
macro_rules! normal_laws {
    ($($(#[$doc:meta])* $kind:ident => $law:ty, kernel $kern:ty, $name:literal;)*) => {
        /// Normal force model (`model ...`).
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum NormalKind {
            $($(#[$doc])* $kind,)*
        }

        impl NormalKind {
            /// Every kind with its script name, in the table's order.
            pub const NAMES: &[(&str, NormalKind)] = &[$(($name, NormalKind::$kind),)*];

            /// What the rest of rdem needs to know of the law ([`normal::LawTraits`]).
            pub fn traits(self) -> normal::LawTraits {
                match self {
                    $(Self::$kind => <$law as normal::Normal>::TRAITS,)*
                }
            }
        }

        impl ContactModel {
            /// [`ContactModel::dispatch`]'s first choice: the normal law.
            fn d_normal<V: Visitor>(&self, v: V) -> V::Output {
                match self.normal {
                    $(NormalKind::$kind => self.d_tan::<$kern, V>(v),)*
                }
            }
        }
    };
}

normal_laws! {
    /// `hertz`.
    Hertz => normal::Hertz, kernel normal::Hertz, "hertz";
    /// `hooke`.
    Hooke => normal::Hooke, kernel normal::Hooke, "hooke";
    /// `hooke/hysteresis` (Walton–Braun).
    HookeHysteresis => normal::HookeHysteresis, kernel normal::HookeHysteresis, "hooke/hysteresis";
    /// `hertz/stiffness`: the per-type-pair `kn`, `kt`, `gamman`, `gammat` given directly,
    /// each times √(R*δ) (the damping also times m*).
    HertzStiffness => normal::HertzStiffness, kernel normal::Stiffness, "hertz/stiffness";
    /// `hooke/stiffness`: the per-type-pair `kn`, `kt` and damping given directly
    /// (`gamman`, `gammat` times m*, or with `absolute_damping on` `gamman_abs`, `gammat_abs`).
    HookeStiffness => normal::HookeStiffness, kernel normal::Stiffness, "hooke/stiffness";
    /// `jkr` (LIGGGHTS_Flexible_Fibers, PICI): the JKR adhesive contact, which holds
    /// while the spheres are apart down to δ = −δ_c ([`jkr::Jkr`]).
    Jkr => jkr::Jkr, kernel jkr::Jkr, "jkr";
    /// `jkr/pfm`: LIGGGHTS-PFM's `model jkr`, with `cohesionEnergyDensity`, acting only
    /// while the spheres overlap ([`jkr_pfm::JkrPfm`]). A script's `model jkr` is this
    /// law when `cohesionEnergyDensity` is defined and `workOfAdhesion` is not
    /// ([`ContactModel::resolve_jkr`]).
    JkrPfm => jkr_pfm::JkrPfm, kernel jkr_pfm::JkrPfm, "jkr/pfm";
    /// `hysteretic/nonlinear1` (LIGGGHTS-INL): elasto-plastic, loading α k₁ δ², linear
    /// unloading, an adhesive branch ([`hysteretic`]).
    HystereticNonlinear1 => hysteretic::HystereticNonlinear, kernel hysteretic::HystereticNonlinear, "hysteretic/nonlinear1";
    /// `hysteretic/nonlinear2` (LIGGGHTS-INL): as nonlinear1 with exponential unloading
    /// ([`hysteretic`]; the two share one kernel).
    HystereticNonlinear2 => hysteretic::HystereticNonlinear, kernel hysteretic::HystereticNonlinear, "hysteretic/nonlinear2";
}

impl NormalKind {
    /// True for the models whose stiffness and damping come from `kn`, `kt`, `gamman`,
    /// `gammat` rather than from Young's modulus and the coefficient of restitution.
    pub fn is_stiffness(self) -> bool {
        self.traits().stiffness
    }
}

/// A vocabulary of sub-models, one row each: the kind and its script name. The kind enum
/// and its name table (`NAMES`, which [`names`] lists) come from this one declaration;
/// the kernel dispatch below matches every kind (a missing arm does not compile).
macro_rules! model_kinds {
    ($(#[$edoc:meta])* $Enum:ident { $($(#[$doc:meta])* $kind:ident = $name:literal,)* }) => {
        $(#[$edoc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum $Enum {
            $($(#[$doc])* $kind,)*
        }

        impl $Enum {
            /// Every kind with its script name, in the table's order.
            pub const NAMES: &[(&str, $Enum)] = &[$(($name, $Enum::$kind),)*];
        }
    };
}

model_kinds! {
    /// Tangential model (`tangential ...`).
    TangentialKind {
        /// `off`, LIGGGHTS 3.8's default when `tangential` is not given: no tangential
        /// force (and no `coefficientFriction` needed). Its kernel is `no_history`'s
        /// with the damping switched off ([`ContactModel::kernel_flags`]), which gives
        /// no force. (LIGGGHTS-PFM defaults to `no_history` and has no `off`.)
        Off = "off",
        /// `history`: incremental spring with Coulomb cap.
        History = "history",
        /// `no_history`: damping only, with Coulomb cap.
        NoHistory = "no_history",
        /// `incremental_history` (LIGGGHTS-PFM): the stored tangential force gains
        /// increments ([`tangential::IncrementalHistory`]).
        IncrementalHistory = "incremental_history",
    }
}

model_kinds! {
    /// Rolling friction model (`rolling_friction ...`).
    RollingKind {
        /// No rolling friction.
        Off = "off",
        /// `cdt`: constant directional torque.
        Cdt = "cdt",
        /// `cdtnonlinear2` (LIGGGHTS-INL): as `cdt` with the normal model's whole force.
        CdtNonlinear2 = "cdtnonlinear2",
        /// `epsd`: elastic–plastic spring–dashpot (Ai et al.).
        Epsd = "epsd",
        /// `epsd2`: Iwashita–Oda spring, no damping.
        Epsd2 = "epsd2",
        /// `epsd3`: as `epsd` with the rolling stiffness prefactor given by the user
        /// (`rollingStiffness`) instead of 2.25.
        Epsd3 = "epsd3",
    }
}

model_kinds! {
    /// Cohesion model (`cohesion ...`).
    CohesionKind {
        /// No cohesion.
        Off = "off",
        /// `sjkr`: F = k · (exact lens contact area).
        Sjkr = "sjkr",
        /// `sjkr2`: F = k · 2π δ (2R*).
        Sjkr2 = "sjkr2",
        /// `bond`: the parallel-bond model ([`crate::bond`]); the contact itself has no
        /// cohesion.
        Bond = "bond",
        /// `bond/nonlinear` (LIGGGHTS-INL): the bond with hysteretic normal force and
        /// torques ([`crate::bond::nonlinear`]).
        BondNonlinear = "bond/nonlinear",
        /// `easo/capillary/viscous`: liquid bridges ([`liquid`]).
        Easo = "easo/capillary/viscous",
    }
}

model_kinds! {
    /// Surface model (`surface ...`).
    SurfaceKind {
        /// `default`: smooth spheres.
        Default = "default",
        /// `multicontact`: each contact's overlap corrected for the particle's other
        /// contacts ([`crate::multicontact`], with `fix multicontact/halfspace`).
        Multicontact = "multicontact",
    }
}

/// Model keywords that are plain switches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Flags {
    /// `tangential_damping on|off` (default on).
    pub tangential_damping: bool,
    /// `limitForce on|off` (default off): no attractive normal contact force.
    pub limit_force: bool,
    /// `torsionTorque on|off` (rolling models, default off).
    pub torsion_torque: bool,
    /// `tangential_reduce on|off` (cohesion models, default off).
    pub tangential_reduce: bool,
    /// `absolute_damping on|off` (`hooke/stiffness` only, default off): the damping
    /// coefficients are `gamman_abs`, `gammat_abs` as given, not `gamman`, `gammat` times m*.
    pub absolute_damping: bool,
    /// The rolling law, for the kernel that chooses it per contact ([`rolling::Spring`]);
    /// set from the model's own field by [`ContactModel::kernel_flags`].
    pub(crate) rolling: RollingKind,
    /// The cohesion law, for the kernel that chooses it per contact ([`cohesion::Pull`]);
    /// set by [`ContactModel::kernel_flags`].
    pub(crate) cohesion: CohesionKind,
    /// The normal law, for the kernel that chooses it per contact
    /// ([`hysteretic::HystereticNonlinear`]); set by [`ContactModel::kernel_flags`].
    pub(crate) normal: NormalKind,
}

impl Default for Flags {
    fn default() -> Self {
        Self {
            tangential_damping: true,
            limit_force: false,
            torsion_torque: false,
            tangential_reduce: false,
            absolute_damping: false,
            rolling: RollingKind::Off,
            cohesion: CohesionKind::Off,
            normal: NormalKind::Hertz,
        }
    }
}

/// A full contact model selection, as `pair_style gran` or `fix wall/gran` give it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ContactModel {
    /// Normal model.
    pub normal: NormalKind,
    /// Tangential model.
    pub tangential: TangentialKind,
    /// Rolling friction model.
    pub rolling: RollingKind,
    /// Cohesion model.
    pub cohesion: CohesionKind,
    /// Surface model.
    pub surface: SurfaceKind,
    /// Switches.
    pub flags: Flags,
    /// Switches of `cohesion bond` (used only with [`CohesionKind::Bond`]).
    pub bond: crate::bond::BondFlags,
}

impl Default for ContactModel {
    fn default() -> Self {
        Self::hertz_history()
    }
}

impl ContactModel {
    /// `model hertz tangential history`, the most common choice.
    pub fn hertz_history() -> Self {
        Self {
            normal: NormalKind::Hertz,
            tangential: TangentialKind::History,
            rolling: RollingKind::Off,
            cohesion: CohesionKind::Off,
            surface: SurfaceKind::Default,
            flags: Flags::default(),
            bond: crate::bond::BondFlags::default(),
        }
    }

    /// The switches the kernels read: [`ContactModel::flags`] with the rolling and
    /// cohesion laws, which the kernels that serve several laws choose by.
    pub fn kernel_flags(&self) -> Flags {
        Flags {
            rolling: self.rolling,
            cohesion: self.cohesion,
            normal: self.normal,
            // `tangential off` runs the `no_history` kernel, which gives no force
            // without its damping.
            tangential_damping: self.flags.tangential_damping
                && self.tangential != TangentialKind::Off,
            ..self.flags
        }
    }

    /// Which optional material properties this model needs.
    pub fn needs(&self) -> Needs {
        Needs {
            no_tangential: self.tangential == TangentialKind::Off,
            rolling_friction: self.rolling != RollingKind::Off,
            rolling_damping: matches!(self.rolling, RollingKind::Epsd | RollingKind::Epsd3),
            rolling_stiffness: self.rolling == RollingKind::Epsd3,
            work_of_adhesion: self.normal.traits().adhesion,
            cohesion: matches!(self.cohesion, CohesionKind::Sjkr | CohesionKind::Sjkr2)
                || self.normal == NormalKind::JkrPfm,
            jkr_pfm: self.normal == NormalKind::JkrPfm,
            liquid: self.cohesion == CohesionKind::Easo,
            characteristic_velocity: self.normal.traits().characteristic_velocity,
            hysteresis: self.normal.traits().hysteresis,
            hysteretic_nonlinear: match self.normal {
                NormalKind::HystereticNonlinear1 => Some(1),
                NormalKind::HystereticNonlinear2 => Some(2),
                _ => None,
            },
            stiffness: if self.normal.is_stiffness() {
                Some(self.flags.absolute_damping)
            } else {
                None
            },
        }
    }

    /// Settles which JKR law a script's `model jkr` means, before a run: LIGGGHTS_Flexible_
    /// Fibers' and PICI's ([`NormalKind::Jkr`]) reads `workOfAdhesion`, LIGGGHTS-PFM's
    /// ([`NormalKind::JkrPfm`]) `cohesionEnergyDensity`. It is PFM's when only
    /// `cohesionEnergyDensity` is defined; with neither, the error names both.
    pub fn resolve_jkr(&mut self, m: &Materials) -> Result<()> {
        if self.normal != NormalKind::Jkr || !m.work_of_adhesion.is_empty() {
            return Ok(());
        }
        if m.cohesion_energy_density.is_empty() {
            return Err(Error::Invalid {
                what: "workOfAdhesion",
                reason: "model jkr needs fix property/global workOfAdhesion peratomtypepair \
                         (LIGGGHTS_Flexible_Fibers' and PICI's law, with resolutionJKR) or \
                         cohesionEnergyDensity peratomtypepair (LIGGGHTS-PFM's law)"
                    .into(),
            });
        }
        self.normal = NormalKind::JkrPfm;
        Ok(())
    }

    /// True with `cohesion bond` or `cohesion bond/nonlinear`.
    pub fn has_bonds(&self) -> bool {
        self.bond_law().is_some()
    }

    /// The bond law, with `cohesion bond` or `cohesion bond/nonlinear`.
    pub fn bond_law(&self) -> Option<crate::bond::Law> {
        match self.cohesion {
            CohesionKind::Bond => Some(crate::bond::Law::Parallel),
            CohesionKind::BondNonlinear => Some(crate::bond::Law::Nonlinear),
            _ => None,
        }
    }

    /// The bond law's history layout ([`crate::bond::Layout`]), with bonds.
    pub fn bond_layout(&self) -> Option<crate::bond::Layout> {
        self.bond_law().map(|l| l.layout())
    }

    /// Number of f64 history values per particle pair: the contact's, and with bonds
    /// the bond's around them ([`crate::bond`]: its vectors first, its flag and d₀ last).
    pub fn history_width(&self) -> usize {
        let w = self.dispatch(HistoryWidth);
        match self.bond_layout() {
            Some(l) => l.vec + w + l.pair_tail,
            None => w,
        }
    }

    /// True when the normal law's contact holds while the particles are apart (a JKR
    /// neck, [`normal::Normal::NECK`]).
    pub fn holds_apart(&self) -> bool {
        self.dispatch(Neck)
    }

    /// Number of f64 history values of the contact law alone (no bond).
    pub fn contact_history_width(&self) -> usize {
        self.dispatch(HistoryWidth)
    }

    /// Number of f64 history values per particle for a wall (as [`Self::history_width`],
    /// the bond's tail also holding the anchor point).
    pub fn wall_history_width(&self) -> usize {
        let w = self.dispatch(HistoryWidth);
        match self.bond_layout() {
            Some(l) => l.vec + w + l.wall_tail,
            None => w,
        }
    }

    /// Of the pair history values, how many leading ones change sign when the two
    /// particles of a pair swap roles (vectors attached to the i→j orientation).
    pub fn history_odd(&self) -> usize {
        let odd = self.dispatch(HistoryOdd);
        match self.bond_layout() {
            Some(l) => l.vec + odd,
            None => odd,
        }
    }

    /// Calls `v.visit::<K>()` with the kernel type `K` of this selection: the one place
    /// where the runtime choice becomes a type.
    pub fn dispatch<V: Visitor>(&self, v: V) -> V::Output {
        self.d_normal(v)
    }
    fn d_tan<N: normal::Normal, V: Visitor>(&self, v: V) -> V::Output {
        match self.tangential {
            TangentialKind::History => self.d_roll::<N, tangential::History, V>(v),
            TangentialKind::NoHistory | TangentialKind::Off => {
                self.d_roll::<N, tangential::NoHistory, V>(v)
            }
            TangentialKind::IncrementalHistory => {
                self.d_roll::<N, tangential::IncrementalHistory, V>(v)
            }
        }
    }
    // Rolling and cohesion laws that keep the same history share a kernel, which picks
    // the law per contact from `Flags` (a branch that goes the same way all run): with
    // one kernel per law, the passes were compiled for 360 kernels, most of rdem's build
    // time. `off` keeps kernels of its own: sharing them cost in.dense 9 % of its speed.
    fn d_roll<N: normal::Normal, T: tangential::Tangential, V: Visitor>(&self, v: V) -> V::Output {
        match self.rolling {
            RollingKind::Off => self.d_coh::<N, T, rolling::Off, V>(v),
            RollingKind::Cdt | RollingKind::CdtNonlinear2 => self.d_coh::<N, T, rolling::Cdt, V>(v),
            RollingKind::Epsd | RollingKind::Epsd2 | RollingKind::Epsd3 => {
                self.d_coh::<N, T, rolling::Spring, V>(v)
            }
        }
    }
    fn d_coh<N: normal::Normal, T: tangential::Tangential, R: rolling::Rolling, V: Visitor>(
        &self,
        v: V,
    ) -> V::Output {
        match self.cohesion {
            // `N::SELDOM` is a constant: only one of the two is compiled.
            CohesionKind::Off if N::SELDOM => v.visit::<Kernel<N, T, R, cohesion::Pull>>(),
            CohesionKind::Off => v.visit::<Kernel<N, T, R, cohesion::Off>>(),
            CohesionKind::Sjkr | CohesionKind::Sjkr2 => {
                v.visit::<Kernel<N, T, R, cohesion::Pull>>()
            }
            CohesionKind::Bond | CohesionKind::BondNonlinear => {
                v.visit::<Kernel<N, T, R, cohesion::Bonded>>()
            }
            CohesionKind::Easo => v.visit::<Kernel<N, T, R, liquid::Easo>>(),
        }
    }
}

/// Something to run with a concrete kernel type (a pair pass, a wall pass, ...).
pub trait Visitor {
    /// What the visit returns.
    type Output;
    /// Runs with kernel `K`.
    fn visit<K: ContactKernel>(self) -> Self::Output;
}

struct HistoryWidth;
impl Visitor for HistoryWidth {
    type Output = usize;
    fn visit<K: ContactKernel>(self) -> usize {
        K::HIST
    }
}
struct Neck;
impl Visitor for Neck {
    type Output = bool;
    fn visit<K: ContactKernel>(self) -> bool {
        K::NECK
    }
}
struct HistoryOdd;
impl Visitor for HistoryOdd {
    type Output = usize;
    fn visit<K: ContactKernel>(self) -> usize {
        K::HIST_ODD
    }
}

/// Geometry and kinematics of one contact, as seen from particle i. For a wall, j is the
/// wall: `rj = ∞`, `inertia_j = ∞`, `cj = 0`, `wj = 0`.
#[derive(Debug, Clone, Copy)]
pub struct Geom {
    /// Unit normal pointing from j to i.
    pub n: DVec3,
    /// Overlap δ > 0.
    pub delta: f64,
    /// Centre distance (for a wall: distance from the wall to the centre).
    pub dist: f64,
    /// Radius of i.
    pub ri: f64,
    /// Radius of j (∞ for a wall).
    pub rj: f64,
    /// Effective radius R*.
    pub r_star: f64,
    /// Effective mass m*.
    pub m_star: f64,
    /// Lever arm of i, r_i − δ/2.
    pub ci: f64,
    /// Lever arm of j, r_j − δ/2 (0 for a wall).
    pub cj: f64,
    /// v_i − v_j (for a wall: v_i − v_wall).
    pub vr: DVec3,
    /// Angular velocity of i.
    pub wi: DVec3,
    /// Angular velocity of j (0 for a wall).
    pub wj: DVec3,
    /// Factor on ω_i in the rolling models: 1 for a pair; for a wall LIGGGHTS uses
    /// c_i/(r_i − δ) = (r_i − δ/2)/(r_i − δ).
    pub roll_scale: f64,
    /// Rolling inertia of i about the contact, I_i + m_i r_i².
    pub inertia_i: f64,
    /// Rolling inertia of j about the contact (∞ for a wall).
    pub inertia_j: f64,
    /// Timestep.
    pub dt: f64,
    /// Surface liquid content of i (liquid-bridge models; 0 otherwise).
    pub lq_i: f64,
    /// Surface liquid content of j (0 for a wall).
    pub lq_j: f64,
    /// Whether this evaluation advances the contact history. False for the force
    /// evaluation of a run's set-up, as in LIGGGHTS: the tangential spring is used as
    /// stored, rolling springs add their increment without storing it, and hysteresis
    /// records the largest overlap but does not move onto its adhesive branch.
    pub update: bool,
}

impl Geom {
    /// The contact of a particle (radius `r`, mass `m`, velocity relative to the wall
    /// surface `vr`, spin `wi`) with a wall at distance `dist` < r along the unit normal
    /// `n` from the wall to the centre: j has infinite radius and mass, no spin and no
    /// lever arm, and the rolling models see ω_i scaled by c_i/(r − δ) as in LIGGGHTS.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn wall(
        n: DVec3,
        dist: f64,
        r: f64,
        m: f64,
        vr: DVec3,
        wi: DVec3,
        dt: f64,
        update: bool,
    ) -> Self {
        let delta = r - dist;
        Self {
            n,
            delta,
            dist,
            ri: r,
            rj: f64::INFINITY,
            r_star: r,
            m_star: m,
            ci: r - 0.5 * delta,
            cj: 0.0,
            vr,
            wi,
            wj: DVec3::ZERO,
            roll_scale: (r - 0.5 * delta) / dist,
            inertia_i: (crate::particles::INERTIA_SPHERE + 1.0) * m * r * r,
            inertia_j: f64::INFINITY,
            dt,
            lq_i: 0.0,
            lq_j: 0.0,
            update,
        }
    }
}

/// Result of one contact: the force on i (j gets the opposite) and the torques on both.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactForce {
    /// Force on i.
    pub f_i: DVec3,
    /// Torque on i.
    pub t_i: DVec3,
    /// Torque on j.
    pub t_j: DVec3,
    /// Normal force magnitude (positive = repulsive), cohesion included.
    pub fn_total: f64,
}

/// What the normal sub-model hands on to the others.
#[derive(Debug, Clone, Copy, Default)]
pub struct NormalOut {
    /// Normal contact force, elastic plus damping, after `limitForce` (positive = repulsive).
    pub fn_contact: f64,
    /// Elastic part alone.
    pub fn_elastic: f64,
    /// The normal load that sets the Coulomb and rolling limits and the unloading test of
    /// `tangential incremental_history`: [`NormalOut::fn_contact`] for every law but
    /// LIGGGHTS-PFM's jkr, which takes Hertz's force there ([`jkr_pfm`]).
    pub fn_load: f64,
    /// Normal stiffness k_n.
    pub kn: f64,
    /// Tangential stiffness k_t.
    pub kt: f64,
    /// Tangential damping coefficient γ_t.
    pub gamma_t: f64,
}

/// A complete contact law: one type per sub-model combination.
pub trait ContactKernel {
    /// History values per contact.
    const HIST: usize;
    /// Leading history values that flip sign when i and j swap.
    const HIST_ODD: usize;
    /// True for a liquid-bridge model: it reads the liquid contents ([`Geom::lq_i`]) and
    /// acts on pairs that do not touch ([`ContactKernel::separated`]); its history is the
    /// last [`ContactKernel::BRIDGE_HIST`] values, which a separation does not clear.
    const BRIDGE: bool;
    /// History values of the bridge (at the end of the history).
    const BRIDGE_HIST: usize;
    /// True for the kernels of `cohesion bond` ([`cohesion::Bonded`]): the passes compile
    /// their bond code only for these.
    const BONDS: bool;
    /// True when the normal law's contact holds while the particles are apart
    /// ([`normal::Normal::NECK`]): the passes then ask [`ContactKernel::holds`].
    const NECK: bool;
    /// Force and torques of one contact; `hist` has `HIST` values.
    fn contact(g: &Geom, c: &PairCoeff, flags: Flags, hist: &mut [f64]) -> ContactForce;
    /// Whether the contact of a pair apart by −`delta` still holds (only for `NECK`
    /// kernels; `hist` is the whole contact history): see [`normal::Normal::holds`].
    fn holds(delta: f64, r_star: f64, c: &PairCoeff, hist: &mut [f64], update: bool) -> bool;
    /// A listed pair that does not touch (only for `BRIDGE` kernels): `hist` is the
    /// bridge's history.
    fn separated(s: &liquid::Separated, c: &PairCoeff, hist: &mut [f64]) -> cohesion::Bridge;
}

/// The kernel made of normal model `N`, tangential `T`, rolling `R` and cohesion `C`.
pub struct Kernel<N, T, R, C>(std::marker::PhantomData<(N, T, R, C)>);

impl<N: normal::Normal, T: tangential::Tangential, R: rolling::Rolling, C: cohesion::Cohesion>
    ContactKernel for Kernel<N, T, R, C>
{
    // Layout: [tangential vector | rolling | tangential scalars | normal | cohesion]; the
    // first two are vectors tied to i→j.
    const HIST: usize = T::HIST + R::HIST + N::HIST + C::HIST;
    const HIST_ODD: usize = T::ODD + R::HIST;
    const BRIDGE: bool = C::BRIDGE;
    const BRIDGE_HIST: usize = C::HIST;
    const BONDS: bool = C::BONDS;
    const NECK: bool = N::NECK;

    // Inlined into each pass (the hot loops), except in this crate's unit-test build:
    // there each kernel's law is compiled once and called, which computes the same bits
    // (inlining does not change floating-point results in Rust) and builds in a fraction
    // of the time. Every other build, the integration tests' among them, inlines it.
    #[cfg_attr(not(test), inline(always))]
    #[cfg_attr(test, inline(never))]
    fn contact(g: &Geom, c: &PairCoeff, flags: Flags, hist: &mut [f64]) -> ContactForce {
        contact::<N, T, R, C>(g, c, flags, hist)
    }

    #[inline(always)]
    fn holds(delta: f64, r_star: f64, c: &PairCoeff, hist: &mut [f64], update: bool) -> bool {
        let at = T::HIST + R::HIST;
        N::holds(delta, r_star, c, &mut hist[at..at + N::HIST], update)
    }

    #[inline(always)]
    fn separated(s: &liquid::Separated, c: &PairCoeff, hist: &mut [f64]) -> cohesion::Bridge {
        C::separated(s, c, hist)
    }
}

/// Forgets the history of a contact that has ended. Only what is set is written (the
/// step after a separation): a plain fill would be a memset call for every listed pair
/// out of contact, every step.
#[inline(always)]
pub fn clear_history(hist: &mut [f64]) {
    if hist.iter().any(|&h| h != 0.0) {
        hist.iter_mut().for_each(|h| *h = 0.0);
    }
}

/// One contact: normal force, cohesion, tangential force with Coulomb cap, torques from the
/// tangential force on the lever arms c_i, c_j, and the rolling torque.
#[inline(always)]
pub fn contact<
    N: normal::Normal,
    T: tangential::Tangential,
    R: rolling::Rolling,
    C: cohesion::Cohesion,
>(
    g: &Geom,
    c: &PairCoeff,
    flags: Flags,
    hist: &mut [f64],
) -> ContactForce {
    let (h_tan, rest) = hist.split_at_mut(T::ODD);
    let (h_roll, rest) = rest.split_at_mut(R::HIST);
    let (h_tan_even, rest) = rest.split_at_mut(T::HIST - T::ODD);
    let (h_norm, h_coh) = rest.split_at_mut(N::HIST);
    let vn = g.vr.dot(g.n);
    if N::NECK && g.delta <= 0.0 {
        // A JKR neck, apart: the normal law alone; the springs start anew at the next touch.
        let no = N::normal(g, c, vn, flags, h_norm);
        if g.update {
            h_tan.fill(0.0);
            h_roll.fill(0.0);
            h_tan_even.fill(0.0);
        }
        return ContactForce {
            f_i: no.fn_contact * g.n,
            t_i: DVec3::ZERO,
            t_j: DVec3::ZERO,
            fn_total: no.fn_contact,
        };
    }
    let vt = g.vr - vn * g.n;
    // Relative tangential velocity of the contact points.
    let vt_rel = vt - (g.ci * g.wi + g.cj * g.wj).cross(g.n);
    let no = N::normal(g, c, vn, flags, h_norm);
    // A liquid bridge adds a viscous tangential force (on the same lever arms as the
    // tangential model's); the other cohesion models only pull.
    let (f_coh, ft_coh) = if C::BRIDGE {
        C::touching(g, c, flags, vt_rel, h_coh)
    } else {
        (C::force(g, c, flags), DVec3::ZERO)
    };
    // The normal load that sets the Coulomb and rolling limits: the normal model's force
    // (damping included); with `tangential_reduce on` the cohesive pull is added to it and
    // the magnitude taken, as LIGGGHTS 3.8 does (its manual words it the other way round).
    let load = if flags.tangential_reduce {
        (no.fn_load - f_coh).abs()
    } else {
        no.fn_load.abs()
    };
    let mut ft = T::force(g, c, &no, load, vt_rel, flags, h_tan, h_tan_even);
    if C::BRIDGE {
        ft += ft_coh;
    }
    let fn_total = no.fn_contact - f_coh;
    let f_i = fn_total * g.n + ft;
    let nxft = g.n.cross(ft);
    let mut t_i = -g.ci * nxft;
    let mut t_j = -g.cj * nxft;
    let tr = R::torque(g, c, &no, load, flags, h_roll);
    t_i += tr;
    t_j -= tr;
    ContactForce {
        f_i,
        t_i,
        t_j,
        fn_total,
    }
}

#[cfg(test)]
mod tests;

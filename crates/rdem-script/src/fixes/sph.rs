//! The SPH fix styles (`atom_style sph`, see [`rdem::sph`]): `sph/density/continuity`,
//! `sph/density/summation`,
//! `sph/density/corr`, `sph/pressure`, `nve/sph`, `nve/sph/stationary`, `wall/sph`. Each
//! becomes an engine fix; the kernel of the density fixes and the wall is set by
//! `set group all sphkernel NAME` after them, as in the LIGGGHTS tutorials.

use rdem::region::MAX_SURFACE_CONTACTS;
use rdem::sph::{Eos, SphFix, SphRegionWall, SphWall};
use rdem::{Fix, FixKind};

use super::engine::{engine_fix, InEngine};
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Accept, Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row of `sph/density/continuity`.
pub(super) const ROW_CONTINUITY: FixRow = style(
    "sph/density/continuity",
    continuity,
    Stages::ENGINE,
    "the SPH density rate dρ/dt = Σ m_b (v_a − v_b)·∇W_ab (atom_style sph)",
);
/// The registry row of `sph/density/summation`.
pub(super) const ROW_SUMMATION: FixRow = style(
    "sph/density/summation",
    summation,
    Stages::ENGINE,
    "the SPH density by summation ρ_a = Σ m_b W_ab (a itself included)",
);
/// The registry row of `sph/density/corr`.
pub(super) const ROW_CORR: FixRow = style(
    "sph/density/corr",
    corr,
    Stages::ENGINE,
    "`shepard every N`: the Shepard density filter every N steps",
);
/// The registry row of `sph/pressure`.
pub(super) const ROW_PRESSURE: FixRow = style(
    "sph/pressure",
    pressure,
    Stages::ENGINE,
    "`Tait B ρ0 γ`, `relativ B ρ0`, `absolut B`: the SPH equation of state",
);
/// The registry row of `nve/sph`.
pub(super) const ROW_NVE: FixRow = style(
    "nve/sph",
    nve,
    Stages::ENGINE,
    "velocity Verlet for SPH particles, with their density",
);
/// The registry row of `nve/sph/stationary`.
pub(super) const ROW_NVE_STATIONARY: FixRow = style(
    "nve/sph/stationary",
    nve_stationary,
    Stages::ENGINE,
    "SPH boundary particles: their density evolves, they do not move",
);
/// The registry row of `wall/sph`.
pub(super) const ROW_WALL: FixRow = style(
    "wall/sph",
    wall,
    Stages::ENGINE,
    "`xplane|yplane|zplane lo hi r0 D` (lo, hi a position or NULL): a repulsive SPH wall",
)
.notes("the force D((r0/r)⁴ − (r0/r)²) pushes a particle within r0 of a plane away from it, as LIGGGHTS 3.8 (measured)");

/// The registry row of `wall/region/sph`.
pub(super) const ROW_WALL_REGION: FixRow = style(
    "wall/region/sph",
    wall_region,
    Stages::ENGINE.and(Stages::PRE_STEP),
    "`region-ID r0 D`: the wall/sph force from each part of its surface within r0, plus the pressure force of the particle's copy at the wall",
)
.notes("block, sphere, cylinder, cone and plane regions, side in (each face, a cylinder's or cone's side and its finite end caps) or out (the nearest point of the shape), and unions and intersections of them, either side, as LAMMPS' region surfaces; a moving region (move/rotate) is placed before each step; mesh/tet regions stop with a located error");

/// The SPH fixes need atom_style sph.
fn need_sph(sim: &Sim, a: &Args, head: &FixHead) -> CmdResult {
    if !sim.setup.sph {
        return Err(a.error_at(
            STYLE_WORD,
            format!("fix {} needs atom_style sph", head.style),
            None,
        ));
    }
    Ok(())
}

fn continuity(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    a.done()?;
    engine_fix(
        sim,
        a,
        head,
        FixKind::Sph(SphFix::Continuity { kernel: None }),
    )
}

fn summation(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    a.done()?;
    engine_fix(
        sim,
        a,
        head,
        FixKind::Sph(SphFix::Summation { kernel: None }),
    )
}

fn corr(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    a.keyword("sph/density/corr style", &["shepard"])?;
    a.keyword("shepard keyword", &["every"])?;
    let every = a.count("every N")?;
    if every == 0 {
        return Err(a.error_prev("every must be > 0", None));
    }
    a.done()?;
    engine_fix(
        sim,
        a,
        head,
        FixKind::Sph(SphFix::Shepard {
            every,
            kernel: None,
        }),
    )
}

fn pressure(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    let eos = match a.keyword("equation of state", &["Tait", "relativ", "absolut"])? {
        "Tait" => Eos::Tait {
            b: a.f64("B")?,
            rho0: a.positive("density0")?,
            gamma: a.f64("gamma")?,
        },
        "relativ" => Eos::Relativ {
            b: a.f64("B")?,
            rho0: a.f64("density0")?,
        },
        _ => Eos::Absolut { b: a.f64("B")? },
    };
    a.done()?;
    engine_fix(sim, a, head, FixKind::Sph(SphFix::Pressure(eos)))
}

fn nve(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    a.done()?;
    engine_fix(sim, a, head, FixKind::Sph(SphFix::Nve))
}

fn nve_stationary(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    a.done()?;
    engine_fix(sim, a, head, FixKind::Sph(SphFix::NveStationary))
}

fn wall(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    let axis = match a.keyword("wall/sph style", &["xplane", "yplane", "zplane"])? {
        "xplane" => 0,
        "yplane" => 1,
        _ => 2,
    };
    let mut planes = [None; 2];
    for (k, plane) in planes.iter_mut().enumerate() {
        let what = ["lo (a position or NULL)", "hi (a position or NULL)"][k];
        *plane = a.num_or_var(what, Accept::Null)?.num();
    }
    let r0 = a.positive("r0")?;
    let d = a.f64("D")?;
    a.done()?;
    let w = SphWall {
        axis,
        planes,
        r0,
        d,
        kernel: None,
    };
    engine_fix(sim, a, head, FixKind::WallSph(w))
}

fn wall_region(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    need_sph(sim, a, head)?;
    let id = sim.region_id(a)?;
    let region = crate::regions::region_now(sim, &id).map_err(|e| a.error_prev(e, None))?;
    if region.max_surface_contacts().is_none() {
        return Err(a.error_prev(
            format!(
                "fix wall/region/sph supports block, sphere, cylinder, cone and plane regions, either side, and unions and intersections of them with at most {MAX_SURFACE_CONTACTS} faces in reach, only so far"
            ),
            None,
        ));
    }
    let moving = crate::regions::is_dynamic(sim, &id).then_some(id);
    let r0 = a.positive("r0")?;
    let d = a.f64("D")?;
    a.done()?;
    let w = SphRegionWall {
        region,
        r0,
        d,
        kernel: None,
        sl: Vec::new(),
    };
    sim.world_ref(a)?;
    let fix = Fix::new(&head.id, head.groupbit, FixKind::WallRegionSph(w))
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(WallRegion {
        inner: InEngine::new(fix),
        moving,
    }))
}

/// `fix wall/region/sph`: the engine's wall, and the ID of its region if it moves.
struct WallRegion {
    inner: InEngine,
    /// The region's ID when it moves (placed before each step).
    moving: Option<String>,
}

impl ScriptFix for WallRegion {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    /// A moving region where it is at the coming step (or at the set-up), as LIGGGHTS
    /// places it before the wall's force.
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let Some(id) = &self.moving else {
            return Ok(());
        };
        let who = "fix wall/region/sph";
        let region = ctx.at_step(who, |sim| crate::regions::region_now(sim, id))??;
        let fix = ctx
            .world()
            .fix_mut(&head.id)
            .ok_or("fix wall/region/sph is not in the engine")?;
        if let FixKind::WallRegionSph(w) = &mut fix.kind {
            w.region = region;
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}

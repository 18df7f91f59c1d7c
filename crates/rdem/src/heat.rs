//! Heat conduction through contacts (LIGGGHTS' `fix heat/gran/conduction`, after
//! Chaudhuri et al., Chem. Eng. Sci. 61 (2006) 6348), with the particle temperature
//! uniform inside each particle.
//!
//! Each touching pair i–j exchanges the heat flow `Q = h (T_j − T_i)` (i gains Q, j loses
//! it) with the conductance `h = 4 k_i k_j / (k_i + k_j) · √A`, `k` the thermal
//! conductivity of each particle's type and `A` the contact area:
//!
//! - `overlap` (default): the area of the circle where the two spheres intersect,
//!   `A = π a²`, `a² = −(d−r_i−r_j)(d+r_i−r_j)(d−r_i+r_j)(d+r_i+r_j) / (4 d²)`, `d` the
//!   centre distance; with `area_correction` the overlap `r_i + r_j − d` is first scaled
//!   by `(Y*/Y*_orig)^(1/p)`, `p` the stress–strain exponent of the contact model (3/2
//!   Hertz, 1 Hooke), to undo a softened Young's modulus;
//! - `constant A`: the given area;
//! - `projection`: `π r²` with `r` the larger of the two radii (what LIGGGHTS 3.8's code
//!   does; its manual says the smaller).
//!
//! A wall at a fixed temperature `T_w` (`fix wall/gran ... temperature`, `fix
//! mesh/surface ... temperature`) gives each particle it touches `Q = h (T_w − T_i)`, the
//! conductance from the particle's and the wall type's conductivities and the area of the
//! cap the wall cuts off, `A = π (r² − (r − δ)²)` (δ the overlap).
//!
//! Each step (the order of [`crate::step`]): the heat flows of the group's particles are
//! zeroed in the initial integration; after the post-force fixes the flows of the step's
//! contacts — the positions of this step, the temperatures of the previous one — are
//! summed per particle (ghosts' shares sent to their owners); in the final integration
//! each particle of the group takes `T += (Q + Q_source) dt / (m c)`, `c` its type's
//! heat capacity (a type with |c| ≤ 1e-8 keeps its temperature). This is what LIGGGHTS
//! 3.8 does: explicit Euler, and a pair where only one particle is in the group still
//! conducts (only the temperatures of the group change). The set-up before a run
//! computes no heat flow, as in LIGGGHTS.
//!
//! The sums run serially in neighbor-list order, so they do not depend on the thread
//! count; the buffers are kept between steps (no allocation per step).

use glam::DVec3;

use crate::comm::Comm;
use crate::error::{Error, Result};
use crate::fix::{Fix, FixKind};
use crate::neighbor::NeighborList;
use crate::particles::{Particles, PropId};
use crate::wall::MeshSurface;

/// Names of the per-particle properties, as LIGGGHTS names them.
pub const TEMP: &str = "Temp";
/// Heat flow into each particle at the last step (power).
pub const HEAT_FLUX: &str = "heatFlux";
/// Heat source of each particle (power; `set ... property/atom heatSource`).
pub const HEAT_SOURCE: &str = "heatSource";
/// Half of each contact's flow times the centre-to-centre vector, summed per particle.
pub const DIRECTIONAL_HEAT_FLUX: &str = "directionalHeatFlux";

/// Capacities at or below this magnitude leave the temperature unchanged (LIGGGHTS'
/// `SMALL` of its scalar transport equation).
const SMALL_CAPACITY: f64 = 1e-8;

/// Conductivities below this give no conduction (LIGGGHTS' `SMALL`).
const SMALL_CONDUCTIVITY: f64 = 1e-8;

/// How the contact area of a pair is computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactArea {
    /// From the overlap of the spheres (`contact_area overlap`, the default).
    Overlap,
    /// A fixed area (`contact_area constant A`).
    Constant(f64),
    /// π r² of the larger radius (`contact_area projection`).
    Projection,
}

/// The handles of the per-particle properties heat conduction uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatProps {
    /// Temperature (forwarded to ghosts every step).
    pub temp: PropId,
    /// Heat flow of the last step.
    pub flux: PropId,
    /// Heat source.
    pub source: PropId,
    /// Directional heat flow (3 values).
    pub dir_flux: PropId,
}

impl HeatProps {
    /// Registers the four properties (existing ones are reused) with their defaults:
    /// temperature `t0`, zero flows and sources; the temperature is forwarded to ghosts
    /// every step.
    pub fn register(p: &mut Particles, t0: f64) -> Result<Self> {
        let temp = p.add_property(TEMP, 1, &[t0])?;
        p.set_forward(temp);
        Ok(Self {
            temp,
            flux: p.add_property(HEAT_FLUX, 1, &[0.0])?,
            source: p.add_property(HEAT_SOURCE, 1, &[0.0])?,
            dir_flux: p.add_property(DIRECTIONAL_HEAT_FLUX, 3, &[0.0; 3])?,
        })
    }
}

/// Heat conduction between touching particles and from walls at a fixed temperature.
#[derive(Debug, Clone)]
pub struct HeatConduction {
    /// Group whose temperatures change (bit mask).
    pub groupbit: u32,
    /// Whether contacts conduct. False when only radiation
    /// ([`crate::heat_radiation`]) is defined: the heat flows are still zeroed and the
    /// temperatures integrated (LIGGGHTS' scalar transport equation, which outlives the
    /// fix that made it).
    pub conducts: bool,
    /// Contact area of particle pairs.
    pub area: ContactArea,
    /// `area_correction yes`: the overlap scaling `(Y*/Y*_orig)^(1/p)` per type pair,
    /// `ntypes²` values by (type i − 1) · ntypes + (type j − 1).
    pub deltan_ratio: Option<Vec<f64>>,
    /// Thermal conductivity of each type (index type − 1).
    pub conductivity: Vec<f64>,
    /// Heat capacity per mass of each type (index type − 1).
    pub capacity: Vec<f64>,
    /// The per-particle properties.
    pub props: HeatProps,
    /// Heat flow per particle (ghosts too) during the pass.
    flow: Vec<f64>,
    /// Directional flow per particle (ghosts too) during the pass.
    dir: Vec<DVec3>,
    /// One component of `dir` for the reverse communication.
    comp: Vec<f64>,
}

impl HeatConduction {
    /// Conduction for group `groupbit` with contact area `area`; the coefficient tables
    /// are empty until [`HeatConduction::set_coefficients`].
    pub fn new(groupbit: u32, area: ContactArea, props: HeatProps) -> Result<Self> {
        if let ContactArea::Constant(a) = area {
            if !(a > 0.0 && a.is_finite()) {
                return Err(Error::Invalid {
                    what: "heat conduction contact area",
                    reason: format!("{a} must be > 0"),
                });
            }
        }
        Ok(Self {
            groupbit,
            conducts: true,
            area,
            deltan_ratio: None,
            conductivity: Vec::new(),
            capacity: Vec::new(),
            props,
            flow: Vec::new(),
            dir: Vec::new(),
            comp: Vec::new(),
        })
    }

    /// Sets the per-type conductivities and capacities (and the area correction table,
    /// `ntypes²` values), checked: finite, conductivities ≥ 0.
    pub fn set_coefficients(
        &mut self,
        conductivity: Vec<f64>,
        capacity: Vec<f64>,
        deltan_ratio: Option<Vec<f64>>,
    ) -> Result<()> {
        let n = conductivity.len();
        if capacity.len() != n || deltan_ratio.as_ref().is_some_and(|r| r.len() != n * n) {
            return Err(Error::Invalid {
                what: "heat conduction coefficients",
                reason: format!(
                    "{n} conductivities, {} capacities: one of each per atom type",
                    capacity.len()
                ),
            });
        }
        if let Some(k) = conductivity.iter().find(|k| !(**k >= 0.0 && k.is_finite())) {
            return Err(Error::Invalid {
                what: "thermalConductivity",
                reason: format!("{k} must be >= 0"),
            });
        }
        if let Some(c) = capacity.iter().find(|c| !c.is_finite()) {
            return Err(Error::Invalid {
                what: "thermalCapacity",
                reason: format!("{c} is not finite"),
            });
        }
        self.conductivity = conductivity;
        self.capacity = capacity;
        self.deltan_ratio = deltan_ratio;
        Ok(())
    }

    fn k(&self, ty: u32) -> f64 {
        self.conductivity
            .get((ty as usize).wrapping_sub(1))
            .copied()
            .unwrap_or(0.0)
    }

    fn c(&self, ty: u32) -> f64 {
        self.capacity
            .get((ty as usize).wrapping_sub(1))
            .copied()
            .unwrap_or(0.0)
    }

    /// The conductance factor `4 k_a k_b / (k_a + k_b)` (0 when either is below 1e-5).
    fn k_eff(&self, a: u32, b: u32) -> f64 {
        let (ka, kb) = (self.k(a), self.k(b));
        if ka < SMALL_CONDUCTIVITY || kb < SMALL_CONDUCTIVITY {
            0.0
        } else {
            4.0 * ka * kb / (ka + kb)
        }
    }

    fn ratio(&self, a: u32, b: u32) -> f64 {
        match &self.deltan_ratio {
            Some(r) => {
                let n = self.conductivity.len();
                r[(a as usize - 1) * n + b as usize - 1]
            }
            None => 1.0,
        }
    }

    /// The conductance of a particle pair at centre distance `d` (touching).
    pub fn pair_conductance(&self, ri: f64, rj: f64, ti: u32, tj: u32, d: f64) -> f64 {
        let area = match self.area {
            ContactArea::Overlap => {
                let mut r = d;
                if self.deltan_ratio.is_some() {
                    r = ri + rj - (ri + rj - d) * self.ratio(ti, tj);
                }
                -std::f64::consts::FRAC_PI_4
                    * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
                    / (r * r)
            }
            ContactArea::Constant(a) => a,
            ContactArea::Projection => std::f64::consts::PI * ri.max(rj).powi(2),
        };
        self.k_eff(ti, tj) * area.sqrt()
    }

    /// The conductance between a particle of radius `r` and type `ty` and a wall of type
    /// `wall_type` that it overlaps by `delta`.
    pub fn wall_conductance(&self, r: f64, ty: u32, wall_type: u32, delta: f64) -> f64 {
        let area = match self.area {
            ContactArea::Overlap => {
                let delta = delta * self.ratio(ty, wall_type);
                let rc = r - delta;
                (r * r - rc * rc) * std::f64::consts::PI
            }
            ContactArea::Constant(a) => a,
            ContactArea::Projection => std::f64::consts::PI * r * r,
        };
        self.k_eff(ty, wall_type) * area.sqrt()
    }

    /// The heat flow into particle `i` from particle `j` touching it at centre distance
    /// `d`, from the temperatures they have now (LIGGGHTS' per-contact `heatFlux` output
    /// of `compute pair/gran/local`); 0 when neither is in the group.
    pub fn pair_flow(&self, p: &Particles, i: usize, j: usize, d: f64) -> f64 {
        if p.mask[i] & self.groupbit == 0 && p.mask[j] & self.groupbit == 0 {
            return 0.0;
        }
        let temp = &p.props[self.props.temp.0].data;
        let h = self.pair_conductance(p.radius[i], p.radius[j], p.ty[i], p.ty[j], d);
        (temp[j] - temp[i]) * h
    }

    /// The heat flow into particle `i` from a wall of type `wall_type` at temperature
    /// `t_wall` (`None`: an adiabatic wall, no flow) that it overlaps by `delta`, from the
    /// particle's temperature now (`compute wall/gran/local`'s `heatFlux`).
    pub fn wall_flow(
        &self,
        p: &Particles,
        i: usize,
        wall_type: u32,
        t_wall: Option<f64>,
        delta: f64,
    ) -> f64 {
        let Some(tw) = t_wall else { return 0.0 };
        let temp = &p.props[self.props.temp.0].data;
        (tw - temp[i]) * self.wall_conductance(p.radius[i], p.ty[i], wall_type, delta)
    }

    /// Initial integration: the heat flows of the group's owned particles zeroed (the
    /// sources are kept).
    pub fn reset_flux(&self, p: &mut Particles) {
        let n = p.nlocal();
        let (flux, dir) = (self.props.flux.0, self.props.dir_flux.0);
        for i in 0..n {
            if p.mask[i] & self.groupbit != 0 {
                p.props[flux].data[i] = 0.0;
                p.props[dir].data[3 * i..3 * i + 3].fill(0.0);
            }
        }
    }

    /// After the post-force fixes: the heat flows of this step's contacts — pairs of
    /// `list` (each pair once; a pair counts when either particle is in the group) and the
    /// walls with a temperature among `fixes` — added to the particles' heat flows.
    pub fn conduct(
        &mut self,
        p: &mut Particles,
        list: &NeighborList,
        fixes: &[Fix],
        meshes: &[MeshSurface],
        comm: &dyn Comm,
    ) {
        if !self.conducts {
            return;
        }
        let n = p.nlocal();
        let len = p.len();
        let mut flow = std::mem::take(&mut self.flow);
        let mut dir = std::mem::take(&mut self.dir);
        flow.clear();
        flow.resize(len, 0.0);
        dir.clear();
        dir.resize(len, DVec3::ZERO);
        {
            let temp = &p.props[self.props.temp.0].data;
            let bit = self.groupbit;
            if list.first.len() == n + 1 {
                for i in 0..n {
                    let (xi, ri, ti) = (p.x[i], p.radius[i], p.ty[i]);
                    for &j in list.partners(i) {
                        let j = j as usize;
                        if p.mask[i] & bit == 0 && p.mask[j] & bit == 0 {
                            continue;
                        }
                        let del = xi - p.x[j];
                        let rsq = del.length_squared();
                        let rj = p.radius[j];
                        let radsum = ri + rj;
                        if rsq >= radsum * radsum {
                            continue;
                        }
                        let h = self.pair_conductance(ri, rj, ti, p.ty[j], rsq.sqrt());
                        let q = (temp[j] - temp[i]) * h;
                        flow[i] += q;
                        flow[j] -= q;
                        let half = 0.5 * q * del;
                        dir[i] += half;
                        dir[j] += half;
                    }
                }
            }
            for fix in fixes {
                match &fix.kind {
                    FixKind::WallGran(wall) => {
                        let Some(tw) = wall.temperature else { continue };
                        for &i in wall.candidate_list() {
                            let i = i as usize;
                            let r = p.radius[i];
                            let (d, _) = wall.shape.distance(p.x[i]);
                            let delta = r - d;
                            if delta > 0.0 {
                                let h = self.wall_conductance(r, p.ty[i], wall.wall_type, delta);
                                flow[i] += (tw - temp[i]) * h;
                            }
                        }
                    }
                    FixKind::MeshWall(wall) => {
                        if !wall.meshes.iter().any(|&m| meshes[m].temperature.is_some()) {
                            continue;
                        }
                        for (i, fi) in flow[..n].iter_mut().enumerate() {
                            wall.for_each_contact(meshes, p, i, |surface, dist| {
                                if let Some(tw) = surface.temperature {
                                    let r = p.radius[i];
                                    let h = self.wall_conductance(
                                        r,
                                        p.ty[i],
                                        surface.wall_type,
                                        r - dist,
                                    );
                                    *fi += (tw - temp[i]) * h;
                                }
                            });
                        }
                    }
                    _ => {}
                }
            }
        }
        comm.reverse_scalar(p, &mut flow);
        let comp = &mut self.comp;
        for a in 0..3 {
            // The components one at a time through the scalar reverse communication.
            comp.clear();
            comp.extend(dir.iter().map(|d| d[a]));
            comm.reverse_scalar(p, comp);
            for (d, v) in dir[..n].iter_mut().zip(comp.iter()) {
                d[a] = *v;
            }
        }
        let fl = &mut p.props[self.props.flux.0].data;
        for (f, q) in fl[..n].iter_mut().zip(&flow) {
            *f += q;
        }
        let dl = &mut p.props[self.props.dir_flux.0].data;
        for (d, q) in dl[..3 * n].chunks_exact_mut(3).zip(&dir) {
            for (a, v) in d.iter_mut().enumerate() {
                *v += q[a];
            }
        }
        self.flow = flow;
        self.dir = dir;
    }

    /// Final integration: `T += (Q + Q_source) dt / (m c)` for the group's owned
    /// particles whose type has a capacity above 1e-8 in magnitude.
    pub fn integrate(&self, p: &mut Particles, dt: f64) {
        let n = p.nlocal();
        for i in 0..n {
            if p.mask[i] & self.groupbit == 0 {
                continue;
            }
            let c = self.c(p.ty[i]);
            if c.abs() <= SMALL_CAPACITY {
                continue;
            }
            let q = p.props[self.props.flux.0].data[i] + p.props[self.props.source.0].data[i];
            let m = p.rmass[i];
            p.props[self.props.temp.0].data[i] += q * dt / (m * c);
        }
    }

    /// Σ m c T over the owned particles (all of them, as LIGGGHTS' thermal energy of
    /// the fix: not only the group's), before the sum over ranks.
    pub fn thermal_energy(&self, p: &Particles) -> f64 {
        let temp = &p.props[self.props.temp.0].data;
        // A fold from +0.0 (`sum` starts from −0.0): no particles print `0`, as in
        // LIGGGHTS, not `-0`; any other sum is unchanged.
        (0..p.nlocal())
            .map(|i| self.c(p.ty[i]) * p.rmass[i] * temp[i])
            .fold(0.0, |s, x| s + x)
    }
}

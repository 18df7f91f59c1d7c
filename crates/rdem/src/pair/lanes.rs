//! The contact kernel on [`L`] contacts at once, for the models that have a lane form:
//! `model hertz`, `tangential history` or `no_history`, no rolling friction, no cohesion
//! (the commonest choice by far).
//!
//! The pair pass gathers the touching pairs of a few rows of the near list into a
//! [`Batch`] (structure of arrays: one column per input, history beside its pair), runs
//! [`Batch::compute`] over it and then adds the results to the particles in the order of
//! the per-pair pass. Every lane does the operations of the scalar kernel
//! ([`crate::contact::contact`] with [`crate::contact::normal::Hertz`]) in the same
//! order, branches taken as selects, and Rust never fuses a multiply and an add, so each
//! contact's result is the scalar kernel's bit for bit, whatever the lane width or
//! instruction set.
//!
//! The lanes are plain `[f64; L]` arrays; LLVM turns their element-wise loops into vector
//! instructions. [`Batch::compute`] is compiled three times, for the baseline x86-64
//! (SSE2), for AVX2 and for AVX-512, and runs the one chosen at run time
//! ([`Isa::from_env`]: `RDEM_SIMD=auto` picks the widest the CPU has). A lane crate
//! such as `wide` picks its instruction set when it is compiled, so it cannot serve a
//! run-time choice; the arrays here can, through `#[target_feature]`.

use std::ops::{Add, Div, Mul, Neg, Sub};

use crate::contact::{
    CoeffTable, CohesionKind, ContactModel, Flags, NormalKind, PairCoeff, RollingKind,
    TangentialKind,
};

/// Contacts per lane group: 8 doubles fill an AVX-512 register (two AVX2 ones).
pub const L: usize = 8;

/// The lane form of a contact model, when it has one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneModel {
    /// `tangential history` (else `no_history`).
    pub history: bool,
    /// The coefficient columns, when every type pair has the same.
    pub uniform: Option<[f64; 5]>,
}

impl LaneModel {
    /// The lane form of `model`, or `None` when only the per-pair kernel has it.
    pub fn of(model: &ContactModel, table: &CoeffTable) -> Option<Self> {
        let plain = model.normal == NormalKind::Hertz
            && model.rolling == RollingKind::Off
            && model.cohesion == CohesionKind::Off;
        let all = table.all();
        let bits = |c: &PairCoeff| coeff_cols(c).map(f64::to_bits);
        let uniform = all
            .first()
            .filter(|f| all.iter().all(|c| bits(c) == bits(f)))
            .map(coeff_cols);
        plain.then_some(Self {
            history: model.tangential == TangentialKind::History,
            uniform,
        })
    }
}

/// The instruction sets [`Batch::compute`] is compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// The baseline of the target (SSE2 on x86-64; the only one elsewhere).
    Base,
    /// AVX2 and FMA (x86-64-v3).
    Avx2,
    /// AVX-512 F and VL (x86-64-v4).
    Avx512,
}

impl Isa {
    /// The lane kernel's instruction set as `RDEM_SIMD` asks for it: unset or `off`, the
    /// per-pair kernel (`None`, the default: on the machines measured so far the lane
    /// kernel is not faster, see the README); `auto`, the widest this CPU has; `base`,
    /// `avx2` or `avx512`, that one or the widest below it this CPU has. Another value
    /// is reported on standard error and taken as `off`.
    pub fn from_env() -> Option<Self> {
        let best = Self::best();
        let capped = |want: Self| if want as u8 <= best as u8 { want } else { best };
        match std::env::var("RDEM_SIMD").as_deref() {
            Err(_) | Ok("off") => None,
            Ok("auto") => Some(best),
            Ok("base") => Some(Self::Base),
            Ok("avx2") => Some(capped(Self::Avx2)),
            Ok("avx512") => Some(capped(Self::Avx512)),
            Ok(other) => {
                eprintln!(
                    "WARNING: RDEM_SIMD={other} is none of off, auto, base, avx2, avx512: \
                     the per-pair contact kernel is used"
                );
                None
            }
        }
    }

    /// The widest instruction set this CPU has.
    pub fn best() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            if is_x86_feature_detected!("avx512f") && is_x86_feature_detected!("avx512vl") {
                return Self::Avx512;
            }
            if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
                return Self::Avx2;
            }
        }
        Self::Base
    }

    /// Every instruction set this CPU can run, narrowest first.
    pub fn available() -> Vec<Self> {
        let best = Self::best();
        [Self::Base, Self::Avx2, Self::Avx512]
            .into_iter()
            .filter(|&i| i as u8 <= best as u8)
            .collect()
    }
}

/// One lane group of doubles.
#[derive(Clone, Copy)]
struct V([f64; L]);

macro_rules! lanewise {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for V {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: V) -> V {
                V(std::array::from_fn(|l| self.0[l] $op o.0[l]))
            }
        }
        impl $tr<f64> for V {
            type Output = V;
            #[inline(always)]
            fn $f(self, o: f64) -> V {
                V(std::array::from_fn(|l| self.0[l] $op o))
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for V {
    type Output = V;
    #[inline(always)]
    fn neg(self) -> V {
        V(self.0.map(|a| -a))
    }
}

/// A lane mask.
#[derive(Clone, Copy)]
struct M([bool; L]);

impl V {
    #[inline(always)]
    fn splat(a: f64) -> V {
        V([a; L])
    }
    #[inline(always)]
    fn sqrt(self) -> V {
        V(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> V {
        V(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn gt(self, o: V) -> M {
        M(std::array::from_fn(|l| self.0[l] > o.0[l]))
    }
    #[inline(always)]
    fn lt(self, o: V) -> M {
        M(std::array::from_fn(|l| self.0[l] < o.0[l]))
    }
}

impl M {
    /// Whether any lane is set.
    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().any(|&b| b)
    }

    /// `a` where the mask is set, else `b`.
    #[inline(always)]
    fn select(self, a: V, b: V) -> V {
        V(std::array::from_fn(
            |l| if self.0[l] { a.0[l] } else { b.0[l] },
        ))
    }
}

/// The columns of a [`Batch`]: the inputs of a contact, then its outputs.
#[derive(Clone, Copy)]
#[repr(usize)]
pub enum Col {
    /// r = x_i − x_j.
    Dx,
    Dy,
    Dz,
    /// Radii and masses.
    Ri,
    Rj,
    Mi,
    Mj,
    /// v_i − v_j.
    Vx,
    Vy,
    Vz,
    /// ω_i and ω_j.
    Wix,
    Wiy,
    Wiz,
    Wjx,
    Wjy,
    Wjz,
    /// The tangential spring (history), read and written back.
    Hx,
    Hy,
    Hz,
    /// The type pair's E*, G*, Hertz damping factors and μ (not filled when every type
    /// pair has the same: [`Batch::uniform`]).
    EStar,
    GStar,
    DampN,
    DampT,
    Mu,
    /// Outputs: force on i, torques on i and j.
    Fx,
    Fy,
    Fz,
    Tix,
    Tiy,
    Tiz,
    Tjx,
    Tjy,
    Tjz,
}

/// Number of columns.
const NCOL: usize = Col::Tjz as usize + 1;

/// One lane group of a [`Batch`]: column c of contact l is `self.0[c][l]` (each column
/// one cache line).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
struct Group([[f64; L]; NCOL]);

/// The touching pairs of a few rows of the near list, gathered for the lane kernel:
/// [`L`] contacts per [`Group`], one column per input and output, so that a batch of a
/// few rows stays in the first-level cache.
#[derive(Debug, Clone, Default)]
pub struct Batch {
    /// Contacts held.
    pub n: usize,
    /// The lane groups (kept between batches; only the first `n.div_ceil(L)` are used).
    groups: Vec<Group>,
    /// Per contact: partner j, its history slot, its near-list position.
    pub j: Vec<u32>,
    pub slot: Vec<u32>,
    pub k: Vec<u32>,
    /// [`Batch::select`]'s picks.
    picked: Vec<u32>,
    /// The coefficient columns (`EStar` to `Mu`) every contact shares, when every type
    /// pair has the same (then [`Batch::push`] leaves them out).
    pub uniform: Option<[f64; 5]>,
}

impl Batch {
    /// Empties the batch.
    pub fn clear(&mut self) {
        self.n = 0;
        self.j.clear();
        self.slot.clear();
        self.k.clear();
    }

    /// Picks the m in `0..len` for which `pick(m)` holds, in order, and gives their
    /// number (the i-th is [`Batch::picked`]`(i)`); `pick` is called for each m in turn,
    /// and the picking has no branch on its result.
    #[inline(always)]
    pub fn select(&mut self, len: usize, mut pick: impl FnMut(usize) -> bool) -> usize {
        if self.picked.len() <= len {
            self.picked.resize(len + 1, 0);
        }
        let picked = &mut self.picked[..=len];
        let mut n = 0;
        for m in 0..len {
            picked[n] = m as u32;
            n += pick(m) as usize;
        }
        n
    }

    /// The i-th m picked by the last [`Batch::select`].
    #[inline(always)]
    pub fn picked(&self, i: usize) -> usize {
        self.picked[i] as usize
    }

    /// Appends a contact: `vals` are the input columns in [`Col`] order, `Dx` to `Hz`,
    /// and `coeff` the coefficient columns (ignored when [`Batch::uniform`]).
    #[inline(always)]
    pub fn push(
        &mut self,
        j: u32,
        slot: u32,
        k: u32,
        vals: [f64; Col::Hz as usize + 1],
        coeff: impl FnOnce() -> [f64; 5],
    ) {
        let (g, l) = (self.n / L, self.n % L);
        if g == self.groups.len() {
            self.groups.push(Group([[0.0; L]; NCOL]));
        }
        let grp = &mut self.groups[g].0;
        for (c, v) in vals.into_iter().enumerate() {
            grp[c][l] = v;
        }
        if self.uniform.is_none() {
            for (c, v) in coeff().into_iter().enumerate() {
                grp[Col::EStar as usize + c][l] = v;
            }
        }
        self.j.push(j);
        self.slot.push(slot);
        self.k.push(k);
        self.n += 1;
    }

    /// Column `col` of contact `c`.
    #[inline(always)]
    pub fn at(&self, col: Col, c: usize) -> f64 {
        self.groups[c / L].0[col as usize][c % L]
    }

    /// The output of contact `c`: force on i, torques on i and j, and the new spring.
    #[inline(always)]
    pub fn out(&self, c: usize) -> [f64; 12] {
        let (g, l) = (&self.groups[c / L].0, c % L);
        [
            Col::Fx,
            Col::Fy,
            Col::Fz,
            Col::Tix,
            Col::Tiy,
            Col::Tiz,
            Col::Tjx,
            Col::Tjy,
            Col::Tjz,
            Col::Hx,
            Col::Hy,
            Col::Hz,
        ]
        .map(|col| g[col as usize][l])
    }

    /// Runs the kernel on every contact held, with instruction set `isa`: fills the
    /// output columns and overwrites the spring columns with the new spring.
    pub fn compute(&mut self, isa: Isa, m: LaneModel, flags: Flags, dt: f64, update: bool) {
        if self.n == 0 {
            return;
        }
        // The last lane group is filled up with copies of the last contact: real inputs,
        // so no lane computes on garbage; their outputs are never read.
        let ngroups = self.n.div_ceil(L);
        let last = (self.n - 1) % L;
        for col in &mut self.groups[ngroups - 1].0[..=Col::Mu as usize] {
            let v = col[last];
            col[last + 1..].fill(v);
        }
        let a = Args {
            m,
            flags,
            dt,
            update,
            uniform: self.uniform,
        };
        // One call per group: a loop over groups inside one function is vectorised by
        // LLVM across groups (strided gathers), not within a group.
        let groups = &mut self.groups[..ngroups];
        match isa {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 if Isa::best() == Isa::Avx512 => {
                for g in groups {
                    // SAFETY: the CPU has AVX-512 F and VL (checked just above).
                    unsafe { group_avx512(&a, &mut g.0) }
                }
            }
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 | Isa::Avx512 if Isa::best() != Isa::Base => {
                for g in groups {
                    // SAFETY: the CPU has AVX2 and FMA (checked just above).
                    unsafe { group_avx2(&a, &mut g.0) }
                }
            }
            _ => {
                for g in groups {
                    group_base(&a, &mut g.0)
                }
            }
        }
    }
}

/// What every lane group of one [`Batch::compute`] shares.
struct Args {
    m: LaneModel,
    flags: Flags,
    dt: f64,
    update: bool,
    uniform: Option<[f64; 5]>,
}

#[inline(never)]
fn group_base(a: &Args, g: &mut [[f64; L]; NCOL]) {
    group(a, g)
}

#[cfg(target_arch = "x86_64")]
#[inline(never)]
#[target_feature(enable = "avx2,fma")]
fn group_avx2(a: &Args, g: &mut [[f64; L]; NCOL]) {
    group(a, g)
}

#[cfg(target_arch = "x86_64")]
#[inline(never)]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn group_avx512(a: &Args, g: &mut [[f64; L]; NCOL]) {
    group(a, g)
}

/// One lane group. Each line is the scalar kernel's, lane-wise.
#[inline(always)]
fn group(a: &Args, data: &mut [[f64; L]; NCOL]) {
    let ld = |c: Col| V(data[c as usize]);
    let (dx, dy, dz) = (ld(Col::Dx), ld(Col::Dy), ld(Col::Dz));
    // |r|² as `DVec3::length_squared` sums it.
    let rsq = dx * dx + dy * dy + dz * dz;
    let (ri, rj, mi, mj) = (ld(Col::Ri), ld(Col::Rj), ld(Col::Mi), ld(Col::Mj));
    let (vx, vy, vz) = (ld(Col::Vx), ld(Col::Vy), ld(Col::Vz));
    let (wix, wiy, wiz) = (ld(Col::Wix), ld(Col::Wiy), ld(Col::Wiz));
    let (wjx, wjy, wjz) = (ld(Col::Wjx), ld(Col::Wjy), ld(Col::Wjz));
    let [e_star, g_star, damp_n, damp_t, mu] = match a.uniform {
        Some(c) => c.map(V::splat),
        None => [Col::EStar, Col::GStar, Col::DampN, Col::DampT, Col::Mu].map(ld),
    };
    let zero = V::splat(0.0);

    // Geometry (the pair pass's `contact`).
    let radsum = ri + rj;
    let dist = rsq.sqrt();
    let delta = radsum - dist;
    let inv_d = V::splat(1.0) / dist;
    let pos = dist.gt(zero);
    let nx = pos.select(dx * inv_d, zero);
    let ny = pos.select(dy * inv_d, zero);
    let nz = pos.select(dz * inv_d, V::splat(1.0));
    let msum = mi + mj;
    let inv = V::splat(1.0) / (radsum * msum);
    let r_star = ri * rj * msum * inv;
    let m_star = mi * mj * radsum * inv;
    let ci = ri - delta * 0.5;
    let cj = rj - delta * 0.5;

    // Relative velocities (`contact::contact`).
    let vn = vx * nx + vy * ny + vz * nz;
    let vtx = vx - vn * nx;
    let vty = vy - vn * ny;
    let vtz = vz - vn * nz;
    let ax = ci * wix + cj * wjx;
    let ay = ci * wiy + cj * wjy;
    let az = ci * wiz + cj * wjz;
    let vrx = vtx - (ay * nz - ny * az);
    let vry = vty - (az * nx - nz * ax);
    let vrz = vtz - (ax * ny - nx * ay);

    // Hertz.
    let sq = (r_star * delta).sqrt();
    let kt = g_star * 8.0 * sq;
    let kn = e_star * (4.0 / 3.0) * sq;
    let s = (sq * m_star).sqrt();
    let gamma_n = damp_n * s;
    let gamma_t = damp_t * s;
    let fe = kn * delta;
    let f = fe + (-gamma_n) * vn;
    let fn_contact = if a.flags.limit_force {
        f.lt(zero).select(zero, f)
    } else {
        f
    };
    let load = fn_contact.abs();
    let ft_max = mu * load;

    // Tangential.
    let (ftx, fty, ftz) = if a.m.history {
        let (mut sx, mut sy, mut sz) = (ld(Col::Hx), ld(Col::Hy), ld(Col::Hz));
        if a.update {
            sx = sx + vrx * a.dt;
            sy = sy + vry * a.dt;
            sz = sz + vrz * a.dt;
            let sd = sx * nx + sy * ny + sz * nz;
            sx = sx - sd * nx;
            sy = sy - sd * ny;
            sz = sz - sd * nz;
        }
        let nkt = -kt;
        let (px, py, pz) = (nkt * sx, nkt * sy, nkt * sz);
        let mag2 = px * px + py * py + pz * pz;
        let cap_on = mag2.gt(ft_max * ft_max);
        let (ux, uy, uz) = if a.flags.tangential_damping {
            (px - gamma_t * vrx, py - gamma_t * vry, pz - gamma_t * vrz)
        } else {
            (px, py, pz)
        };
        let st = |c: Col, v: V, data: &mut [[f64; L]; NCOL]| data[c as usize] = v.0;
        if !cap_on.any() {
            // No lane slides (the common case in a bed): the divisions are skipped.
            if a.update {
                st(Col::Hx, sx, data);
                st(Col::Hy, sy, data);
                st(Col::Hz, sz, data);
            }
            (ux, uy, uz)
        } else {
            let q = ft_max / mag2.sqrt();
            let (cx, cy, cz) = (px * q, py * q, pz * q);
            if a.update {
                let kpos = kt.gt(zero);
                let reset = |c: V| kpos.select((-c) / kt, zero);
                st(Col::Hx, cap_on.select(reset(cx), sx), data);
                st(Col::Hy, cap_on.select(reset(cy), sy), data);
                st(Col::Hz, cap_on.select(reset(cz), sz), data);
            }
            (
                cap_on.select(cx, ux),
                cap_on.select(cy, uy),
                cap_on.select(cz, uz),
            )
        }
    } else if a.flags.tangential_damping {
        let ngt = -gamma_t;
        let (px, py, pz) = (ngt * vrx, ngt * vry, ngt * vrz);
        let mag2 = px * px + py * py + pz * pz;
        let cap_on = mag2.gt(ft_max * ft_max);
        let q = ft_max / mag2.sqrt();
        (
            cap_on.select(px * q, px),
            cap_on.select(py * q, py),
            cap_on.select(pz * q, pz),
        )
    } else {
        (zero, zero, zero)
    };

    // Force and torques; no cohesion (f_coh = 0) and no rolling torque (+ 0).
    let fn_total = fn_contact - 0.0;
    let st = |c: Col, v: V, data: &mut [[f64; L]; NCOL]| data[c as usize] = v.0;
    st(Col::Fx, fn_total * nx + ftx, data);
    st(Col::Fy, fn_total * ny + fty, data);
    st(Col::Fz, fn_total * nz + ftz, data);
    let tx = ny * ftz - fty * nz;
    let ty = nz * ftx - ftz * nx;
    let tz = nx * fty - ftx * ny;
    let (nci, ncj) = (-ci, -cj);
    st(Col::Tix, nci * tx + 0.0, data);
    st(Col::Tiy, nci * ty + 0.0, data);
    st(Col::Tiz, nci * tz + 0.0, data);
    st(Col::Tjx, ncj * tx - 0.0, data);
    st(Col::Tjy, ncj * ty - 0.0, data);
    st(Col::Tjz, ncj * tz - 0.0, data);
}

/// The coefficient columns of a type pair, in [`Col`] order (`EStar` to `Mu`).
#[inline(always)]
pub fn coeff_cols(c: &PairCoeff) -> [f64; 5] {
    [c.e_star, c.g_star, c.hertz_damp_n, c.hertz_damp_t, c.mu]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{cohesion, contact, normal::Hertz, rolling, tangential, Geom};
    use glam::DVec3;
    use proptest::prelude::*;

    /// One contact's inputs, as the pair pass has them.
    #[derive(Debug, Clone)]
    struct Input {
        d: DVec3,
        ri: f64,
        rj: f64,
        mi: f64,
        mj: f64,
        vr: DVec3,
        wi: DVec3,
        wj: DVec3,
        hist: [f64; 3],
        coeff: PairCoeff,
    }

    fn v3(s: f64) -> impl Strategy<Value = DVec3> {
        (-s..s, -s..s, -s..s).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn input() -> impl Strategy<Value = Input> {
        let coeff = (
            1e6..1e8f64,
            1e5..1e7f64,
            0.0..3.0f64,
            0.0..3.0f64,
            0.0..1.0f64,
        );
        (
            (v3(1.0), 0.5..1.0f64, 0.3..1.0f64, 0.3..1.0f64),
            (1e-3..1e-2f64, 1e-3..1e-2f64),
            (v3(3.0), v3(500.0), v3(500.0)),
            // Springs from none to far past the Coulomb limit, so some lanes slide.
            prop_oneof![Just(DVec3::ZERO), v3(1e-6), v3(1e-3)],
            coeff,
        )
            .prop_map(
                |((dir, gap, ri, rj), (mi, mj), (vr, wi, wj), h, (e, g, dn, dt, mu))| {
                    let ri = ri * 1e-3;
                    let rj = rj * 1e-3;
                    // Overlapping: |d| below r_i + r_j by a fraction of it.
                    let len = (ri + rj) * (1.0 - 0.05 * gap);
                    let d = if dir.length() > 1e-3 {
                        dir.normalize() * len
                    } else {
                        DVec3::X * len
                    };
                    Input {
                        d,
                        ri,
                        rj,
                        mi,
                        mj,
                        vr,
                        wi,
                        wj,
                        hist: h.to_array(),
                        coeff: PairCoeff {
                            e_star: e,
                            g_star: g,
                            hertz_damp_n: dn,
                            hertz_damp_t: dt,
                            mu,
                            ..Default::default()
                        },
                    }
                },
            )
    }

    /// The per-pair kernel on `c`, as the pair pass calls it: force and torques on i and
    /// j, and the spring after.
    fn scalar(c: &Input, history: bool, flags: Flags, dt: f64, update: bool) -> [f64; 12] {
        let rsq = c.d.length_squared();
        let (ri, rj, mi, mj) = (c.ri, c.rj, c.mi, c.mj);
        let radsum = ri + rj;
        let dist = rsq.sqrt();
        let delta = radsum - dist;
        let inv = 1.0 / (radsum * (mi + mj));
        let g = Geom {
            n: c.d * (1.0 / dist),
            delta,
            dist,
            ri,
            rj,
            r_star: ri * rj * (mi + mj) * inv,
            m_star: mi * mj * radsum * inv,
            ci: ri - 0.5 * delta,
            cj: rj - 0.5 * delta,
            vr: c.vr,
            wi: c.wi,
            wj: c.wj,
            roll_scale: 1.0,
            inertia_i: 0.0,
            inertia_j: 0.0,
            dt,
            lq_i: 0.0,
            lq_j: 0.0,
            update,
        };
        let mut h = c.hist;
        let out = if history {
            contact::<Hertz, tangential::History, rolling::Off, cohesion::Off>(
                &g, &c.coeff, flags, &mut h,
            )
        } else {
            contact::<Hertz, tangential::NoHistory, rolling::Off, cohesion::Off>(
                &g,
                &c.coeff,
                flags,
                &mut [],
            )
        };
        let [a, b, cc] = [out.f_i, out.t_i, out.t_j].map(|v| v.to_array());
        [
            a[0], a[1], a[2], b[0], b[1], b[2], cc[0], cc[1], cc[2], h[0], h[1], h[2],
        ]
    }

    /// Every contact through the lane kernel on instruction set `isa`.
    fn lanes(
        cs: &[Input],
        uniform: bool,
        isa: Isa,
        history: bool,
        flags: Flags,
        dt: f64,
        update: bool,
    ) -> Vec<[f64; 12]> {
        let mut b = Batch {
            uniform: uniform.then(|| coeff_cols(&cs[0].coeff)),
            ..Batch::default()
        };
        for (k, c) in cs.iter().enumerate() {
            let vals = [
                c.d.x, c.d.y, c.d.z, c.ri, c.rj, c.mi, c.mj, c.vr.x, c.vr.y, c.vr.z, c.wi.x,
                c.wi.y, c.wi.z, c.wj.x, c.wj.y, c.wj.z, c.hist[0], c.hist[1], c.hist[2],
            ];
            b.push(k as u32, k as u32, k as u32, vals, || coeff_cols(&c.coeff));
        }
        let model = LaneModel {
            history,
            uniform: b.uniform,
        };
        b.compute(isa, model, flags, dt, update);
        (0..cs.len()).map(|c| b.out(c)).collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// On every instruction set this CPU has, with and without history, damping,
        /// `limitForce` and the spring update, shared or per-contact coefficients, the
        /// lane kernel gives each contact the per-pair kernel's bits.
        #[test]
        fn lane_kernel_gives_the_per_pair_bits(
            mut cs in prop::collection::vec(input(), 1..20),
            history: bool,
            damping: bool,
            limit: bool,
            update: bool,
            uniform: bool,
        ) {
            if uniform {
                let c0 = cs[0].coeff;
                for c in &mut cs {
                    c.coeff = c0;
                }
            }
            let flags = Flags {
                tangential_damping: damping,
                limit_force: limit,
                ..Flags::default()
            };
            let dt = 1e-5;
            let want: Vec<[u64; 12]> = cs
                .iter()
                .map(|c| scalar(c, history, flags, dt, update).map(f64::to_bits))
                .collect();
            for isa in Isa::available() {
                let got: Vec<[u64; 12]> = lanes(&cs, uniform, isa, history, flags, dt, update)
                    .into_iter()
                    .map(|o| o.map(f64::to_bits))
                    .collect();
                prop_assert_eq!(&got, &want, "{:?}", isa);
            }
        }
    }

    /// The generator reaches both sides of the Coulomb limit (else the sliding lanes
    /// would go untested).
    #[test]
    fn some_lanes_slide_and_some_stick() {
        let c = Input {
            d: DVec3::X * 1.9e-3,
            ri: 1e-3,
            rj: 1e-3,
            mi: 5e-3,
            mj: 5e-3,
            vr: DVec3::ZERO,
            wi: DVec3::ZERO,
            wj: DVec3::ZERO,
            hist: [0.0; 3],
            coeff: PairCoeff {
                e_star: 1e7,
                g_star: 1e6,
                hertz_damp_n: 1.0,
                hertz_damp_t: 1.0,
                mu: 0.5,
                ..Default::default()
            },
        };
        let stick = Input {
            hist: [0.0, 1e-6, 0.0],
            ..c.clone()
        };
        let slide = Input {
            hist: [0.0, 1e-3, 0.0],
            ..c.clone()
        };
        let flags = Flags::default();
        let [a, b] = [&stick, &slide].map(|c| scalar(c, true, flags, 1e-5, true));
        // Sticking keeps the spring; sliding shortens it to the Coulomb limit.
        assert_eq!(a[10], 1e-6);
        assert!(b[10] < 1e-3 * 0.5, "spring {} not reset", b[10]);
        for isa in Isa::available() {
            let out = lanes(
                &[stick.clone(), slide.clone()],
                true,
                isa,
                true,
                flags,
                1e-5,
                true,
            );
            assert_eq!(out[0].map(f64::to_bits), a.map(f64::to_bits));
            assert_eq!(out[1].map(f64::to_bits), b.map(f64::to_bits));
        }
    }
}

//! `fix mesh/surface/stress/servo`: a mesh translated along an axis at a velocity a PID
//! controller sets from the force the particles exert on it (`ctrlPV force`), or turned
//! about the axis through its centre of mass at an angular velocity set from the torque
//! about that point (`ctrlPV torque`).
//!
//! The law, measured on LIGGGHTS 3.8 (a lid pressed on a sphere, thermo every step; the
//! runs are recorded in rdem-cli's `tests/servo_wall.rs`) and reproduced there to 1e-9:
//!
//! - process value `pv = −F·a` (`F` the total force of the particles on the mesh, `a` the
//!   unit axis), target `T`, normalised error `e = (T − pv) / |T|`;
//! - at the end of each step (after the force pass and the mesh stress, LIGGGHTS'
//!   `final_integrate`): `S += e dt`, `o = kp e + ki S + kd (pv_old − pv) / (|T| dt)`;
//!   when `|o| > 1` it is clipped to ±1 and, with `ki ≠ 0`, `S` is reset so that
//!   `kp e + ki S = ±1` (anti-wind-up). The wall velocity is `o · vmax · a`;
//! - at the start of the next step (LIGGGHTS' `initial_integrate`) the mesh and its
//!   centre of mass move by that velocity times dt. A new servo starts at rest, so it
//!   first moves in the second step; stopped (`fix_modify ID integrate stop`) it neither
//!   moves nor updates the controller, and it keeps its velocity and sums for `start`, and its vertices
//!   keep that velocity for the contacts (LIGGGHTS 3.8 does so).
//!
//! `ctrlPV torque` is the same law with the torque about the centre of mass for the force
//! and angular velocity for velocity: the largest angular speed is `vmax / reach`
//! (`reach` the largest distance of a vertex from the axis, so that no vertex moves
//! faster than `vmax`); the mesh turns by `ω·a dt` about the axis through `com` at the
//! start of the step, and its vertices carry `ω × (x − com)` of their positions at the
//! controller update (LIGGGHTS 3.8, measured in rdem-cli's `tests/servo_torque.rs`).
//!
//! `mode auto` replaces the PID by a proportional law with a scheduled gain (the manual's
//! "alternative controller"; measured on LIGGGHTS 3.8 with the runs of rdem-cli's
//! `tests/servo_auto.rs`): with `vmin = ratio · rmin / dt` (`rmin` the smallest particle
//! radius at the start of the run, 10⁶ without particles), the wall velocity is
//! `g · e · a`, where `g = vmax` while no particle is a wall-contact candidate of the mesh
//! (within radius + skin of a triangle at the last neighbor build, summed over the ranks),
//! and otherwise `g = vmin` for `|e| ≥ 1`, `0.1 vmin` for `|e| ≤ 0.9`, linear in between;
//! the speed is then clipped to `vmin` (with candidates) or `vmax` (without).

use glam::DVec3;

/// A servo-controlled mesh: parameters and controller state.
#[derive(Debug, Clone, PartialEq)]
pub struct Servo {
    /// Unit axis of the motion.
    pub axis: DVec3,
    /// `target_val`: the force (along the axis) to reach.
    pub target: f64,
    /// `vel_max`: the largest speed.
    pub vmax: f64,
    /// Proportional gain.
    pub kp: f64,
    /// Integral gain.
    pub ki: f64,
    /// Derivative gain.
    pub kd: f64,
    /// True while the servo moves the mesh (`fix_modify ID integrate start|stop`).
    pub active: bool,
    /// Centre of mass (`com`), moved with the mesh.
    pub com: DVec3,
    /// Wall velocity for the next step.
    pub vel: DVec3,
    /// Time integral of the normalised error.
    pub sum: f64,
    /// Process value of the last controller update.
    pub old_pv: f64,
    /// `ctrlPV torque`: the mesh turns about the axis through [`Servo::com`] and
    /// [`Servo::vel`] is its angular velocity.
    pub torque: bool,
    /// Largest distance of a vertex from the axis through `com` (`ctrlPV torque`; 1
    /// for `ctrlPV force`): speeds are divided by it.
    pub reach: f64,
    /// `mode auto`: the gain-scheduled proportional law instead of the PID.
    pub auto: bool,
    /// `ratio`: the speed near particles in particle radii per timestep (`mode auto`).
    pub ratio: f64,
    /// `ratio · rmin / dt`, set at the start of each run by [`Servo::start_run`].
    pub vmin: f64,
    /// True when a particle was a wall-contact candidate of the mesh at the last
    /// neighbor build (on any rank).
    pub contacts: bool,
}

impl Servo {
    /// A servo at rest, active, with the given parameters.
    pub fn new(axis: DVec3, com: DVec3, target: f64, vmax: f64, gains: [f64; 3]) -> Self {
        Self {
            axis: axis.normalize(),
            target,
            vmax,
            kp: gains[0],
            ki: gains[1],
            kd: gains[2],
            active: true,
            com,
            vel: DVec3::ZERO,
            sum: 0.0,
            old_pv: 0.0,
            torque: false,
            reach: 1.0,
            auto: false,
            ratio: 0.0,
            vmin: 0.0,
            contacts: false,
        }
    }

    /// The run-start set-up of `mode auto`: `rmin` is the smallest particle radius over
    /// all ranks, `None` without particles (LIGGGHTS 3.8 then takes 10⁶).
    pub fn start_run(&mut self, rmin: Option<f64>, dt: f64) {
        self.vmin = self.ratio * rmin.unwrap_or(1e6) / dt;
    }

    /// A `ctrlPV torque` servo about `axis` through `com` for a mesh with vertices
    /// `verts`; `None` when every vertex lies on the axis.
    pub fn new_torque(
        axis: DVec3,
        com: DVec3,
        target: f64,
        vmax: f64,
        gains: [f64; 3],
        verts: &[DVec3],
    ) -> Option<Self> {
        let mut s = Self::new(axis, com, target, vmax, gains);
        let a = s.axis;
        s.reach = verts
            .iter()
            .map(|&v| a.cross(v - com).length())
            .fold(0.0, f64::max);
        s.torque = true;
        (s.reach > 0.0).then_some(s)
    }

    /// The largest speed: `vmax`, or `vmax / reach` rad/s for `ctrlPV torque`.
    fn top(&self) -> f64 {
        if self.torque {
            self.vmax / self.reach
        } else {
            self.vmax
        }
    }

    /// The controller update at the end of a step whose total force (`ctrlPV force`) or
    /// torque about `com` (`ctrlPV torque`) on the mesh is `load` (summed over all
    /// ranks), with timestep `dt`: sets [`Servo::vel`].
    pub fn control(&mut self, load: DVec3, dt: f64) {
        if !self.active {
            return;
        }
        let pv = -load.dot(self.axis);
        let scale = self.target.abs();
        let e = (self.target - pv) / scale;
        if self.auto {
            self.vel = self.axis * self.auto_speed(e);
            return;
        }
        self.sum += e * dt;
        let de = (self.old_pv - pv) / (scale * dt);
        self.old_pv = pv;
        let mut out = self.kp * e + self.ki * self.sum + self.kd * de;
        if out.abs() > 1.0 {
            out = out.signum();
            if self.ki != 0.0 {
                self.sum = (out - self.kp * e) / self.ki;
            }
        }
        self.vel = self.axis * (out * self.top());
    }

    /// The signed speed of `mode auto` for the normalised error `e` (see the module
    /// documentation), clipped.
    fn auto_speed(&self, e: f64) -> f64 {
        // The schedule's corners: the error band and the gain's floor (LIGGGHTS 3.8).
        const LOW: f64 = 0.9;
        const HIGH: f64 = 1.0;
        const FLOOR: f64 = 0.1;
        let top = self.top();
        let (gain, limit) = if self.contacts {
            let m = self.vmin / self.reach;
            let g = match e.abs() {
                a if a <= LOW => FLOOR * m,
                a if a >= HIGH => m,
                a => FLOOR * m + (1.0 - FLOOR) * m * (a - LOW) / (HIGH - LOW),
            };
            (g, m)
        } else {
            (top, top)
        };
        let v = gain * e;
        if v.abs() > limit {
            limit * v.signum()
        } else {
            v
        }
    }

    /// The displacement of the mesh in a step of `dt` (zero when stopped or turning).
    pub fn displacement(&self, dt: f64) -> DVec3 {
        if self.active && !self.torque {
            self.vel * dt
        } else {
            DVec3::ZERO
        }
    }

    /// The angle the mesh turns about the axis in a step of `dt` (`ctrlPV torque`; zero
    /// when stopped).
    pub fn turn(&self, dt: f64) -> f64 {
        if self.active && self.torque {
            self.vel.dot(self.axis) * dt
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without contact the error is 1 (normalised): the speed is vmax (kp + ki n dt)
    /// after n updates, as LIGGGHTS 3.8 moved its lid (target −2, vmax 4, kp 0.5,
    /// ki 100, dt 1e-5: 2.004, 2.008, 2.012 m/s down); a stopped servo keeps its state.
    #[test]
    fn free_servo_speeds_up_with_the_integral() {
        let mut s = Servo::new(DVec3::Z, DVec3::ZERO, -2.0, 4.0, [0.5, 100.0, 0.001]);
        for n in 1..=3 {
            s.control(DVec3::ZERO, 1e-5);
            assert!(
                (s.vel.z + 2.0 + 0.004 * n as f64).abs() < 1e-12,
                "{}",
                s.vel.z
            );
        }
        s.active = false;
        s.control(DVec3::ZERO, 1e-5);
        assert!((s.vel.z + 2.012).abs() < 1e-12);
        assert_eq!(s.displacement(1e-5), DVec3::ZERO);
    }

    /// At the target force the error is zero and, without integral, the wall rests; a
    /// force beyond the target reverses it; a jump in force is clipped to vmax and the
    /// integral is reset so that kp e + ki S = ±1.
    #[test]
    fn rests_at_the_target_and_clips() {
        let mut s = Servo::new(DVec3::Z, DVec3::ZERO, -1.0, 0.1, [0.5, 0.0, 0.0]);
        s.control(DVec3::Z, 1e-5);
        assert_eq!(s.vel, DVec3::ZERO);
        s.control(DVec3::Z * 1.5, 1e-5);
        assert!((s.vel.z - 0.025).abs() < 1e-15);
        let mut s = Servo::new(DVec3::Z, DVec3::ZERO, -1.0, 0.1, [0.5, 10.0, 0.0]);
        s.control(DVec3::Z * 5.0, 1e-5);
        assert_eq!(s.vel.z, 0.1);
        assert!((0.5 * 4.0 + 10.0 * s.sum - 1.0).abs() < 1e-12);
    }

    /// `ctrlPV torque`: the reach is the farthest vertex from the axis (a 0.1 m paddle:
    /// 0.1) and the angular speed without load is kp · vmax / reach; the mesh turns by
    /// ω dt; a mesh on its axis has no torque servo.
    #[test]
    fn torque_servo_turns_at_most_vmax_at_its_reach() {
        let verts = [
            DVec3::ZERO,
            DVec3::new(0.1, 0.0, 0.0),
            DVec3::new(0.1, 0.0, 0.02),
        ];
        let mut s = Servo::new_torque(
            DVec3::Z * 2.0,
            DVec3::ZERO,
            0.01,
            0.05,
            [1.0, 0.0, 0.0],
            &verts,
        )
        .unwrap();
        assert!((s.reach - 0.1).abs() < 1e-15);
        s.control(DVec3::ZERO, 1e-5);
        assert!((s.vel.z - 0.5).abs() < 1e-15);
        assert_eq!(s.displacement(1e-5), DVec3::ZERO);
        assert!((s.turn(1e-5) - 5e-6).abs() < 1e-20);
        // A torque of −0.005 about +z: half the error, half the speed.
        s.control(DVec3::Z * -0.005, 1e-5);
        assert!((s.vel.z - 0.25).abs() < 1e-15);
        let on_axis = [DVec3::ZERO, DVec3::Z];
        assert!(Servo::new_torque(DVec3::Z, DVec3::ZERO, 1.0, 1.0, [1.0; 3], &on_axis).is_none());
    }

    /// `mode auto`: vmax without candidates; with them vmin · e for |e| ≥ 1 (clipped to
    /// vmin), 0.1 vmin · e for |e| ≤ 0.9 and the linear blend between (|e| = 0.95:
    /// gain 0.55 vmin).
    #[test]
    fn auto_mode_schedules_its_gain() {
        let mut s = Servo::new(DVec3::Z, DVec3::ZERO, -1.0, 0.5, [0.01, 0.0, 0.0]);
        s.auto = true;
        s.ratio = 1e-4;
        s.start_run(Some(0.005), 1e-5);
        assert!((s.vmin - 0.05).abs() < 1e-15);
        s.control(DVec3::ZERO, 1e-5);
        assert_eq!(s.vel.z, -0.5);
        s.contacts = true;
        s.control(DVec3::ZERO, 1e-5);
        assert!((s.vel.z + 0.05).abs() < 1e-15);
        s.control(DVec3::Z * 0.05, 1e-5);
        assert!((s.vel.z + 0.55 * 0.05 * 0.95).abs() < 1e-15, "{}", s.vel.z);
        s.control(DVec3::Z * 0.5, 1e-5);
        assert!((s.vel.z + 0.005 * 0.5).abs() < 1e-15);
        s.control(DVec3::Z * 3.0, 1e-5);
        assert!((s.vel.z - 0.05).abs() < 1e-15);
        s.start_run(None, 1e-5);
        assert!((s.vmin - 1e7).abs() < 1e-6);
    }
}

//! `fix mesh/surface/stress/servo`: a mesh translated along an axis at a velocity a PID
//! controller sets from the force the particles exert on it.
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
        }
    }

    /// The controller update at the end of a step whose total force on the mesh is
    /// `force` (summed over all ranks), with timestep `dt`: sets [`Servo::vel`].
    pub fn control(&mut self, force: DVec3, dt: f64) {
        if !self.active {
            return;
        }
        let pv = -force.dot(self.axis);
        let scale = self.target.abs();
        let e = (self.target - pv) / scale;
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
        self.vel = self.axis * (out * self.vmax);
    }

    /// The displacement of the mesh in a step of `dt` (zero when stopped).
    pub fn displacement(&self, dt: f64) -> DVec3 {
        if self.active {
            self.vel * dt
        } else {
            DVec3::ZERO
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
}

//! `fix ID group lineforce x y z` and `fix ID group planeforce x y z` (LIGGGHTS 3.8, from
//! LAMMPS): after the forces, each particle of the group keeps only the part of its
//! force along the direction (x, y, z) (`lineforce`), or loses that part (`planeforce`),
//! so that it moves along a line or in a plane. Torques are left alone, as in LIGGGHTS.
//! They act in definition order with the other post-force fixes (a wall or gravity
//! defined after them adds its force unprojected, as in LIGGGHTS), through the engine's
//! post-force extension point ([`rdem::fix::ForceFix`]).

use glam::DVec3;
use rdem::fix::ForceFix;
use rdem::par::View;
use rdem::FixKind;

use super::engine::engine_fix;
use super::{style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row of `lineforce`.
pub(super) const ROW_LINE: FixRow = style(
    "lineforce",
    parse_line,
    Stages::ENGINE,
    "`x y z`: each force replaced by its part along the direction (motion along a line)",
);

/// The registry row of `planeforce`.
pub(super) const ROW_PLANE: FixRow = style(
    "planeforce",
    parse_plane,
    Stages::ENGINE,
    "`x y z`: each force loses its part along the direction (motion in the plane normal to it)",
);

/// The projection as the engine runs it.
#[derive(Debug, Clone)]
struct Project {
    /// Unit direction.
    dir: DVec3,
    /// Keep the part along `dir` (lineforce) or remove it (planeforce).
    keep: bool,
}

impl ForceFix for Project {
    fn apply(
        &self,
        p: &View,
        lo: usize,
        f: &mut [DVec3],
        _torque: &mut [DVec3],
        groupbit: u32,
        _dt: f64,
    ) {
        for (k, f) in f.iter_mut().enumerate() {
            if p.mask[lo + k] & groupbit == 0 {
                continue;
            }
            let along = f.dot(self.dir) * self.dir;
            *f = if self.keep { along } else { *f - along };
        }
    }

    fn clone_box(&self) -> Box<dyn ForceFix> {
        Box::new(self.clone())
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead, keep: bool) -> CmdResult<Box<dyn ScriptFix>> {
    let at = a.pos();
    let d = a.vec3("direction")?;
    a.done()?;
    if d.length_squared() == 0.0 {
        return Err(a.error_at(at, "the direction is zero", None));
    }
    let fix = Project {
        dir: d.normalize(),
        keep,
    };
    engine_fix(sim, a, head, FixKind::Force(Box::new(fix)))
}

fn parse_line(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    parse(sim, a, head, true)
}

fn parse_plane(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    parse(sim, a, head, false)
}

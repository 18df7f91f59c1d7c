//! `fix ID group nve/nonspherical [integration_scheme 0|1|2|3]` (LIGGGHTS-INL; not in
//! LIGGGHTS 3.8, which stops with "Invalid fix style"): the integrator of INL's
//! non-spherical bodies. In LIGGGHTS-INL a `fix multisphere` keeps its clumps still until
//! a `fix nve/nonspherical` is defined; then every clump moves as a rigid body.
//!
//! rdem's `fix multisphere` integrates its clumps itself, as LIGGGHTS 3.8 does (with the
//! NO_SQUISH rotation, INL's `integration_scheme 1`), so this fix adds nothing to a run:
//! a script that defines both moves its clumps once per step, as in INL. Checked with a
//! LIGGGHTS-INL build (a clump dropped on a plane, 20000 steps): INL's trajectory is the
//! same to every printed digit whatever the fix's group (even an empty one), its
//! `integration_scheme` (0 to 3) and whether it comes before or after the `fix
//! multisphere`; and without `fix multisphere` it moves nothing (a sphere under gravity
//! stays put), as here. rdem keeps LIGGGHTS 3.8's rule that `fix multisphere` alone moves
//! the clumps; so that the two cannot part silently, `unfix` of this fix is refused while
//! a `fix multisphere` is defined (in INL it would stop the clumps).

use super::{style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "nve/nonspherical",
    parse,
    Stages::NONE,
    "`[integration_scheme 0\\|1\\|2\\|3]` (LIGGGHTS-INL): the clumps of `fix multisphere` move as rigid bodies",
)
.notes("rdem's `fix multisphere` integrates its clumps itself (LIGGGHTS 3.8), so this fix changes nothing in a run that has one; LIGGGHTS-INL gives the same trajectory for every `integration_scheme`, group and order (checked). `unfix` is refused while a `fix multisphere` is defined: in LIGGGHTS-INL it would stop the clumps. Superquadric and convex bodies: not supported");

/// The fix: no state, see the module documentation.
struct NveNonspherical;

fn parse(_sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    while !a.is_done() {
        a.keyword("fix nve/nonspherical keyword", &["integration_scheme"])?;
        let scheme = a.u64("integration_scheme (0, 1, 2 or 3)")?;
        if scheme > 3 {
            return Err(a.error_prev(
                format!("fix nve/nonspherical: integration_scheme {scheme} is not one of LIGGGHTS-INL's"),
                Some("valid: 0 (Richardson iterations), 1 (symplectic, the default), 2 (leap-frog predictor-corrector) or 3 (Woodem)".into()),
            ));
        }
    }
    Ok(Box::new(NveNonspherical))
}

impl ScriptFix for NveNonspherical {
    fn check_unfix(&self, sim: &Sim, head: &FixHead) -> Result<(), Error> {
        match sim.defs.fixes.iter().find(|f| f.head.style == "multisphere") {
            Some(ms) => Err(format!(
                "unfix {}: in LIGGGHTS-INL this stops the clumps of fix multisphere '{}'; rdem's \
                 fix multisphere moves them itself (as LIGGGHTS 3.8), so it cannot stop them this way \
                 (fix_modify {} fflag off off off tflag off off off holds them)",
                head.id,
                ms.id(),
                ms.id()
            )
            .into()),
            None => Ok(()),
        }
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

//! `rdem -check` runs no step, but a run's set-up and end happen as in a real run: what
//! the end of a run undoes (fix adapt's `reset yes`) is undone, so later lines are checked
//! against the state a real run would leave.

use crate::common;

#[test]
fn adapt_reset_restores_radii_after_a_checked_run() {
    let src = "units si\n\
        atom_style granular\n\
        boundary f f f\n\
        region box block 0 1 0 1 0 1 units box\n\
        create_box 1 box\n\
        create_atoms 1 single 0.5 0.5 0.5 units box\n\
        set atom 1 diameter 0.1 density 1000\n\
        fix integr all nve/sphere\n\
        variable d atom 0.3\n\
        fix grow all adapt 1 atom diameter v_d reset yes\n\
        timestep 1e-5\n\
        run 10\n";
    let mut i = common::interpreter();
    let checked = i.check_bytes("in.adapt", src.as_bytes());
    assert!(checked.problems.is_empty(), "{:?}", checked.problems.len());
    let w = i.sim.world.as_ref().expect("box");
    // 0.05 before the run, 0.15 during it (the set-up applies v_d), 0.05 after.
    assert_eq!(w.particles.radius[0], 0.05);
}

//! [`StageCtx`]: what a fix's run-time stage ([`super::ScriptFix::pre_step`],
//! [`super::ScriptFix::end_of_step`], [`super::ScriptFix::end_of_run`]) may reach.

use crate::error::Error;
use rdem::World;

use crate::args::NumOrVar;
use crate::context;
use crate::sim::Sim;

/// What a fix sees while one of its run-time stages acts: the world (there is one during
/// a run), the rest of the script state read-only as a value resolver (variables,
/// computes, regions, the other fixes: [`StageCtx::view`]), the screen and log, and the
/// step. The fix itself is out of the script's fix list meanwhile, so it is not in the
/// view.
pub struct StageCtx<'a> {
    sim: &'a mut Sim,
    /// The step the stage belongs to (at a run's set-up and end: the current step).
    pub step: u64,
    /// The stage runs at a run's set-up (before or after its forces).
    pub setup: bool,
}

impl<'a> StageCtx<'a> {
    /// The context of a stage at `step`; `None` without a world (no run then).
    pub(crate) fn new(sim: &'a mut Sim, step: u64, setup: bool) -> Option<Self> {
        sim.world.as_ref()?;
        Some(Self { sim, step, setup })
    }

    /// The world.
    pub fn world(&mut self) -> &mut World {
        self.sim
            .world
            .as_mut()
            .expect("a stage context has a world")
    }

    /// The world, read-only.
    pub fn world_ref(&self) -> &World {
        self.sim
            .world
            .as_ref()
            .expect("a stage context has a world")
    }

    /// The script state, read-only: what variables, computes, thermo keywords, regions and
    /// the other fixes' values are evaluated against.
    pub fn view(&self) -> &Sim {
        self.sim
    }

    /// The values of a fix's `number | NULL | v_name` arguments as at the stage's step:
    /// numbers as they are, `NULL` as `None`, variables evaluated with the world's step
    /// counter on [`StageCtx::step`] (see [`context::eval_equal_at`]); errors name `who`,
    /// `hint` follows the message for a variable of another style.
    pub fn values_at(
        &mut self,
        values: &[&NumOrVar],
        who: &str,
        hint: &str,
    ) -> Result<Vec<Option<f64>>, Error> {
        context::values_at(self.sim, self.step, values, who, hint)
    }

    /// The equal-style variables `names` as at the stage's step (`None`: no variable).
    pub fn eval_equal_at(
        &mut self,
        names: &[Option<&str>],
        who: &str,
        hint: &str,
    ) -> Result<Vec<Option<f64>>, Error> {
        context::eval_equal_at(self.sim, self.step, names, who, hint)
    }

    /// `f` on the script state with the world's step counter on the stage's step.
    pub fn at_step<T>(&mut self, who: &str, f: impl FnOnce(&Sim) -> T) -> Result<T, Error> {
        context::at_step(self.sim, self.step, who, |sim| f(sim))
    }

    /// Simulated time.
    pub fn time(&self) -> f64 {
        self.sim.time()
    }

    /// Sets the timestep from the next step on (the simulated time goes on from now).
    pub fn set_timestep(&mut self, dt: f64) -> Result<(), Error> {
        self.sim.set_timestep(dt)
    }

    /// Ends the current run after this step, as if it had been asked for no more steps;
    /// the script goes on with its next command.
    pub fn end_run(&mut self) {
        self.sim.script.stop_requested = true;
    }

    /// True under `rdem -check` (the stages run at the set-up only).
    pub fn checking(&self) -> bool {
        self.sim.script.check
    }

    /// A line on the screen and in the log.
    pub fn line(&mut self, text: &str) {
        self.sim.outputs.out.line(text);
    }

    /// A warning, once per run of the script.
    pub fn warn_once(&mut self, text: &str) {
        self.sim.warn_once(text);
    }

    /// The outcome of a file write that only MPI rank 0 does, made the same on every rank
    /// (see [`super::agree_write`]).
    pub fn agree_write(&self, what: &str, r: Result<(), Error>) -> Result<(), Error> {
        super::agree_write(self.sim, what, r)
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use rdem::FixKind;

    use super::*;
    use crate::input::Interpreter;
    use crate::Output;

    /// A fix's stage called directly, without a run: `fix gravity` with a variable
    /// magnitude g = 2·step takes it at the context's step (7 here, the world being at
    /// step 0) in its pre-step stage, and the world's step counter is left as it was.
    #[test]
    fn a_pre_step_stage_evaluates_variables_at_the_context_step() {
        let mut i = Interpreter::new(Sim::new(Output::captured()));
        i.run_source(
            "in.t",
            "region box block 0 1 0 1 0 1 units box\n\
             create_box 1 box\n\
             variable g equal 2*step\n\
             fix grav all gravity v_g vector 0 0 -1\n",
        )
        .unwrap();
        let k = i.sim.fix_index("grav").unwrap();
        super::super::with_fix(&mut i.sim, k, |f, sim, head| {
            let mut ctx = StageCtx::new(sim, 7, false).unwrap();
            f.pre_step(&mut ctx, head)
        })
        .unwrap();
        let w = i.sim.world.as_mut().unwrap();
        assert_eq!(w.step, 0);
        match &w.fix_mut("grav").unwrap().kind {
            FixKind::Gravity { accel } => assert_eq!(*accel, DVec3::new(0.0, 0.0, -14.0)),
            other => panic!("{other:?}"),
        }
    }

    /// Without a box there is no stage context.
    #[test]
    fn no_world_no_context() {
        let mut sim = Sim::new(Output::captured());
        assert!(StageCtx::new(&mut sim, 0, true).is_none());
    }
}

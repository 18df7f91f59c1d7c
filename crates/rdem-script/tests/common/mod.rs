//! Helpers shared by the rdem-script test files: an interpreter with captured output, the
//! script runs that give it back with the rendered error, and the screen text.
#![allow(dead_code)]

use rdem_script::{Interpreter, Output, ScriptReport, Sim};

/// The report as text, without colour and wide enough that no line wraps.
pub fn render(r: &ScriptReport) -> String {
    let mut out = String::new();
    miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
        .with_width(10_000)
        .render_report(&mut out, r)
        .expect("render");
    out
}

/// A fresh interpreter whose screen output is captured.
pub fn interpreter() -> Interpreter {
    Interpreter::new(Sim::new(Output::captured()))
}

/// What the interpreter printed so far.
pub fn screen(i: &Interpreter) -> String {
    i.sim.outputs.out.captured.clone().unwrap_or_default()
}

/// Runs script `src` (named `name` in messages) in a fresh interpreter that must
/// succeed: the interpreter; a failure panics with the rendered error and the screen.
pub fn run(name: &str, src: &str) -> Interpreter {
    let mut i = interpreter();
    if let Err(e) = i.run_source(name, src) {
        panic!("{}\n--- output ---\n{}", render(&e), screen(&i));
    }
    i
}

/// Runs script `src` (named `name` in messages) in a fresh interpreter: the interpreter,
/// or the rendered error.
pub fn try_run(name: &str, src: &str) -> Result<Interpreter, String> {
    let mut i = interpreter();
    match i.run_source(name, src) {
        Ok(()) => Ok(i),
        Err(e) => Err(render(&e)),
    }
}

/// [`try_run`] that also gives the screen: the interpreter and its screen, or the
/// rendered error.
pub fn try_run_screen(name: &str, src: &str) -> Result<(Interpreter, String), String> {
    try_run(name, src).map(|i| {
        let out = screen(&i);
        (i, out)
    })
}

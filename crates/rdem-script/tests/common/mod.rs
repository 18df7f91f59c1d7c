//! Helpers shared by the rdem-script test files: an interpreter with captured output, the
//! script runs that give it back with the rendered error, the screen text and a scratch
//! directory.
#![allow(dead_code)]

use rdem_script::{Interpreter, Output, ScriptReport, Sim};

/// The material block of one atom type most scripts here use (the one of
/// `data/parity/mat.in`): E = 5·10⁶ Pa, ν = 0.45, e = 0.9, μ = 0.05.
///
/// A macro, so that `concat!` can build a `const` script around it; [`MATERIALS`] is the
/// same text for `format!`.
macro_rules! materials {
    () => {
        "\
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
"
    };
}
#[allow(unused_imports)]
pub(crate) use materials;

/// The text of [`materials!`].
pub const MATERIALS: &str = materials!();

/// A fresh, empty directory under the system temp directory, named after `prefix`, the
/// process and a counter.
pub fn scratch_dir(prefix: &str) -> std::path::PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!(
        "rdem-{prefix}-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

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

/// Runs script `src` (named `name` in messages) in interpreter `i`; it must succeed: a
/// failure panics with the rendered error and the screen.
pub fn run_on(i: &mut Interpreter, name: &str, src: &str) {
    if let Err(e) = i.run_source(name, src) {
        panic!("{}\n--- output ---\n{}", render(&e), screen(i));
    }
}

/// Runs script `src` (named `name` in messages) in a fresh interpreter that must
/// succeed: the interpreter; a failure panics with the rendered error and the screen.
pub fn run(name: &str, src: &str) -> Interpreter {
    let mut i = interpreter();
    run_on(&mut i, name, src);
    i
}

/// Runs script `src` (named `name` in messages) in a fresh interpreter that must fail:
/// the rendered error.
pub fn error(name: &str, src: &str) -> String {
    match try_run(name, src) {
        Ok(_) => panic!("{name}: the script ran without an error"),
        Err(e) => e,
    }
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

/// [`run`] for the screen: what the script printed; a failure panics with the rendered
/// error and the screen.
pub fn run_screen(name: &str, src: &str) -> String {
    screen(&run(name, src))
}

/// [`try_run`] for the screen: what the script printed, or the rendered error.
pub fn try_screen(name: &str, src: &str) -> Result<String, String> {
    try_run(name, src).map(|i| screen(&i))
}

/// [`try_run`] that also gives the screen: the interpreter and its screen, or the
/// rendered error.
pub fn try_run_screen(name: &str, src: &str) -> Result<(Interpreter, String), String> {
    try_run(name, src).map(|i| {
        let out = screen(&i);
        (i, out)
    })
}

//! `rdem`: runs a LIGGGHTS 3.8 input script. The command's whole behaviour is
//! [`main`], which the `rdem` binary calls with its arguments (and the Python package's
//! `rdem` command with `sys.argv`).
//!
//! The flags are LIGGGHTS' own (`-in`, `-var`, `-log`, `-echo`, `-screen`, `-nocite`),
//! single-dash long words with a variable number of values after `-var`; clap cannot take
//! that syntax, so the few flags are parsed by hand here (see [`parse`]).

use std::io::{IsTerminal, Read};
use std::process::ExitCode;

use rdem_script::output::Echo;
use rdem_script::{Interpreter, Output, Sim};

const USAGE: &str = "\
rdem — a DEM simulator for granular materials that runs LIGGGHTS 3.8 input scripts

Usage: rdem [options] [-in in.script]      (without -in the script is read from standard input)

Options (LIGGGHTS' own):
  -in FILE                 input script
  -var NAME VALUE...       define an index variable (as 'variable NAME index VALUE...')
  -log FILE|none           log file (default log.liggghts)
  -echo none|screen|log|both   echo input commands (default log)
  -screen FILE|none        screen output to a file, or none
  -nocite                  accepted (rdem writes no citation file)
Options (rdem):
  -check, --check          check the script without running it: report every line rdem
                           cannot run (each with its file:line and caret), then one
                           summary line; exit 1 if there is any. No step runs and no
                           file is written (no dump, data, log or print file).
  --threads N              worker threads (also RDEM_THREADS; default: all cores)
  -h, --help               this text
  -V, --version            version
";

/// Command-line settings.
#[derive(Debug, Default, PartialEq)]
struct Cli {
    input: Option<String>,
    vars: Vec<(String, Vec<String>)>,
    log: Option<String>,
    echo: Option<Echo>,
    screen: Option<String>,
    threads: Option<usize>,
    check: bool,
    help: bool,
    version: bool,
}

/// Parses the command line (without the program name).
fn parse(args: &[String]) -> Result<Cli, String> {
    let mut c = Cli::default();
    let mut i = 0;
    let value = |i: usize, flag: &str| -> Result<String, String> {
        args.get(i + 1)
            .cloned()
            .ok_or_else(|| format!("{flag} needs a value"))
    };
    while i < args.len() {
        let a = args[i].as_str();
        match a {
            "-in" | "-i" => {
                c.input = Some(value(i, a)?);
                i += 2;
            }
            "-var" | "-v" => {
                let name = value(i, a)?;
                // The first value is taken whatever it looks like (`-var dx -0.2`, as
                // LAMMPS does); further values end at the next word starting with '-'.
                let mut vals: Vec<String> = args.get(i + 2).cloned().into_iter().collect();
                i += 2 + vals.len();
                while !vals.is_empty() && i < args.len() && !args[i].starts_with('-') {
                    vals.push(args[i].clone());
                    i += 1;
                }
                if vals.is_empty() {
                    return Err(format!("-var {name} needs at least one value"));
                }
                c.vars.push((name, vals));
            }
            "-log" | "-l" => {
                c.log = Some(value(i, a)?);
                i += 2;
            }
            "-echo" | "-e" => {
                let v = value(i, a)?;
                c.echo = Some(match v.as_str() {
                    "none" => Echo::None,
                    "screen" => Echo::Screen,
                    "log" => Echo::Log,
                    "both" => Echo::Both,
                    _ => return Err(format!("-echo {v}: use none, screen, log or both")),
                });
                i += 2;
            }
            "-screen" | "-sc" => {
                c.screen = Some(value(i, a)?);
                i += 2;
            }
            "-nocite" | "-nc" => i += 1,
            "-check" | "--check" => {
                c.check = true;
                i += 1;
                // `rdem -check in.x`: the script may follow the flag.
                if c.input.is_none() && args.get(i).is_some_and(|a| !a.starts_with('-')) {
                    c.input = Some(args[i].clone());
                    i += 1;
                }
            }
            "--threads" | "-threads" => {
                let v = value(i, a)?;
                c.threads = Some(
                    v.parse()
                        .ok()
                        .filter(|&n: &usize| n >= 1)
                        .ok_or_else(|| format!("--threads {v}: give a whole number >= 1"))?,
                );
                i += 2;
            }
            "-h" | "--help" | "-help" => {
                c.help = true;
                i += 1;
            }
            "-V" | "--version" => {
                c.version = true;
                i += 1;
            }
            other => {
                let known = [
                    "-in",
                    "-var",
                    "-log",
                    "-echo",
                    "-screen",
                    "-nocite",
                    "-check",
                    "--threads",
                    "--help",
                    "--version",
                ];
                return Err(format!(
                    "unknown option '{other}' (options: {})",
                    known.join(" ")
                ));
            }
        }
    }
    Ok(c)
}

/// Runs the `rdem` command with `args` (the arguments after the program name); returns
/// its exit status.
pub fn main(args: &[String]) -> ExitCode {
    let cli = match parse(args) {
        Ok(c) => c,
        Err(m) => {
            eprintln!("rdem: {m}\n\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    if cli.help {
        print!("{USAGE}");
        return ExitCode::SUCCESS;
    }
    if cli.version {
        let mpi = if cfg!(feature = "mpi") {
            " (with MPI)"
        } else {
            ""
        };
        println!("rdem {}{mpi}", env!("CARGO_PKG_VERSION"));
        return ExitCode::SUCCESS;
    }
    // Under mpirun every rank runs this; MPI ends when the guard is dropped at exit.
    #[cfg(feature = "mpi")]
    let _mpi = rdem::comm::init_mpi();
    let (rank, nprocs) = rdem::comm::process_rank_size();
    // Where failing ranks meet before stopping (made now, while every rank is here).
    let stop_line = rdem::comm::StopLine::new();
    let threads = match cli.threads {
        Some(n) => n,
        None => match std::env::var("RDEM_THREADS") {
            Ok(v) => match v.parse::<usize>() {
                Ok(n) if n >= 1 => n,
                _ => {
                    eprintln!("rdem: RDEM_THREADS={v}: give a whole number >= 1");
                    return ExitCode::from(2);
                }
            },
            // All cores, shared between the ranks started on this machine.
            Err(_) => rdem::par::cores_per_process(),
        },
    };
    if cli.check {
        return check(&cli, threads, rank);
    }
    let mut out = Output::stdout();
    // Only rank 0 prints and keeps the log, as in LIGGGHTS.
    if rank != 0 {
        out.set_screen(None);
    }
    match cli.screen.as_deref() {
        Some("none") => out.set_screen(None),
        Some(f) => match std::fs::File::create(f) {
            Ok(h) => out.set_screen(Some(Box::new(std::io::BufWriter::new(h)))),
            Err(e) => {
                eprintln!("rdem: cannot open screen file '{f}': {e}");
                return ExitCode::from(1);
            }
        },
        None => {}
    }
    let log = cli.log.clone().unwrap_or_else(|| "log.liggghts".into());
    if log != "none" && rank == 0 {
        if let Err(e) = out.set_log(Some(&log), false) {
            eprintln!("rdem: cannot open log file '{log}': {e}");
            return ExitCode::from(1);
        }
    }
    if let Some(e) = cli.echo {
        out.echo = e;
    }
    out.line(&format!(
        "rdem {} (runs LIGGGHTS 3.8 input scripts)",
        env!("CARGO_PKG_VERSION")
    ));
    // The force pass runs on this pool (its results do not depend on the thread count).
    // The main thread is one of its workers, so that the pass's fork-joins start without
    // waking another thread (which would cost a single-thread run a tenth of its speed).
    if let Err(e) = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .use_current_thread()
        .build_global()
    {
        eprintln!("rdem: cannot start {threads} threads: {e}");
        return ExitCode::from(1);
    }
    out.line(&format!(
        "  using {threads} thread{}",
        if threads == 1 { "" } else { "s" }
    ));
    let mut sim = Sim::new(out);
    sim.script.threads = threads;
    for (name, vals) in &cli.vars {
        if let Err(e) = sim.script.vars.define(name, "index", vals) {
            eprintln!("rdem: -var {name}: {}", e.message);
            return ExitCode::from(2);
        }
    }
    let show_progress = std::io::stderr().is_terminal() && cli.screen.is_none() && rank == 0;
    if show_progress {
        sim.outputs.progress = Some(progress_reporter());
    }
    let mut interp = Interpreter::new(sim);
    let result = match &cli.input {
        Some(f) => interp.run_file(f),
        None => {
            let mut s = Vec::new();
            if let Err(e) = std::io::stdin().read_to_end(&mut s) {
                eprintln!("rdem: cannot read the script from standard input: {e}");
                return ExitCode::from(1);
            }
            interp.run_bytes("<stdin>", &s)
        }
    };
    interp.sim.outputs.out.flush();
    match result {
        Ok(()) => {
            interp.sim.outputs.out.line(&format!(
                "Total wall time: {}",
                hms(interp.sim.script.started.elapsed().as_secs())
            ));
            interp.sim.outputs.out.flush();
            ExitCode::SUCCESS
        }
        Err(report) => {
            let text = format!("{:?}", miette::Report::new(*report));
            interp.sim.outputs.out.log_line(&format!("ERROR: {text}"));
            interp.sim.outputs.out.flush();
            // Every rank reads the same script and every command's failure (and every
            // file write's) is agreed on by all ranks, so every rank stops here and rank 0
            // reports. A failure that some ranks did not see would leave the others
            // blocked: after a grace time the failing ranks report and abort the job.
            if nprocs == 1 || stop_line.all_stopping(std::time::Duration::from_secs(20)) {
                if rank == 0 {
                    eprintln!("{text}");
                }
                return ExitCode::from(1);
            }
            eprintln!("rdem: MPI rank {rank} stopped alone; stopping every rank\n{text}");
            stop_line.abort(1)
        }
    }
}

/// `rdem -check`: runs the script in check mode (see `rdem_script::check`) with no screen
/// output and no log file; prints every report on standard error, then the notes and the
/// summary line on standard output. Exit 1 if any line cannot run.
fn check(cli: &Cli, threads: usize, rank: usize) -> ExitCode {
    if let Err(e) = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .use_current_thread()
        .build_global()
    {
        eprintln!("rdem: cannot start {threads} threads: {e}");
        return ExitCode::from(1);
    }
    let mut out = Output::stdout();
    out.set_screen(None);
    out.echo = Echo::None;
    let mut sim = Sim::new(out);
    sim.script.threads = threads;
    for (name, vals) in &cli.vars {
        if let Err(e) = sim.script.vars.define(name, "index", vals) {
            eprintln!("rdem: -var {name}: {}", e.message);
            return ExitCode::from(2);
        }
    }
    let mut interp = Interpreter::new(sim);
    let (name, checked) = match &cli.input {
        Some(f) => (f.clone(), interp.check_file(f)),
        None => {
            let mut s = Vec::new();
            if let Err(e) = std::io::stdin().read_to_end(&mut s) {
                eprintln!("rdem: cannot read the script from standard input: {e}");
                return ExitCode::from(1);
            }
            ("<stdin>".to_string(), interp.check_bytes("<stdin>", &s))
        }
    };
    let summary = checked.summary(&name);
    let ok = checked.problems.is_empty();
    if rank == 0 {
        for p in checked.problems {
            eprintln!("{:?}", miette::Report::new(p.report));
        }
        for n in &checked.notes {
            println!("{n}");
        }
        println!("{summary}");
    }
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

fn hms(s: u64) -> String {
    format!("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60)
}

/// A progress line on standard error (percent done and time remaining) for runs that
/// take more than a couple of seconds.
fn progress_reporter() -> Box<dyn FnMut(u64, u64)> {
    let mut bar: Option<(indicatif::ProgressBar, u64)> = None;
    let mut started = std::time::Instant::now();
    Box::new(move |done, total| {
        if done < total && bar.as_ref().is_none_or(|(_, t)| *t != total) {
            if let Some((b, _)) = bar.take() {
                b.finish_and_clear();
            }
            started = std::time::Instant::now();
            let b = indicatif::ProgressBar::new(total);
            b.set_style(
                indicatif::ProgressStyle::with_template(
                    "  step {pos}/{len} {percent:>3}% [{bar:30}] {elapsed_precise} elapsed, {eta_precise} left",
                )
                .expect("valid template")
                .progress_chars("=> "),
            );
            b.set_draw_target(indicatif::ProgressDrawTarget::hidden());
            bar = Some((b, total));
        }
        if let Some((b, _)) = &bar {
            // Show only runs long enough to need it.
            if started.elapsed().as_secs_f64() > 2.0 && b.is_hidden() {
                b.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            }
            b.set_position(done);
            if done >= total {
                b.finish_and_clear();
                bar = None;
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| x.to_string()).collect()
    }

    #[test]
    fn liggghts_flags() {
        let c = parse(&s(&[
            "-in",
            "in.x",
            "-var",
            "n",
            "1",
            "2",
            "-log",
            "none",
            "-echo",
            "both",
            "-nocite",
            "--threads",
            "2",
        ]))
        .unwrap();
        assert_eq!(c.input.as_deref(), Some("in.x"));
        assert_eq!(c.vars, vec![("n".to_string(), s(&["1", "2"]))]);
        assert_eq!(c.log.as_deref(), Some("none"));
        assert_eq!(c.echo, Some(Echo::Both));
        assert_eq!(c.threads, Some(2));
        assert!(parse(&s(&["-bogus"]))
            .unwrap_err()
            .contains("unknown option"));
        assert!(parse(&s(&["--threads", "0"])).is_err());
        assert!(parse(&s(&["-var", "n"])).is_err());
        // A negative first value is a value (LAMMPS), later ones end the list.
        let c = parse(&s(&["-var", "dx", "-0.2", "-var", "y", "1", "-3"]));
        assert!(c.is_err(), "'-3' is not an option");
        let c = parse(&s(&["-var", "dx", "-0.2", "-var", "y", "1", "2"])).unwrap();
        assert_eq!(
            c.vars,
            vec![
                ("dx".to_string(), s(&["-0.2"])),
                ("y".to_string(), s(&["1", "2"]))
            ]
        );
        for args in [
            &["-check", "in.x"][..],
            &["--check", "in.x"],
            &["-in", "in.x", "-check"],
            &["-check", "-in", "in.x", "-var", "a", "1"],
        ] {
            let c = parse(&s(args)).unwrap();
            assert!(c.check, "{args:?}");
            assert_eq!(c.input.as_deref(), Some("in.x"), "{args:?}");
        }
    }
}

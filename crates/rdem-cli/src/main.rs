//! The `rdem` binary: [`rdem_cli::main`] with the process's arguments.

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    rdem_cli::main(&args)
}

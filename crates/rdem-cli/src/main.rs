//! The `rdem` binary: [`rdem_cli::main`] with the process's arguments.

fn main() -> std::process::ExitCode {
    map_large_blocks();
    let args: Vec<String> = std::env::args().skip(1).collect();
    rdem_cli::main(&args)
}

/// Blocks of 4 MiB and more (the per-particle arrays, the neighbor list and its search's
/// scratch in large runs) get their own mapping, given back to the system when freed.
/// glibc otherwise raises its mapping threshold each time such a block is freed and serves
/// the next ones from its heap, where freed space stays resident: at a million particles
/// that was about 20 MiB of the peak resident memory. Smaller blocks are unaffected (the
/// dense bench bed runs at the same speed).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn map_large_blocks() {
    // SAFETY: mallopt only sets a parameter of glibc's allocator; it is called before any
    // other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 4 << 20);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn map_large_blocks() {}

//! "Memory usage per processor" is the process's real peak resident memory: compared
//! with the peak that GNU time measures from outside, on the benchmark lattice
//! (`../shared/bench/in.lattice`) at n = 50, 125,000 spheres settling, where the
//! engine's own count of its arrays gave about half of it.

use crate::common;

#[test]
fn the_printed_memory_is_the_measured_peak_within_10_percent() {
    let time = std::path::Path::new("/usr/bin/time");
    assert!(
        time.exists(),
        "GNU time (Debian package `time`) is needed: scripts/test.sh installs it"
    );
    let script =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/bench/in.lattice");
    let dir = common::scratch_dir("memory");
    let out = std::process::Command::new(time)
        .args(["-f", "%M", "-o", "peak.txt", env!("CARGO_BIN_EXE_rdem")])
        .arg("-in")
        .arg(&script)
        .args(["-var", "n", "50", "-log", "none"])
        .env("RDEM_THREADS", "1")
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("with 125000 atoms"), "{text}");
    let printed: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("Memory usage per processor = "))
        .and_then(|l| l.strip_suffix(" Mbytes"))
        .expect("the memory line")
        .parse()
        .unwrap();
    let kb: f64 = std::fs::read_to_string(dir.join("peak.txt"))
        .unwrap()
        .split_whitespace()
        .last()
        .unwrap()
        .parse()
        .unwrap();
    let measured = kb / 1024.0;
    assert!(
        (printed - measured).abs() <= 0.1 * measured,
        "printed {printed} MiB, measured peak {measured} MiB"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

//! "Memory usage per processor" is the process's real peak resident memory: compared
//! with the peak that GNU time measures from outside, on 125,000 spheres settling from a
//! lattice (the layout of shared/bench/in.lattice at n = 50), where the engine's own
//! count of its arrays gave about half of it.

mod common;

const LATTICE: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block 0 0.1 0 0.1 0 0.1 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
lattice sc 0.002 origin 0.5 0.5 0.5
create_atoms 1 box
set type 1 diameter 0.00201 density 2500
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zw all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix integr all nve/sphere
run 20
";

#[test]
fn the_printed_memory_is_the_measured_peak_within_10_percent() {
    let time = std::path::Path::new("/usr/bin/time");
    assert!(
        time.exists(),
        "GNU time (Debian package `time`) is needed: scripts/test.sh installs it"
    );
    let dir = common::scratch_dir("memory");
    std::fs::write(dir.join("in.lattice"), LATTICE).unwrap();
    let out = std::process::Command::new(time)
        .args(["-f", "%M", "-o", "peak.txt", env!("CARGO_BIN_EXE_rdem")])
        .args(["-in", "in.lattice", "-log", "none"])
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

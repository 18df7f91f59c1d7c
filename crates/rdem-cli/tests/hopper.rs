//! The hopper example (`examples/hopper`): discharge through a circular orifice in the
//! flat floor of an STL silo follows the Beverloo law
//! W = C ρ_b √g (D − k d)^{5/2} (C = 0.58, k = 1.5) within 15 % for two orifice sizes.
//!
//! ρ_b is the bulk density the script prints after settling, d = 5 mm the mean bead
//! diameter, W the mass through the orifice (fix massflow/mesh) between 0.05 s and
//! 0.6 s after opening (steps 11000 to 22000), averaged over three packings (insertion
//! seeds); one thread (the result is the same for any thread count). One packing's rate
//! scatters by about ±6 % around the mean.
//!
//! LIGGGHTS 3.8 on the same script (`liggghts -in in.hopper -var D 25|35 -var seed N`):
//! D = 25 mm over nine seeds (10039, 20011, 30011, 40009, 50021, 60013, 70001, 80021,
//! 90001) W = 0.1008 kg/s on average (0.085–0.107, standard error 0.0022); D = 35 mm over
//! the first five 0.3032 kg/s (0.301–0.309). rdem over the same seeds: 0.0960 (−4.8 %)
//! and 0.2853 kg/s (−5.9 %); these three seeds give 0.0981 and 0.2857 kg/s. Where the
//! two codes part is in the issue notes.

use std::path::Path;
use std::process::Command;

mod common;
use common::{copy_dir, thermo_rows};

/// (bulk density, discharge rate) of the example with orifice `d_mm`.
fn discharge(d_mm: u32, seed: u64) -> (f64, f64) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/hopper");
    let tmp =
        std::env::temp_dir().join(format!("rdem-hopper-{d_mm}-{seed}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    copy_dir(&src, &tmp);
    let _ = std::fs::remove_dir_all(tmp.join("post"));
    let out = Command::new(env!("CARGO_BIN_EXE_rdem"))
        .args([
            "-in",
            "in.hopper",
            "-log",
            "none",
            "-var",
            "D",
            &d_mm.to_string(),
            "-var",
            "seed",
            &seed.to_string(),
        ])
        .env("RDEM_THREADS", "1")
        .current_dir(&tmp)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{}\n{text}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rhob: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("bulk density "))
        .expect("bulk density line")
        .trim()
        .parse()
        .unwrap();
    let rows = thermo_rows(&text);
    let mass_at = |step: f64| {
        rows.iter()
            .rev()
            .find(|r| r[0] == step && r.len() == 5)
            .unwrap_or_else(|| panic!("no row at {step}: {text}"))[3]
    };
    let rate = (mass_at(22000.0) - mass_at(11000.0)) / (11000.0 * 5e-5);
    let _ = std::fs::remove_dir_all(&tmp);
    (rhob, rate)
}

fn beverloo(rhob: f64, d_orifice: f64) -> f64 {
    0.58 * rhob * 9.81f64.sqrt() * (d_orifice - 1.5 * 0.005).powf(2.5)
}

/// Insertion seeds of the three packings each orifice drains.
const SEEDS: [u64; 3] = [10039, 20011, 30011];

#[test]
fn discharge_follows_beverloo() {
    for d_mm in [25, 35] {
        let mut ratios = Vec::new();
        for seed in SEEDS {
            let (rhob, w) = discharge(d_mm, seed);
            let b = beverloo(rhob, d_mm as f64 / 1000.0);
            eprintln!(
                "D = {d_mm} mm, seed {seed}: bulk density {rhob:.1} kg/m3, W = {w:.5} kg/s, Beverloo {b:.5} kg/s ({:+.1} %)",
                100.0 * (w / b - 1.0)
            );
            assert!(
                (rhob - 1450.0).abs() < 100.0,
                "bulk density {rhob} (random packing of glass beads ~0.58-0.62 of 2500)"
            );
            ratios.push(w / b);
        }
        let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
        assert!(
            (mean - 1.0).abs() < 0.15,
            "D = {d_mm} mm: W / Beverloo over three packings {ratios:?}, mean {mean}"
        );
    }
}

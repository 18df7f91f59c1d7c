//! SPH (`atom_style sph`, `pair_style sph/artVisc/tensCorr`, the `sph/...` fixes,
//! `wall/sph`, `nve/sph[/stationary]`) against LIGGGHTS 3.8, from the per-atom values of
//! small cases step by step to the first steps of the tutorials `sph_2` and `sph_1`.
//!
//! The reference files in `tests/data/sph/` are LIGGGHTS 3.8's outputs of the scripts
//! beside them (`regenerate.sh` remakes them); rdem runs the same scripts.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::common;
use common::{rdem_command, scratch_dir, thermo_rows, tutorial_copy, TUTORIALS};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/sph")
}

/// One step of a text dump: the column names and the rows (sorted by id).
type Frame = (Vec<String>, Vec<Vec<f64>>);

/// Every step of a `dump custom` text file.
fn read_dump(path: &Path) -> BTreeMap<u64, Frame> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let lines: Vec<&str> = text.lines().collect();
    let mut out = BTreeMap::new();
    let mut k = 0;
    while k < lines.len() {
        if lines[k].starts_with("ITEM: TIMESTEP") {
            let step: u64 = lines[k + 1].trim().parse().unwrap();
            let n: usize = lines[k + 3].trim().parse().unwrap();
            let cols: Vec<String> = lines[k + 8]
                .split_whitespace()
                .skip(2)
                .map(String::from)
                .collect();
            let mut rows: Vec<Vec<f64>> = lines[k + 9..k + 9 + n]
                .iter()
                .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
                .collect();
            rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
            out.insert(step, (cols, rows));
            k += 9 + n;
        } else {
            k += 1;
        }
    }
    out
}

/// Compares rdem's dump `name` (in `dir`) with LIGGGHTS' (in `tests/data/sph`): the
/// same steps, atoms and columns, every value within `tol` relative to the largest
/// magnitude of its column at that step (positions: relative to 1 m). Returns the
/// largest difference found.
fn compare_dumps(dir: &Path, name: &str, tol: f64) -> f64 {
    let ours = read_dump(&dir.join(name));
    let theirs = read_dump(&data().join(name));
    assert_eq!(
        ours.keys().collect::<Vec<_>>(),
        theirs.keys().collect::<Vec<_>>(),
        "{name}: steps"
    );
    let mut worst: f64 = 0.0;
    for (step, (cols, rows)) in &theirs {
        let (ocols, orows) = &ours[step];
        assert_eq!(cols, ocols, "{name}: columns");
        assert_eq!(rows.len(), orows.len(), "{name} step {step}: atoms");
        for c in 0..cols.len() {
            let scale = rows.iter().map(|r| r[c].abs()).fold(
                if matches!(cols[c].as_str(), "x" | "y" | "z") {
                    1.0
                } else {
                    1e-300
                },
                f64::max,
            );
            for (r, o) in rows.iter().zip(orows) {
                let d = (r[c] - o[c]).abs() / scale;
                worst = worst.max(d);
                assert!(
                    d <= tol,
                    "{name} step {step} atom {} column {}: LIGGGHTS {} rdem {} (relative {d:e})",
                    r[0],
                    cols[c],
                    r[c],
                    o[c]
                );
            }
        }
    }
    worst
}

/// Three particles, two fluid and one boundary particle of another type, seven steps in
/// two runs: positions, velocities, forces, densities and pressures equal LIGGGHTS 3.8's
/// at every step to 1e-11 of each column's magnitude (the same formulas in the same
/// order; the rest is round-off). This checks every term of the pair style (pressure,
/// artificial viscosity with per-type α, β, c, smoothing lengths mixed as means,
/// tensile correction for negative and for positive pressures), the density rate, the
/// Shepard filter every 3 steps, Tait's equation, `nve/sph` (with its velocity
/// estimate), `nve/sph/stationary`, and what the set-up of a run does (no pair force,
/// dρ/dt zeroed, gravity acting).
#[test]
fn three_particles_match_liggghts_step_by_step() {
    let (dir, _) = common::run_data_script("sph", &data(), "in.three", &[]);
    let worst = compare_dumps(&dir, "three.dump", 1e-11);
    eprintln!("three particles: largest relative difference {worst:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every kernel (`cubicspline`, `cubicspline2d`, `wendland`, `wendland2d`, `spiky`,
/// `spiky2d`) on pairs at nine distances: the density by summation (W, the particle's
/// own share included), the pressure and the pressure force (dW/dr) equal LIGGGHTS
/// 3.8's to 1e-12 relative, with its rounded normalisation constants.
#[test]
fn kernels_and_density_summation_match_liggghts() {
    let (dir, _) = common::run_data_script("sph", &data(), "in.kernels", &[]);
    for name in [
        "cubicspline",
        "cubicspline2d",
        "wendland",
        "wendland2d",
        "spiky",
        "spiky2d",
    ] {
        let worst = compare_dumps(&dir, &format!("kernel_{name}.dump"), 1e-12);
        eprintln!("kernel {name}: largest relative difference {worst:e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `fix wall/sph` with both planes, and `sph/pressure absolut` and `relativ`: forces,
/// positions and pressures equal LIGGGHTS 3.8's for three steps to 1e-12.
#[test]
fn wall_and_equations_of_state_match_liggghts() {
    let (dir, _) = common::run_data_script("sph", &data(), "in.wall", &[]);
    let worst = compare_dumps(&dir, "wall.dump", 1e-12);
    eprintln!("wall/sph: largest relative difference {worst:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `fix wall/region/sph` on a block (particles of two types near three faces), a sphere
/// (near its surface in several directions), a z cylinder with finite ends (near its
/// curved surface, its lower cap, and the edge where the upper cap meets the curved
/// surface, feeling both) and an open x cylinder; side out: a sphere, a block (near
/// faces, edges and corners) and a finite cylinder (curved surface, caps, rims); two
/// planes (side in and out); a union of two overlapping blocks (particles near the
/// parts' inner faces feel nothing), the intersection of a slab and a sphere, and a
/// cone side in (its slanted side, caps and lower rim) and out (side, caps, upper rim); at
/// several distances, with positive and negative pressures, moving towards or away from
/// the walls; the outside of an L-shaped union (its inner edge, and a face under the
/// parts' overlap that gives nothing); a moving block and a turning cylinder: forces, velocities, positions, densities and pressures equal LIGGGHTS
/// 3.8's for three steps to 1e-12.
#[test]
fn wall_region_matches_liggghts() {
    // A block, a sphere, a z cylinder with its caps and an open x cylinder (side in);
    // a sphere, a block and a finite cylinder side out (faces, edges, corners, rims);
    // planes on either side; a union of two blocks (its inner faces give nothing) and
    // the intersection of a slab and a sphere; a cone, side in and out; a side-out
    // union; a block that moves and a cylinder that turns.
    for case in [
        "wall_region",
        "wall_sphere",
        "wall_cylinder",
        "wall_xcylinder",
        "wall_sphere_out",
        "wall_block_out",
        "wall_cylinder_out",
        "wall_plane",
        "wall_union",
        "wall_intersect",
        "wall_cone",
        "wall_cone_out",
        "wall_union_out",
        "wall_move",
        "wall_rotate",
    ] {
        let (dir, _) = common::run_data_script("sph", &data(), &format!("in.{case}"), &[]);
        let worst = compare_dumps(&dir, &format!("{case}.dump"), 1e-12);
        eprintln!("wall/region/sph {case}: largest relative difference {worst:e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// The tutorial sph_2 (2d dam break, 754 particles: 295 fluid, 459 boundary particles
/// with a wall/sph gate) run unmodified up to its `unfix wall`, i.e. `run 1` and
/// `run 5000`, with its VTK dumps: the atom count and the kinetic energy of every thermo
/// row, then the fluid's mean and largest height and mean x, equal LIGGGHTS 3.8's
/// (`tests/data/sph/sph_2_short.log`). Tolerance 1e-6 relative: the same formulas in
/// the same order, except that sums over neighbours run in another order (rdem's
/// neighbour list), whose round-off grows over 5000 steps of a fluid that is
/// starting to move (measured: below 1e-8).
#[test]
fn sph_2_first_5001_steps_match_liggghts() {
    let (src, dir) = tutorial_copy("sph_2", "in.sph_2", "sph2");
    let script = std::fs::read_to_string(src.join("in.sph_2")).unwrap();
    let part: String = script
        .lines()
        .take_while(|l| !l.starts_with("unfix"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("in.part"), part).unwrap();
    std::fs::copy(data().join("stats.in"), dir.join("stats.in")).unwrap();
    std::fs::write(
        dir.join("wrapper.in"),
        "include in.part\ninclude stats.in\n",
    )
    .unwrap();
    let out = rdem_command(None)
        .args(["-in", "wrapper.in", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "sph_2: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reference = std::fs::read_to_string(data().join("sph_2_short.log")).unwrap();
    let (ours, theirs) = (thermo_rows(&text), thermo_rows(&reference));
    assert_eq!(ours.len(), theirs.len(), "thermo rows:\n{text}");
    let mut worst: f64 = 0.0;
    for (o, t) in ours.iter().zip(&theirs) {
        assert_eq!(o[0], t[0], "step");
        assert_eq!(o[1], t[1], "atoms at step {}", t[0]);
        assert_eq!(t[1], 754.0);
        // ke and the volume (in 2d the box's area), or, in the last row, ke and the
        // fluid statistics; the last column of the tutorial's rows is the CPU time.
        let cols = if o.len() == 6 { 2..6 } else { 2..4 };
        for c in cols {
            let d = (o[c] - t[c]).abs() / t[c].abs().max(1e-12);
            worst = worst.max(d);
            assert!(
                d < 1e-6,
                "step {} column {c}: LIGGGHTS {} rdem {} (relative {d:e})",
                t[0],
                t[c],
                o[c]
            );
        }
    }
    eprintln!("sph_2 first 5001 steps: largest relative difference {worst:e}");
    // LIGGGHTS 3.8 writes the snapshots of steps 1000..5000 and not one at step 1,
    // where the dump is defined (measured), each with its bounding box file.
    let mut vtk: Vec<String> = std::fs::read_dir(dir.join("post"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".vtk") && !n.contains("boundingBox"))
        .collect();
    vtk.sort();
    assert_eq!(
        vtk,
        [
            "sph_1000.vtk",
            "sph_2000.vtk",
            "sph_3000.vtk",
            "sph_4000.vtk",
            "sph_5000.vtk"
        ],
        "VTK snapshots"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The tutorial sph_1 (3d dam break, 2655 particles, `wall/region/sph` box and a
/// `wall/sph` gate) up to its `unfix wall`, its `run 5000` cut to `run 2000` (the rest
/// unmodified): atoms, kinetic energy and volume of every thermo row equal LIGGGHTS
/// 3.8's (`tests/data/sph/sph_1_2000.log`) to 1e-6 relative, as for sph_2 (measured:
/// equal to the 8 printed digits, also over 25 001 steps).
#[test]
fn sph_1_first_2001_steps_match_liggghts() {
    let src = Path::new(TUTORIALS).join("sph_1");
    assert!(
        src.join("in.sph_1").exists(),
        "{} is missing: install the liggghts-doc package",
        src.display()
    );
    let dir = scratch_dir("sph1");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let script = std::fs::read_to_string(src.join("in.sph_1")).unwrap();
    let part: String = script
        .lines()
        .take_while(|l| !l.starts_with("unfix"))
        .map(|l| {
            if l.split_whitespace().eq(["run", "5000"]) {
                "run 2000\n".to_string()
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    assert!(part.contains("run 2000"), "sph_1 has no 'run 5000'");
    std::fs::write(dir.join("in.part"), part).unwrap();
    let out = rdem_command(None)
        .args(["-in", "in.part", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "sph_1: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reference = std::fs::read_to_string(data().join("sph_1_2000.log")).unwrap();
    let (ours, theirs) = (thermo_rows(&text), thermo_rows(&reference));
    assert_eq!(ours.len(), theirs.len(), "thermo rows:\n{text}");
    let mut worst: f64 = 0.0;
    for (o, t) in ours.iter().zip(&theirs) {
        assert_eq!(o[0], t[0], "step");
        assert_eq!(o[1], t[1], "atoms at step {}", t[0]);
        assert_eq!(t[1], 2655.0);
        for c in 2..4 {
            let d = (o[c] - t[c]).abs() / t[c].abs().max(1e-12);
            worst = worst.max(d);
            assert!(
                d < 1e-6,
                "step {} column {c}: LIGGGHTS {} rdem {} (relative {d:e})",
                t[0],
                t[c],
                o[c]
            );
        }
    }
    eprintln!("sph_1 first 2001 steps: largest relative difference {worst:e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// An unknown kernel or SPH keyword stops with a located error listing the valid ones;
/// the manual's old `artVisc alpha beta eta` values are refused, as LIGGGHTS 3.8 does.
#[test]
fn sph_errors_are_located_and_list_the_choices() {
    let head = "atom_style sph\ndimension 2\nboundary f f p\nregion r block 0 1 0 1 -0.001 0.001 units box\ncreate_box 1 r\n";
    for (line, want) in [
        (
            "pair_style sph/artVisc/tensCorr quintic 0.01",
            "cubicspline",
        ),
        (
            "pair_style sph/artVisc/tensCorr cubicspline2d 0.01 artVisc 0.1 0 1e-8",
            "property/global",
        ),
        (
            "pair_style sph/artVisc/tensCorr cubicspline2d 0.01 visc",
            "artVisc",
        ),
        ("fix p all sph/pressure tait 1 2 3", "Tait"),
        ("fix c all sph/density/corr shepherd every 3", "shepard"),
    ] {
        let out = common::run_script_raw(&format!("{head}{line}\n"), None);
        let err = String::from_utf8_lossy(&out.stderr).into_owned()
            + &String::from_utf8_lossy(&out.stdout);
        assert!(!out.status.success(), "{line}: accepted");
        assert!(err.contains("in.test:6"), "{line}: not located:\n{err}");
        assert!(err.contains(want), "{line}: no '{want}' in:\n{err}");
    }
}

/// `wall/region/sph` on a region it does not support (a union of five blocks, which
/// could give 30 contacts at once) stops at the region's word with the shapes it does
/// support.
#[test]
fn wall_region_on_other_shapes_is_a_located_error() {
    let script = std::fs::read_to_string(data().join("in.wall_region")).unwrap();
    let shapes = "supports block, sphere, cylinder, cone and plane";
    let region = "region        b1 block 0. 0.9 -0.5 0.3 0. 0.9 units box\n\
         region        b2 block 0. 0.8 -0.5 0.3 0. 0.9 units box\n\
         region        b3 block 0. 0.7 -0.5 0.3 0. 0.9 units box\n\
         region        b4 block 0. 0.6 -0.5 0.3 0. 0.9 units box\n\
         region        b5 block 0. 0.5 -0.5 0.3 0. 0.9 units box\n\
         region        boxw union 5 b1 b2 b3 b4 b5";
    let bad = script.replace(
        "region        boxw block 0. 0.9 -0.5 0.3 0. 0.9 units box",
        region,
    );
    assert_ne!(bad, script);
    let out = common::run_script_raw(&bad, None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains(shapes), "{err}");
    assert!(err.contains("at most 24"), "{err}");
    assert!(err.contains("in.test:"), "located: {err}");
}

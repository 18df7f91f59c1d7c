//! `region mesh/tet` from scripts: the liggghts-doc tutorial `mesh_tet` run unmodified
//! creates the 13121 lattice atoms LIGGGHTS 3.8 creates and runs to its end; hand-made
//! meshes with lattice points on their faces, moved, scaled and turned, give LIGGGHTS'
//! counts exactly; `fix insert/pack ... all_in yes` fills the mesh with whole spheres; a
//! malformed VTK file and the keywords LIGGGHTS refuses stop with the script line.
//!
//! The LIGGGHTS figures are in `tests/data/mesh_tet/` (`mesh_tet.log`, `counts.txt`),
//! with the script and meshes that made them and `regenerate.sh`.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common;
use common::{run_kept, tutorial_copy, TUTORIALS};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mesh_tet")
}

/// The N of the first `Created N atoms` line.
fn created(out: &str) -> Option<u64> {
    out.lines().find_map(|l| {
        l.strip_prefix("Created ")?
            .strip_suffix(" atoms")?
            .parse()
            .ok()
    })
}

/// (steps, atoms) of the last `Loop time of ...` line.
fn last_loop(out: &str) -> (u64, u64) {
    let l = out
        .lines()
        .rfind(|l| l.starts_with("Loop time of"))
        .expect("a Loop time line");
    let w: Vec<&str> = l.split_whitespace().collect();
    let at = |key: &str| -> u64 {
        let k = w
            .iter()
            .position(|x| x.trim_end_matches(',') == key)
            .expect(key);
        w[k - 1].parse().unwrap()
    };
    (at("steps"), at("atoms"))
}

#[test]
fn tutorial_creates_the_atoms_liggghts_creates() {
    let (_, dir) = tutorial_copy("mesh_tet", "in.mesh_tet", "mesh-tet-tutorial");
    let out = Command::new(env!("CARGO_BIN_EXE_rdem"))
        .args(["-in", "in.mesh_tet", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lig = std::fs::read_to_string(data().join("mesh_tet.log")).unwrap();
    assert_eq!(created(&lig), Some(13121), "the stored LIGGGHTS log");
    assert_eq!(created(&text), created(&lig));
    assert_eq!(last_loop(&text), last_loop(&lig));
    // The dump of the second run was written.
    assert!(dir.join("post/tetmesh_800.vtk").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn lattice_counts_match_liggghts() {
    let template = std::fs::read_to_string(data().join("case.in")).unwrap();
    let counts = std::fs::read_to_string(data().join("counts.txt")).unwrap();
    let want = |name: &str| -> u64 {
        counts
            .lines()
            .find_map(|l| {
                let w: Vec<&str> = l.split_whitespace().collect();
                (w.first() == Some(&name)).then(|| w[1].parse().unwrap())
            })
            .unwrap_or_else(|| panic!("no count for {name}"))
    };
    let cases = std::fs::read_to_string(data().join("cases.txt")).unwrap();
    let mut n = 0;
    for line in cases
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let w: Vec<&str> = line.split_whitespace().collect();
        let script = template
            .replace("@FILE@", w[1])
            .replace("@SCALE@", w[2])
            .replace("@MOVE@", &w[3..6].join(" "))
            .replace("@ROTATE@", &w[6..9].join(" "))
            .replace("@D@", w[9]);
        let mesh = std::fs::read_to_string(data().join(w[1])).unwrap();
        let (dir, out) = run_kept("mesh-tet-case", &script, &[(w[1], &mesh)], None);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{}: {text}", w[0]);
        assert_eq!(created(&text), Some(want(w[0])), "case {}", w[0]);
        let _ = std::fs::remove_dir_all(&dir);
        n += 1;
    }
    assert_eq!(n, 8);
}

/// The tutorial's mesh (a 20-sided prism of radius 0.75 from z = 0 to 1) filled by
/// `fix insert/pack` with 500 spheres of radius 0.04, `all_in yes`: all 500 go in, each
/// whole inside the prism (rdem measures the distance to the mesh's surface; LIGGGHTS
/// 3.8 lets spheres poke out of the side by up to about half a radius).
#[test]
fn insert_pack_fills_the_mesh_with_whole_spheres() {
    let mesh = std::fs::read_to_string(Path::new(TUTORIALS).join("mesh_tet/data/test.vtk"))
        .expect("liggghts-doc tutorial mesh");
    let script = "atom_style granular\natom_modify map array\nboundary m m m\nnewton off\n\
        communicate single vel yes\nunits si\n\
        region reg block -1 1 -1 1 -0.05 1.05 units box\ncreate_box 1 reg\n\
        neighbor 0.002 bin\nneigh_modify delay 0\n\
        fix m1 all property/global youngsModulus peratomtype 5.e6\n\
        fix m2 all property/global poissonsRatio peratomtype 0.45\n\
        fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9\n\
        fix m4 all property/global coefficientFriction peratomtypepair 1 0.05\n\
        pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 0.00001\n\
        region mesh mesh/tet file test.vtk scale 1. move 0. 0. 0. rotate 0. 0. 0. units box\n\
        fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.04\n\
        fix pdd all particledistribution/discrete 32452843 1 pts 1.0\n\
        fix ins all insert/pack seed 86028121 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 500 region mesh\n\
        fix integr all nve/sphere\nrun 1\n\
        variable r2 atom x*x+y*y\ncompute mr all reduce max v_r2 z\ncompute mn all reduce min z\n\
        thermo_style custom step atoms c_mr[1] c_mr[2] c_mn\nrun 0\n";
    let (dir, out) = run_kept("mesh-tet-pack", script, &[("test.vtk", &mesh)], None);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let row = common::thermo_rows(&text).pop().expect("thermo row");
    assert_eq!(row[1], 500.0, "{text}");
    let r = 0.04;
    assert!(
        row[2].sqrt() + r <= 0.75 + 1e-12,
        "max radius {}",
        row[2].sqrt()
    );
    assert!(row[3] + r <= 1.0 + 1e-12 && row[4] - r >= -1e-12, "{row:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

fn stderr_of(script: &str, files: &[(&str, &str)]) -> String {
    let (dir, out) = run_kept("mesh-tet-bad", script, files, None);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(out.status.code(), Some(1), "{script}");
    String::from_utf8_lossy(&out.stderr).to_string()
}

#[test]
fn bad_files_and_keywords_stop_at_the_script_line() {
    let head = "units si\nregion reg block -1 2 -1 2 -1 2\ncreate_box 1 reg\n";
    let good = std::fs::read_to_string(data().join("five.vtk")).unwrap();
    let line = "region m mesh/tet file m.vtk scale 1 move 0 0 0 rotate 0 0 0\n";
    let script = format!("{head}{line}");
    // A coordinate that is not a number: the VTK file's line, the script's line 4.
    let bad = good.replacen("1 1 1\n", "1 one 1\n", 1);
    let e = stderr_of(&script, &[("m.vtk", &bad)]);
    assert!(
        e.contains("VTK file m.vtk, line 13") && e.contains("'one'"),
        "{e}"
    );
    assert!(e.contains("in.test:4"), "{e}");
    // Binary files are not read.
    let e = stderr_of(&script, &[("m.vtk", &good.replace("ASCII", "BINARY"))]);
    assert!(e.contains("line 3") && e.contains("binary"), "{e}");
    // A missing file.
    let e = stderr_of(&script, &[]);
    assert!(e.contains("cannot read VTK file m.vtk"), "{e}");
    // The keywords come in LIGGGHTS' order.
    let e = stderr_of(
        &format!("{head}region m mesh/tet file m.vtk move 0 0 0 scale 1 rotate 0 0 0\n"),
        &[("m.vtk", &good)],
    );
    assert!(e.contains("scale"), "{e}");
    // units lattice: refused, as LIGGGHTS does.
    let e = stderr_of(
        &format!(
            "{head}region m mesh/tet file m.vtk scale 1 move 0 0 0 rotate 0 0 0 units lattice\n"
        ),
        &[("m.vtk", &good)],
    );
    assert!(e.contains("units lattice"), "{e}");
    // A node outside the box, as LIGGGHTS refuses it.
    let e = stderr_of(
        &format!("{head}region m mesh/tet file m.vtk scale 3 move 0 0 0 rotate 0 0 0\n"),
        &[("m.vtk", &good)],
    );
    assert!(e.contains("outside the simulation box"), "{e}");
}

//! `create_particles` and `spheres_different_types` (LIGGGHTS-INL) against LIGGGHTS-INL
//! itself.
//!
//! The fork (idaholab/LIGGGHTS-INL d69df36) was built here (`make mpi_no_vtk`) and ran
//! the scripts of `tests/data/create_particles`, written for these tests; the `inl_*.txt`
//! files are what it printed.
//! - `in.place`: an L of three spheres turned twice and thrown, five spheres out of any
//!   plane turned by a quaternion that is not of unit length, three spheres of their own
//!   types read from a file and scaled, placed in lattice units, and a single sphere.
//!   rdem prints the fork's tag, type, position and velocity of every sphere to all 15
//!   printed digits but one (3e-16 m; measured), so the spheres go about the same
//!   bounding-sphere centre, turned the same way, and take the same tags; the test
//!   allows 1e-13 of the 40 m box. The fork's masses of a `multiplespheres` template's
//!   spheres are 8.6e-13 above 4/3 π r³ ρ (its single sphere's are exact), rdem's are
//!   exact: the test allows 1e-11.
//! - `in.bonded`: two columns of touching spheres of two types, bonded by `cohesion
//!   bond/nonlinear` across the columns too, one end frozen, the other thrown; rdem
//!   follows the fork's thermo rows to 7.2e-11 of each column's scale (measured); the
//!   test allows 1e-9. Placed about the centre of mass by the template's principal axes
//!   (as rdem placed such spheres at first, off by 1e-19 m), spheres given touching do
//!   not touch exactly, a contact starts or not by rounding, and the rows part from the
//!   fork's: by 2.3e-5 of a spin within 250 steps (measured on these columns upright).

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/create_particles")
}

/// The `ATOM i type mass x y z vx vy vz` lines of a screen output.
fn atoms(out: &str) -> Vec<Vec<f64>> {
    out.lines()
        .filter_map(|l| l.strip_prefix("ATOM "))
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// Every sphere of four templates where the fork puts it, with its type, mass and
/// velocity.
#[test]
fn particles_go_where_the_fork_puts_them() {
    let (dir, out) = common::run_data_script("create_place", &data(), "in.place", &["typed.txt"]);
    let _ = std::fs::remove_dir_all(dir);
    let got = atoms(&out);
    let want = atoms(&std::fs::read_to_string(data().join("inl_place.txt")).unwrap());
    assert_eq!(want.len(), 12);
    assert_eq!(got.len(), want.len(), "{out}");
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g[..2], w[..2], "tag and type: {g:?} vs {w:?}");
        assert!((g[2] / w[2] - 1.0).abs() < 1e-11, "mass: {g:?} vs {w:?}");
        for k in 3..9 {
            assert!((g[k] - w[k]).abs() < 40.0 * 1e-13, "{g:?} vs {w:?}");
        }
    }
}

/// Bonded columns made by create_particles follow the fork, serially, on two MPI ranks
/// (the box is cut through the columns: the spheres of one copy are made on both ranks
/// and still take the tags of the template's order) and with two threads.
#[test]
fn bonded_columns_follow_the_fork() {
    let want = common::reference_rows(&data().join("inl_bonded.txt"));
    let (dir, out) =
        common::run_data_script("create_bonded", &data(), "in.bonded", &["column.txt"]);
    let got = common::thermo_rows(&out);
    common::assert_columns(&got, &want, 1, 1e-9, "in.bonded");
    let threads = common::rdem_in(&dir, "in.bonded", None)
        .env("RDEM_THREADS", "2")
        .output()
        .unwrap();
    assert_eq!(
        common::thermo_rows(&common::success("2 threads", &threads)),
        got
    );
    if common::have_mpirun() {
        let ranks = common::rdem_in(&dir, "in.bonded", Some(2))
            .output()
            .unwrap();
        let text = common::success("2 ranks", &ranks);
        assert!(text.contains("1 by 1 by 2 MPI processor grid"), "{text}");
        common::assert_columns(&common::thermo_rows(&text), &got, 1, 1e-11, "2 ranks");
    }
    let _ = std::fs::remove_dir_all(dir);
}

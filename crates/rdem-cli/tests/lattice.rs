//! `lattice hcp` (LAMMPS' hexagonal close packing, which LIGGGHTS 3.8 has and
//! LIGGGHTS_SEAICE's packing scripts use): `create_atoms` on it, with an `origin` shift,
//! in a box region and a region in lattice units, places the atoms LIGGGHTS 3.8 placed
//! for `tests/data/lattice/in.hcp` (its dump stored beside it), in the same order, within
//! 1e-15 m.

use crate::common;

#[test]
fn hcp_points_are_liggghts_points() {
    let data = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/lattice"));
    let (dir, _) = common::run_data_script("lattice", data, "in.hcp", &[]);
    let got = common::dump_frames(&std::fs::read_to_string(dir.join("d.txt")).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
    let want =
        common::dump_frames(&std::fs::read_to_string(data.join("hcp.liggghts.dump")).unwrap());
    let (got, want) = (&got[0].1, &want[0].1);
    assert_eq!(got.len(), 116);
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(want) {
        assert_eq!(g[0], w[0]);
        for k in 1..4 {
            assert!(
                (g[k] - w[k]).abs() < 1e-15,
                "atom {}: {g:?} against {w:?}",
                w[0]
            );
        }
    }
}

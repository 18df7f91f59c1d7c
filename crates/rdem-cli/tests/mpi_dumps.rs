#![cfg(feature = "mpi")]
//! Dumps and data files under MPI: every rank sends its owned particles (or, for
//! `dump euler/vtk`, its per-cell sums) to rank 0, which writes the files. A 2-rank run of
//! tests/data/mpi/in.dumps must leave the same files as the serial run: every particle
//! exactly once, sorted by id, with the serial values (the force sums of 2 ranks add the
//! contacts in another order, so values agree to rounding, not bit for bit), `proc` of
//! `dump atom/vtk` the owning rank (the box is split at half its x extent), the
//! euler/vtk cells the serial ones, and `write_data` before the run byte-identical.
//! Skipped (with a note) when `mpirun` is not on PATH.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::common;
use common::{have_mpirun, rdem_in, success};

const N: usize = 1024;
/// Half the box's x extent: rank 0 owns x < SPLIT, rank 1 the rest.
const SPLIT: f64 = 0.0304;

/// The data file: 16 × 8 × 8 spheres (d = 4 mm) 3.8 mm apart, tags in scrambled order,
/// type 2 in the first five x layers, varied velocities and spins.
fn init_data() -> String {
    let mut atoms = String::new();
    let mut vel = String::new();
    let mut k = 0usize;
    for iz in 0..8 {
        for iy in 0..8 {
            for ix in 0..16 {
                let tag = (k * 389) % N + 1;
                let at = |i: usize| 0.0019 + 0.0038 * i as f64;
                let ty = if ix < 5 { 2 } else { 1 };
                atoms += &format!(
                    "{tag} {ty} 0.004 2500 {:?} {:?} {:?}\n",
                    at(ix),
                    at(iy),
                    at(iz)
                );
                let kf = k as f64;
                vel += &format!(
                    "{tag} {:?} {:?} {:?} 0 0 {:?}\n",
                    0.2 * (1.3 * kf).sin(),
                    0.2 * (0.7 * kf).cos(),
                    0.15 * (2.1 * kf + 1.0).sin(),
                    3.0 * (0.3 * kf).sin()
                );
                k += 1;
            }
        }
    }
    format!(
        "rdem MPI dump test\n\n{N} atoms\n2 atom types\n\n0 0.0608 xlo xhi\n0 0.0304 ylo yhi\n\
         0 0.0304 zlo zhi\n\nAtoms\n\n{atoms}\nVelocities\n\n{vel}"
    )
}

/// Runs in.dumps (`nsteps` steps) on `np` ranks (`None`: without mpirun); returns the
/// files of `post/` by name.
fn run(np: Option<usize>, nsteps: u64) -> BTreeMap<String, String> {
    let tag = np.map_or("serial".to_string(), |n| format!("np{n}"));
    let d = common::scratch_dir(&format!("mpi-dumps-{tag}-{nsteps}"));
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mpi/in.dumps");
    std::fs::copy(src, d.join("in.dumps")).unwrap();
    std::fs::write(d.join("init.data"), init_data()).unwrap();
    let out = rdem_in(&d, "in.dumps", np)
        .args(["-var", "nsteps", &nsteps.to_string()])
        .output()
        .unwrap();
    success(&tag, &out);
    let files = std::fs::read_dir(d.join("post"))
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read_to_string(e.path()).unwrap(),
            )
        })
        .collect();
    // Nothing but post/ and the inputs: no rank wrote files of its own elsewhere.
    let mut names: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["in.dumps", "init.data", "post"], "{tag}: files");
    let _ = std::fs::remove_dir_all(&d);
    files
}

/// Equal within rounding: relative 1e-12, or 1e-12 of the quantity's `scale` (a sum of
/// contact forces that cancels to ~1e-15 keeps only its rounding error).
fn close(a: f64, b: f64, scale: f64) -> bool {
    a == b || (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) + 1e-12 * scale
}

/// The rows of a `dump custom` text snapshot, as numbers.
fn text_rows(text: &str) -> Vec<Vec<f64>> {
    let (_, atoms) = text.split_once("ITEM: ATOMS").expect("ITEM: ATOMS");
    atoms
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// The number after "ITEM: NUMBER OF ATOMS".
fn text_count(text: &str) -> usize {
    let (_, rest) = text.split_once("ITEM: NUMBER OF ATOMS\n").unwrap();
    rest.lines().next().unwrap().trim().parse().unwrap()
}

fn ids(rows: &[Vec<f64>]) -> Vec<u64> {
    rows.iter().map(|r| r[0] as u64).collect()
}

/// Every id 1..=n exactly once, in increasing order.
fn assert_all_sorted(ids: &[u64], n: usize, what: &str) {
    let want: Vec<u64> = (1..=n as u64).collect();
    assert_eq!(ids, want.as_slice(), "{what}: ids");
}

/// Rows equal column by column within rounding (column scale: its largest magnitude).
fn assert_rows_close(got: &[Vec<f64>], want: &[Vec<f64>], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: rows");
    let ncol = want.first().map_or(0, Vec::len);
    let scale: Vec<f64> = (0..ncol)
        .map(|c| want.iter().map(|r| r[c].abs()).fold(0.0, f64::max))
        .collect();
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.len(), w.len(), "{what} row {k}");
        for c in 0..w.len() {
            assert!(
                close(g[c], w[c], scale[c]),
                "{what} row {k} column {c}: {} vs serial {}",
                g[c],
                w[c]
            );
        }
    }
}

/// The numbers of the `DataArray` called `name` in an ASCII VTK XML file.
fn xml_array(text: &str, name: &str) -> Vec<f64> {
    let key = format!("Name=\"{name}\"");
    let start = text.find(&key).unwrap_or_else(|| panic!("no array {name}"));
    let body = &text[start..];
    let body = &body[body.find('>').unwrap() + 1..];
    // The values end at the next element (`</DataArray>` or an `<InformationKey>`).
    let body = &body[..body.find('<').unwrap()];
    body.split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect()
}

/// Checks a 2-rank `dump atom/vtk` file against the serial one.
fn check_atom_vtu(got: &str, want: &str, what: &str) {
    let id: Vec<u64> = xml_array(got, "id").iter().map(|&v| v as u64).collect();
    assert_all_sorted(&id, N, what);
    assert_eq!(xml_array(want, "id"), xml_array(got, "id"), "{what}: id");
    let points = xml_array(got, "Points");
    let proc = xml_array(got, "proc");
    assert_eq!(proc.len(), N, "{what}: proc");
    let seen: BTreeSet<u64> = proc.iter().map(|&p| p as u64).collect();
    assert_eq!(seen, BTreeSet::from([0, 1]), "{what}: proc values");
    for (k, &p) in proc.iter().enumerate() {
        let x = points[3 * k];
        let owner = if x < SPLIT { 0.0 } else { 1.0 };
        assert_eq!(
            p, owner,
            "{what}: particle {} at x = {x} has proc {p}",
            id[k]
        );
    }
    assert!(
        xml_array(want, "proc").iter().all(|&p| p == 0.0),
        "{what}: serial proc"
    );
    for name in [
        "Points",
        "radii",
        "type",
        "mass",
        "velocity_lin",
        "velocity_ang",
        "force",
    ] {
        let (g, w) = (xml_array(got, name), xml_array(want, name));
        assert_eq!(g.len(), w.len(), "{what} {name}: length");
        let scale = w.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for (k, (a, b)) in g.iter().zip(&w).enumerate() {
            assert!(
                close(*a, *b, scale),
                "{what} {name}[{k}]: {a} vs serial {b}"
            );
        }
    }
}

/// Same words; numbers (printed with %f) equal within 1e-9 relative or one unit in the
/// sixth decimal (a sum over two ranks may round the last printed digit the other way).
fn check_euler(got: &str, want: &str, what: &str) {
    let (g, w): (Vec<&str>, Vec<&str>) = (
        got.split_whitespace().collect(),
        want.split_whitespace().collect(),
    );
    assert_eq!(g.len(), w.len(), "{what}: words");
    let mut numbers = 0;
    for (a, b) in g.iter().zip(&w) {
        match (a.parse::<f64>(), b.parse::<f64>()) {
            (Ok(x), Ok(y)) if a.contains('.') || b.contains('.') => {
                numbers += 1;
                assert!(
                    (x - y).abs() <= 1e-9 * x.abs().max(y.abs()) || (x - y).abs() <= 1.000001e-6,
                    "{what}: {a} vs serial {b}"
                );
            }
            _ => assert_eq!(a, b, "{what}"),
        }
    }
    assert!(numbers > 100, "{what}: {numbers} numbers");
}

/// The sections of a data file as rows of numbers (header lines as text).
fn data_rows(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut head = Vec::new();
    let mut rows = Vec::new();
    for l in text.lines() {
        let nums: Option<Vec<f64>> = l.split_whitespace().map(|w| w.parse().ok()).collect();
        match nums {
            Some(v) if v.len() > 3 => rows.push(v),
            _ => head.push(l.to_string()),
        }
    }
    (head, rows)
}

fn compare(nsteps: u64) {
    let serial = run(None, nsteps);
    let two = run(Some(2), nsteps);
    assert_eq!(
        two.keys().collect::<Vec<_>>(),
        serial.keys().collect::<Vec<_>>(),
        "the 2-rank run writes the serial run's files, no more"
    );
    let steps: Vec<u64> = (0..=nsteps).step_by(5).collect();
    assert!(serial.contains_key(&format!("txt_{nsteps}.dump")));
    for s in &steps {
        let what = format!("txt_{s}.dump");
        let (g, w) = (&two[&what], &serial[&what]);
        assert_eq!(text_count(g), N, "{what}: count");
        let (rg, rw) = (text_rows(g), text_rows(w));
        assert_all_sorted(&ids(&rg), N, &what);
        assert_eq!(rg[0].len(), 17, "{what}: columns");
        assert_rows_close(&rg, &rw, &what);

        let what = format!("atom_{s}.vtu");
        check_atom_vtu(&two[&what], &serial[&what], &what);

        let what = format!("euler_{s}.vtk");
        check_euler(&two[&what], &serial[&what], &what);
    }
    // The `%` dump (no sort): one file (rank 0 writes all), every particle once.
    for s in (0..=nsteps).step_by(10) {
        let what = format!("rank0_{s}.dump");
        let mut rows = text_rows(&two[&what]);
        rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
        assert_all_sorted(&ids(&rows), N, &what);
        let mut want = text_rows(&serial[&what]);
        want.sort_by(|a, b| a[0].total_cmp(&b[0]));
        assert_eq!(rows, want, "{what}");
    }
    // The group dump and write_dump: the particles of the group, sorted.
    for what in ["upper.dump", "wd.dump"] {
        let (g, w) = (&two[what], &serial[what]);
        let snaps_g: Vec<&str> = g.split("ITEM: TIMESTEP").skip(1).collect();
        let snaps_w: Vec<&str> = w.split("ITEM: TIMESTEP").skip(1).collect();
        assert_eq!(snaps_g.len(), snaps_w.len(), "{what}: snapshots");
        for (a, b) in snaps_g.iter().zip(&snaps_w) {
            let (ra, rb) = (text_rows(a), text_rows(b));
            assert!(ra.len() > 100 && ra.len() < N, "{what}: {} rows", ra.len());
            let id = ids(&ra);
            assert!(id.windows(2).all(|p| p[0] < p[1]), "{what}: sorted");
            assert_eq!(id, ids(&rb), "{what}: ids");
            // Printed with %g: rounding differences may show in the 6th digit.
            for (x, y) in ra.iter().zip(&rb) {
                for (u, v) in x.iter().zip(y) {
                    assert!((u - v).abs() <= 1e-5 * u.abs().max(v.abs()), "{what}");
                }
            }
        }
    }
    // write_data before the run: byte-identical; after it, the same within rounding.
    assert_eq!(two["start.data"], serial["start.data"], "start.data");
    let (hg, rg) = data_rows(&two["end.data"]);
    let (hw, rw) = data_rows(&serial["end.data"]);
    assert_eq!(hg, hw, "end.data header");
    assert_eq!(rg.len(), 2 * N, "end.data: atoms and velocities");
    assert_all_sorted(&ids(&rg[..N]), N, "end.data Atoms");
    assert_all_sorted(&ids(&rg[N..]), N, "end.data Velocities");
    assert_rows_close(&rg[..N], &rw[..N], "end.data Atoms");
    assert_rows_close(&rg[N..], &rw[N..], "end.data Velocities");
    for what in ["atom.pvd", "euler.pvd"] {
        assert_eq!(two[what], serial[what], "{what}");
    }
}

/// Step 0 only (`run 0`): positions and velocities as read, forces at set-up.
#[test]
fn two_ranks_write_the_serial_files_at_setup() {
    if !have_mpirun() {
        return;
    }
    compare(0);
}

/// Ten steps, snapshots at 0, 5 and 10.
#[test]
fn two_ranks_write_the_serial_files_after_ten_steps() {
    if !have_mpirun() {
        return;
    }
    compare(10);
}

/// `dump decomposition/vtk` on 2 ranks (`processors 1 1 2`) and serially: the file
/// LIGGGHTS 3.8 wrote for the same script on 2 ranks (byte for byte), and the grid as
/// VTK's own reader sees it: one cell per subdomain, the cut at the middle of z.
#[test]
fn the_decomposition_dump_is_the_processor_grid() {
    let script = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
processors 1 1 2
region reg block -0.05 0.05 -0.05 0.05 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
create_atoms 1 single 0 0 0.05
set type 1 diameter 0.01 density 2500
fix integr all nve/sphere
dump d all decomposition/vtk 100 d*.vtk
run 200
";
    let liggghts = "# vtk DataFile Version 2.0
LIGGGHTS mesh/gran/VTK export
ASCII
DATASET RECTILINEAR_GRID
DIMENSIONS 2 2 3
X_COORDINATES 2 float
-0.050000 0.050000 
Y_COORDINATES 2 float
-0.050000 0.050000 
Z_COORDINATES 3 float
0.000000 0.050000 0.100000 
";
    const READER: &str = "import sys, vtk
r = vtk.vtkRectilinearGridReader()
r.SetFileName(sys.argv[1])
r.Update()
g = r.GetOutput()
z = g.GetZCoordinates()
print(g.GetNumberOfCells(), ' '.join('%g' % z.GetValue(i) for i in range(z.GetNumberOfTuples())))
";
    let read = |p: &Path| {
        let out = std::process::Command::new("python3")
            .args(["-c", READER])
            .arg(p)
            .output()
            .expect("python3 runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap().trim().to_string()
    };
    let serial = script.replace("processors 1 1 2\n", "");
    let (dir, _) = common::run_kept_ok("decomposition", &serial, &[], None);
    assert_eq!(read(&dir.join("d100.vtk")), "1 0 0.1");
    let _ = std::fs::remove_dir_all(&dir);
    if !have_mpirun() {
        return;
    }
    let (dir, _) = common::run_kept_ok("decomposition", script, &[], Some(2));
    for step in [0, 100, 200] {
        let text = std::fs::read_to_string(dir.join(format!("d{step}.vtk"))).unwrap();
        assert_eq!(text, liggghts, "step {step}");
    }
    assert_eq!(read(&dir.join("d100.vtk")), "2 0 0.05 0.1");
    let _ = std::fs::remove_dir_all(&dir);
}

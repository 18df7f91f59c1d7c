//! `fix ave/euler`, the `dump euler/vtk` text and `compute stress/atom` against LIGGGHTS
//! 3.8 (reference scripts and outputs in crates/rdem-io/tests/data/liggghts/euler_vtk),
//! and the euler file read back by VTK's own reader.

use std::path::{Path, PathBuf};
use std::process::Command;

use rdem_script::{context, euler, Interpreter};

use crate::common;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rdem-io/tests/data/liggghts/euler_vtk")
}

fn read(name: &str) -> String {
    std::fs::read_to_string(data_dir().join(name)).unwrap()
}

fn run(i: &mut Interpreter, src: &str) {
    common::run_on(i, "in.test", src);
}

/// The reference script without its dump lines (this helper does not own the dump
/// command; the text is produced with [`euler::euler_snapshot`] instead) and without the
/// final `run`.
fn script_without_dumps_and_run(name: &str) -> String {
    read(name)
        .lines()
        .filter(|l| !l.starts_with("dump") && !l.starts_with("run"))
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

/// Same line structure, words equal, numbers equal within the %f precision: at most one
/// unit in the sixth decimal (LIGGGHTS and rdem sum the contact forces in different
/// orders, so a value near a rounding boundary may round the other way).
fn assert_same_vtk(ours: &str, theirs: &str, what: &str) {
    let (a, b): (Vec<&str>, Vec<&str>) = (ours.lines().collect(), theirs.lines().collect());
    assert_eq!(a.len(), b.len(), "{what}: line count");
    let mut max_diff: f64 = 0.0;
    for (k, (la, lb)) in a.iter().zip(&b).enumerate() {
        let (wa, wb): (Vec<&str>, Vec<&str>) = (
            la.split_whitespace().collect(),
            lb.split_whitespace().collect(),
        );
        assert_eq!(
            wa.len(),
            wb.len(),
            "{what} line {}: '{la}' vs '{lb}'",
            k + 1
        );
        for (x, y) in wa.iter().zip(&wb) {
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(u), Ok(v)) if x.contains('.') || y.contains('.') => {
                    let d = (u - v).abs();
                    max_diff = max_diff.max(d);
                    assert!(d <= 1.000001e-6, "{what} line {}: '{la}' vs '{lb}'", k + 1);
                }
                _ => assert_eq!(x, y, "{what} line {}: '{la}' vs '{lb}'", k + 1),
            }
        }
    }
    eprintln!("{what}: max difference {max_diff:e}");
}

/// LIGGGHTS' fix ave/euler + dump euler/vtk on 512 overlapping spheres with varied
/// velocities, at steps 0, 5 and 10 (nevery 5). Each snapshot comes from one unbroken
/// `run` from step 0, as in the reference (LIGGGHTS' own `run 5` + `run 5` differs from
/// its `run 10` in the 5th decimal of v_avg at step 10, and rdem matches either way of
/// running it).
#[test]
fn ave_euler_matches_liggghts() {
    for step in [0, 5, 10] {
        let mut i = common::interpreter();
        run(&mut i, &script_without_dumps_and_run("in.euler"));
        run(&mut i, &format!("run {step}\n"));
        let ours = euler::euler_snapshot(&i.sim, None).unwrap();
        let theirs = read(&format!("out/euler_{step}.vtk"));
        assert_same_vtk(&ours, &theirs, &format!("euler_{step}.vtk"));
        assert_eq!(euler::euler_fix_id(&i.sim), Some("euler"));
    }
}

/// compute stress/atom on two overlapping spheres after 2 steps against LIGGGHTS' dump
/// (%.17g): all 6 components, with and without the kinetic term.
#[test]
fn stress_atom_matches_liggghts() {
    let mut i = common::interpreter();
    run(&mut i, &script_without_dumps_and_run("in.stress"));
    run(&mut i, "run 2\n");
    let text = read("out/stress_2.txt");
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2);
    let w = i.sim.world.as_ref().unwrap();
    for (cid, first) in [("s", 10), ("sp", 16)] {
        for col in 1..=6 {
            let vals = context::compute_peratom(&i.sim, cid, Some(col)).unwrap();
            for row in &rows {
                let idx = w.particles.find_tag(row[0] as _).unwrap();
                let (got, want) = (vals[idx], row[first + col - 1]);
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs(),
                    "c_{cid}[{col}] of atom {}: {got} vs LIGGGHTS {want}",
                    row[0]
                );
            }
        }
    }
    // The reduce of the thermo line works on the per-atom array.
    run(
        &mut i,
        "compute r2 all reduce sum c_s[1] c_s[4]\nvariable a equal c_r2[1]\n",
    );
    let sum = context::eval_equal(&i.sim, "c_r2[1]").unwrap();
    let want = rows[0][10] + rows[1][10];
    assert!((sum - want).abs() <= 1e-9 * want.abs());
    let atom = context::eval_atom(&i.sim, "c_s[1]+c_s[2]+c_s[3]").unwrap();
    assert_eq!(atom.len(), 2);
}

/// Keywords, the single-instance rule and the file-name rules.
#[test]
fn command_errors() {
    let head: String = script_without_dumps_and_run("in.stress")
        .lines()
        .filter(|l| !l.starts_with("compute") && !l.starts_with("thermo"))
        .collect::<Vec<_>>()
        .join("\n")
        + "\n";
    let mut i = common::interpreter();
    run(&mut i, &head);
    run(
        &mut i,
        "fix e1 all ave/euler nevery 2 cell_size_relative 3 parallel yes\n",
    );
    assert!(i
        .run_source(
            "in.t",
            "fix e2 all ave/euler nevery 2 cell_size_relative 3 parallel no\n"
        )
        .is_err());
    assert!(i
        .run_source(
            "in.t",
            "fix e1 all ave/euler nevery 2 cell_size 3 parallel no\n"
        )
        .is_err());
    assert!(i
        .run_source("in.t", "compute x all stress/atom pair bogus\n")
        .is_err());
    run(&mut i, "compute k all stress/atom ke\nrun 0\n");
    let k = context::compute_peratom(&i.sim, "k", Some(1)).unwrap();
    let w = i.sim.world.as_ref().unwrap();
    let p = &w.particles;
    for (j, kj) in k.iter().enumerate() {
        assert_eq!(*kj, -(p.rmass[j] * p.v[j].x * p.v[j].x));
    }
    assert!(euler::check_euler_dump_name("post/e_*.vtk").is_ok());
    for bad in ["post/e.vtk", "post/e_*_%.vtk", "post/e_*.bin"] {
        assert!(euler::check_euler_dump_name(bad).is_err(), "{bad}");
    }
}

/// The euler file of step 10 read by VTK (vtkGenericDataObjectReader): a vtkPolyData with
/// 27 points and vertices and the four point arrays with our values.
#[test]
fn euler_file_reads_back_with_vtk() {
    let mut i = common::interpreter();
    run(&mut i, &script_without_dumps_and_run("in.euler"));
    run(&mut i, "run 10\n");
    let dir = std::env::temp_dir().join(format!("rdem-euler-{}", std::process::id()));
    let path = dir.join("post/euler_10.vtk");
    euler::write_euler_snapshot(&i.sim, None, &path).unwrap();
    let script = r#"
import sys, vtk
r = vtk.vtkGenericDataObjectReader()
r.SetFileName(sys.argv[1]); r.ReadAllScalarsOn(); r.ReadAllVectorsOn(); r.Update()
o = r.GetOutput()
print("class", o.GetClassName(), o.GetNumberOfPoints(), o.GetNumberOfVerts())
pts = o.GetPoints()
print("points", *[pts.GetPoint(i)[a] for i in range(o.GetNumberOfPoints()) for a in range(3)])
pd = o.GetPointData()
for k in range(pd.GetNumberOfArrays()):
    a = pd.GetArray(k)
    vals = [a.GetComponent(i, c) for i in range(a.GetNumberOfTuples()) for c in range(a.GetNumberOfComponents())]
    print("array", a.GetName(), a.GetNumberOfComponents(), *[repr(v) for v in vals])
"#;
    let out = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(&path)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let line = |key: &str| -> Vec<String> {
        text.lines()
            .find(|l| l.starts_with(key))
            .unwrap_or_else(|| panic!("no '{key}' in {text}"))
            .split_whitespace()
            .map(String::from)
            .collect()
    };
    assert_eq!(line("class"), ["class", "vtkPolyData", "27", "27"]);
    let nums = |v: &[String]| -> Vec<f64> { v.iter().map(|s| s.parse().unwrap()).collect() };
    let rdem::euler::EulerCells {
        centre,
        v_avg,
        volume_fraction,
        radius,
        pressure,
    } = {
        let f = i
            .sim
            .defs
            .fixes
            .iter()
            .find(|f| f.id() == "euler")
            .expect("fix euler");
        let e = f
            .downcast::<rdem_script::fixes::ave_euler::AveEuler>()
            .expect("an ave/euler fix");
        e.cells.clone().unwrap()
    };
    let close = |got: &[f64], want: &[f64], what: &str| {
        assert_eq!(got.len(), want.len(), "{what}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() <= 5e-7 + 1e-6 * w.abs(), "{what}: {g} vs {w}");
        }
    };
    let flat = |v: &[rdem::DVec3]| -> Vec<f64> { v.iter().flat_map(|c| c.to_array()).collect() };
    close(&nums(&line("points")[1..]), &flat(&centre), "points");
    let arrays: Vec<Vec<String>> = text
        .lines()
        .filter(|l| l.starts_with("array"))
        .map(|l| l.split_whitespace().map(String::from).collect())
        .collect();
    let names: Vec<(&str, &str)> = arrays
        .iter()
        .map(|a| (a[1].as_str(), a[2].as_str()))
        .collect();
    assert_eq!(
        names,
        [
            ("v_avg", "3"),
            ("volumefraction", "1"),
            ("radius", "1"),
            ("pressure", "1")
        ]
    );
    close(&nums(&arrays[0][3..]), &flat(&v_avg), "v_avg");
    close(&nums(&arrays[1][3..]), &volume_fraction, "volumefraction");
    close(&nums(&arrays[2][3..]), &radius, "radius");
    // Pressures are large numbers: %f keeps 6 decimals, float32 keeps ~7 digits.
    for (g, w) in nums(&arrays[3][3..]).iter().zip(&pressure) {
        assert!(
            (g - w).abs() <= 1e-6 * w.abs() + 1e-6,
            "pressure {g} vs {w}"
        );
    }
    assert!(pressure.iter().all(|&p| p > 0.0));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The reference script unmodified, dumps included (`dump e all euler/vtk 5
/// out/euler_*.vtk`, one `run 10`), run in a temporary directory: the files written at
/// steps 0, 5 and 10 match LIGGGHTS' (line structure, numbers within %f), and a ParaView
/// collection `out/euler.pvd` lists them with time = step × dt.
#[test]
fn dump_euler_vtk_writes_liggghts_files_and_a_collection() {
    let dir = std::env::temp_dir().join(format!("rdem-euler-dump-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let script = read("in.euler");
    let cwd = std::env::current_dir().unwrap();
    std::env::set_current_dir(&dir).unwrap();
    let mut i = common::interpreter();
    let r = i.run_source("in.euler", &script);
    std::env::set_current_dir(cwd).unwrap();
    if let Err(e) = r {
        panic!("{e:?}");
    }
    for step in [0, 5, 10] {
        let name = format!("out/euler_{step}.vtk");
        let ours = std::fs::read_to_string(dir.join(&name)).unwrap();
        assert_same_vtk(&ours, &read(&name), &name);
    }
    let pvd = std::fs::read_to_string(dir.join("out/euler.pvd")).unwrap();
    let dt: f64 = script
        .lines()
        .find_map(|l| l.strip_prefix("timestep"))
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    for step in [0u32, 5, 10] {
        let entry = format!("file=\"euler_{step}.vtk\"");
        let line = pvd
            .lines()
            .find(|l| l.contains(&entry))
            .unwrap_or_else(|| panic!("{pvd}"));
        let t: f64 = line
            .split("timestep=\"")
            .nth(1)
            .and_then(|r| r.split('"').next())
            .unwrap()
            .parse()
            .unwrap();
        assert!((t - f64::from(step) * dt).abs() < 1e-15, "{line}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// `cell_size_relative cx cy cz` (LIGGGHTS-PFM's form; LIGGGHTS 3.8 takes one value and
/// stops at the second): the cell edges per axis are those multiples of the largest
/// diameter, so the cell counts are floor(box extent / (c · 2 r_max)) per axis.
#[test]
fn cell_sizes_per_axis() {
    let head: String = script_without_dumps_and_run("in.stress")
        .lines()
        .filter(|l| !l.starts_with("compute") && !l.starts_with("thermo"))
        .collect::<Vec<_>>()
        .join("\n")
        + "\n";
    let mut i = common::interpreter();
    run(&mut i, &head);
    run(
        &mut i,
        "fix e all ave/euler nevery 1 cell_size_relative 3 1.5 1 parallel yes\nrun 0\n",
    );
    let w = i.sim.world.as_ref().unwrap();
    let p = &w.particles;
    let d = 2.0 * p.radius[..p.nlocal()].iter().copied().fold(0.0, f64::max);
    let ext = w.domain.boxhi - w.domain.boxlo;
    let n: Vec<usize> = [3.0, 1.5, 1.0]
        .iter()
        .enumerate()
        .map(|(a, c)| ((ext[a] / (c * d)).floor() as usize).max(1))
        .collect();
    assert!(
        n[0] < n[1] && n[1] < n[2],
        "{n:?}: the test needs distinct counts"
    );
    let k = i.sim.fix_index("e").unwrap();
    let fix = i.sim.defs.fixes[k]
        .downcast::<rdem_script::fixes::ave_euler::AveEuler>()
        .unwrap();
    assert_eq!(fix.cells.as_ref().unwrap().len(), n[0] * n[1] * n[2]);
    // A word that is not a number where cy stands.
    assert!(i
        .run_source(
            "in.t",
            "fix e all ave/euler nevery 1 cell_size_relative 3 x 1 parallel yes\n"
        )
        .is_err());
}

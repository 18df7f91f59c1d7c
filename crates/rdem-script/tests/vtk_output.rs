//! VTK output through the interpreter: `dump atom/vtk` against LIGGGHTS 3.8's own files
//! for the same script, every VTK file kind read back with VTK's own readers (Python
//! bindings, `pip install vtk`), the `.pvd` collections, and file names.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common;

fn reference_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rdem-io/tests/data/liggghts/atom_vtk")
}

/// One `<DataArray>` of an ASCII VTK XML file.
#[derive(Debug)]
struct Array {
    ty: String,
    name: String,
    ncomp: usize,
    values: Vec<f64>,
}

fn attr(tag: &str, key: &str) -> Option<String> {
    let k = tag.find(&format!(" {key}=\""))? + key.len() + 3;
    Some(tag[k..k + tag[k..].find('"').unwrap()].to_string())
}

/// The data arrays of an ASCII VTK XML file, in file order (independent of the writer).
fn read_ascii_xml(text: &str) -> Vec<Array> {
    let mut out = Vec::new();
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        let l = l.trim();
        if !l.starts_with("<DataArray ") {
            continue;
        }
        assert_eq!(attr(l, "format").as_deref(), Some("ascii"), "{l}");
        let mut values = Vec::new();
        for v in lines.by_ref() {
            let v = v.trim();
            if v.starts_with('<') {
                break;
            }
            values.extend(v.split_whitespace().map(|t| t.parse::<f64>().unwrap()));
        }
        out.push(Array {
            ty: attr(l, "type").unwrap(),
            name: attr(l, "Name").unwrap(),
            ncomp: attr(l, "NumberOfComponents").map_or(1, |s| s.parse().unwrap()),
            values,
        });
    }
    out
}

/// The text with every number replaced by `#`: the layout of the file.
fn skeleton(text: &str) -> String {
    let mut out = String::new();
    let cs: Vec<char> = text.chars().collect();
    let mut k = 0;
    while k < cs.len() {
        let c = cs[k];
        let prev_word = k > 0 && (cs[k - 1].is_alphanumeric() || cs[k - 1] == '_');
        let starts =
            c.is_ascii_digit() || (c == '-' && k + 1 < cs.len() && cs[k + 1].is_ascii_digit());
        if starts && !prev_word {
            while k < cs.len() && (cs[k].is_ascii_digit() || "+-.e".contains(cs[k])) {
                k += 1;
            }
            out.push('#');
        } else {
            out.push(c);
            k += 1;
        }
    }
    out
}

/// The reference script with its dumps writing under `dir`.
fn reference_script(dir: &Path) -> String {
    fs::read_to_string(reference_dir().join("in.atom_vtk"))
        .unwrap()
        .replace("post/", &format!("{}/post/", dir.display()))
}

/// `dump atom/vtk` on a 36-sphere lattice (overlapping neighbours, a ramped velocity
/// field, gravity, two types and sizes) for 10 steps, against LIGGGHTS 3.8's files for
/// the same script: same file set, same layout (every line equal once numbers are
/// masked), same arrays in the same order, ids/types/procs equal, float data within
/// 1e-9 relative (of the array's largest magnitude), points equal as float32.
#[test]
fn atom_vtk_matches_liggghts() {
    let dir = common::scratch_dir("vtk-liggghts");
    let i = common::run("in.test", &reference_script(&dir));
    let mut names: Vec<String> = fs::read_dir(dir.join("post"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "atoms.pvd",
            "atoms_0.vtu",
            "atoms_10.vtu",
            "atoms_5.vtu",
            "heavy.pvd",
            "heavy_0.vtu",
            "heavy_10.vtu"
        ]
    );
    let mut worst: f64 = 0.0;
    for file in [
        "atoms_0.vtu",
        "atoms_5.vtu",
        "atoms_10.vtu",
        "heavy_0.vtu",
        "heavy_10.vtu",
    ] {
        let ours = fs::read_to_string(dir.join("post").join(file)).unwrap();
        let theirs = fs::read_to_string(reference_dir().join("post").join(file)).unwrap();
        assert_eq!(skeleton(&ours), skeleton(&theirs), "{file}");
        let (a, b) = (read_ascii_xml(&ours), read_ascii_xml(&theirs));
        let layout = |v: &[Array]| -> Vec<(String, String, usize, usize)> {
            v.iter()
                .map(|a| (a.name.clone(), a.ty.clone(), a.ncomp, a.values.len()))
                .collect()
        };
        assert_eq!(layout(&a), layout(&b), "{file}");
        let names: Vec<&str> = a.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "radii",
                "id",
                "type",
                "proc",
                "mass",
                "velocity_lin",
                "velocity_ang",
                "force",
                "Points",
                "connectivity",
                "offsets",
                "types"
            ]
        );
        for (x, y) in a.iter().zip(&b) {
            match x.ty.as_str() {
                "Float64" => {
                    let scale = y.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    for (u, v) in x.values.iter().zip(&y.values) {
                        let rel = (u - v).abs() / scale.max(f64::MIN_POSITIVE);
                        worst = worst.max(rel);
                        assert!(rel <= 1e-9, "{file} {}: {u} vs {v}", x.name);
                    }
                }
                "Float32" => {
                    for (u, v) in x.values.iter().zip(&y.values) {
                        assert_eq!(*u as f32, *v as f32, "{file} {}", x.name);
                    }
                }
                _ => assert_eq!(x.values, y.values, "{file} {}", x.name),
            }
        }
    }
    eprintln!("largest relative difference from LIGGGHTS: {worst:e}");
    // The collection: times are step × dt.
    let pvd = fs::read_to_string(dir.join("post/atoms.pvd")).unwrap();
    let sets = pvd_sets(&pvd);
    assert_eq!(
        sets,
        [
            (0.0, "atoms_0.vtu".to_string()),
            (5.0 * 1e-5, "atoms_5.vtu".into()),
            (10.0 * 1e-5, "atoms_10.vtu".into())
        ]
    );
    assert_eq!(i.sim.world.as_ref().unwrap().step, 10);
    fs::remove_dir_all(&dir).unwrap();
}

/// `(timestep, file)` of every DataSet of a `.pvd`.
fn pvd_sets(text: &str) -> Vec<(f64, String)> {
    assert!(text.starts_with("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\""));
    text.lines()
        .map(str::trim)
        .filter(|l| l.starts_with("<DataSet "))
        .map(|l| {
            (
                attr(l, "timestep").unwrap().parse().unwrap(),
                attr(l, "file").unwrap(),
            )
        })
        .collect()
}

const LATTICE: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block 0 0.01 0 0.01 0 0.01 units box
create_box 2 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
lattice sc 0.002
region lat block 1 4 1 3 1 3 units lattice
create_atoms 1 region lat
set group all diameter 0.00204 density 2500
group heavy id 1:10
set group heavy type 2 diameter 0.00206 density 3000
velocity all set 0.01 -0.02 0.03 units box
velocity all ramp vx -0.1 0.1 y 0.002 0.006 units box
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix integr all nve/sphere
";

/// What VTK's readers see in a file.
#[derive(Debug, Default)]
struct Seen {
    class: String,
    npoints: usize,
    ncells: usize,
    points: Vec<f64>,
    /// (name, components, values) in file order.
    arrays: Vec<(String, usize, Vec<f64>)>,
}

const READER: &str = r#"
import sys, vtk
for f in sys.argv[1:]:
    if f.endswith('.vtu'):
        r = vtk.vtkXMLUnstructuredGridReader()
    elif f.endswith('.vtp'):
        r = vtk.vtkXMLPolyDataReader()
    elif f.endswith('.vtr'):
        r = vtk.vtkXMLRectilinearGridReader()
    else:
        r = vtk.vtkGenericDataObjectReader()
        r.ReadAllScalarsOn(); r.ReadAllVectorsOn(); r.ReadAllFieldsOn()
    r.SetFileName(f)
    r.Update()
    if hasattr(r, 'GetErrorCode') and r.GetErrorCode() != 0:
        raise SystemExit('error reading ' + f)
    o = r.GetOutput()
    print('file', f)
    print('class', o.GetClassName(), o.GetNumberOfPoints(), o.GetNumberOfCells())
    if o.GetClassName() != 'vtkRectilinearGrid':
        pts = o.GetPoints()
        print('points', *[repr(pts.GetPoint(i)[a]) for i in range(o.GetNumberOfPoints()) for a in range(3)])
    else:
        print('bounds', *[repr(b) for b in o.GetBounds()])
    pd = o.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(k)
        vals = [a.GetComponent(i, c) for i in range(a.GetNumberOfTuples()) for c in range(a.GetNumberOfComponents())]
        print('array', a.GetName(), a.GetNumberOfComponents(), *[repr(v) for v in vals])
"#;

/// Reads `files` with VTK's readers (one python3 process).
fn vtk_read(files: &[PathBuf]) -> BTreeMap<PathBuf, Seen> {
    let out = Command::new("python3")
        .arg("-c")
        .arg(READER)
        .args(files)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("ERROR"), "{stderr}");
    let text = String::from_utf8(out.stdout).unwrap();
    let mut seen = BTreeMap::new();
    let mut cur: Option<(PathBuf, Seen)> = None;
    for l in text.lines() {
        let mut w = l.split_whitespace();
        let key = w.next().unwrap();
        let nums =
            |w: std::str::SplitWhitespace| -> Vec<f64> { w.map(|s| s.parse().unwrap()).collect() };
        match key {
            "file" => {
                if let Some((p, s)) = cur.take() {
                    seen.insert(p, s);
                }
                cur = Some((PathBuf::from(w.next().unwrap()), Seen::default()));
            }
            "class" => {
                let s = &mut cur.as_mut().unwrap().1;
                s.class = w.next().unwrap().into();
                s.npoints = w.next().unwrap().parse().unwrap();
                s.ncells = w.next().unwrap().parse().unwrap();
            }
            "points" | "bounds" => cur.as_mut().unwrap().1.points = nums(w),
            "array" => {
                let name = w.next().unwrap().to_string();
                let nc = w.next().unwrap().parse().unwrap();
                cur.as_mut().unwrap().1.arrays.push((name, nc, nums(w)));
            }
            _ => panic!("{l}"),
        }
    }
    if let Some((p, s)) = cur.take() {
        seen.insert(p, s);
    }
    assert_eq!(seen.len(), files.len());
    seen
}

/// Every VTK file kind rdem writes, read back by VTK: `dump atom/vtk` in ASCII, base64
/// binary, zlib and LZ4 (vtkXMLUnstructuredGridReader), `dump custom/vtk` as legacy
/// ASCII and BINARY (vtkGenericDataObjectReader with ReadAllScalarsOn), `.vtp`
/// (vtkXMLPolyDataReader) and `.vtu`, with their bounding boxes; array names, order and
/// values against the engine's state; and the `.pvd` collections.
#[test]
fn every_vtk_file_reads_back_with_vtk() {
    let dir = common::scratch_dir("vtk-readers");
    let d = dir.display();
    let script = format!(
        "{LATTICE}\
dump a all atom/vtk 5 {d}/post/ascii_*.vtu
dump b heavy atom/vtk 5 {d}/post/bin_*.vtu
dump_modify b binary yes
dump z all atom/vtk 5 {d}/post/zlib_*.vtu
dump_modify z binary yes compressor zlib
dump l all atom/vtk 5 {d}/post/lz4_*.vtu
dump_modify l compressor lz4
dump c all custom/vtk 5 {d}/post/leg_*.vtk id type x y z vx vy vz fx fy fz omegax omegay omegaz radius mass
dump_modify c sort id
dump cb all custom/vtk 5 {d}/post/legbin_*.vtk id type x y z ix iy iz vx vy vz radius
dump_modify cb sort id binary yes
dump p all custom/vtk 5 {d}/post/poly_*.vtp id type vx vy vz fx fy fz radius
dump_modify p sort id
dump u all custom/vtk 5 {d}/post/grid_*.vtu id type omegax omegay omegaz
dump_modify u sort id compressor lz4
run 10
"
    );
    let i = common::run("in.test", &script);
    let w = i.sim.world.as_ref().unwrap();
    let p = &w.particles;
    let mut order: Vec<usize> = (0..p.nlocal()).collect();
    order.sort_by_key(|&k| p.tag[k]);
    let heavy: Vec<usize> = order.iter().copied().filter(|&k| p.tag[k] <= 10).collect();
    let post = dir.join("post");
    let files: Vec<PathBuf> = [
        "ascii_10.vtu",
        "bin_10.vtu",
        "zlib_10.vtu",
        "lz4_10.vtu",
        "leg_10.vtk",
        "leg_boundingBox_10.vtk",
        "legbin_10.vtk",
        "legbin_boundingBox_10.vtk",
        "poly_10.vtp",
        "poly_boundingBox_10.vtr",
        "grid_10.vtu",
        "grid_boundingBox_10.vtr",
    ]
    .iter()
    .map(|f| post.join(f))
    .collect();
    // The encodings are what was asked for.
    let head = |f: &str| fs::read_to_string(post.join(f)).unwrap();
    assert!(head("ascii_10.vtu").contains("format=\"ascii\""));
    assert!(head("bin_10.vtu").contains("format=\"binary\""));
    assert!(!head("bin_10.vtu").contains("compressor"));
    assert!(head("zlib_10.vtu").contains("compressor=\"vtkZLibDataCompressor\""));
    assert!(head("lz4_10.vtu").contains("compressor=\"vtkLZ4DataCompressor\""));
    assert!(head("poly_10.vtp").contains("compressor=\"vtkZLibDataCompressor\""));
    assert!(head("grid_10.vtu").contains("compressor=\"vtkLZ4DataCompressor\""));
    assert!(fs::read(post.join("legbin_10.vtk"))
        .unwrap()
        .starts_with(b"# vtk DataFile Version 5.1\nGenerated by rdem\nBINARY\n"));
    let seen = vtk_read(&files);
    let get = |f: &str| &seen[&post.join(f)];

    let vec3 = |sel: &[usize], v: &[rdem::DVec3]| -> Vec<f64> {
        sel.iter().flat_map(|&k| v[k].to_array()).collect()
    };
    let scalar = |sel: &[usize], f: &dyn Fn(usize) -> f64| -> Vec<f64> {
        sel.iter().map(|&k| f(k)).collect()
    };
    let points32 = |sel: &[usize]| -> Vec<f64> {
        sel.iter()
            .flat_map(|&k| p.x[k].to_array())
            .map(|x| x as f32 as f64)
            .collect()
    };
    // atom/vtk: every encoding gives the same arrays, exactly.
    for (f, sel) in [
        ("ascii_10.vtu", &order),
        ("bin_10.vtu", &heavy),
        ("zlib_10.vtu", &order),
        ("lz4_10.vtu", &order),
    ] {
        let s = get(f);
        assert_eq!(s.class, "vtkUnstructuredGrid", "{f}");
        assert_eq!((s.npoints, s.ncells), (sel.len(), sel.len()), "{f}");
        assert_eq!(s.points, points32(sel), "{f}");
        let names: Vec<&str> = s.arrays.iter().map(|a| a.0.as_str()).collect();
        assert_eq!(
            names,
            [
                "radii",
                "id",
                "type",
                "proc",
                "mass",
                "velocity_lin",
                "velocity_ang",
                "force"
            ],
            "{f}"
        );
        let want: [(usize, Vec<f64>); 8] = [
            (1, scalar(sel, &|k| p.radius[k])),
            (1, scalar(sel, &|k| p.tag[k] as f64)),
            (1, scalar(sel, &|k| p.ty[k] as f64)),
            (1, vec![0.0; sel.len()]),
            (1, scalar(sel, &|k| p.rmass[k])),
            (3, vec3(sel, &p.v)),
            (3, vec3(sel, &p.omega)),
            (3, vec3(sel, &p.f)),
        ];
        for (a, (nc, vals)) in s.arrays.iter().zip(want) {
            assert_eq!(a.1, nc, "{f} {}", a.0);
            assert_eq!(a.2, vals, "{f} {}", a.0);
        }
    }
    assert!(p.omega.iter().any(|o| o.length() > 1.0));
    assert!(p.ty.contains(&2));

    // custom/vtk, legacy ASCII (%.11g) and BINARY (exact), .vtp and .vtu (exact).
    let close = |a: &[f64], b: &[f64], rel: f64| {
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= rel * y.abs(), "{x} vs {y}");
        }
    };
    let leg = get("leg_10.vtk");
    assert_eq!(leg.class, "vtkPolyData");
    assert_eq!((leg.npoints, leg.ncells), (36, 36));
    close(&leg.points, &points32(&order), 5e-6); // %g: 6 digits
    let names: Vec<&str> = leg.arrays.iter().map(|a| a.0.as_str()).collect();
    assert_eq!(names, ["id", "type", "mass", "v", "f", "radius", "omega"]);
    close(&leg.arrays[3].2, &vec3(&order, &p.v), 1e-10);
    close(&leg.arrays[4].2, &vec3(&order, &p.f), 1e-10);
    close(&leg.arrays[6].2, &vec3(&order, &p.omega), 1e-10);
    let legbin = get("legbin_10.vtk");
    let names: Vec<(&str, usize)> = legbin.arrays.iter().map(|a| (a.0.as_str(), a.1)).collect();
    assert_eq!(
        names,
        [("id", 1), ("type", 1), ("i", 3), ("v", 3), ("radius", 1)]
    );
    assert_eq!(legbin.points, points32(&order));
    assert_eq!(legbin.arrays[0].2, scalar(&order, &|k| p.tag[k] as f64));
    assert_eq!(legbin.arrays[2].2, vec![0.0; 108]);
    assert_eq!(legbin.arrays[3].2, vec3(&order, &p.v));
    assert_eq!(legbin.arrays[4].2, scalar(&order, &|k| p.radius[k]));
    let poly = get("poly_10.vtp");
    assert_eq!(poly.class, "vtkPolyData");
    assert_eq!((poly.npoints, poly.ncells), (36, 36));
    assert_eq!(poly.points, points32(&order));
    let names: Vec<&str> = poly.arrays.iter().map(|a| a.0.as_str()).collect();
    assert_eq!(names, ["id", "type", "v", "f", "radius"]);
    assert_eq!(poly.arrays[1].2, scalar(&order, &|k| p.ty[k] as f64));
    assert_eq!(poly.arrays[3].2, vec3(&order, &p.f));
    let grid = get("grid_10.vtu");
    assert_eq!(grid.class, "vtkUnstructuredGrid");
    let names: Vec<&str> = grid.arrays.iter().map(|a| a.0.as_str()).collect();
    assert_eq!(names, ["id", "type", "omega"]);
    assert_eq!(grid.arrays[2].2, vec3(&order, &p.omega));
    for f in [
        "leg_boundingBox_10.vtk",
        "legbin_boundingBox_10.vtk",
        "poly_boundingBox_10.vtr",
        "grid_boundingBox_10.vtr",
    ] {
        let b = get(f);
        assert_eq!(b.class, "vtkRectilinearGrid", "{f}");
        assert_eq!(b.npoints, 8, "{f}");
        if f.ends_with(".vtr") {
            assert_eq!(b.points, [0.0, 0.01, 0.0, 0.01, 0.0, 0.01], "{f}");
        }
    }

    // One collection per series, each entry readable, times step × dt.
    let mut pvds: Vec<String> = fs::read_dir(&post)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".pvd"))
        .collect();
    pvds.sort();
    assert_eq!(
        pvds,
        [
            "ascii.pvd",
            "bin.pvd",
            "grid.pvd",
            "leg.pvd",
            "legbin.pvd",
            "lz4.pvd",
            "poly.pvd",
            "zlib.pvd"
        ]
    );
    let mut listed = Vec::new();
    for name in &pvds {
        let sets = pvd_sets(&fs::read_to_string(post.join(name)).unwrap());
        let stem = name.trim_end_matches(".pvd");
        let times: Vec<f64> = sets.iter().map(|s| s.0).collect();
        assert_eq!(times, [0.0, 5e-5, 10.0 * 1e-5], "{name}");
        for (k, (_, file)) in sets.iter().enumerate() {
            assert!(file.starts_with(&format!("{stem}_{}.", 5 * k)), "{file}");
            listed.push(post.join(file));
        }
    }
    let seen = vtk_read(&listed);
    for (f, s) in &seen {
        assert_eq!(
            s.npoints,
            if f.to_string_lossy().contains("bin_") && !f.to_string_lossy().contains("legbin") {
                10
            } else {
                36
            },
            "{}",
            f.display()
        );
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// File names: `pad`, `%`, missing directories, a name without `*` (one file, overwritten,
/// no collection), `write_dump`, and the keyword errors.
#[test]
fn vtk_file_names_and_options() {
    let dir = common::scratch_dir("vtk-names");
    let d = dir.display();
    let script = format!(
        "{LATTICE}\
dump a all atom/vtk 4 {d}/deep/er/pad_*.vtu
dump_modify a pad 6
dump b all atom/vtk 4 {d}/one.vtu
dump c heavy atom/vtk 4 {d}/rank%_*.vtu
dump_modify c sort id
dump e all custom/vtk 4 {d}/pp/pad_*.vtp id vx
dump_modify e pad 3 binary no
run 10
write_dump all atom/vtk {d}/wd_*.vtu modify binary yes
"
    );
    common::run("in.test", &script);
    for f in [
        "deep/er/pad_000000.vtu",
        "deep/er/pad_000004.vtu",
        "deep/er/pad_000008.vtu",
        "deep/er/pad.pvd",
        "one.vtu",
        "rank0_0.vtu",
        "rank0_8.vtu",
        "rank0.pvd",
        "pp/pad_000.vtp",
        "pp/pad_boundingBox_008.vtr",
        "pp/pad.pvd",
        "wd_10.vtu",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    // Without '*': one file, the last snapshot, and no collection.
    assert!(!dir.join("one.pvd").exists());
    assert!(!dir.join("wd.pvd").exists());
    let one = read_ascii_xml(&fs::read_to_string(dir.join("one.vtu")).unwrap());
    assert_eq!(one[1].values.len(), 36);
    let pad = pvd_sets(&fs::read_to_string(dir.join("deep/er/pad.pvd")).unwrap());
    let files: Vec<&str> = pad.iter().map(|s| s.1.as_str()).collect();
    assert_eq!(
        files,
        ["pad_000000.vtu", "pad_000004.vtu", "pad_000008.vtu"]
    );
    assert!(fs::read_to_string(dir.join("pp/pad_004.vtp"))
        .unwrap()
        .contains("format=\"ascii\""));
    assert!(fs::read_to_string(dir.join("wd_10.vtu"))
        .unwrap()
        .contains("format=\"binary\""));
    // No temporary files are left behind.
    let mut stack = vec![dir.clone()];
    while let Some(d) = stack.pop() {
        for e in fs::read_dir(&d).unwrap() {
            let e = e.unwrap();
            if e.file_type().unwrap().is_dir() {
                stack.push(e.path());
            } else {
                assert!(!e.file_name().to_string_lossy().ends_with(".tmp"));
            }
        }
    }

    for (bad, msg) in [
        ("dump x all atom/vtk 1 a_*.vtu id", "takes no columns"),
        (
            "dump x all atom/vtk 1 a_*.vtu\ndump_modify x compressor gzip",
            "unknown compressor 'gzip'",
        ),
        (
            "dump x all custom/vtk 1 a_*.vtk id\ndump_modify x compressor zlib",
            "legacy .vtk files cannot be compressed",
        ),
        (
            "dump x all custom 1 a_*.txt id\ndump_modify x binary yes",
            "binary applies to the particle VTK dump styles",
        ),
        (
            "dump x all atom/vtk 1 a_*.vtu\ndump_modify x sort off",
            "always sorts by id",
        ),
        (
            "dump x all custom/vtk 1 a_*.pvtp id",
            "must end in .vtk, .vtp or .vtu",
        ),
    ] {
        let mut i = common::interpreter();
        let e = i
            .run_source("in.bad", &format!("{LATTICE}{bad}\n"))
            .unwrap_err();
        let text = format!("{:?}", miette::Report::new(*e));
        assert!(text.contains(msg), "{bad}: {text}");
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// A dump whose directory cannot be created stops the run with the file and the reason.
#[test]
fn write_errors_name_the_file() {
    let dir = common::scratch_dir("vtk-errors");
    fs::write(dir.join("plain"), b"").unwrap();
    let d = dir.display();
    let mut i = common::interpreter();
    let e = i
        .run_source(
            "in.err",
            &format!("{LATTICE}dump a all atom/vtk 1 {d}/plain/a_*.vtu\nrun 1\n"),
        )
        .unwrap_err();
    let text = format!("{:?}", miette::Report::new(*e));
    assert!(text.contains("plain"), "{text}");
    assert!(text.contains("create directory"), "{text}");
    fs::remove_dir_all(&dir).unwrap();
}

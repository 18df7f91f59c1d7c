//! `compute pair/gran/local` and `dump local`: two overlapping spheres (r 1 mm and 0.9 mm,
//! centre distance 1.811 mm, the second moving at (−0.01, 0.02, 0.03) m/s) under Hertz
//! with tangential history, two steps. The dump files must equal LIGGGHTS 3.8's byte for
//! byte (`tests/data/local/`, recorded with the command in each script's header), and the
//! normal force must be the closed-form Hertz force with its damping.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/local")
}

fn read(p: PathBuf) -> String {
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn default_columns_match_liggghts_byte_for_byte() {
    let dir = common::run_data_script("local", &data(), "in.pair", &[]).0;
    for f in ["pair0.txt", "pair2.txt"] {
        assert_eq!(
            read(dir.join("post").join(f)),
            read(data().join(f)),
            "{f} differs from LIGGGHTS 3.8's"
        );
    }
}

#[test]
fn keyword_order_is_liggghts_order() {
    // Keywords given as delta contactArea force_tangential force_normal; LIGGGHTS writes
    // force_normal, force_tangential, contactArea, delta.
    let dir = common::run_data_script("local", &data(), "in.pair_split", &[]).0;
    assert_eq!(read(dir.join("post/q2.txt")), read(data().join("q2.txt")));
}

/// The last row of a `dump local` file as numbers.
fn last_row(text: &str) -> Vec<f64> {
    let line = text.lines().last().unwrap();
    line.split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect()
}

#[test]
fn normal_force_is_damped_hertz() {
    let dir = common::run_data_script("local", &data(), "in.pair", &[]).0;
    let r = last_row(&read(dir.join("post/pair2.txt")));
    assert_eq!(
        r.len(),
        25,
        "pos vel id force torque history(3) contactArea"
    );
    let xi = [r[0], r[1], r[2]];
    let xj = [r[3], r[4], r[5]];
    let vi = [r[6], r[7], r[8]];
    let vj = [r[9], r[10], r[11]];
    assert_eq!((r[12], r[13], r[14]), (1.0, 2.0, 0.0));
    let d: Vec<f64> = (0..3).map(|a| xi[a] - xj[a]).collect();
    let dist = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    let n: Vec<f64> = d.iter().map(|x| x / dist).collect();
    let (ri, rj) = (0.001, 0.0009);
    let delta = ri + rj - dist;
    // LIGGGHTS' Hertz: E* = E/(2(1 − ν²)), kn = 4/3 E* √(R* δ), γn = 2√(5/6) β √(Sn m*),
    // Sn = 2 E* √(R* δ), β = ln e/√(ln² e + π²).
    let (e, nu, rest) = (1e7, 0.3, 0.5f64);
    let estar = e / (2.0 * (1.0 - nu * nu));
    let rstar = ri * rj / (ri + rj);
    let vol = |r: f64| 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let (mi, mj) = (2500.0 * vol(ri), 2500.0 * vol(rj));
    let mstar = mi * mj / (mi + mj);
    let sq = (rstar * delta).sqrt();
    let kn = 4.0 / 3.0 * estar * sq;
    let beta = rest.ln() / (rest.ln().powi(2) + std::f64::consts::PI.powi(2)).sqrt();
    let gamma = -2.0 * (5.0f64 / 6.0).sqrt() * beta * (2.0 * estar * sq * mstar).sqrt();
    let vn: f64 = (0..3).map(|a| (vi[a] - vj[a]) * n[a]).sum();
    let fn_want = kn * delta - gamma * vn;
    let f = [r[15], r[16], r[17]];
    let fn_got: f64 = (0..3).map(|a| f[a] * n[a]).sum();
    // The dump prints 6 significant digits, positions included: δ is known to ~1e-4.
    assert!(
        (fn_got - fn_want).abs() < 2e-3 * fn_want,
        "normal force {fn_got} vs Hertz {fn_want}"
    );
    // Contact area: the spheres' intersection circle, π a².
    let x = (dist * dist + ri * ri - rj * rj) / (2.0 * dist);
    let area = std::f64::consts::PI * (ri * ri - x * x);
    assert!(
        (r[24] - area).abs() < 2e-3 * area,
        "area {} vs {area}",
        r[24]
    );
}

#[test]
fn ms_id_is_not_supported_yet() {
    let dir = common::scratch_dir("local");
    let script =
        read(data().join("in.pair")).replace("pair/gran/local\n", "pair/gran/local ms_id\n");
    std::fs::write(dir.join("in.x"), script).unwrap();
    let out = common::rdem_command(None)
        .current_dir(&dir)
        .args(["-in", "in.x", "-log", "none"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(text.contains("'ms_id' is not supported yet"), "{text}");
    assert!(text.contains("delta, contactPoint or heatFlux"), "{text}");
}

#[test]
fn contact_point_matches_liggghts_byte_for_byte() {
    // 35 columns, contactPoint last whatever the keyword order; the force chains with the
    // contact point as a third point (3 points, 3 lines, a blank line after the nine
    // point values, as VTK's legacy writer puts it).
    let dir = common::run_data_script("local", &data(), "in.point", &[]).0;
    for f in ["pt2.txt", "pt2.vtk"] {
        assert_eq!(
            read(dir.join("post").join(f)),
            read(data().join(f)),
            "{f} differs from LIGGGHTS 3.8's"
        );
    }
    // Closed form: on the line of centres, r_i/(r_i + r_j) of the way from i to j.
    let r = last_row(&read(dir.join("post/pt2.txt")));
    assert_eq!(r.len(), 35);
    let (ri, rj) = (0.001, 0.0009);
    for a in 0..3 {
        let want = r[a] + (r[3 + a] - r[a]) * ri / (ri + rj);
        // Six printed digits of positions up to 1.8 mm: each known to 5e-9 m. (Halving
        // the overlap instead, r_i − δ/2 from i, would be 2.3e-6 m off.)
        assert!(
            (r[32 + a] - want).abs() < 4e-9,
            "contact point {a}: {} vs {want}",
            r[32 + a]
        );
    }
}

/// `text` with every number replaced by `#`, and the numbers. A number starts with a digit
/// or a minus sign not inside a word (`Float64`, `vel1` and `L2_NORM_RANGE` stay text).
fn skeleton(text: &str) -> (String, Vec<f64>) {
    let b = text.as_bytes();
    let (mut out, mut nums, mut k) = (String::new(), Vec::new(), 0);
    while k < b.len() {
        let c = b[k];
        if c.is_ascii_alphabetic() || c == b'_' {
            let s = k;
            while k < b.len() && (b[k].is_ascii_alphanumeric() || b[k] == b'_') {
                k += 1;
            }
            out.push_str(&text[s..k]);
        } else if c.is_ascii_digit() || (c == b'-' && b.get(k + 1).is_some_and(u8::is_ascii_digit))
        {
            let s = k;
            k += 1;
            while k < b.len()
                && (b[k].is_ascii_digit()
                    || b[k] == b'.'
                    || matches!(b[k], b'e' | b'E')
                    || (matches!(b[k], b'+' | b'-') && matches!(b[k - 1], b'e' | b'E')))
            {
                k += 1;
            }
            nums.push(text[s..k].parse::<f64>().unwrap());
            out.push('#');
        } else {
            out.push(c as char);
            k += 1;
        }
    }
    (out, nums)
}

#[test]
fn xml_force_chains_match_liggghts() {
    // `.vtp` (PolyData) and `.vtu` (UnstructuredGrid) as LIGGGHTS 3.8 writes them through
    // VTK: the same text, every number printed in full (shortest round trip). The contact
    // law's last bits differ (rdem and LIGGGHTS sum in another order): measured worst
    // 3.2e-13 relative, so numbers must agree to 1e-11.
    let dir = common::run_data_script("local", &data(), "in.point", &[]).0;
    for f in ["pt2.vtp", "pu2.vtu"] {
        let (ours, a) = skeleton(&read(dir.join("post").join(f)));
        let (theirs, b) = skeleton(&read(data().join(f)));
        assert_eq!(ours, theirs, "{f}: layout differs from LIGGGHTS 3.8's");
        assert_eq!(a.len(), b.len());
        for (k, (x, y)) in a.iter().zip(&b).enumerate() {
            assert!(
                (x - y).abs() <= 1e-11 * y.abs(),
                "{f}: number {k}: rdem {x}, LIGGGHTS {y}"
            );
        }
    }
    // Without contacts, the files are the same byte for byte.
    let dir = common::run_data_script("local", &data(), "in.none", &[]).0;
    for f in ["none2.vtp", "none2.vtu"] {
        assert_eq!(read(dir.join("post").join(f)), read(data().join(f)), "{f}");
    }
}

#[test]
fn xml_force_chains_read_back_in_vtk() {
    let probe = std::process::Command::new("python3")
        .args(["-c", "import vtk"])
        .output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("note: python3 with vtk not found; VTK read-back skipped");
        return;
    }
    // ASCII, and binary (base64) and zlib variants, which LIGGGHTS 3.8 also writes with
    // `dump_modify binary yes` / `compressor zlib`: VTK must read the same values.
    let script = read(data().join("in.point")).replace(
        "run 2",
        "dump d7 all local/gran/vtk 2 post/bin*.vtp pgl\n\
         dump_modify d7 binary yes\n\
         dump d8 all local/gran/vtk 2 post/zl*.vtu pgl\n\
         dump_modify d8 compressor zlib\n\
         run 2",
    );
    let dir = common::scratch_dir("local");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    std::fs::write(dir.join("in.x"), script).unwrap();
    let out = common::rdem_command(None)
        .current_dir(&dir)
        .args(["-in", "in.x", "-log", "none"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let code = r#"import sys, vtk
def read(f):
    r = vtk.vtkXMLPolyDataReader() if f.endswith('.vtp') else vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(f); r.Update(); o = r.GetOutput(); cd = o.GetCellData()
    arrays = [cd.GetArrayName(k) for k in range(cd.GetNumberOfArrays())]
    vals = [cd.GetArray(a).GetComponent(c, m) for a in arrays for c in range(o.GetNumberOfCells()) for m in range(cd.GetArray(a).GetNumberOfComponents())]
    pts = [o.GetPoint(k) for k in range(o.GetNumberOfPoints())]
    return o.GetNumberOfPoints(), o.GetNumberOfCells(), arrays, vals, pts
a = read(sys.argv[1])
print(a[0], a[1], ' '.join(a[2]))
print(a[4][2])
for f in sys.argv[2:]:
    print(read(f) == a)
"#;
    let post = dir.join("post");
    let out = std::process::Command::new("python3")
        .args(["-c", code])
        .args(["pt2.vtp", "bin2.vtp", "zl2.vtu"].map(|f| post.join(f)))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<&str> = text.lines().collect();
    // As LIGGGHTS' pt2.vtp: 3 points, 3 lines, these arrays.
    assert_eq!(
        lines[0],
        "3 3 vel1 vel2 id1 id2 force force_normal force_tangential torque contact_area delta"
    );
    // The third point is the contact point (LIGGGHTS: 0.000947364 0.000105285 3.15274e-08).
    let p: Vec<f64> = lines[1]
        .trim_matches(|c| c == '(' || c == ')')
        .split(", ")
        .map(|w| w.parse().unwrap())
        .collect();
    for (x, y) in p.iter().zip([0.000947364, 0.000105285, 3.15274e-08]) {
        // LIGGGHTS printed six digits: within half a unit of the sixth.
        assert!((x - y).abs() < 5e-6 * y.abs(), "{p:?}");
    }
    assert_eq!(
        &lines[2..],
        ["True", "True"],
        "binary and zlib read as ASCII"
    );
}

#[test]
fn force_chain_vtk_matches_liggghts_byte_for_byte() {
    let dir = common::run_data_script("local", &data(), "in.vtk", &[]).0;
    assert_eq!(
        read(dir.join("post/all2.vtk")),
        read(data().join("all2.vtk"))
    );
    // A ParaView collection beside the series, one entry per snapshot (steps 0 and 2).
    let pvd = read(dir.join("post/all.pvd"));
    assert_eq!(pvd.matches("<DataSet").count(), 2, "{pvd}");
}

#[test]
fn force_chain_vtk_reads_back_in_vtk() {
    let probe = std::process::Command::new("python3")
        .args(["-c", "import vtk"])
        .output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("note: python3 with vtk not found; VTK read-back skipped");
        return;
    }
    let dir = common::run_data_script("local", &data(), "in.vtk_many", &[]).0;
    let code = "import sys, vtk\n\
r = vtk.vtkGenericDataObjectReader(); r.SetFileName(sys.argv[1]); r.Update()\n\
o = r.GetOutput(); cd = o.GetCellData()\n\
ids = sorted((int(cd.GetArray('id1').GetValue(k)), int(cd.GetArray('id2').GetValue(k))) for k in range(o.GetNumberOfCells()))\n\
print(o.GetNumberOfPoints(), o.GetNumberOfCells(), cd.GetNumberOfArrays(), ids)\n\
f = cd.GetArray('force'); n = cd.GetArray('force_normal'); t = cd.GetArray('force_tangential')\n\
print(max(abs(f.GetComponent(k, c) - n.GetComponent(k, c) - t.GetComponent(k, c)) for k in range(o.GetNumberOfCells()) for c in range(3)))\n";
    let out = std::process::Command::new("python3")
        .args(["-c", code])
        .arg(dir.join("post/many2.vtk"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut lines = text.lines();
    // As LIGGGHTS' file for the same script: 10 points, 5 lines, 10 arrays, these pairs.
    assert_eq!(
        lines.next().unwrap(),
        "10 5 10 [(1, 2), (4, 5), (6, 7), (8, 9), (10, 11)]"
    );
    let resid: f64 = lines.next().unwrap().parse().unwrap();
    // Each value has 11 significant digits; forces are below 0.5 N.
    assert!(resid < 1e-10, "force != normal + tangential by {resid}");
}

/// `dump_modify label` (as LIGGGHTS_SEAICE's scripts write `label 'BONDS'`): the header
/// lines of a local dump name the label instead of ENTRIES; LIGGGHTS 3.8 wrote this file
/// for the same script (two spheres overlapping by 0.1 mm, `pos force` columns 1 and 2).
/// Other dump styles refuse the keyword, as LIGGGHTS 3.8 applies it to dump local only.
#[test]
fn the_label_names_the_entries() {
    let head = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
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
create_atoms 1 single 0.0099 0 0.05
set type 1 diameter 0.01 density 2500
fix integr all nve/sphere
compute pl all pair/gran/local pos force
";
    let script = format!(
        "{head}dump d all local 10 d*.local c_pl[1] c_pl[2]
dump_modify d pad 3 label 'BONDS' first yes
run 10
"
    );
    let (dir, _) = common::run_kept_ok("label", &script, &[], None);
    let got = std::fs::read_to_string(dir.join("d010.local")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let liggghts = "ITEM: TIMESTEP
10
ITEM: NUMBER OF BONDS
1
ITEM: BOX BOUNDS ff ff ff
-0.05 0.05
-0.05 0.05
0 0.1
ITEM: BONDS c_pl[1] c_pl[2] 
-7.85012e-07 0 
";
    assert_eq!(got, liggghts);
    let out = common::run_script_raw(
        &format!("{head}dump d all custom 10 d.txt id x\ndump_modify d label BONDS\n"),
        None,
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("label applies to dump local only"), "{err}");
}

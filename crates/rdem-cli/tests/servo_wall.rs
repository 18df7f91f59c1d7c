//! `fix mesh/surface/stress/servo`: a PID-controlled lid. Its screen output is compared
//! with LIGGGHTS 3.8 runs of the same scripts, recorded below with the command that made
//! them (`liggghts -in in.x -log none`, `floor.stl` = [`common::floor_stl`]), and its
//! resting state with the closed form of a Hertzian column.

use crate::common;

use common::{floor_stl, run_with_files, run_with_files_raw, thermo_rows};

/// A sphere (radius 5 mm) on a floor under a lid 0.2 mm above it; `{LID}` is the servo.
const SPHERE: &str = "atom_style granular
atom_modify map array
communicate single vel yes
boundary f f f
units si
newton off
region box block -0.1 0.1 -0.1 0.1 -0.01 0.2 units box
create_box 1 box
create_atoms 1 single 0.0 0.0 0.005
set atom 1 diameter 0.01 density 2500
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix g all gravity 9.81 vector 0 0 -1
{LID}
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes lid
fix fl all wall/gran model hertz tangential history primitive type 1 zplane 0
fix nve all nve/sphere
variable zz equal z[1]
thermo_style custom step atoms f_lid[3] f_lid[9] v_zz
thermo_modify format float %.10g
thermo 50
";

/// Runs `script` with floor.stl; its thermo rows.
fn rows(script: &str) -> Vec<Vec<f64>> {
    let out = run_with_files(script, &[("floor.stl", &floor_stl())], None);
    thermo_rows(&out)
}

/// Parses recorded rows "step a b c".
fn recorded(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// Compares rows (step, force, lid z, ...) of rdem (`got`, which also has the atom
/// count in column 1) with LIGGGHTS' (`want`), rows of a repeated step once: force
/// within `ftol` (N), positions within `ztol` (m).
fn compare(got: &[Vec<f64>], want: &[Vec<f64>], ftol: f64, ztol: f64) {
    let mut got: Vec<&Vec<f64>> = got.iter().collect();
    got.dedup_by(|a, b| a[0] == b[0]);
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(want) {
        assert_eq!(g[0], w[0]);
        assert!(
            (g[2] - w[1]).abs() <= ftol,
            "step {}: force {} vs {}",
            w[0],
            g[2],
            w[1]
        );
        for k in 2..w.len() {
            assert!(
                (g[k + 1] - w[k]).abs() <= ztol,
                "step {}: column {k} {} vs {}",
                w[0],
                g[k + 1],
                w[k]
            );
        }
    }
}

/// LIGGGHTS 3.8, [`SPHERE`] with `fix lid all mesh/surface/stress/servo file floor.stl
/// type 1 move 0 0 0.0102 com 0 0 0.0102 ctrlPV force axis 0 0 1 target_val -1 vel_max
/// 0.05 kp 0.5 ki 20 kd 1e-4` and `run 1400`: step, f_lid[3], f_lid[9], z of the sphere.
const LIGGGHTS_PID: &str = "0 0 0.0102 0.005
50 0 0.0101876275 0.004998848862
100 0 0.010174755 0.004995982374
150 0 0.0101616325 0.004992645229
200 0 0.01014826 0.004990074992
250 0 0.0101346375 0.004988933285
300 0 0.010120765 0.004989131602
350 0 0.0101066425 0.004990103573
400 0 0.01009227 0.004991215605
450 0 0.0100776475 0.004992033375
500 0 0.010062775 0.004992388232
550 0 0.0100476525 0.004992324339
600 0 0.01003228 0.004992006566
650 0 0.0100166575 0.004991628075
700 0 0.010000785 0.004991337985
750 0.03594946441 0.009984968334 0.004990854935
800 0.08771796154 0.009966715094 0.004985773049
850 0.1197743619 0.009942131539 0.004973119626
900 0.1655759096 0.009917834742 0.00495778327
950 0.2340604377 0.009894434558 0.004944943227
1000 0.3088721134 0.009872793984 0.004934622528
1050 0.3731574489 0.009855377535 0.004925838173
1100 0.4096821446 0.009849265085 0.004921201407
1150 0.4326512497 0.009849265085 0.004922757981
1200 0.4358783648 0.009849265085 0.004924240646
1250 0.4311542509 0.009849265085 0.004924089961
1300 0.4298213981 0.009849265085 0.00492374097
1350 0.4306933237 0.009849265085 0.004923728545
1400 0.4311039083 0.009849265085 0.004923804395";

/// The full PID (integral, derivative on the force, clipping at vel_max with the
/// integral reset) as LIGGGHTS 3.8 runs it: the lid descends at vel_max (kp + ki t)
/// until it touches the sphere at step 730, then oscillates against it, clipped. rdem
/// followed LIGGGHTS to 1e-15 at every step when this was written; the tolerance is
/// 1e-6 N and 1e-9 m.
#[test]
fn pid_servo_follows_liggghts_step_by_step() {
    let lid = "fix lid all mesh/surface/stress/servo file floor.stl type 1 move 0 0 0.0102 com 0 0 0.0102 ctrlPV force axis 0 0 1 target_val -1 vel_max 0.05 kp 0.5 ki 20 kd 1e-4";
    let got = rows(&(SPHERE.replace("{LID}", lid) + "run 1400\n"));
    compare(&got, &recorded(LIGGGHTS_PID), 1e-6, 1e-9);
}

/// LIGGGHTS 3.8, [`SPHERE`] with `... target_val -0.5 vel_max 0.05 kp 0.5 ki 0 kd 1e-4`
/// and `run 1000`, `fix_modify lid servo/integrate stop`, `run 100`, `fix_modify lid
/// servo/integrate start`, `run 400` (the repeated rows of step 1000 and 1100 once).
const LIGGGHTS_STOP_START: &str = "0 0 0.0102 0.005
50 0 0.01018775 0.004998848862
100 0 0.01017525 0.004995982374
150 0 0.01016275 0.004992645229
200 0 0.01015025 0.004990074992
250 0 0.01013775 0.004988933285
300 0 0.01012525 0.004989131602
350 0 0.01011275 0.004990103573
400 0 0.01010025 0.004991215605
450 0 0.01008775 0.004992033375
500 0 0.01007525 0.004992388232
550 0 0.01006275 0.004992324339
600 0 0.01005025 0.004992006566
650 0 0.01003775 0.004991628075
700 0 0.01002525 0.004991337985
750 0 0.01001275 0.004991204751
800 0 0.01000025 0.004991219094
850 0.04505171584 0.009988220088 0.004991218243
900 0.04242956882 0.009988148038 0.004990592975
950 0.04068447126 0.009988148038 0.004990202024
1000 0.04026913391 0.009988148038 0.004990073682
1050 -0.03274931213 0.009988148038 0.004993168773
1100 -0.02320083018 0.009988148038 0.004999699347
1150 0.08877972705 0.009988148038 0.005002403618
1200 0.06188690011 0.009988148038 0.004998253931
1250 0.04357129085 0.009988148038 0.004992607333
1300 0.0333983005 0.009987566207 0.004988994173
1350 0.0377259922 0.009985787732 0.004987456574
1400 0.04178861144 0.00998561732 0.004987599156
1450 0.04783391359 0.00998561732 0.004988576948
1500 0.05171487306 0.00998561732 0.004989501008";

/// Stopped, the lid stays where it is while its vertices keep their last velocity for
/// the contact (the sphere feels the damping of a rising lid: −0.037 N at step 1001 in
/// LIGGGHTS 3.8), and the controller resumes where it was; without integral the
/// clipping leaves no state. Tolerances 1e-6 N and 1e-9 m.
#[test]
fn servo_stops_and_starts_between_runs_as_liggghts() {
    let lid = "fix lid all mesh/surface/stress/servo file floor.stl type 1 move 0 0 0.0102 com 0 0 0.0102 ctrlPV force axis 0 0 1 target_val -0.5 vel_max 0.05 kp 0.5 ki 0 kd 1e-4";
    let script = SPHERE.replace("{LID}", lid)
        + "run 1000\nfix_modify lid servo/integrate stop\nrun 100\nfix_modify lid servo/integrate start\nrun 400\n";
    compare(&rows(&script), &recorded(LIGGGHTS_STOP_START), 1e-6, 1e-9);
}

/// 27 spheres (radius 2 mm) in 3 × 3 columns of 3 settle on a floor under a stopped lid
/// (one bounces against it at step 1000); `integrate start` then lowers the lid at
/// kp · vel_max = 0.05 m/s until the bed pushes back with |target_val| = 0.5 N.
const BED: &str = "atom_style granular
atom_modify map array
communicate single vel yes
boundary f f f
newton off
units si
region box block -0.02 0.02 -0.02 0.02 -0.001 0.03 units box
create_box 1 box
lattice sc 0.0045
region bed block -0.008 0.008 -0.008 0.008 0.002 0.017 units box
create_atoms 1 region bed
set group all diameter 0.004 density 2500
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix g all gravity 9.81 vector 0 0 -1
fix lid all mesh/surface/stress/servo file floor.stl type 1 scale 0.1 move 0 0 0.0145 com 0 0 0.0145 ctrlPV force axis 0 0 1 target_val -0.5 vel_max 0.1 kp 0.5
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes lid
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix xlo all wall/gran model hertz tangential history primitive type 1 xplane -0.0066
fix xhi all wall/gran model hertz tangential history primitive type 1 xplane 0.0066
fix ylo all wall/gran model hertz tangential history primitive type 1 yplane -0.0066
fix yhi all wall/gran model hertz tangential history primitive type 1 yplane 0.0066
fix nve all nve/sphere
thermo_style custom step atoms ke f_lid[3] f_lid[9]
thermo_modify format float %.8g
thermo 500
fix_modify lid integrate stop
run 5000
fix_modify lid integrate start
run 12000
";

/// LIGGGHTS 3.8 on [`BED`] (`liggghts -in in.bed -log none`): step, f_lid[3], f_lid[9].
const LIGGGHTS_BED: &str = "0 0 0.0145
500 0 0.0145
1000 1.1610446 0.0145
1500 0 0.0145
2000 0 0.0145
2500 0 0.0145
3000 0 0.0145
3500 0 0.0145
4000 0 0.0145
4500 0 0.0145
5000 0 0.0145
5500 0 0.0142505
6000 0 0.0140005
6500 0 0.0137505
7000 0 0.0135005
7500 0 0.0132505
8000 0 0.0130005
8500 0 0.0127505
9000 0 0.0125005
9500 0 0.0122505
10000 0 0.0120005
10500 0.34817688 0.011839768
11000 0.47327252 0.011803081
11500 0.4956947 0.011796917
12000 0.49931521 0.01179593
12500 0.4998913 0.011795773
13000 0.49998275 0.011795748
13500 0.49999726 0.011795744
14000 0.49999957 0.011795744
14500 0.49999993 0.011795744
15000 0.49999999 0.011795744
15500 0.5 0.011795744
16000 0.5 0.011795744
16500 0.5 0.011795744
17000 0.5 0.011795744";

/// The lid comes to rest where the bed pushes back with the target force, and there the
/// closed form of the columns holds: each column carries 0.5/9 N from the lid plus the
/// weights W = ρ (4/3) π R³ g of the spheres above each contact, and each Hertz contact
/// is compressed by δ = (F / ((4/3) E* √R*))^(2/3), E* = E / (2 (1 − ν²)), R* = R at the
/// walls and R/2 between spheres: the lid rests at 6R − Σδ = 0.0117957436 m. rdem
/// matches LIGGGHTS 3.8 over the whole run (settling, bounce against the stopped lid,
/// approach and rest) within 1e-4 N and 1e-9 m, the rest force within 1e-6 N and the
/// rest position within 1e-9 m of the closed form.
#[test]
fn servo_lid_rests_on_a_settled_bed_at_the_target_force() {
    let got = rows(&BED.replace("%.8g", "%.10g"));
    // Without the kinetic energy column (rdem's and LIGGGHTS' agree there too).
    let no_ke: Vec<Vec<f64>> = got.iter().map(|r| [&r[..2], &r[3..]].concat()).collect();
    compare(&no_ke, &recorded(LIGGGHTS_BED), 1e-4, 1e-9);
    let last = got.last().unwrap();
    assert!((last[3] - 0.5).abs() < 1e-6, "{last:?}");
    let (e, nu, r) = (5e6_f64, 0.45_f64, 0.002_f64);
    let es = e / (2.0 * (1.0 - nu * nu));
    let w = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * 9.81;
    let f = 0.5 / 9.0;
    let delta = |load: f64, rs: f64| (load / (4.0 / 3.0 * es * rs.sqrt())).powf(2.0 / 3.0);
    let z = 6.0 * r
        - delta(f + 3.0 * w, r)
        - delta(f + 2.0 * w, r / 2.0)
        - delta(f + w, r / 2.0)
        - delta(f, r);
    assert!((z - 0.011795743562559).abs() < 1e-12);
    assert!(
        (last[4] - z).abs() < 1e-9,
        "lid at {}, closed form {z}",
        last[4]
    );
}

/// Runs [`SPHERE`] with `lid` as the servo line and `tail` after it (no run unless
/// `tail` has one); the exit status and the screen and error output together.
fn run_lid(lid: &str, tail: &str) -> (bool, String) {
    let out = run_with_files_raw(
        &(SPHERE.replace("{LID}", lid) + tail),
        &[("floor.stl", &floor_stl())],
        None,
    );
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.success(), text)
}

/// Wrong or unsupported servo words stop with an error that names them (and the line);
/// the bare `integrate` of LIGGGHTS' old scripts runs with LIGGGHTS 3.8's deprecation
/// warning.
#[test]
fn servo_errors_name_the_word() {
    const OK: &str = "fix lid all mesh/surface/stress/servo file floor.stl type 1 move 0 0 0.0102 com 0 0 0.0102 ctrlPV force axis 0 0 1 target_val -1 vel_max 0.05";
    let cases: [(String, &str, &str); 12] = [
        (OK.replace("com 0 0 0.0102 ", ""), "", "needs 'com x y z'"),
        (
            OK.replace("ctrlPV force", "ctrlPV shear"),
            "",
            "unknown ctrlPV 'shear'",
        ),
        (
            OK.to_string() + " mode auto",
            "",
            "mode auto needs 'ratio dr'",
        ),
        (OK.to_string() + " mode manual ratio 0.1", "", "auto"),
        (OK.to_string() + " mode auto ratio -1", "", "ratio"),
        (
            OK.replace("axis 0 0 1", "axis 0 0 v_a"),
            "",
            "a variable axis is not supported",
        ),
        (
            OK.replace("vel_max 0.05", "vel_max 80"),
            "",
            "must be below skin / (2 timestep) = 50",
        ),
        (
            OK.replace("target_val -1", "target_val 0"),
            "",
            "target_val must not be 0",
        ),
        (
            OK.replace("axis 0 0 1", "axis 0 0 0"),
            "",
            "the axis has no direction",
        ),
        (
            OK.replace("stress/servo", "stress"),
            "",
            "'com' is a keyword of fix mesh/surface/stress/servo",
        ),
        (OK.to_string(), "fix_modify lid integrate go\n", "start"),
        (
            OK.to_string(),
            "fix mv all move/mesh mesh lid linear 0 0 1\n",
            "cannot also be moved by move/mesh",
        ),
    ];
    for (lid, tail, want) in &cases {
        let (ok, text) = run_lid(lid, tail);
        assert!(
            !ok && text.contains(want) && text.contains("in.test:"),
            "{lid} {tail}: {text}"
        );
    }
    let (ok, text) = run_lid(OK, "fix_modify lid integrate stop\nrun 10\n");
    assert!(ok && text.contains("deprecated"), "{text}");
    let (ok, text) = run_lid(OK, "fix_modify lid servo/target_val -2 servo/vel_max 0.1 servo/ctrlParam 1 0 0 servo/integrate stop\nrun 10\n");
    assert!(ok && !text.contains("deprecated"), "{text}");
    let rows = thermo_rows(&text);
    assert!(
        rows.iter().all(|r| r[3] == 0.0102),
        "a stopped servo stays: {rows:?}"
    );
}

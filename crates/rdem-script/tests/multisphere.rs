//! Multisphere clumps through the interpreter: `fix particletemplate/multisphere` (inline
//! and file spheres, `scale`, `mass`/`inertia_tensor`), insertion of whole clumps by
//! `insert/pack` and `insert/rate/region` with the overlap check on their spheres and
//! their orientation, `fix multisphere` (`fix_modify fflag/tflag`), the clump energies,
//! whole clumps removed at a fixed face, and the located errors.

use std::f64::consts::PI;

use rdem_script::Interpreter;

use crate::common;
use common::render;

const HEAD: &str = "\
atom_style sphere
atom_modify map array sort 0 0
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.02 0.02 -0.02 0.02 0.0 0.04 units box
create_box 1 reg
neighbor 0.0002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1.e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
";

/// A dumbbell: spheres of 1 mm and 0.8 mm radius, centres 1.6 mm apart.
const DUMBBELL: &str = "fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 1000000 spheres 0 0 0 0.001 0.0016 0 0 0.0008 type 1\n";

/// The exact volume of the dumbbell: two balls less their lens, π (R + r − d)² (d² + 2dr
/// − 3r² + 2dR + 6rR − 3R²) / (12 d).
fn dumbbell_volume() -> f64 {
    let (r1, r2, d): (f64, f64, f64) = (1e-3, 0.8e-3, 1.6e-3);
    let lens = PI
        * (r1 + r2 - d).powi(2)
        * (d * d + 2.0 * d * r2 - 3.0 * r2 * r2 + 2.0 * d * r1 + 6.0 * r2 * r1 - 3.0 * r1 * r1)
        / (12.0 * d);
    4.0 / 3.0 * PI * (r1.powi(3) + r2.powi(3)) - lens
}

fn run(tail: &str) -> Result<(Interpreter, String), String> {
    common::try_run_screen("in.ms", &format!("{HEAD}{tail}"))
}

fn bodies(i: &Interpreter) -> &[rdem::multisphere::RigidBody] {
    let ms = i.sim.world.as_ref().unwrap().multisphere.as_ref();
    ms.map_or(&[][..], |m| &m.bodies[..])
}

/// The template's mass is the density times the Monte Carlo volume: 2500 × 6.27978 mm³
/// within 0.5 % (10⁶ points in a box of about 3.4 × 2 × 2 mm³: a standard error near
/// 0.1 %); the file form with `scale` gives the same template as the inline one (the
/// same seed, so the same points).
#[test]
fn template_mass_and_file_form() {
    let dir = std::env::temp_dir().join(format!("rdem-ms-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("dumbbell.txt");
    std::fs::write(
        &file,
        "# x y z r, in mm\n0 0 0 1\n1.6 0 0 0.8   # the small one\n\n",
    )
    .unwrap();
    let (i, out) = run(&format!(
        "{DUMBBELL}fix pts2 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 1000000 spheres file {} scale 0.001 type 2\n",
        file.display()
    ))
    .unwrap();
    let t1 = &i.sim.defs.templates["pts1"];
    let t2 = &i.sim.defs.templates["pts2"];
    let (c1, c2) = (t1.clump.as_ref().unwrap(), t2.clump.as_ref().unwrap());
    let want = 2500.0 * dumbbell_volume();
    let m = c1.template.props.mass;
    assert!(((m - want) / want).abs() < 5e-3, "{m} against {want}");
    assert!((c2.template.props.mass - m).abs() < 1e-12 * m);
    assert_eq!(t1.mean_mass(), m);
    // The bounding radius is about the centre of mass: the far side of the small sphere.
    let far = c1
        .template
        .spheres
        .iter()
        .map(|s| s.x.length() + s.r)
        .fold(0.0, f64::max);
    assert_eq!(c1.template.bound_radius, far);
    assert!(far > 1.7e-3 && far < 1.9e-3, "{far}");
    assert!(
        out.contains("Multisphere template pts1: 2 spheres"),
        "{out}"
    );
}

/// `insert/pack` of 40 dumbbells with the overlap check: 80 spheres, 40 bodies, no
/// sphere overlapping one of another clump, each body's spheres 1.6 mm apart; all move
/// at the inserted velocity, so `ke/multisphere` is Σ ½ M v² = ½ (40 M) v² and
/// `erotate/multisphere` is 0; after a free fall of 1000 steps (no contacts: the gaps
/// stay) each centre has fallen by v t + ½ g t².
#[test]
fn insert_pack_places_whole_clumps_without_overlaps() {
    let (i, _) = run(&format!(
        "{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
region bc block -0.012 0.012 -0.012 0.012 0.01 0.03 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0. 0. -0.5 insert_every once overlapcheck yes all_in yes region bc particles_in_region 40
fix integr all multisphere
compute ke all ke/multisphere
compute er all erotate/multisphere
thermo_style custom step atoms c_ke c_er
thermo_modify norm no
run 1
variable ke0 equal c_ke
variable er0 equal c_er
print \"KE ${{ke0}} ER ${{er0}}\"
"
    ))
    .unwrap();
    let w = i.sim.world.as_ref().unwrap();
    assert_eq!(w.particles.nlocal(), 80);
    let b = bodies(&i);
    assert_eq!(b.len(), 40);
    let m = b[0].mass;
    let p = &w.particles;
    let body = p.property(rdem::multisphere::bodies::BODY_PROP).unwrap();
    let tags = &p.props[body.0].data;
    for a in 0..80 {
        for c in a + 1..80 {
            let d = (p.x[a] - p.x[c]).length();
            if tags[a] == tags[c] {
                assert!((d - 1.6e-3).abs() < 1e-12, "{d}");
            } else {
                assert!(
                    d >= p.radius[a] + p.radius[c],
                    "spheres {a} and {c} overlap"
                );
            }
        }
    }
    // The region holds whole bounding spheres (all_in yes).
    for bd in b {
        assert!(
            bd.x.z > 0.01 + 1.69e-3 && bd.x.z < 0.03 - 1.69e-3,
            "{}",
            bd.x
        );
    }
    let v = 0.5 + 9.81 * 1e-6 / 2.0;
    let ke: f64 = b.iter().map(|x| x.kinetic_energy().0).sum();
    assert!((ke - 0.5 * 40.0 * m * v * v).abs() < 1e-12 * ke);
}

/// `orientation constant q` turns the template as its spheres were given: q = (cos 30°,
/// 0, sin 30°, 0) turns the dumbbell's axis (+x) by 60° about y, so the small sphere sits
/// at 1.6 mm × (cos 60°, 0, −sin 60°) from the large one; LIGGGHTS 3.8 placed it there
/// (x 0.2065070 → 1.0065070 mm, z 4.9200771 → 3.5344364 mm: Δ = (0.8, 0, −1.38564) mm).
/// `orientation template` keeps the axis along +x.
/// Ten-sphere rods (4.5 mm long, bounding radius 2.75 mm about the centre) packed by
/// `insert/pack` without `all_in` into a cylinder region whose top is 0.4 mm below the
/// box top, with `thermo_modify lost ignore` (a real script's set-up): LIGGGHTS 3.8
/// draws each centre at least one bounding radius inside every box face, so no sphere
/// starts outside the box, and it kept all 15,000 spheres of a like script at step 1
/// (measured 2026-12-04: x within ±0.01947 in a ±0.02 box, top sphere at 0.0568 of
/// 0.06). rdem stopped at `run 1` with "particle ... outside the simulation box".
#[test]
fn packed_clumps_start_inside_the_box() {
    let rod: String = (0..10)
        .map(|k| format!(" {} 0 0 0.0005", 0.0005 * k as f64))
        .collect();
    let (i, _) = run(&format!(
        "fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 10 ntry 100000 spheres{rod} type 1
fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zlo all wall/gran model hertz tangential history primitive type 1 zplane 0.0
region bc cylinder z 0. 0. 0.0198 0.004 0.0396 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 orientation random insert_every once overlapcheck yes region bc particles_in_region 150 ntry_mc 10000
fix integr all multisphere
thermo_modify lost ignore
run 1
"
    ))
    .unwrap();
    let w = i.sim.world.as_ref().unwrap();
    let p = &w.particles;
    assert_eq!(bodies(&i).len(), 150);
    assert_eq!(p.nlocal(), 1500);
    let rbound = 2.25e-3 + 0.5e-3;
    for k in 0..p.nlocal() {
        let (x, r) = (p.x[k], p.radius[k]);
        assert!(
            w.domain.is_in_domain(x - r) && w.domain.is_in_domain(x + r),
            "sphere {k} at {x} (r {r}) is not wholly in the box"
        );
    }
    for b in bodies(&i) {
        let c = b.x;
        for a in 0..3 {
            assert!(
                c[a] - rbound >= w.domain.boxlo[a] - 1e-12
                    && c[a] + rbound <= w.domain.boxhi[a] + 1e-12,
                "centre {c} closer than the bounding radius to a face"
            );
        }
    }
}

#[test]
fn orientation_constant_turns_the_template_as_given() {
    for (law, want) in [
        (
            "constant 0.8660254037844387 0 0.5 0",
            [0.8e-3, 0.0, -1.6e-3 * (60f64).to_radians().sin()],
        ),
        ("template", [1.6e-3, 0.0, 0.0]),
    ] {
        let (i, _) = run(&format!(
            "{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
region bc block -0.001 0.001 -0.001 0.001 0.004 0.006 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 orientation {law} insert_every once region bc particles_in_region 1
fix integr all multisphere
run 1
"
        ))
        .unwrap();
        let p = &i.sim.world.as_ref().unwrap().particles;
        let d = p.x[1] - p.x[0];
        for k in 0..3 {
            assert!(
                (d[k] - want[k]).abs() < 1e-12,
                "{law}: {d} against {want:?}"
            );
        }
    }
}

/// `insert/rate/region` makes clumps during the run; `fix_modify ms fflag off off off
/// tflag off off off` then keeps every existing clump's velocity and spin (no force or
/// torque acts on them, as LIGGGHTS' switches do) while the free spheres of another
/// template fall.
#[test]
fn rate_insertion_and_fflag() {
    let (mut i, _) = run(&format!(
        "{DUMBBELL}fix pts3 all particletemplate/sphere 15485867 atom_type 1 density constant 2500 radius constant 0.0005
fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix pdd2 all particledistribution/discrete 15485869 1 pts3 1.0
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
region bc block -0.012 0.012 -0.012 0.012 0.01 0.03 units box
fix ins all insert/rate/region seed 32452843 distributiontemplate pdd1 nparticles 10 particlerate 1000000 insert_every 100 overlapcheck yes region bc
fix ms all multisphere
fix nve all nve/sphere
run 200
"
    ))
    .unwrap();
    let before: Vec<_> = bodies(&i).iter().map(|b| (b.v, b.omega())).collect();
    assert_eq!(before.len(), 10);
    assert!(before.iter().all(|(v, _)| v.z < -1e-3), "they fall");
    i.run_source(
        "in.more",
        "unfix ins
fix_modify ms fflag off off off tflag off off off
region top block -0.012 0.012 -0.012 0.012 0.032 0.039 units box
fix ins2 all insert/pack seed 32452867 distributiontemplate pdd2 insert_every once overlapcheck yes region top particles_in_region 30
run 1000
",
    )
    .map_err(|e| render(&e))
    .unwrap();
    let b = bodies(&i);
    assert_eq!(b.len(), 10);
    for (bd, (v, w)) in b.iter().zip(&before) {
        assert!(bd.fflag == [false; 3] && bd.tflag == [false; 3]);
        assert_eq!(bd.v, *v);
        assert!((bd.omega() - *w).length() <= 1e-12 * w.length().max(1.0));
    }
    let w = i.sim.world.as_ref().unwrap();
    assert_eq!(w.particles.nlocal(), 20 + 30);
    let falling = (0..w.particles.nlocal())
        .filter(|&k| w.particles.v[k].z < -0.005)
        .count();
    assert_eq!(falling, 30);
}

/// A clump crossing a fixed face (`boundary f`, `thermo_modify lost ignore`) goes whole
/// as soon as one of its spheres is out, as LIGGGHTS removes the body.
#[test]
fn a_clump_leaving_the_box_goes_whole() {
    let (i, _) = run(&format!(
        "{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
region bc block -0.001 0.001 -0.001 0.001 0.0019 0.002 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0 0 -1 orientation constant 0.7071067811865476 0 0.7071067811865476 0 insert_every once region bc particles_in_region 1
fix ms all multisphere
thermo_modify lost ignore
run 1
"
    ))
    .unwrap();
    assert_eq!(bodies(&i).len(), 1);
    // The clump starts wholly in the box (its bounding sphere, 1.86 mm, inside the
    // faces, as insertion wants) and falls 2 mm: its lower sphere leaves the box while
    // the upper, 1.6 mm above it, is still inside.
    let w = i.sim.world.as_ref().unwrap();
    assert_eq!(w.particles.nlocal(), 2);
    assert!((0..2).all(|k| w.particles.x[k].z > 0.0));
    let mut i = i;
    i.run_source("in.more", "run 2000\n")
        .map_err(|e| render(&e))
        .unwrap();
    assert_eq!(bodies(&i).len(), 0);
    assert_eq!(i.sim.world.as_ref().unwrap().particles.nlocal(), 0);
}

/// The errors, each at its word.
#[test]
fn errors_point_at_the_word() {
    let cases: [(&str, &str); 7] = [
        (
            "fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 spheres 0 0 0 0.001 nspheres 1 ntry 100000 type 1\n",
            "'spheres' must come after 'nspheres N'",
        ),
        (
            "fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 3 ntry 100000 spheres file /nonexistent/file.txt type 1\n",
            "/nonexistent/file.txt",
        ),
        (
            "fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 100000 spheres 0 0 0 0.001 0.0016 0 0 0.0008 type 1 mass 1e-5\n",
            "'mass' and 'inertia_tensor' together",
        ),
        (
            "fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 100000 spheres 0 0 0 0.001 0.0016 0 0 0.0008\n",
            "needs 'type MT'",
        ),
        (
            &format!("{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0\nregion bc block -0.01 0.01 -0.01 0.01 0.01 0.03 units box\nfix ins all insert/pack seed 32452843 distributiontemplate pdd1 insert_every once region bc particles_in_region 3\nrun 1\n"),
            "needs a fix multisphere",
        ),
        (
            &format!("{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0\nregion bc block -0.01 0.01 -0.01 0.01 0.01 0.03 units box\nfix ins all insert/pack/dense seed 32452843 distributiontemplate pdd1 region bc volumefraction_region 0.3\n"),
            "is a multisphere clump",
        ),
        (
            "fix ms all multisphere\nset group all density 2000\n",
            "set may not be used together with fix multisphere 'ms'",
        ),
    ];
    for (tail, want) in cases {
        let e = run(tail)
            .err()
            .unwrap_or_else(|| panic!("no error for {tail}"));
        assert!(e.contains(want), "{want}: {e}");
        assert!(e.contains("in.ms:"), "{e}");
    }
}

/// A flat-bottomed silo of 674 dumbbells (24 × 24 mm, walls as planes, a bottom plate
/// of STL triangles with a 14 × 14 mm orifice) filled, settled on a plug for 0.15 s,
/// then discharged: the clumps that leave between 0.075 s and 0.3 s after the plug is
/// removed (they fall out through a fixed face 20 mm below), against LIGGGHTS 3.8 on the
/// same script within 10 %.
///
/// How the LIGGGHTS figures were got: this script (the plate written by the same
/// rectangles) run by `liggghts -in in.silo -log none`, twice, with the insertion seeds
/// 32452843 and 49979687 (no `orientation` keyword: LIGGGHTS 3.8 and rdem both insert
/// the dumbbells as the template has them, along x); the atom counts of its thermo
/// output at steps 22500 and 45000 were 1256 → 536 and 1266 → 542, so 360 and 362
/// clumps left (measured 2026-12-02; the two seeds differ by 0.5 %).
#[test]
fn silo_discharge_against_liggghts() {
    let dir = std::env::temp_dir().join(format!("rdem-ms-silo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plate = dir.join("plate.stl");
    let (l, h) = (0.012, 0.007);
    let mut stl = String::from("solid plate\n");
    for (x0, x1, y0, y1) in [
        (-l, l, -l, -h),
        (-l, l, h, l),
        (-l, -h, -h, h),
        (h, l, -h, h),
    ] {
        for tri in [
            [(x0, y0), (x1, y0), (x1, y1)],
            [(x0, y0), (x1, y1), (x0, y1)],
        ] {
            stl.push_str("facet normal 0 0 1\n outer loop\n");
            for (x, y) in tri {
                stl.push_str(&format!("  vertex {x} {y} 0.0\n"));
            }
            stl.push_str(" endloop\nendfacet\n");
        }
    }
    stl.push_str("endsolid plate\n");
    std::fs::write(&plate, stl).unwrap();
    let script = format!(
        "atom_style sphere
atom_modify map array sort 0 0
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.012 0.012 -0.012 0.012 -0.02 0.07 units box
create_box 1 reg
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1.e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix xlo all wall/gran model hertz tangential history primitive type 1 xplane -0.012
fix xhi all wall/gran model hertz tangential history primitive type 1 xplane 0.012
fix ylo all wall/gran model hertz tangential history primitive type 1 yplane -0.012
fix yhi all wall/gran model hertz tangential history primitive type 1 yplane 0.012
fix plate all mesh/surface file {} type 1
fix bottom all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate
fix plug all wall/gran model hertz tangential history primitive type 1 zplane 0.0
{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
region bc block -0.0105 0.0105 -0.0105 0.0105 0.004 0.068 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 insert_every once overlapcheck yes all_in yes region bc volumefraction_region 0.15 ntry_mc 1000000
fix integr all multisphere
thermo 5000
thermo_modify lost ignore norm no
run 15000
",
        plate.display()
    );
    let mut i = common::interpreter();
    i.run_source("in.silo", &script)
        .map_err(|e| render(&e))
        .unwrap();
    let inserted = bodies(&i).len();
    assert!(
        (660..=690).contains(&inserted),
        "{inserted} clumps inserted (LIGGGHTS: 674)"
    );
    i.run_source("in.silo1", "unfix plug\nrun 7500\n")
        .map_err(|e| render(&e))
        .unwrap();
    let n0 = i.sim.natoms();
    i.run_source("in.silo2", "run 22500\n")
        .map_err(|e| render(&e))
        .unwrap();
    let n1 = i.sim.natoms();
    assert_eq!(
        n1 as usize,
        2 * bodies(&i).len(),
        "spheres left without their clump"
    );
    let left = (n0 - n1) as f64 / 2.0;
    let liggghts = (360.0 + 362.0) / 2.0;
    eprintln!("rdem: {left} clumps discharged ({n0} -> {n1} spheres); LIGGGHTS 360, 362");
    assert!(
        (left / liggghts - 1.0).abs() < 0.1,
        "{left} clumps discharged against LIGGGHTS' {liggghts}"
    );
}

/// Restart files carry the clumps: 40 dumbbells poured on a floor for 3000 steps,
/// `write_restart`, 2000 more steps; a second interpreter reads the file, defines the
/// same settings and fixes, and runs the 2000 steps: every body ends where the unbroken
/// run's does, to round-off (its spheres are rewritten in their file order, so contact
/// sums may differ in the last bits).
#[test]
fn restart_files_carry_the_clumps() {
    let dir = std::env::temp_dir().join(format!("rdem-ms-restart-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ms.restart");
    let settings = "fix m1 all property/global youngsModulus peratomtype 1.e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
";
    let (mut i, _) = run(&format!(
        "{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
region bc block -0.008 0.008 -0.008 0.008 0.002 0.012 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0. 0. -0.5 insert_every once overlapcheck yes region bc particles_in_region 40
fix ms all multisphere
run 3000
unfix ins
write_restart {}
",
        file.display()
    ))
    .unwrap();
    i.run_source("in.more", "run 2000\n")
        .map_err(|e| render(&e))
        .unwrap();
    let mut j = common::interpreter();
    j.run_source(
        "in.back",
        &format!(
            "read_restart {}\nneighbor 0.0002 bin\nneigh_modify delay 0\n{settings}fix ms all multisphere\nrun 2000\n",
            file.display()
        ),
    )
    .map_err(|e| render(&e))
    .unwrap();
    let (a, b) = (bodies(&i), bodies(&j));
    assert_eq!(a.len(), 40);
    assert_eq!(b.len(), 40);
    let moved: f64 = a.iter().map(|x| x.v.length()).sum::<f64>();
    assert!(moved > 0.0);
    for (x, y) in a.iter().zip(b) {
        assert!((x.x - y.x).length() < 1e-12, "{} against {}", x.x, y.x);
        assert!((x.v - y.v).length() < 1e-9, "{} against {}", x.v, y.v);
        assert!((x.q.dot(y.q)).abs() > 1.0 - 1e-12);
    }
}

/// `dump custom ... mol id_multisphere` writes each sphere's clump tag twice, as LIGGGHTS
/// 3.8 does (its multisphere tutorial's dump has `mol` 1 for the first clump's 50 spheres
/// and 2 for the second's), and -1 for a free sphere (LIGGGHTS 3.8, measured on a mix of
/// dumbbells and spheres: `1 -1 -1 1 ...` for a sphere, `3 2 2 1 ...` for a clump's).
#[test]
fn dump_mol_is_the_clump_tag() {
    let dir = std::env::temp_dir().join(format!("rdem-ms-dump-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("d.txt");
    run(&format!(
        "{DUMBBELL}fix pts3 all particletemplate/sphere 15485867 atom_type 1 density constant 2500 radius constant 0.0005
fix pdd1 all particledistribution/discrete 15485867 2 pts1 0.9 pts3 0.1
region bc block -0.012 0.012 -0.012 0.012 0.01 0.03 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 insert_every once overlapcheck yes region bc particles_in_region 20
fix ms all multisphere
run 1
dump d all custom 1 {} id mol radius id_multisphere
run 0
",
        file.display()
    ))
    .unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    let rows: Vec<(u64, i64, f64)> = text
        .lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(w[1], w[3], "mol and id_multisphere: {l}");
            (
                w[0].parse().unwrap(),
                w[1].parse().unwrap(),
                w[2].parse().unwrap(),
            )
        })
        .collect();
    assert!(!rows.is_empty());
    let mut per_body = std::collections::BTreeMap::new();
    for &(_, mol, r) in &rows {
        if r == 0.0005 {
            assert_eq!(mol, -1, "a free sphere");
        } else {
            *per_body.entry(mol).or_insert(0) += 1;
        }
    }
    assert!(per_body.len() >= 2, "{rows:?}");
    assert!(per_body.keys().all(|&m| m >= 1));
    assert!(per_body.values().all(|&n| n == 2), "{per_body:?}");
}

/// Reads the rows of the last snapshot of a `dump local` text file.
fn local_rows(path: &std::path::Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let last = text.rfind("ITEM: ENTRIES").unwrap();
    text[last..]
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// `compute multisphere property ...` in `dump local` and `compute multisphere/single` in
/// a variable, against LIGGGHTS 3.8 on the same script: three dumbbells inserted by
/// `insert/pack` (template orientation, the default), v = (0.1, 0, −0.5) m/s,
/// ω = (1, 2, 3) rad/s, flying free under gravity for 1000 steps of 1 µs. LIGGGHTS'
/// row (the same for each body), from `liggghts -in in.ms` with this test's commands
/// (insertion seed 67867967, as LIGGGHTS asks the seeds to differ):
/// vcm 0.1 0 −0.509805, fcm 0 0 −0.000154169, torque 0 0 0, angmom 5.54731e-12
/// 2.92325e-11 4.38592e-11, omega 0.999992 2.00186 2.99876, density 2500, atomtype 1,
/// clumptype 1, masstotal 1.57154e-05, inertia 5.55682e-12 1.46169e-11 1.46205e-11,
/// ex_space 0.999994 0.00313995 −0.00174285. Tolerances: exact for velocity, force and
/// the integers (the same gravity and start), 0.5 % for what follows from the Monte
/// Carlo mass properties (each code draws its own points: a standard error near 0.1 %).
/// The placement differs (each code draws its own positions), so `xcm` is checked
/// against the bodies' own state and the single compute against the local one.
#[test]
fn body_output_against_liggghts() {
    let dir = std::env::temp_dir().join(format!("rdem-ms-local-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (f1, f2) = (dir.join("l1.txt"), dir.join("l2.txt"));
    let (i, out) = run(&format!(
        "fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zwalls all wall/gran model hertz tangential history primitive type 1 zplane 0.0
{DUMBBELL}fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
region bc block -0.01 0.01 -0.01 0.01 0.002 0.01 units box
fix ins all insert/pack seed 67867967 distributiontemplate pdd1 vel constant 0.1 0. -0.5 omega constant 1 2 3 insert_every once overlapcheck yes all_in yes region bc particles_in_region 3
fix ms all multisphere
compute cx all multisphere property xcm
compute cv all multisphere property vcm
compute cf all multisphere property fcm
compute ct all multisphere property torque
compute cq all rigid property quat
compute ca all multisphere property angmom
compute co all multisphere property omega
compute cd all multisphere property density
compute cty all multisphere property atomtype
compute cct all multisphere property clumptype
compute cid all multisphere property id_multisphere
compute cm all multisphere property masstotal
compute ci all multisphere property inertia
compute cex all multisphere property ex_space
compute s1 all multisphere/single id 2 property xcm
compute s2 all multisphere/single id 2 property masstotal
dump d1 all local 1000 {} c_cid c_cx[1] c_cx[2] c_cx[3] c_cv[1] c_cv[2] c_cv[3] c_cf[1] c_cf[2] c_cf[3] c_ct[1] c_ct[2] c_ct[3]
dump d2 all local 1000 {} c_cid c_cq[1] c_cq[2] c_cq[3] c_cq[4] c_ca[1] c_ca[2] c_ca[3] c_co[1] c_co[2] c_co[3] c_cd c_cty c_cct c_cm c_ci[1] c_ci[2] c_ci[3] c_cex[1] c_cex[2] c_cex[3]
run 1000
variable z2 equal c_s1[3]
variable m2 equal c_s2
print \"BODY2 ${{z2}} ${{m2}}\"
",
        f1.display(),
        f2.display()
    ))
    .unwrap();
    let (r1, r2) = (local_rows(&f1), local_rows(&f2));
    assert_eq!(r1.len(), 3);
    assert_eq!(r2.len(), 3);
    let close = |got: f64, want: f64, tol: f64, what: &str| {
        assert!(
            (got - want).abs() <= tol * want.abs().max(1e-300),
            "{what}: rdem {got}, LIGGGHTS {want}"
        );
    };
    let b = bodies(&i);
    for (k, (a, c)) in r1.iter().zip(&r2).enumerate() {
        assert_eq!(a[0], (k + 1) as f64, "rows in tag order");
        assert_eq!(c[0], a[0]);
        for j in 0..3 {
            // %g: six significant digits.
            let want = b[k].x[j];
            assert!((a[1 + j] - want).abs() < 1e-5 * want.abs(), "xcm {a:?}");
        }
        close(a[4], 0.1, 1e-12, "vcm x");
        assert_eq!(a[5], 0.0, "vcm y");
        close(a[6], -0.509805, 1e-6, "vcm z");
        assert_eq!((a[7], a[8]), (0.0, 0.0), "fcm x, y");
        close(a[9], -0.000154169, 5e-3, "fcm z");
        for j in 10..13 {
            assert!(a[j].abs() < 1e-20, "torque {a:?}");
        }
        // quat (w, x, y, z): the x axis it turns is ex_space.
        let q = glam::DQuat::from_xyzw(c[2], c[3], c[4], c[1]);
        assert!((q.length() - 1.0).abs() < 1e-5, "{q}");
        let ex = glam::DVec3::new(c[18], c[19], c[20]);
        assert!((q * glam::DVec3::X - ex).length() < 1e-5, "{q} {ex}");
        for (j, want) in [5.54731e-12, 2.92325e-11, 4.38592e-11].iter().enumerate() {
            close(c[5 + j], *want, 5e-3, "angmom");
        }
        for (j, want) in [0.999992, 2.00186, 2.99876].iter().enumerate() {
            close(c[8 + j], *want, 5e-3, "omega");
        }
        assert_eq!(
            &c[11..14],
            &[2500.0, 1.0, 1.0],
            "density, atomtype, clumptype"
        );
        close(c[14], 1.57154e-05, 5e-3, "masstotal");
        for (j, want) in [5.55682e-12, 1.46169e-11, 1.46205e-11].iter().enumerate() {
            close(c[15 + j], *want, 5e-3, "inertia");
        }
        // The long axis, up to its sign.
        let want = glam::DVec3::new(0.999994, 0.00313995, -0.00174285);
        assert!(ex.dot(want).abs() > 1.0 - 1e-5, "ex_space {ex}");
    }
    let line = out.lines().find(|l| l.starts_with("BODY2")).unwrap();
    let w: Vec<f64> = line
        .split_whitespace()
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    assert!((w[0] - b[1].x.z).abs() < 1e-9, "{line}");
    assert!((w[1] - b[1].mass).abs() < 1e-9 * b[1].mass, "{line}");
}

/// `delete_atoms region` takes a clump whole when the region holds any of its spheres
/// (as LIGGGHTS removes a body with any of its spheres), and `set` runs on the spheres
/// with `allow_group_and_set yes` (LIGGGHTS 3.8 refuses it without).
#[test]
fn delete_atoms_takes_whole_clumps_and_set_needs_allow_group_and_set() {
    let (mut i, _) = run(&format!(
        "{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
region bc block -0.012 0.012 -0.012 0.012 0.01 0.03 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 insert_every once overlapcheck yes region bc particles_in_region 40
fix ms all multisphere allow_group_and_set yes
run 1
"
    ))
    .unwrap();
    // The clumps with no sphere at x >= 0, and those with spheres on both sides.
    let (mut keep, mut straddle) = (0, 0);
    {
        let w = i.sim.world.as_ref().unwrap();
        let p = &w.particles;
        let id = p.property(rdem::multisphere::bodies::BODY_PROP).unwrap();
        let ms = w.multisphere.as_ref().unwrap();
        for &t in &ms.tags {
            let xs: Vec<f64> = (0..p.nlocal())
                .filter(|&k| p.props[id.0].data[k] == t as f64)
                .map(|k| p.x[k].x)
                .collect();
            assert_eq!(xs.len(), 2);
            keep += xs.iter().all(|&x| x < 0.0) as usize;
            straddle += (xs.iter().any(|&x| x < 0.0) && xs.iter().any(|&x| x >= 0.0)) as usize;
        }
    }
    assert!(straddle > 0, "no clump straddles x = 0");
    i.run_source(
        "in.del",
        "region half block 0 0.02 -0.02 0.02 0 0.04 units box
delete_atoms region half
set group all density 2000
run 1
",
    )
    .map_err(|e| render(&e))
    .unwrap();
    let out = common::screen(&i);
    let w = i.sim.world.as_ref().unwrap();
    let n = w.particles.nlocal();
    assert_eq!(bodies(&i).len(), keep);
    assert_eq!(n, 2 * keep, "spheres left without their clump");
    assert!(out.contains(&format!("Deleted {} atoms", 80 - n)), "{out}");
    assert!(w.particles.density[..n].iter().all(|&d| d == 2000.0));
}

/// LIGGGHTS 3.8 on this script (three dumbbells dropped at 0.5 m/s onto a floor, where
/// they bounce and tumble): `erotate/sphere` and the sum of `erotate/sphere/atom` are 0
/// at every step, a clump's spheres counting nothing; `erotate` equals
/// `erotate/multisphere`; `check/timestep/gran` takes a clump's sphere with its template's
/// density and the mass of a sphere of that density: 0.0144442156072523 of the Rayleigh
/// time, and the Hertz fractions below while they fall (rdem took the spheres' shares of
/// their body's mass, and counted their spin in erotate/sphere).
#[test]
fn clump_spheres_in_erotate_sphere_and_check_timestep_as_liggghts() {
    let (_, out) = run(&format!(
        "fix gravi all gravity 9.81 vector 0 0 -1
fix zw all wall/gran model hertz tangential history primitive type 1 zplane 0.0
{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
region bc block -0.01 0.01 -0.01 0.01 0.004 0.008 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0 0 -0.5 \
    insert_every once overlapcheck yes particles_in_region 3 region bc
fix ms all multisphere
fix ts all check/timestep/gran 1000 0.1 0.1
compute 1 all erotate/sphere
compute 2 all erotate
compute 3 all erotate/multisphere
compute 4 all erotate/sphere/atom
compute 5 all reduce sum c_4
thermo_style custom step atoms c_1 c_2 c_3 c_5 f_ts[1] f_ts[2]
thermo_modify format float %.15g
thermo 1000
run 1000
run 20000
"
    ))
    .unwrap();
    let rows: Vec<Vec<f64>> = out
        .lines()
        .filter_map(|l| {
            let w: Vec<f64> = l
                .split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect();
            (w.len() == 8 && l.split_whitespace().count() == 8).then_some(w)
        })
        .collect();
    assert!(rows.len() > 20, "{out}");
    let hertz = [
        (1000.0, 0.00466089101703584),
        (3000.0, 0.00469622632346029),
        (6000.0, 0.00474731398649329),
    ];
    for (step, h) in hertz {
        let r = rows.iter().find(|r| r[0] == step).unwrap();
        assert!(
            (r[7] / h - 1.0).abs() < 1e-12,
            "Hertz fraction {r:?} vs {h}"
        );
    }
    let mut spun = false;
    for r in &rows[1..] {
        assert_eq!(r[1], 6.0, "{r:?}");
        assert_eq!(
            (r[2], r[5]),
            (0.0, 0.0),
            "clump spheres count nothing {r:?}"
        );
        assert_eq!(r[3], r[4], "erotate is the clumps' energy {r:?}");
        assert!((r[6] / 0.0144442156072523 - 1.0).abs() < 1e-12, "{r:?}");
        spun |= r[4] > 1e-7;
    }
    assert!(spun, "the clumps never turned: {out}");
}

/// Issue 41's clump case, built anew: 140 dumbbells (two 1 mm spheres 1.5 mm apart)
/// poured by `insert/rate/region` from a cylinder region clear of the wall into a
/// `zcylinder` wall of radius 1 cm on a floor, `f f f`, 40000 steps. LIGGGHTS 3.8 keeps
/// all 280 spheres and ends with a mean height of 3.5674, 3.5277 and 3.5812 mm for the
/// insertion seeds 86028121, 49979687 and 67867967 (rdem: 3.5827, 3.5224, 3.5202 mm).
/// rdem must keep every sphere at every thermo row, inside the cylinder (centre distance
/// from the axis plus radius below R + 0.01 mm), and end within LIGGGHTS' spread: the 95 %
/// prediction interval of one more LIGGGHTS run from its three, mean ± 4.303 · s · √(4/3)
/// = [3.423, 3.695] mm.
#[test]
fn dumbbells_poured_into_a_cylinder_stay_in_it_as_in_liggghts() {
    let script = "\
atom_style sphere
atom_modify map array sort 0 0
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.011 0.011 -0.011 0.011 0.0 0.05 units box
create_box 1 reg
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zwall all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix cwall all wall/gran model hertz tangential history primitive type 1 zcylinder 0.01 0. 0.
fix pts1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 1000000 spheres 0. 0. 0. 0.001 0.0015 0. 0. 0.001 type 1
fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
region bc cylinder z 0.0 0.0 0.0065 0.01 0.045 units box
fix ins all insert/rate/region seed 86028121 distributiontemplate pdd1 nparticles 140 particlerate 7000 insert_every 1000 overlapcheck yes vel constant 0. 0. -0.3 region bc ntry_mc 10000
fix integr all multisphere
compute z all reduce ave z
thermo_style custom step atoms ke c_z
thermo 2000
thermo_modify lost warn norm no
run 40000
";
    let (i, out) = common::try_run_screen("in.dumb", script).unwrap_or_else(|e| panic!("{e}"));
    assert!(!out.contains("lost at step"), "{out}");
    let rows: Vec<Vec<f64>> = out
        .lines()
        .filter_map(|l| {
            let r: Result<Vec<f64>, _> = l.split_whitespace().map(str::parse::<f64>).collect();
            r.ok().filter(|r| r.len() == 4)
        })
        .collect();
    assert_eq!(rows.len(), 21, "{out}");
    for r in &rows[1..] {
        assert_eq!(r[1], 280.0, "step {}: {out}", r[0]);
    }
    let p = &i.sim.world.as_ref().unwrap().particles;
    let reach = (0..p.nlocal())
        .map(|k| p.x[k].truncate().length() + p.radius[k])
        .fold(0.0, f64::max);
    assert!(reach < 0.01 + 1e-5, "{reach}");
    let z = rows.last().unwrap()[3];
    assert!((3.423e-3..=3.695e-3).contains(&z), "mean height {z}");
}

/// `particletemplate/multiplespheres` without bonds (stock LIGGGHTS 3.8): each template's
/// spheres go in as separate particles, placed as the clump would be. LIGGGHTS 3.8, for
/// 5 templates of three touching 2 mm spheres 4 mm apart on x inserted by insert/pack,
/// made 15 atoms of mass 8.37758e-05 each (ρ·4/3·π·r³), three in a row on x 4 mm apart
/// with the default orientation and turned about the middle one with `orientation
/// random`; no `fix multisphere` is needed. rdem does the same; `bonded yes/implicit`
/// without bond atoms and the rigid-body keywords are located errors, and `bonded yes`
/// is LIGGGHTS-INL's (a bond ID per copy).
#[test]
fn multiplespheres_insert_separate_spheres() {
    let template = "fix pts1 all particletemplate/multiplespheres 15485863 atom_type 1 \
        density constant 2500 nspheres 3 ntry 100000 spheres 0 0 0 0.002 0.004 0 0 0.002 0.008 0 0 0.002";
    let tail = |orientation: &str| {
        format!(
            "{template}\nfix pdd1 all particledistribution/discrete 49979687 1 pts1 1.0\n\
             fix integr all nve/sphere\n\
             region ins block -0.015 0.015 -0.015 0.015 0.005 0.035 units box\n\
             fix ins all insert/pack seed 67867967 distributiontemplate pdd1 insert_every once \
             {orientation} overlapcheck yes all_in yes particles_in_region 5 region ins\nrun 1\n"
        )
    };
    let mass = 2500.0 * 4.0 / 3.0 * PI * 0.002f64.powi(3);
    for orientation in ["", "orientation random"] {
        let (i, out) = run(&tail(orientation)).unwrap_or_else(|e| panic!("{e}"));
        let p = &i.sim.world.as_ref().unwrap().particles;
        assert_eq!(p.nlocal(), 15, "{out}");
        assert!(bodies(&i).is_empty());
        for k in 0..15 {
            assert!((p.rmass[k] - mass).abs() < 1e-12 * mass);
            assert_eq!(p.radius[k], 0.002);
        }
        for t in 0..5 {
            let (a, b, c) = (p.x[3 * t], p.x[3 * t + 1], p.x[3 * t + 2]);
            // One step of the touching spheres moves them by far less than 1e-12 m.
            assert!(((b - a).length() - 0.004).abs() < 1e-12, "{a} {b}");
            assert!(((c - a).length() - 0.008).abs() < 1e-12, "{a} {c}");
            if orientation.is_empty() {
                assert!((b - a - glam::DVec3::new(0.004, 0.0, 0.0)).length() < 1e-12);
            }
        }
    }
    // LIGGGHTS-INL's `bonded yes` without bond atoms: each copy's spheres share a bond
    // ID (the step, 1, plus a fraction), different for each copy.
    let (i, out) = run(&tail("").replacen(template, &format!("{template} bonded yes"), 1))
        .unwrap_or_else(|e| panic!("{e}"));
    let p = &i.sim.world.as_ref().unwrap().particles;
    assert_eq!(p.nlocal(), 15, "{out}");
    let id = p.property("bond_random_id").expect("the property");
    let ids = &p.props[id.0].data[..15];
    for t in 0..5 {
        let c = &ids[3 * t..3 * t + 3];
        assert!(
            c[0] > 1.0 && c[0] < 2.0 && c[1] == c[0] && c[2] == c[0],
            "{ids:?}"
        );
        assert!(
            (0..5).filter(|&u| ids[3 * u] == c[0]).count() == 1,
            "{ids:?}"
        );
    }
    for (extra, msg) in [
        (
            "bonded yes/implicit",
            "bonded templates need an atom style with bonds",
        ),
        (
            "type 1",
            "unknown particletemplate/multiplespheres keyword 'type'",
        ),
    ] {
        let Err(e) = run(&format!("{template} {extra}\n")) else {
            panic!("{extra} ran")
        };
        assert!(e.contains(msg), "{e}");
    }
}

/// LIGGGHTS-INL's `fix nve/nonspherical`: with a `fix multisphere`, the clumps move as
/// they do without it (rdem's fix multisphere integrates them, as LIGGGHTS 3.8; INL's
/// trajectory of a dropped clump is the same for every scheme, group and order, checked
/// with an INL build): the same bits, in either order and with any scheme. Its errors
/// point at the word, and its `unfix` is refused while the clumps would stop in INL.
#[test]
fn nve_nonspherical_moves_the_clumps_once() {
    let drop = |fixes: &str| {
        let (i, _) = run(&format!(
            "{DUMBBELL}fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zw all wall/gran model hertz tangential history primitive type 1 zplane 0.0
region bc block -0.01 0.01 -0.01 0.01 0.002 0.012 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0.1 0 -0.5 insert_every once overlapcheck yes region bc particles_in_region 5
{fixes}run 60000
"
        ))
        .unwrap();
        let b: Vec<_> = bodies(&i).iter().map(|b| (b.x, b.v, b.omega())).collect();
        assert_eq!(b.len(), 5);
        b
    };
    let alone = drop("fix ms all multisphere\n");
    // They fell onto the plane and bounced off it, spinning: a run that moves them.
    let hit = alone
        .iter()
        .filter(|(_, v, w)| (v.z - (-0.5 - 9.81 * 0.06)).abs() > 0.01 && w.length() > 1.0)
        .count();
    assert_eq!(hit, 5, "{alone:?}");
    for fixes in [
        "fix ms all multisphere\nfix integr all nve/nonspherical\n",
        "fix integr all nve/nonspherical integration_scheme 3\nfix ms all multisphere\n",
        "group none type 2\nfix ms all multisphere\nfix integr none nve/nonspherical integration_scheme 0\n",
    ] {
        assert_eq!(drop(fixes), alone, "{fixes}");
    }
    let cases: [(&str, &str); 3] = [
        (
            "fix integr all nve/nonspherical integration_scheme 4\n",
            "integration_scheme 4 is not one of LIGGGHTS-INL's",
        ),
        (
            "fix integr all nve/nonspherical scheme 1\n",
            "integration_scheme",
        ),
        (
            "fix ms all multisphere\nfix integr all nve/nonspherical\nunfix integr\n",
            "unfix integr: in LIGGGHTS-INL this stops the clumps of fix multisphere 'ms'",
        ),
    ];
    for (tail, want) in cases {
        let e = run(tail).map(|_| ()).unwrap_err();
        assert!(e.contains(want), "{tail}: {e}");
        assert!(e.contains("in.ms:"), "{tail}: {e}");
    }
    // Without clumps it may go: it moved nothing.
    run("fix integr all nve/nonspherical\nunfix integr\n").unwrap();
}

//! The run loop and the commands around it, through the interpreter: thermo layout as
//! LIGGGHTS prints it, fix adapt (growth count and mass), insert/rate/region, ave/time,
//! check/timestep/gran, data files, dumps, groups, set, velocity, delete_atoms, run upto.

use rdem_script::Interpreter;

use crate::common;
use common::screen;

/// A box 0.1 × 0.1 × 0.15 with one type and materials, no particles.
const HEAD: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.05 0.05 -0.05 0.05 0. 0.15 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
",
    common::materials!(),
    "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
"
);

fn printed(i: &Interpreter, key: &str) -> f64 {
    let s = screen(i);
    s.lines()
        .find_map(|l| l.strip_prefix(key))
        .unwrap_or_else(|| panic!("no '{key}' in\n{s}"))
        .trim()
        .parse()
        .unwrap()
}

/// Header and set-up row byte for byte as LIGGGHTS 3.8 printed them for the cohesion
/// tutorial (tests/data/tutorials/cohesion.log in rdem-cli).
#[test]
fn thermo_layout_is_liggghts() {
    let i = common::run(
        "in.test",
        &format!(
        "{HEAD}compute rke all erotate/sphere\nthermo_style custom step atoms ke c_rke vol\nrun 0\n"
    ),
    );
    let s = screen(&i);
    assert!(
        s.contains("\n    Step    Atoms         KinEng            rke         Volume \n       0        0              0              0         0.0015 \n"),
        "{s}"
    );
    assert!(s.contains("Loop time of "), "{s}");
}

/// fix adapt: applied at set-up and at every multiple of N (LIGGGHTS: 1 + 100/10 = 11
/// growths in a 100-step run); the mass follows the radius at constant density.
#[test]
fn adapt_grows_radius_and_mass() {
    let i = common::run("in.test", &format!(
        "{HEAD}create_atoms 1 single 0 0 0.05 units box\ncreate_atoms 1 single 0.02 0 0.05 units box\n\
         set type 1 diameter 0.002 density 2500\ncompute r all property/atom radius\n\
         variable d atom 2.0*c_r*1.01\nfix grow all adapt 10 atom diameter v_d\nrun 100\n"
    ));
    let w = i.sim.world.as_ref().unwrap();
    let r = 0.001 * 1.01f64.powi(11);
    for k in 0..2 {
        assert!(
            (w.particles.radius[k] / r - 1.0).abs() < 1e-12,
            "{}",
            w.particles.radius[k]
        );
        let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        assert!((w.particles.rmass[k] / m - 1.0).abs() < 1e-12);
    }
}

/// insert/rate/region: rate × dt × insert_every particles per insertion until nparticles.
#[test]
fn insert_rate_region_counts() {
    let i = common::run("in.test", &format!(
        "{HEAD}fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.002\n\
         fix pd all particledistribution/discrete 10009 1 pts 1.0\n\
         region inlet block -0.04 0.04 -0.04 0.04 0.08 0.14 units box\n\
         fix ins all insert/rate/region seed 10037 distributiontemplate pd nparticles 130 \
         particlerate 50000 insert_every 100 overlapcheck yes all_in yes region inlet\n\
         fix nve all nve/sphere\nrun 350\n"
    ));
    let s = screen(&i);
    // 50000 /s × 1e-5 s × 100 steps = 50 per insertion at steps 1, 101, 201; the third
    // would exceed nparticles and adds only the remaining 30; none after that.
    let counts: Vec<&str> = s
        .lines()
        .filter(|l| l.starts_with("INFO: Particle insertion ins: inserted"))
        .collect();
    assert_eq!(counts.len(), 3, "{s}");
    for (c, (n, step)) in counts.iter().zip([(50, 1), (50, 101), (30, 201)]) {
        assert!(
            c.contains(&format!("inserted {n} particle templates")),
            "{c}"
        );
        assert!(c.ends_with(&format!("at step {step}")), "{c}");
    }
    assert_eq!(i.sim.natoms(), 130);
}

/// A `mass M` limit stands for M over the expected particle mass, rounded down, as in
/// LIGGGHTS 3.8: `insert/rate/region ... mass M` with M the mass of 10.8 particles
/// (r = 5 mm, 2500 kg/m³) inserted 10 there ("10 particles (mass 1.308997e-02)"), and
/// the tutorial conveyor's `insert/stream ... mass 30.` (382.99 particles' mass) 382.
/// rdem rounded to the nearest, 11 and 383. A mass of exactly 10 particles gives 10.
#[test]
fn a_mass_limit_counts_whole_particles_rounded_down() {
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.005f64.powi(3);
    for (mass, count) in [(10.8 * m, 10), (10.0 * m, 10), (10.3 * m, 10)] {
        let i = common::run("in.test", &format!(
            "{HEAD}fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.005\n\
             fix pd all particledistribution/discrete 10009 1 pts 1.0\n\
             region inlet block -0.04 0.04 -0.04 0.04 0.02 0.14 units box\n\
             fix ins all insert/rate/region seed 10037 distributiontemplate pd mass {mass:.17e} \
             massrate 1 insert_every 100 overlapcheck yes vel constant 0 0 0 region inlet\n\
             fix nve all nve/sphere\nrun 3000\n"
        ));
        assert_eq!(i.sim.natoms(), count, "mass of {} particles", mass / m);
    }
}

/// ave/time: the mean of the samples nfreq − (nrepeat−1)·nevery … nfreq; `ave running`
/// averages the window means.
#[test]
fn ave_time_windows() {
    let i = common::run(
        "in.test",
        &format!(
            "{HEAD}variable s equal step\nfix a all ave/time 2 3 10 v_s\n\
         fix b all ave/time 2 3 10 v_s ave running\nrun 20\n\
         variable fa equal f_a\nvariable fb equal f_b\nprint \"a=${{fa}}\"\nprint \"b=${{fb}}\"\n"
        ),
    );
    // Window at 20: steps 16, 18, 20 -> 18; running: (8 + 18)/2 = 13.
    assert_eq!(printed(&i, "a="), 18.0);
    assert_eq!(printed(&i, "b="), 13.0);
}

/// check/timestep/gran reports dt as fractions of the Rayleigh time of the smallest
/// particle: π r √(ρ/G) / (0.1631 ν + 0.8766).
#[test]
fn check_timestep_rayleigh_fraction() {
    let i = common::run(
        "in.test",
        &format!(
        "{HEAD}create_atoms 1 single 0 0 0.05 units box\nset type 1 diameter 0.004 density 2500\n\
         fix ts all check/timestep/gran 10 0.5 0.5\nrun 10\nvariable fr equal f_ts[1]\n\
         print \"fr=${{fr}}\"\n"
    ),
    );
    let g: f64 = 5e6 / (2.0 * 1.45);
    let t_r = std::f64::consts::PI * 0.002 * (2500.0 / g).sqrt() / (0.1631 * 0.45 + 0.8766);
    let fr = printed(&i, "fr=");
    assert!((fr - 1e-5 / t_r).abs() < 1e-12, "{fr} vs {}", 1e-5 / t_r);
}

/// write_data then read_data in a new run gives back every particle exactly.
#[test]
fn data_file_round_trip() {
    let d = common::scratch_dir("runloop-data");
    let f = d.join("state.data");
    let i = common::run(
        "in.test",
        &format!(
            "{HEAD}lattice sc 0.01\nregion small block -0.02 0.02 -0.02 0.02 0.02 0.05 units box\n\
         create_atoms 1 region small\nset type 1 diameter 0.004 density 2600\n\
         velocity all set 0.1 NULL -0.2\nwrite_data {}\n",
            f.display()
        ),
    );
    let a = &i.sim.world.as_ref().unwrap().particles;
    // sc points with -0.02 <= x, y <= 0.02 and 0.02 <= z <= 0.05 (region bounds inclusive).
    assert_eq!(a.nlocal(), 5 * 5 * 4);
    let j = common::run(
        "in.test",
        &format!(
            "atom_style granular\nboundary f f f\nunits si\nread_data {}\n",
            f.display()
        ),
    );
    let b = &j.sim.world.as_ref().unwrap().particles;
    assert_eq!(b.nlocal(), a.nlocal());
    for k in 0..a.nlocal() {
        let m = b.find_tag(a.tag[k]).unwrap();
        assert_eq!(a.x[k], b.x[m]);
        assert_eq!(a.v[k], b.v[m]);
        assert_eq!(a.radius[k], b.radius[m]);
        assert_eq!(a.density[k], b.density[m]);
    }
    let _ = std::fs::remove_dir_all(d);
}

/// dump custom writes the requested columns for the group, sorted by id.
#[test]
fn dump_custom_text() {
    let d = common::scratch_dir("runloop-dump");
    common::run("in.test", &format!(
        "{HEAD}create_atoms 1 single 0.01 0 0.05 units box\ncreate_atoms 1 single -0.01 0 0.05 units box\n\
         set atom 2 diameter 0.003\ngroup two id 2\n\
         dump d two custom 5 {}/d.*.txt id type z radius\ndump_modify d sort id\nrun 5\n",
        d.display()
    ));
    let t = std::fs::read_to_string(d.join("d.5.txt")).unwrap();
    assert!(
        t.contains("ITEM: ATOMS id type z radius \n2 1 0.05 0.0015 \n"),
        "{t}"
    );
    assert!(d.join("d.0.txt").exists(), "set-up snapshot");
    let _ = std::fs::remove_dir_all(d);
}

/// group, velocity, delete_atoms (with tag compression) and run upto.
#[test]
fn groups_velocity_delete_and_upto() {
    let i = common::run("in.test", &format!(
        "{HEAD}lattice sc 0.01\ncreate_atoms 1 box\nset type 1 diameter 0.002 density 2500\n\
         region low block INF INF INF INF INF 0.05 units box\ngroup low region low\n\
         velocity low set 0 0 1.5\nvariable n equal count(low)\nvariable vz equal vcm(low,z)\n\
         print \"n=${{n}}\"\nprint \"vz=${{vz}}\"\ndelete_atoms group low\nvariable m equal count(all)\n\
         print \"m=${{m}}\"\nfix nve all nve/sphere\nrun 7\nrun 20 upto\nvariable s equal step\nprint \"s=${{s}}\"\n"
    ));
    // sc lattice, spacing 0.01 in [-0.05,0.05)² × [0,0.15): 10 × 10 × 15 points; z <= 0.05
    // (region bounds inclusive) holds the 6 layers z = 0, ..., 0.05.
    assert_eq!(printed(&i, "n="), 600.0);
    assert!((printed(&i, "vz=") - 1.5).abs() < 1e-12);
    assert_eq!(printed(&i, "m="), 900.0);
    assert_eq!(printed(&i, "s="), 20.0);
    let w = i.sim.world.as_ref().unwrap();
    let mut tags: Vec<u64> = w.particles.tag[..w.particles.nlocal()].to_vec();
    tags.sort();
    assert_eq!(tags, (1..=900).collect::<Vec<u64>>(), "compressed tags");
}

/// thermo_modify norm yes divides extensive keywords by the atom count; lost particles
/// are dropped with lost ignore and stop the run with lost error.
#[test]
fn norm_and_lost() {
    let i = common::run("in.test", &format!(
        "{HEAD}create_atoms 1 single 0 0 0.05 units box\ncreate_atoms 1 single 0.02 0 0.05 units box\n\
         set type 1 diameter 0.002 density 1000\nvelocity all set 2 0 0\n\
         thermo_style custom step ke\nthermo_modify norm yes\nvariable k equal ke\nrun 0\nprint \"k=${{k}}\"\n"
    ));
    let m = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-9;
    // Formulas see the normalised value too: LIGGGHTS 3.8 prints k=8.37758040957278e-06
    // for this script.
    let k = printed(&i, "k=");
    assert!((k - 0.5 * m * 4.0).abs() < 1e-18, "ke {k:e}");
    assert!((k - 8.37758040957278e-06).abs() < 1e-19, "ke {k:e}");
    let s = screen(&i);
    let row = s
        .lines()
        .skip_while(|l| !l.contains("KinEng"))
        .nth(1)
        .unwrap();
    let col: f64 = row.split_whitespace().nth(1).unwrap().parse().unwrap();
    // Printed with %14.8g: 8 significant digits.
    assert!(
        (col / (0.5 * m * 4.0) - 1.0).abs() < 1e-7,
        "normalised column {col:e}"
    );
    // A particle flying out through a fixed face.
    let script = format!(
        "{HEAD}create_atoms 1 single 0.049 0 0.05 units box\nset type 1 diameter 0.001 density 1000\n\
         velocity all set 10 0 0\nfix nve all nve/sphere\nthermo_modify lost ignore\nrun 100\n\
         variable n equal atoms\nprint \"n=${{n}}\"\n"
    );
    assert_eq!(printed(&common::run("in.test", &script), "n="), 0.0);
    let mut j = common::interpreter();
    let err = j
        .run_source("in.test", &script.replace("lost ignore", "lost error"))
        .unwrap_err();
    let text = format!("{:?}", miette::Report::new(*err));
    assert!(text.contains("lost") && text.contains("run 100"), "{text}");
}

/// Inserted particles appear inside their step as in LIGGGHTS: not moved in that step,
/// but given the final half kick (LIGGGHTS 3.8: vz = v0 − g·dt/2 after the insertion
/// step), then integrated normally.
#[test]
fn insertion_happens_inside_the_step() {
    let i = common::run("in.test", &format!(
        "{HEAD}fix g all gravity 9.81 vector 0 0 -1\n\
         fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.002\n\
         fix pd all particledistribution/discrete 10009 1 pts 1.0\n\
         region inlet block -0.04 0.04 -0.04 0.04 0.08 0.14 units box\n\
         fix ins all insert/pack seed 10037 distributiontemplate pd particles_in_region 1 \
         insert_every once overlapcheck yes region inlet vel constant 0 0 -0.5\n\
         fix nve all nve/sphere\ncompute z all property/atom z\ncompute zs all reduce sum c_z\n\
         run 1\nvariable z1 equal c_zs\nvariable v1 equal vz[1]\nprint \"z1=${{z1}}\"\nprint \"v1=${{v1}}\"\n\
         run 1\nvariable z2 equal c_zs\nprint \"z2=${{z2}}\"\n"
    ));
    let dt = 1e-5;
    let v1 = printed(&i, "v1=");
    assert!((v1 - (-0.5 - 9.81 * dt / 2.0)).abs() < 1e-15, "{v1}");
    // The next step moves it by dt · (v1 − g dt/2).
    let (z1, z2) = (printed(&i, "z1="), printed(&i, "z2="));
    let dz = dt * (v1 - 9.81 * dt / 2.0);
    assert!((z2 - z1 - dz).abs() < 1e-15, "{} vs {dz}", z2 - z1);
    // It is inside the inlet where it was placed (not moved in the insertion step).
    assert!((0.08..=0.14).contains(&z1));
}

/// `time` is continuous across timestep changes and `reset_timestep` (LIGGGHTS 3.8 prints
/// 1e-07 for this script: 10 steps of the default SI timestep 1e-8, then dt changes);
/// immediate formulas print with 20 significant digits as LIGGGHTS does.
#[test]
fn time_and_immediate_format() {
    let i = common::run(
        "in.test",
        "units si\nregion r block 0 1 0 1 0 1 units box\ncreate_box 1 r\nreset_timestep 10\n\
         timestep 0.001\nvariable t equal time\nprint \"t=${t}\"\nprint \"third=$(1/3)\"\n",
    );
    assert_eq!(printed(&i, "t="), 1e-7);
    assert!(
        screen(&i).contains("third=0.33333333333333331483\n"),
        "{}",
        screen(&i)
    );
}

/// An equal-style variable enters a formula as its `%.15g` text, as in LIGGGHTS 3.8, which
/// prints `0.33333333333333298176 0.999999999999999` for this script.
#[test]
fn equal_variables_enter_formulas_as_text() {
    let i = common::run(
        "in.test",
        "variable a equal 1/3\nvariable b equal v_a*3\nprint \"x=$(v_a) ${b}\"\n",
    );
    assert!(
        screen(&i).contains("x=0.33333333333333298176 0.999999999999999\n"),
        "{}",
        screen(&i)
    );
}

//! `fix couple/cfd`, `couple/cfd/force`, `couple/cfd/force/implicit` without a CFD
//! solver: as LIGGGHTS 3.8 run alone, the run goes on with no fluid force (measured: the
//! same dump with and without the lines, `f_dragforce` and the other properties 0).

use crate::common;

use rdem_script::Interpreter;

/// 27 spheres (3 × 3 × 3 lattice sites) falling onto a floor and onto each other, with rotation (friction).
const SCRIPT: &str = "\
units si
atom_style sphere
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region domain block 0 0.1 0 0.1 0 0.1 units box
create_box 1 domain
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
lattice sc 0.011
region pile block 3 5 3 5 1 3 units lattice
create_atoms 1 region pile
set type 1 diameter 0.01 density 2500
velocity all set 0.05 -0.02 -0.3
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix integr all nve/sphere
fix grav all gravity 9.81 vector 0.1 0 -1
COUPLING
run 3000
";

fn run(src: &str) -> Result<Interpreter, String> {
    common::try_run("in.cfd", src)
}

/// Positions, velocities and angular velocities by tag, as bits.
fn state(i: &Interpreter) -> Vec<(u64, [u64; 9])> {
    let p = &i.sim.world.as_ref().unwrap().particles;
    let mut v: Vec<(u64, [u64; 9])> = (0..p.nlocal())
        .map(|k| {
            let (x, u, w) = (p.x[k], p.v[k], p.omega[k]);
            let a = [x.x, x.y, x.z, u.x, u.y, u.z, w.x, w.y, w.z].map(f64::to_bits);
            (p.tag[k], a)
        })
        .collect();
    v.sort_by_key(|e| e.0);
    v
}

fn out(i: &Interpreter) -> String {
    common::screen(i)
}

/// The same trajectory, bit for bit, with and without the coupling lines; the warning
/// once; the properties the fixes define exist and are 0.
#[test]
fn no_fluid_force_as_liggghts_alone() {
    let plain = run(&SCRIPT.replace("COUPLING\n", "")).unwrap_or_else(|e| panic!("{e}"));
    let base = state(&plain);
    assert_eq!(base.len(), 27);
    // The particles did move and touch: the comparison means something.
    let p = &plain.sim.world.as_ref().unwrap().particles;
    assert!(p.omega[..p.nlocal()].iter().any(|w| w.length() > 1e-3));
    for force in ["couple/cfd/force", "couple/cfd/force/implicit"] {
        let lines = format!(
            "fix cfd all couple/cfd couple_every 10 mpi\n\
             fix cfd2 all {force}\n\
             compute d all reduce sum f_dragforce[1] f_dragforce[2] f_dragforce[3] f_hdtorque[3]\n\
             thermo_style custom step c_d[1] c_d[2] c_d[3] c_d[4]\n\
             thermo 1000\n"
        );
        let i = run(&SCRIPT.replace("COUPLING\n", &lines)).unwrap_or_else(|e| panic!("{e}"));
        assert!(state(&i) == base, "{force}: the trajectory differs");
        let o = out(&i);
        let warnings: Vec<&str> = o
            .lines()
            .filter(|l| l.contains("CFD coupling is not supported"))
            .collect();
        assert_eq!(warnings.len(), 1, "{o}");
        assert!(
            warnings[0].starts_with("WARNING: line 26:"),
            "{}",
            warnings[0]
        );
        assert!(o.contains("no fluid force acts"), "{o}");
        // The thermo rows: the sums of the properties are 0.
        let rows: Vec<&str> = o
            .lines()
            .filter(|l| l.trim_start().starts_with("3000 "))
            .collect();
        assert_eq!(rows.len(), 1, "{o}");
        assert_eq!(
            rows[0].split_whitespace().skip(1).collect::<Vec<_>>(),
            ["0", "0", "0", "0"],
            "{o}"
        );
        let w = i.sim.world.as_ref().unwrap();
        let mut names = vec!["dragforce", "hdtorque"];
        if force.ends_with("implicit") {
            names.extend(["Ksl", "uf"]);
        } else {
            assert!(w.particles.property("Ksl").is_none());
        }
        for n in names {
            let id = w.particles.property(n).unwrap_or_else(|| panic!("{n}"));
            let prop = &w.particles.props[id.0];
            for k in 0..w.particles.nlocal() {
                assert!(prop.get(k).iter().all(|&v| v == 0.0), "{n}");
            }
        }
    }
}

/// What LIGGGHTS 3.8 refuses (`couple/cfd/force` without `couple/cfd`, a coupling style
/// other than file or MPI), and what rdem refuses where LIGGGHTS would wait for a CFD
/// forever (`file`) or takes keywords rdem does not support: located errors.
#[test]
fn errors() {
    for (lines, want) in [
        ("fix cfd2 all couple/cfd/force", "needs a fix of style couple/cfd"),
        ("fix cfd all couple/cfd couple_every 10 one2one", "one2one"),
        ("fix cfd all couple/cfd couple_every 10 file ../a ../b", "couple/cfd file"),
        ("fix cfd all couple/cfd couple_every 0 mpi", "couple_every"),
        ("fix cfd all couple/cfd every 10 mpi", "every"),
        ("fix cfd all couple/cfd couple_every 10 mpi\nfix cfd2 all couple/cfd/force transfer_density yes", "keyword 'transfer_density' is not supported yet"),
        ("fix cfd all couple/cfd couple_every 10 mpi\nfix cfd2 all couple/cfd/force/implicit CrankNicolson 0.5", "keyword 'CrankNicolson' is not supported yet"),
    ] {
        let e = run(&SCRIPT.replace("COUPLING\n", &format!("{lines}\n")))
            .err()
            .unwrap_or_else(|| panic!("'{lines}' must stop"));
        assert!(e.contains(want), "{lines}: {e}");
        assert!(e.contains("in.cfd:2"), "{lines}: not located: {e}");
    }
}

//! `run N ... every M "c1" "c2"`, `start`/`stop`, `pre`/`post` against LIGGGHTS 3.8.
//!
//! The scene: 1000 spheres (d = 4 mm) on a 10 mm lattice, far apart, moving up at
//! vz = 10 m/s · x / 0.1 m (`velocity ramp`), with a region above z = 0.0935 whose
//! particles `delete_atoms` removes between the chunks, so the count after each chunk
//! says when the chunk ended. The figures were printed by
//! `liggghts -in in.e1 -log none -echo none` (LIGGGHTS 3.8.0, scripts as below).

use crate::common;

const HEAD: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
neighbor 0.001 bin
neigh_modify delay 0
",
    common::materials!(),
    "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-4
lattice sc 0.01
region lat block 0 0.1 0 0.1 0 0.1 units box
create_atoms 1 region lat
set group all diameter 0.004 density 2500
region del block INF INF INF INF 0.0935 INF units box
variable n equal count(all)
fix integr all nve/sphere
thermo_style custom step atoms elapsed elaplong
thermo 4
velocity all set 0 0 0
velocity all ramp vz 0 10 x 0 0.1 units box
thermo_modify lost ignore
"
);

fn run(tail: &str) -> Result<String, String> {
    common::try_screen("in.every", &format!("{HEAD}{tail}"))
}

/// The thermo rows (four numbers each) in order.
fn rows(out: &str) -> Vec<[u64; 4]> {
    out.lines()
        .filter_map(|l| {
            let v: Vec<u64> = l
                .split_whitespace()
                .map(|w| w.parse().ok())
                .collect::<Option<_>>()?;
            (v.len() == 4).then(|| [v[0], v[1], v[2], v[3]])
        })
        .collect()
}

/// LIGGGHTS 3.8 (in.e1):
/// `run 10 every 4 "delete_atoms region del" "print 'n = $n at step $(step)'"` runs
/// chunks of 4, 4 and 2 steps, deleting 10, 40 and 10 atoms after them and printing
/// "n = 990 at step 4", "n = 950 at step 8", "n = 940 at step 10"; each chunk sets up
/// and prints its thermo rows (elapsed from the chunk's first step). `run 5 every 5
/// NULL` is one 5-step run (rows at 10, 12, 15).
#[test]
fn every_runs_the_commands_between_chunks() {
    let out = run(
        "run 10 every 4 \"delete_atoms region del\" \"print 'n = $n at step $(step)'\"
print \"after: ${n}\"
run 5 every 5 NULL
",
    )
    .unwrap();
    let deleted: Vec<&str> = out.lines().filter(|l| l.starts_with("Deleted")).collect();
    assert_eq!(
        deleted,
        [
            "Deleted 10 atoms, new total = 990",
            "Deleted 40 atoms, new total = 950",
            "Deleted 10 atoms, new total = 940"
        ],
        "{out}"
    );
    for l in [
        "n = 990 at step 4",
        "n = 950 at step 8",
        "n = 940 at step 10",
        "after: 940",
    ] {
        assert!(out.lines().any(|x| x == l), "no '{l}' in\n{out}");
    }
    assert_eq!(
        rows(&out),
        [
            [0, 1000, 0, 0],
            [4, 1000, 4, 4],
            [4, 990, 0, 0],
            [8, 990, 4, 4],
            [8, 950, 0, 0],
            [10, 950, 2, 2],
            [10, 940, 0, 0],
            [12, 940, 2, 2],
            [15, 940, 5, 5],
        ]
    );
    assert_eq!(out.matches("Setting up run").count(), 4);
    assert_eq!(out.matches("Loop time of").count(), 4);
}

/// LIGGGHTS 3.8 (in.e2): with `start 0` elaplong counts from step 0 in every chunk;
/// `pre no` sets up only the first chunk (no "Setting up run" before the others) and
/// `post no` prints the loop-time line alone except after the last chunk; a later
/// `run 6 pre no post no` does not set up, and `run 6 start 10 stop 30 post no` counts
/// elaplong from 10.
#[test]
fn start_stop_pre_post_as_liggghts() {
    let out = run(
        "run 10 start 0 stop 100 pre no post no every 4 \"delete_atoms region del\"
run 6 pre no post no
run 6 start 10 stop 30 post no
",
    )
    .unwrap();
    assert_eq!(
        rows(&out),
        [
            [0, 1000, 0, 0],
            [4, 1000, 4, 4],
            [4, 990, 0, 4],
            [8, 990, 4, 8],
            [8, 950, 0, 8],
            [10, 950, 2, 10],
            [10, 940, 0, 0],
            [12, 940, 2, 2],
            [16, 940, 6, 6],
            [16, 940, 0, 6],
            [20, 940, 4, 10],
            [22, 940, 6, 12],
        ],
        "{out}"
    );
    assert_eq!(out.matches("Setting up run").count(), 2, "{out}");
    assert_eq!(out.matches("Loop time of").count(), 5, "{out}");
    // The full summary: after the last chunk of the first run only.
    assert_eq!(out.matches("Pair  time").count(), 1, "{out}");
}

/// The run keywords' errors, each at its word.
#[test]
fn bad_run_keywords_are_located_errors() {
    for (line, want) in [
        ("run 10 start 5", "after the start of the run"),
        ("run 10 stop 5", "before the end of the run"),
        ("run 10 every 0 NULL", "every"),
        ("run 10 pre maybe", "pre"),
        ("run 10 sometimes", "run keyword"),
    ] {
        let e = run(&format!("{line}\n")).unwrap_err();
        assert!(e.contains(want), "{line}: {e}");
    }
    // Everything after `every M` is a command (as in LIGGGHTS: its `pre` here is an
    // unknown command).
    let e = run("run 4 every 4 pre no\n").unwrap_err();
    assert!(e.contains("unknown command 'pre'"), "{e}");
}

//! `read_dump` against LIGGGHTS 3.8: tests/data/read_dump/case.in with each case's
//! read_dump line (regenerate.sh lists them; `liggghts -in caseN.in -log none` wrote
//! caseN.liggghts.dump and caseN.liggghts.txt) must write the same dump byte for byte and
//! print the same counts; a `dump custom` written by rdem and read back gives the
//! positions and velocities exactly; bad words stop with located errors.

use rdem_script::Interpreter;

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/read_dump");

/// Runs `src` (with `include head.in` inlined); the interpreter and its screen output,
/// or the error's text.
fn run(src: &str) -> Result<(Interpreter, String), String> {
    let head = std::fs::read_to_string(format!("{DIR}/head.in")).unwrap();
    common::try_run_screen("case.in", &src.replace("include head.in\n", &head))
}

/// Runs case.in with `line` as its read_dump command and checks the dump and the count
/// lines equal LIGGGHTS' (`case`.liggghts.*).
fn check_case(case: &str, line: &str) {
    let out_path =
        std::env::temp_dir().join(format!("rdem-read-dump-{case}-{}", std::process::id()));
    let line = line.replace("h.dump", &format!("{DIR}/h.dump"));
    let src = std::fs::read_to_string(format!("{DIR}/case.in"))
        .unwrap()
        .replace("READ\n", &format!("{line}\n"))
        .replace("OUT", &out_path.display().to_string());
    let (_, out) = run(&src).unwrap_or_else(|e| panic!("{e}"));
    let ours = std::fs::read_to_string(&out_path).unwrap();
    let theirs = std::fs::read_to_string(format!("{DIR}/{case}.liggghts.dump")).unwrap();
    assert_eq!(ours, theirs, "{case}: dump differs from LIGGGHTS'");
    let counts = |text: &str| -> Vec<String> {
        text.lines()
            .filter(|l| {
                l.starts_with("  ") && l.contains(" atoms ") || l.contains("orthogonal box = ")
            })
            .filter(|l| !l.starts_with("Created"))
            .map(|l| l.trim().to_string())
            .collect()
    };
    let log = std::fs::read_to_string(format!("{DIR}/{case}.liggghts.txt")).unwrap();
    let theirs = counts(&log[log.find("Scanning dump file").unwrap()..]);
    let ours = counts(&out[out.find("Scanning dump file").unwrap()..]);
    assert_eq!(ours[..8], theirs[..8], "{case}: count lines");
    let _ = std::fs::remove_file(out_path);
}

/// `box no add yes` (replace yes): atom 2 replaced (position, radius, velocity; its type 1,
/// mass 0.004188790205 and density 1000 stay), dump atoms 5 and 20 added as IDs 4 and 5
/// (type from the dump, density 1, mass 0.5235987756 of a radius-0.5 sphere), dump atom
/// 21 at x = 1.5 dropped (outside the fixed box); the step becomes 7.
#[test]
fn add_and_replace() {
    check_case(
        "case1",
        "read_dump h.dump 7 x y z radius vx vy vz box no add yes",
    );
}

/// `purge yes replace no add yes` with the dump's box (0..2 in x): the four dump atoms
/// get IDs 1-4 in file order; the one at x = 1.5 stays.
#[test]
fn purge_and_add_with_the_dump_box() {
    check_case(
        "case2",
        "read_dump h.dump 7 x y z radius vx vy vz purge yes replace no add yes",
    );
}

/// `trim yes` with fields `x y radius vx`: atom 2 keeps its z and vy vz, atoms 1 and 3
/// are deleted.
#[test]
fn trim_and_partial_fields() {
    check_case("case3", "read_dump h.dump 7 x y radius vx trim yes");
}

/// `replace no add yes` with fields `x y z vx radius`: atoms 1-3 untouched, added atoms
/// have vy = vz = 0.
#[test]
fn add_without_replace() {
    check_case(
        "case4",
        "read_dump h.dump 7 x y z vx radius box no replace no add yes",
    );
}

/// `purge yes ... box no`: the dump atom at x = 1.5 is dropped, three remain.
#[test]
fn purge_with_the_current_box() {
    check_case(
        "case5",
        "read_dump h.dump 7 x y z radius vx vy vz purge yes replace no add yes box no",
    );
}

/// A `dump custom` written by rdem with `%.17g` and read back into other particles
/// gives the positions, velocities and radii bit for bit, and the dump's step.
#[test]
fn round_trip_of_dump_custom() {
    let path = std::env::temp_dir().join(format!("rdem-read-dump-rt-{}", std::process::id()));
    let p = path.display();
    let setup = std::fs::read_to_string(format!("{DIR}/case.in")).unwrap();
    let setup = &setup[..setup.find("READ").unwrap()];
    let write = format!(
        "{setup}velocity all set 0.1 -0.2 0.3\nset atom 2 vx 0.7\nfix g all gravity 9.81 vector 0 0 -1\nfix i all nve/sphere\n\
         dump d all custom 50 {p} id type x y z vx vy vz radius\n\
         dump_modify d sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\nrun 150\n"
    );
    let (w, _) = run(&write).unwrap_or_else(|e| panic!("{e}"));
    let a = &w.sim.world.as_ref().unwrap().particles;
    let read = format!(
        "{}set group all diameter 0.5\nread_dump {p} 150 x y z vx vy vz radius\n",
        setup.replace("0.9 0.9 0.9", "0.6 0.6 0.6")
    );
    let (r, _) = run(&read).unwrap_or_else(|e| panic!("{e}"));
    let world = r.sim.world.as_ref().unwrap();
    assert_eq!(world.step, 150);
    let b = &world.particles;
    assert_eq!(a.nlocal(), 3);
    assert_eq!(b.nlocal(), 3);
    for t in 1..=3u64 {
        let i = (0..3).find(|&i| a.tag[i] == t).unwrap();
        let j = (0..3).find(|&j| b.tag[j] == t).unwrap();
        assert_eq!(a.x[i], b.x[j], "tag {t}");
        assert_eq!(a.v[i], b.v[j], "tag {t}");
        assert_eq!(a.radius[i], b.radius[j], "tag {t}");
        assert_ne!(a.v[i].z, 0.3, "the particles moved under gravity");
    }
    let _ = std::fs::remove_file(path);
}

/// Words LIGGGHTS 3.8 refuses stop with an error at the word.
#[test]
fn bad_words_are_located_errors() {
    let setup = std::fs::read_to_string(format!("{DIR}/case.in")).unwrap();
    let setup = &setup[..setup.find("READ").unwrap()];
    let h = format!("{DIR}/h.dump");
    for (line, expect) in [
        (format!("read_dump {h} 7 x y z"), "radius field is required"),
        (format!("read_dump {h} 7 x radius q"), "no charge"),
        (format!("read_dump {h} 7 x radius density"), "density"),
        (
            format!("read_dump {h} 7 x radius purge yes add yes"),
            "cannot replace or trim",
        ),
        (format!("read_dump {h} 7 x radius add keep"), "keep"),
        (format!("read_dump {h} 8 x radius"), "no snapshot of step 8"),
        (
            format!("read_dump {h} 7 x radius format xyz"),
            "not supported yet",
        ),
        (
            format!("read_dump {h} 7 x radius label x c_ave"),
            "no column 'c_ave'",
        ),
    ] {
        let e = run(&format!("{setup}{line}\n"))
            .err()
            .unwrap_or_else(|| panic!("{line} ran"));
        assert!(e.contains(expect), "{line}: {e}");
    }
}

//! How scripts are read, checked against LIGGGHTS 3.8 (`liggghts -in in.x -log none`):
//! script files are bytes (comments and quoted text in any encoding), CRLF line ends,
//! numbers written as LIGGGHTS reads them, and the default units of `region` and
//! `create_atoms`. Each test's doc comment records what LIGGGHTS 3.8 did with the same
//! script.

use crate::common;
use common::render;

/// The first lines of every script here: a granular SI set-up.
const PRE: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
";

/// Materials, contact model and time step after `create_box`.
const POST: &str = concat!(
    "\
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

/// A box -0.05..0.05 × -0.05..0.05 × 0..0.15 with materials and no particles.
fn head() -> String {
    format!(
        "{PRE}region reg block -0.05 0.05 -0.05 0.05 0. 0.15 units box\ncreate_box 1 reg\n{POST}"
    )
}

/// Runs `script`; the screen text, or the rendered error report.
fn try_run(script: &str) -> Result<String, String> {
    common::try_screen("in.test", script)
}

/// Runs `script`, which must succeed; the screen text.
fn run(script: &str) -> String {
    try_run(script).unwrap_or_else(|e| panic!("{e}"))
}

/// Lines of `screen` starting with `prefix`.
fn lines_with<'s>(screen: &'s str, prefix: &str) -> Vec<&'s str> {
    screen.lines().filter(|l| l.starts_with(prefix)).collect()
}

/// `region` without `units` and no `lattice`: LIGGGHTS 3.8 runs it and prints
/// `Created orthogonal box = (0 0 0) to (1 1 1)`; its manual gives `units = box` as the
/// default. After `lattice sc 2.0` the same command still gives `(0 0 0) to (1 1 1)`;
/// with `units lattice` it gives `(0 0 0) to (2 2 2)`. `units lattice` with no lattice
/// command gives `(0 0 0) to (1 1 1)` (the default lattice `none 1.0`), and after
/// `lattice none 2.0` it gives `(0 0 0) to (2 2 2)`.
#[test]
fn region_units_default_to_box_and_lattice_defaults_to_none_1() {
    let created = |setup: &str| {
        let s = run(&format!("{PRE}{setup}\ncreate_box 1 reg\n"));
        lines_with(&s, "Created orthogonal box")[0].to_string()
    };
    let unit = "Created orthogonal box = (0 0 0) to (1 1 1)";
    let two = "Created orthogonal box = (0 0 0) to (2 2 2)";
    assert_eq!(created("region reg block 0 1 0 1 0 1"), unit);
    assert_eq!(created("region reg block 0 1 0 1 0 1 units box"), unit);
    assert_eq!(created("region reg block 0 1 0 1 0 1 units lattice"), unit);
    assert_eq!(
        created("lattice sc 2.0\nregion reg block 0 1 0 1 0 1"),
        unit
    );
    assert_eq!(
        created("lattice sc 2.0\nregion reg block 0 1 0 1 0 1 units lattice"),
        two
    );
    assert_eq!(
        created("lattice none 2.0\nregion reg block 0 1 0 1 0 1 units lattice"),
        two
    );
}

/// The same packing in a region written without `units` and with `units box` (LIGGGHTS
/// 3.8: `units box` is the default, see above): the same particles and the same thermo.
#[test]
fn region_without_units_builds_what_units_box_builds() {
    let script = |units: &str| {
        format!(
            "{PRE}region reg block -0.05 0.05 -0.05 0.05 0. 0.15{units}\ncreate_box 1 reg\n{POST}\
             fix g all gravity 9.81 vector 0 0 -1\n\
             fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.002\n\
             fix pd all particledistribution/discrete 10009 1 pts 1.0\n\
             region inlet block -0.04 0.04 -0.04 0.04 0.08 0.14{units}\n\
             fix ins all insert/pack seed 10037 distributiontemplate pd maxattempt 100 insert_every 1000 \
             overlapcheck yes all_in yes vel constant 0.0 0.0 -0.5 region inlet particles_in_region 20 ntry_mc 10000\n\
             fix nve all nve/sphere\ncompute z all property/atom z\ncompute zs all reduce sum c_z\n\
             thermo_style custom step atoms c_zs\nrun 10\n"
        )
    };
    let a = run(&script(""));
    let b = run(&script(" units box"));
    let rows = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| l.trim_start().starts_with("10 ") || l.trim_start().starts_with("0 "))
            .map(String::from)
            .collect()
    };
    assert_eq!(rows(&a).len(), 2, "{a}");
    assert!(rows(&a)[1].contains(" 20 "), "{a}");
    assert_eq!(rows(&a), rows(&b));
}

/// `create_atoms single` without `units`: LIGGGHTS 3.8 places the atom in box units
/// (its manual: "the default for ... units = box"). After `lattice sc 2.0` and
/// `create_atoms 1 single 0.3 0.3 0.3` a sphere of radius 1 at the origin held that atom
/// (`1 atoms in group g`), so it was not moved to 0.6. `create_atoms 1 box` with no
/// lattice stops with `ERROR: Cannot create atoms with undefined lattice`.
#[test]
fn create_atoms_single_defaults_to_box_units() {
    let s = run(&format!(
        "{PRE}lattice sc 2.0\nregion reg block 0 4 0 4 0 4\ncreate_box 1 reg\n\
         create_atoms 1 single 0.3 0.3 0.3\ncreate_atoms 1 single 1.3 0.3 0.3 units box\n\
         region s sphere 0 0 0 1.0\ngroup g region s\n\
         region s3 sphere 0 0 0 1.0 units lattice\ngroup g3 region s3\n"
    ));
    assert!(s.contains("\n1 atoms in group g\n"), "{s}");
    assert!(s.contains("\n2 atoms in group g3\n"), "{s}");
    let e = try_run(&format!(
        "{PRE}region reg block 0 1 0 1 0 1\ncreate_box 1 reg\ncreate_atoms 1 box\n"
    ))
    .unwrap_err();
    assert!(e.contains("create_atoms box/region needs a lattice"), "{e}");
    let e = try_run(&format!(
        "{PRE}lattice none 1.0\nregion reg block 0 1 0 1 0 1\ncreate_box 1 reg\ncreate_atoms 1 box\n"
    ))
    .unwrap_err();
    assert!(e.contains("create_atoms box/region needs a lattice"), "{e}");
}

/// Runs script bytes; the screen text, or the rendered error report.
fn try_run_bytes(script: &[u8]) -> Result<String, String> {
    let mut i = common::interpreter();
    let r = i.run_bytes("in.test", script);
    let screen = common::screen(&i);
    r.map(|()| screen).map_err(|e| render(&e))
}

/// `head()` + `tail` as bytes.
fn script_bytes(tail: &[u8]) -> Vec<u8> {
    let mut b = head().into_bytes();
    b.extend_from_slice(tail);
    b
}

/// A packing run printing thermo rows, to compare two spellings of the same script.
const PACK: &str = "\
fix g all gravity 9.81 vector 0 0 -1
fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.002
fix pd all particledistribution/discrete 10009 1 pts 1.0
region inlet block -0.04 0.04 -0.04 0.04 0.08 0.14 units box
fix ins all insert/pack seed 10037 distributiontemplate pd maxattempt 100 insert_every 1000 &
    overlapcheck yes all_in yes vel constant 0.0 0.0 -0.5 region inlet particles_in_region 20 ntry_mc 10000
fix nve all nve/sphere
compute z all property/atom z
compute zs all reduce sum c_z
thermo_style custom step atoms c_zs
thermo 5
run 10
";

/// The screen text without the wall-clock timings of the run summary and the memory line
/// (the process's peak resident memory so far, which grows with the runs before it in
/// this test process).
fn stable(s: &str) -> String {
    s.lines()
        .filter(|l| {
            !l.starts_with("Loop time")
                && !l.contains(" time (%)")
                && !l.starts_with("Memory usage per processor")
        })
        .map(|l| format!("{l}\n"))
        .collect()
}

/// LIGGGHTS 3.8 runs a script with a Latin-1 `µ` (byte 0xB5) in a comment and in a
/// quoted `print` string: it prints `size 5 \xB5m here` (the byte as it is) and goes on.
/// rdem reads the byte as the Latin-1 `µ`: the script runs as its ASCII twin does, with
/// the same thermo, and prints the text with `µ`.
#[test]
fn latin1_comments_and_quoted_text_are_read() {
    let ascii = script_bytes(
        format!("# comment with um in ASCII\n{PACK}print \"size 5 um here\"\n").as_bytes(),
    );
    let mut latin1 = script_bytes(b"# comment with \xb5m in Latin-1\n");
    latin1.extend_from_slice(PACK.as_bytes());
    latin1.extend_from_slice(b"print \"size 5 \xb5m here\" # \xe9t\xe9\n");
    let a = try_run_bytes(&ascii).unwrap();
    let b = try_run_bytes(&latin1).unwrap_or_else(|e| panic!("{e}"));
    let rows = |s: &str| lines_with(s, "      10").join("\n");
    assert!(rows(&a).contains(" 20 "), "{a}");
    assert_eq!(rows(&a), rows(&b));
    assert!(b.contains("\nsize 5 µm here\n"), "{b}");
    assert_eq!(
        stable(&a.replace("size 5 um here", "size 5 µm here")),
        stable(&b)
    );
    // A file on disk (run_file) reads the same way.
    let d = common::scratch_dir("reading-latin1");
    let path = d.join("in.latin1");
    std::fs::write(&path, &latin1).unwrap();
    let mut i = common::interpreter();
    i.run_file(path.to_str().unwrap()).unwrap();
    assert_eq!(
        stable(&i.sim.outputs.out.captured.clone().unwrap()),
        stable(&b)
    );
}

/// A 0xB5 byte inside a command word: LIGGGHTS 3.8 stops with
/// `ERROR: Unknown command: pri\xB5nt "x"`; as an unquoted argument (`print x\xB5y`) it
/// prints the bytes back. rdem stops at the byte in both cases, with the line, the column
/// (the byte counts as one character) and a caret under it, before running anything.
#[test]
fn a_non_utf8_byte_in_a_command_word_is_an_error_at_it() {
    let n = head().lines().count();
    for (tail, line, col) in [
        (&b"pri\xb5nt \"x\"\n"[..], n + 1, 4),
        (b"print \"\xb5\" # \xb5\nprint x\xb5y\n", n + 2, 8),
        (b"fix g all &\n  gra\xb5vity 9.81 vector 0 0 -1\n", n + 2, 6),
    ] {
        let e = try_run_bytes(&script_bytes(tail)).unwrap_err();
        assert!(e.contains("non-UTF-8 byte 0xB5 in a command word"), "{e}");
        assert!(
            e.contains("only comments and quoted text may use other encodings"),
            "{e}"
        );
        assert!(e.contains(&format!("in.test:{line}:{col}")), "{e}");
        // The caret is under the µ.
        let code = e
            .lines()
            .find(|l| l.contains('µ') && l.contains('│'))
            .unwrap();
        let caret = e.lines().find(|l| l.contains('┬')).unwrap();
        assert_eq!(
            caret.find('┬').map(|k| caret[..k].chars().count()),
            code.find('µ').map(|k| code[..k].chars().count()),
            "{e}"
        );
    }
    // Nothing ran: the error comes before the first command.
    let mut i = common::interpreter();
    let r = i.run_bytes("in.test", b"print \"first\"\npri\xb5nt x\n");
    assert!(r.is_err());
    assert_eq!(i.sim.outputs.out.captured.clone().unwrap(), "");
}

/// `include` and `jump` to another file read bytes too: Latin-1 comments run, a byte in
/// a command word is reported in that file.
#[test]
fn included_and_jumped_to_files_are_read_as_bytes() {
    let d = common::scratch_dir("reading-include");
    let good = d.join("good.inc");
    let bad = d.join("bad.inc");
    std::fs::write(&good, b"# \xb5 \xe9\r\nprint \"in good \xb5\"\r\n").unwrap();
    std::fs::write(&bad, b"print ok\n\nvariable a equal 1\xb5\n").unwrap();
    let s = try_run_bytes(format!("include {}\nprint after\n", good.display()).as_bytes()).unwrap();
    assert_eq!(s, "in good µ\nafter\n");
    let s = try_run_bytes(format!("jump {}\nprint never\n", good.display()).as_bytes()).unwrap();
    assert_eq!(s, "in good µ\n");
    for cmd in ["include", "jump"] {
        let e = try_run_bytes(format!("{cmd} {}\n", bad.display()).as_bytes()).unwrap_err();
        assert!(e.contains("non-UTF-8 byte 0xB5 in a command word"), "{e}");
        assert!(e.contains(&format!("{}:3:19", bad.display())), "{e}");
    }
}

/// LIGGGHTS 3.8 runs a script with CRLF line ends as its LF twin, also through a `&`
/// continuation inside a quoted string (`print "a is &` CRLF `${a} ok"` printed
/// `a is 2 ok`) and a continued `fix ... &` CRLF line. rdem gives the same screen text
/// for both, and an error in a CRLF file has the line, column and caret of the LF file.
#[test]
fn crlf_scripts_run_as_their_lf_twins() {
    let tail = format!(
        "variable a equal 2\nprint \"a is &\n${{a}} ok\"\nprint 'quoted  with spaces' # c\n{PACK}print done"
    );
    let lf = script_bytes(format!("{tail}\n").as_bytes());
    let crlf = script_bytes(format!("{}\r\n", tail.replace('\n', "\r\n")).as_bytes());
    let crlf_cr = script_bytes(format!("{}\r", tail.replace('\n', "\r\n")).as_bytes());
    assert!(crlf.windows(4).any(|w| w == b"&\r\n$"));
    let a = try_run_bytes(&lf).unwrap();
    assert!(a.contains("\na is 2 ok\nquoted  with spaces\n"), "{a}");
    assert!(a.ends_with("\ndone\n"), "{a}");
    assert_eq!(stable(&try_run_bytes(&crlf).unwrap()), stable(&a));
    assert_eq!(stable(&try_run_bytes(&crlf_cr).unwrap()), stable(&a));
    let bad = "variable a equal 2\nfix g all &\n  gravty 9.81 vector 0 0 -1\n";
    let e_lf = try_run_bytes(&script_bytes(bad.as_bytes())).unwrap_err();
    let e_crlf = try_run_bytes(&script_bytes(bad.replace('\n', "\r\n").as_bytes())).unwrap_err();
    let n = head().lines().count();
    assert!(e_lf.contains(&format!("in.test:{}:3", n + 3)), "{e_lf}");
    assert_eq!(e_crlf, e_lf);
}

/// The `WARNING:` lines of a screen text.
fn warnings(s: &str) -> Vec<&str> {
    lines_with(s, "WARNING:")
}

/// Integers written `1.` where LIGGGHTS 3.8 reads them with `atoi`: the seeds of fix
/// particletemplate/sphere, particledistribution/discrete and insert/pack written
/// `10007.`, `10009.`, `10037.`, `particles_in_region 20.` and `run 10.` ran with the same
/// thermo as the plain integers (step 10: 20 atoms, z sum 2.2717043); so did `10037.0`.
/// rdem runs them the same as the plain script, with one warning naming each word's line.
#[test]
fn integers_written_with_a_point_where_liggghts_reads_them() {
    let plain = script_bytes(PACK.as_bytes());
    let dotted = PACK
        .replace("sphere 10007 ", "sphere 10007. ")
        .replace("discrete 10009 ", "discrete 10009. ")
        .replace("seed 10037 ", "seed 10037.0 ")
        .replace("particles_in_region 20 ", "particles_in_region 20. ")
        .replace("run 10\n", "run 10.\n");
    let a = try_run_bytes(&plain).unwrap();
    let b = try_run_bytes(&script_bytes(dotted.as_bytes())).unwrap_or_else(|e| panic!("{e}"));
    assert!(warnings(&a).is_empty(), "{a}");
    let n = head().lines().count();
    assert_eq!(
        warnings(&b),
        vec![
            format!(
                "WARNING: line {}: '10007.' read as the integer 10007 (LIGGGHTS reads it so)",
                n + 2
            ),
            format!(
                "WARNING: line {}: '10009.' read as the integer 10009 (LIGGGHTS reads it so)",
                n + 3
            ),
            format!(
                "WARNING: line {}: '10037.0' read as the integer 10037 (LIGGGHTS reads it so)",
                n + 5
            ),
            format!(
                "WARNING: line {}: '20.' read as the integer 20 (LIGGGHTS reads it so)",
                n + 6
            ),
            format!(
                "WARNING: line {}: '10.' read as the integer 10 (LIGGGHTS reads it so)",
                n + 12
            ),
        ]
    );
    let no_warnings = |s: &str| -> String {
        stable(s)
            .lines()
            .filter(|l| !l.starts_with("WARNING:"))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    assert_eq!(no_warnings(&b), stable(&a));
    // The warning about `run 10.` comes before the run's output.
    let w = b.find("'10.' read as").unwrap();
    assert!(w < b.find("Setting up run").unwrap(), "{b}");
}

/// Integers LIGGGHTS 3.8 reads differently from what they show, or refuses:
/// `seed 10037.5` and `run 10.5` ran there as 10037 and 10 (`atoi`), `run 1e1` ran 1
/// step, `particles_in_region 20.7` inserted 20; rdem stops and says what LIGGGHTS would
/// read. `thermo 5.`, `create_box 1. reg`, `neigh_modify delay 0.`, `dump ... 5. ...`,
/// `fix ave/time 1. ...` and `fix adapt 10. ...` stopped LIGGGHTS with "Expected integer
/// parameter in input script or data file"; rdem stops too.
#[test]
fn integers_liggghts_cuts_or_refuses_are_errors() {
    let n = head().lines().count();
    for (from, to, word, line, help) in [
        (
            "seed 10037 ",
            "seed 10037.5 ",
            "10037.5",
            n + 5,
            Some("10037"),
        ),
        ("run 10\n", "run 10.5\n", "10.5", n + 12, Some("10")),
        ("run 10\n", "run 1e1\n", "1e1", n + 12, Some("1")),
        ("thermo 5\n", "thermo 5.\n", "5.", n + 11, None),
    ] {
        let s = script_bytes(PACK.replace(from, to).as_bytes());
        let e = try_run_bytes(&s).unwrap_err();
        assert!(
            e.contains(&format!("must be a non-negative integer, not '{word}'")),
            "{e}"
        );
        assert!(e.contains(&format!("in.test:{line}:")), "{e}");
        match help {
            Some(v) => assert!(
                e.contains(&format!("LIGGGHTS would read '{word}' as {v}")),
                "{e}"
            ),
            None => assert!(!e.contains("LIGGGHTS would read"), "{e}"),
        }
    }
    let e = try_run(&format!(
        "{PRE}region reg block 0 1 0 1 0 1\ncreate_box 1. reg\n"
    ))
    .unwrap_err();
    assert!(e.contains("not '1.'"), "{e}");
}

/// Floats with a stray `.`: LIGGGHTS 3.8 ran `timestep 0.00001.`, `timestep 1e-5.`,
/// `poissonsRatio peratomtype 0.45.` and a region bound `0.15.` with the same thermo as
/// without the dot (it checks the characters are digits, signs, `.`, `e` and reads the
/// number with `atof`, which stops at the second dot); `0.4.5` ran as 0.4; `1e-5x` and
/// `0.45x` stopped it with "Expected floating point parameter". rdem reads a single
/// trailing dot with a warning, and refuses `0.4.5` (it does not mean 0.4) and `1e-5x`.
#[test]
fn floats_with_a_stray_trailing_point() {
    let plain = script_bytes(PACK.as_bytes());
    let dotted = head()
        .replace("timestep 0.00001\n", "timestep 1e-5.\n")
        .replace("peratomtype 0.45\n", "peratomtype 0.45.\n")
        .replace("0. 0.15 units box\n", "0. 0.15. units box\n")
        + &PACK.replace("region inlet block -0.04 ", "region inlet block -0.04. ");
    let a = try_run_bytes(&plain).unwrap();
    let b = try_run_bytes(dotted.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    let n = head().lines().count();
    assert_eq!(
        warnings(&b),
        vec![
            "WARNING: line 7: '0.15.' read as 0.15 (LIGGGHTS reads it so)".to_string(),
            "WARNING: line 12: '0.45.' read as 0.45 (LIGGGHTS reads it so)".to_string(),
            "WARNING: line 17: '1e-5.' read as 0.00001 (LIGGGHTS reads it so)".to_string(),
            format!(
                "WARNING: line {}: '-0.04.' read as -0.04 (LIGGGHTS reads it so)",
                n + 4
            ),
        ]
    );
    let rows = |s: &str| lines_with(s, "      10").join("\n");
    assert!(rows(&a).contains(" 20 "), "{a}");
    assert_eq!(rows(&a), rows(&b));
    for bad in ["0.4.5", "1e-5x", "0.5.."] {
        let s = head().replace("timestep 0.00001\n", &format!("timestep {bad}\n"));
        let e = try_run(&s).unwrap_err();
        assert!(e.contains(&format!("must be a number, not '{bad}'")), "{e}");
        assert!(e.contains("in.test:17:10"), "{e}");
    }
}

/// `group ID id|type` values where LIGGGHTS 3.8 reads them with `atoi`: with atoms 1 and 2,
/// `group g id 1.` printed "1 atoms in group g" and `group h id 1.5 2` "2 atoms in group
/// h" (1.5 read as 1); `group k id <> 1. 2.` stopped with "Expected integer parameter".
/// rdem takes `1.` (and `1.:2.`) with a warning; `1.5` stays an error.
#[test]
fn group_ids_written_with_a_point() {
    let atoms = "create_atoms 1 single 0 0 0.05 units box\n\
                 create_atoms 1 single 0 0 0.1 units box\n";
    let s = run(&format!(
        "{}{atoms}group g id 1.\ngroup r id 1.:2.\ngroup t type 1.\n",
        head()
    ));
    assert!(s.contains("\n1 atoms in group g\n"), "{s}");
    assert!(s.contains("\n2 atoms in group r\n"), "{s}");
    assert!(s.contains("\n2 atoms in group t\n"), "{s}");
    let n = head().lines().count() + 2;
    let w = warnings(&s);
    assert_eq!(w.len(), 4, "{s}");
    assert_eq!(
        w[0],
        format!(
            "WARNING: line {}: '1.' read as the integer 1 (LIGGGHTS reads it so)",
            n + 1
        )
    );
    let e = try_run(&format!("{}{atoms}group h id 1.5 2\n", head())).unwrap_err();
    assert!(e.contains("'1.5' is not a number or range a:b"), "{e}");
}

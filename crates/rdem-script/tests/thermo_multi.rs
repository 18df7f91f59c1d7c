//! `thermo_modify line multi|one` against LIGGGHTS 3.8, byte for byte:
//! tests/data/thermo_multi/in.multi and the screen LIGGGHTS 3.8 printed for it
//! (`screen.liggghts`, from `liggghts -in in.multi -log none -echo none`). The thermo
//! lines of each run (after `Memory usage`, before `Loop time`) are compared with the CPU
//! seconds masked (the only values that depend on the machine).

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/thermo_multi");

/// The thermo lines of every run, with the numbers after `CPU =` replaced by `#`.
fn thermo_lines(screen: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for l in screen.lines() {
        if l.starts_with("Memory usage") {
            inside = true;
            continue;
        }
        if l.starts_with("Loop time") {
            inside = false;
            out.push("--- end of run".to_string());
            continue;
        }
        if inside && !l.starts_with("WARNING") {
            out.push(mask_cpu(l));
        }
    }
    out
}

/// `CPU = 0.0000` (banner) and `CPU      =         0.0000` (an item) with `#` for the
/// number, keeping the width.
fn mask_cpu(l: &str) -> String {
    let mut s = l.to_string();
    let mut from = 0;
    while let Some(k) = s[from..].find("CPU ") {
        let at = from + k;
        let Some(eq) = s[at..].find('=').map(|e| at + e) else {
            break;
        };
        let rest = &s[eq + 1..];
        let digits_start = eq + 1 + (rest.len() - rest.trim_start().len());
        let end = s[digits_start..]
            .find(' ')
            .map_or(s.len(), |e| digits_start + e);
        s.replace_range(digits_start..end, &"#".repeat(end - digits_start));
        from = end;
    }
    s
}

#[test]
fn multi_layout_as_liggghts() {
    let src = std::fs::read_to_string(format!("{DIR}/in.multi")).unwrap();
    let mut i = common::interpreter();
    if let Err(e) = i.run_source("in.multi", &src) {
        panic!("{:?}", miette::Report::new(*e));
    }
    let ours = thermo_lines(&common::screen(&i));
    let theirs = thermo_lines(&std::fs::read_to_string(format!("{DIR}/screen.liggghts")).unwrap());
    // 5 runs (each closed by its "end of run" line): 3 outputs of a banner and 2 lines,
    // 2 of a banner and 1, 2 of a banner and 6, a header and 2 rows, 2 of a banner and 6.
    assert_eq!(theirs.len(), 10 + 5 + 15 + 4 + 15, "{theirs:#?}");
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert_eq!(
            a, b,
            "line {k} differs:\n rdem:     '{a}'\n LIGGGHTS: '{b}'"
        );
    }
    assert_eq!(ours.len(), theirs.len(), "{ours:#?}");
    // The banner's step and the columns are not masked away.
    assert!(theirs.iter().any(
        |l| l == "Step     =             30 Atoms    =     2 KinEng   =          9.174541376 "
    ));
}

/// `thermo_style multi`: step, atoms, ke and cpu in the multi-line layout (LIGGGHTS
/// 3.8's `screen_style.liggghts` for `in.style_multi`), also with `norm yes`.
#[test]
fn style_multi_as_liggghts() {
    let src = std::fs::read_to_string(format!("{DIR}/in.style_multi")).unwrap();
    let mut i = common::interpreter();
    if let Err(e) = i.run_source("in.style_multi", &src) {
        panic!("{:?}", miette::Report::new(*e));
    }
    let ours = thermo_lines(&common::screen(&i));
    let theirs =
        thermo_lines(&std::fs::read_to_string(format!("{DIR}/screen_style.liggghts")).unwrap());
    // 2 runs: 3 outputs of a banner and 2 lines, then 2.
    assert_eq!(theirs.len(), 9 + 1 + 6 + 1, "{theirs:#?}");
    assert_eq!(ours, theirs);
    assert!(theirs
        .iter()
        .any(|l| l
            == "Step     =             15 Atoms    =              2 KinEng   =         9.1688 "));
}

/// `line yaml` (a later LAMMPS layout) and other words: LIGGGHTS 3.8 stops ("Illegal
/// thermo_modify command"); rdem with a located error listing `one`, `multi`.
#[test]
fn other_line_styles_are_errors() {
    for w in ["yaml", "foo"] {
        let mut i = common::interpreter();
        let e = i
            .run_source("in.t", &format!("thermo_modify line {w}\n"))
            .expect_err("must stop");
        let mut out = String::new();
        miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
            .with_width(10_000)
            .render_report(&mut out, &*e)
            .unwrap();
        assert!(
            out.contains(&format!("'{w}'")) && out.contains("multi"),
            "{out}"
        );
        assert!(out.contains("in.t:1"), "{out}");
    }
}

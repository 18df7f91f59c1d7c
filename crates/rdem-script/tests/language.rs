//! The script language through the interpreter: `$x`, `${name}` and `$(expr)`
//! substitution, `&` continuation, quotes, comments, the variable styles (equal, atom,
//! index, loop, string, getenv), label/jump/next loops, `if`/`elif`/`else`, `include`,
//! `print` and `log` files, and formulas with thermo keywords, group functions, atom
//! values and computes on a two-particle system whose numbers are worked out by hand.
//!
//! Values printed through `${name}` come as C's `%.15g`, so floats are compared with a
//! relative tolerance of 1e-12.
//!
//! Checked on LIGGGHTS 3.8 with the same scripts: the printed lines of
//! `substitution_reads_plain_text_now_and_quoted_text_when_it_runs`, `immediate_formulas`
//! and `continuation_quotes_and_comments` (all but the triple-quoted J5, which LIGGGHTS
//! 3.8 does not have) are identical; the two-particle numbers (counts, masses, xcm, vcm,
//! bound, ke, `x[1]`, `vx[2]`, `mass[1]`, `c_r[1]`, `c_r[2]`, `c_p`, step, atoms, vol)
//! agree to every digit `%.15g` shows (LIGGGHTS prints `$(...)` as `%.20g`, e.g.
//! xcm(all,x) = 0.55555555555555558023; it needs a `run 0` before it evaluates a
//! compute in a formula, rdem evaluates computes on demand).

use rdem_script::Interpreter;

use crate::common;
use common::screen;

fn run(script: &str) -> Interpreter {
    common::run("in.test", script)
}

/// Screen lines that start with `key`, with the key removed and trimmed.
fn lines(i: &Interpreter, key: &str) -> Vec<String> {
    screen(i)
        .lines()
        .filter_map(|l| l.strip_prefix(key))
        .map(|l| l.trim().to_string())
        .collect()
}

/// The numbers of the one screen line that starts with `key`.
fn numbers(i: &Interpreter, key: &str) -> Vec<f64> {
    let l = lines(i, key);
    assert_eq!(l.len(), 1, "one line '{key}' expected in\n{}", screen(i));
    l[0].split_whitespace()
        .map(|w| {
            w.parse()
                .unwrap_or_else(|_| panic!("'{w}' of line '{key}' is not a number"))
        })
        .collect()
}

fn close(got: f64, want: f64) -> bool {
    (got - want).abs() <= 1e-12 * want.abs().max(1e-300)
}

fn assert_close(got: &[f64], want: &[f64], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: {got:?} vs {want:?}");
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(close(*g, *w), "{what}[{k}]: got {g}, want {w}");
    }
}

#[test]
fn substitution_reads_plain_text_now_and_quoted_text_when_it_runs() {
    let i = run(r#"
variable a equal 2.5
variable b equal $(v_a*4)
variable c equal v_a*4
variable n equal 3
variable m equal ${n}*2
variable q equal "v_n*2"
variable a equal 3
variable n equal 5
variable x equal 7
variable w string seven
print "S1 ${a} ${b} ${c} $(v_a/2)"
print "S2 ${m} ${q}"
print "S3 $x ${x}$x $(v_x*2) $(v_x/2)"
print "S4 $w ${w}"
print S5
"#);
    // $(...) outside quotes is evaluated when the line is read (b stays 10); a formula
    // is evaluated when used (c follows a); ${n} outside quotes is read at once (m is
    // 3*2), inside quotes at use (q is 5*2).
    assert_eq!(lines(&i, "S1"), ["3 10 12 1.5"]);
    assert_eq!(lines(&i, "S2"), ["6 10"]);
    // `$x` is the one-letter variable x.
    assert_eq!(lines(&i, "S3"), ["7 77 14 3.5"]);
    // `$w` is the one-letter variable w (a string).
    assert_eq!(lines(&i, "S4"), ["seven seven"]);
    assert_eq!(lines(&i, "S5"), [""]);
}

/// Precedence as LIGGGHTS: unary minus binds tighter than `^`. (Only values that print
/// the same in any format are checked: LIGGGHTS 3.8 writes `$(...)` as `%.20g`.)
#[test]
fn immediate_formulas() {
    let i = run("print \"F $(2*3) $(7/2) $(-2^2) $(round(2.5)+floor(-1.5))\"\n");
    assert_eq!(lines(&i, "F"), ["6 3.5 4 1"]);
}

#[test]
fn continuation_quotes_and_comments() {
    let i = run(concat!(
        "# a comment line\n",
        "   # an indented comment\n",
        "print \"J1: a&\n",
        "b\"\n",
        "print \"J2: one &\n",
        "  two # not a comment\" # a comment\n",
        "print 'J3: single \"double\" inside'\n",
        "print \"J4: it's\"\n",
        "print \"\"\"J5: triple \"quoted\" it's\"\"\"\n",
        "atom_style granular\n",
        "units si\n",
        "region r block 0 2 &\n",
        "    0 1 &\n",
        "    0 3 units box   # the box\n",
        "create_box 1 r\n",
        "print \"J6: $(vol)\"\n",
        "print J7:&\n",
        "\n",
    ));
    assert_eq!(lines(&i, "J1:"), ["ab"]);
    assert_eq!(lines(&i, "J2:"), ["one   two # not a comment"]);
    assert_eq!(lines(&i, "J3:"), ["single \"double\" inside"]);
    assert_eq!(lines(&i, "J4:"), ["it's"]);
    // Triple quotes are an rdem extension (LIGGGHTS 3.8 has only ' and ").
    assert_eq!(lines(&i, "J5:"), ["triple \"quoted\" it's"]);
    assert_eq!(numbers(&i, "J6:"), [6.0]);
    // A final '&' before a blank line ends the command there.
    assert_eq!(lines(&i, "J7:"), [""]);
}

#[test]
fn loop_variable_with_label_jump_and_next() {
    let i = run(r#"
variable i loop 3
label top
print "L${i}"
next i
jump SELF top
print "after the loop"
"#);
    let s = screen(&i);
    let got: Vec<&str> = s
        .lines()
        .filter(|l| l.starts_with('L') || l.starts_with("after"))
        .collect();
    assert_eq!(got, ["L1", "L2", "L3", "after the loop"]);
    // The exhausted loop variable is deleted.
    let r = common::try_run(
        "in.test",
        "variable i loop 2\nlabel a\nnext i\njump SELF a\nprint \"${i}\"\n",
    )
    .map(|_| ());
    assert!(r.unwrap_err().contains("no variable 'i'"));
}

#[test]
fn index_and_padded_loop_variables() {
    let i = run(r#"
variable f index alpha beta gamma
variable k loop 8 10 pad
label again
print "I ${f} ${k}"
next f
next k
jump SELF again
"#);
    assert_eq!(lines(&i, "I"), ["alpha 08", "beta 09", "gamma 10"]);
    // One `next` of an index and a loop variable stops LIGGGHTS 3.8 ("All variables in
    // next command must be same style"), and rdem.
    let mut i = common::interpreter();
    let e = i
        .run_source(
            "in.t",
            "variable f index a b\nvariable k loop 2\nnext f k\n",
        )
        .unwrap_err();
    assert!(e.to_string().contains("same style"), "{e}");
    // An index variable that exists is not redefined (so -var wins).
    let i = run("variable f index first\nvariable f index second\nprint \"X ${f}\"\n");
    assert_eq!(lines(&i, "X"), ["first"]);
}

#[test]
fn string_and_getenv_variables() {
    let path = std::env::var("PATH").unwrap_or_default();
    let i = run(r#"
variable s string "two words"
variable s string replaced
variable p getenv PATH
variable u getenv RDEM_LANGUAGE_TEST_SURELY_UNSET
print "S ${s}"
print "P ${p}"
print "U [${u}]"
"#);
    assert_eq!(lines(&i, "S"), ["replaced"]);
    assert_eq!(lines(&i, "P"), [path.trim()]);
    assert_eq!(lines(&i, "U"), ["[]"]);
}

#[test]
fn if_then_elif_else() {
    let script = |n: i32| {
        format!(
            r#"
variable n equal {n}
if "${{n}} > 5" then "print 'IF big'" elif "${{n}} > 2" "print 'IF middle'" "print 'IF second'" else "print 'IF small'"
if "${{n}} == 4 && 1" then "print 'IF four'"
"#
        )
    };
    assert_eq!(lines(&run(&script(9)), "IF"), ["big"]);
    assert_eq!(lines(&run(&script(4)), "IF"), ["middle", "second", "four"]);
    assert_eq!(lines(&run(&script(1)), "IF"), ["small"]);
}

#[test]
fn include_runs_a_second_file_in_place() {
    let d = common::scratch_dir("language-include");
    let sub = d.join("in.sub");
    std::fs::write(
        &sub,
        "variable inc equal 42\nprint \"INC ${inc} $(v_base+1)\"\n",
    )
    .unwrap();
    let i = run(&format!(
        "variable base equal 10\nprint \"BEFORE\"\ninclude {}\nprint \"AFTER ${{inc}}\"\n",
        sub.display()
    ));
    let s = screen(&i);
    let got: Vec<&str> = s
        .lines()
        .filter(|l| ["BEFORE", "INC", "AFTER"].iter().any(|k| l.starts_with(k)))
        .collect();
    assert_eq!(got, ["BEFORE", "INC 42 11", "AFTER 42"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn print_to_files_and_log() {
    let d = common::scratch_dir("language-print");
    let (p, l) = (d.join("printed.txt"), d.join("log.test"));
    let i = run(&format!(
        r#"
variable v equal 1.25
print "first ${{v}}" file {p}
print "second $(v_v*2)" append {p} screen no
log {l}
print "LOGGED ${{v}}"
log none
print "NOT LOGGED"
"#,
        p = p.display(),
        l = l.display()
    ));
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        "first 1.25\nsecond 2.5\n"
    );
    // `screen no` keeps it off the screen.
    assert!(lines(&i, "second").is_empty());
    let log = std::fs::read_to_string(&l).unwrap();
    assert!(log.contains("LOGGED 1.25"), "{log}");
    assert!(!log.contains("NOT LOGGED"), "{log}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Two spheres in a unit box: atom 1 (diameter 0.1) at (0.2, 0.3, 0.4) with v = (0, 0, -1),
/// atom 2 (diameter 0.2) at (0.6, 0.5, 0.4) with v = (2, 0, -1), density 1000. Masses
/// m1 = π/6, m2 = 4π/3 = 8 m1, total 1.5π.
const TWO: &str = "\
atom_style      granular
atom_modify     map array
boundary        f f f
newton          off
communicate     single vel yes
units           si
region          box block 0 1 0 1 0 1 units box
create_box      1 box
create_atoms    1 single 0.2 0.3 0.4 units box
create_atoms    1 single 0.6 0.5 0.4 units box
set             atom 1 diameter 0.1 density 1000
set             atom 2 diameter 0.2 density 1000
velocity        all set 0.0 0.0 -1.0
set             atom 2 vx 2.0
group           big id 2
reset_timestep  25
timestep        0.001
";

#[test]
fn group_functions_on_two_particles() {
    let i = run(&format!(
        r#"{TWO}
variable n equal count(all)
variable nb equal count(big)
variable m equal mass(all)
variable mb equal mass(big)
variable xx equal xcm(all,x)
variable xy equal xcm(all,y)
variable xz equal xcm(all,z)
variable vx equal vcm(all,x)
variable vy equal vcm(all,y)
variable vz equal vcm(all,z)
variable b1 equal bound(all,xmin)
variable b2 equal bound(all,xmax)
variable b3 equal bound(all,zmax)
variable b4 equal bound(big,ymin)
variable k equal ke(all)
variable kb equal ke(big)
print "N ${{n}} ${{nb}} ${{m}} ${{mb}}"
print "XCM ${{xx}} ${{xy}} ${{xz}}"
print "VCM ${{vx}} ${{vy}} ${{vz}}"
print "B ${{b1}} ${{b2}} ${{b3}} ${{b4}}"
print "KE ${{k}} ${{kb}}"
"#
    ));
    let pi = std::f64::consts::PI;
    assert_close(
        &numbers(&i, "N "),
        &[2.0, 1.0, 1.5 * pi, 4.0 * pi / 3.0],
        "count, mass",
    );
    // Mass-weighted with weights 1 : 8.
    assert_close(
        &numbers(&i, "XCM"),
        &[(0.2 + 8.0 * 0.6) / 9.0, (0.3 + 8.0 * 0.5) / 9.0, 0.4],
        "xcm",
    );
    assert_close(&numbers(&i, "VCM"), &[16.0 / 9.0, 0.0, -1.0], "vcm");
    assert_close(&numbers(&i, "B "), &[0.2, 0.6, 0.4, 0.5], "bound");
    // ½ m1 · 1 + ½ m2 · (4 + 1) = π/12 + 10π/3 = 41π/12; big alone 10π/3.
    assert_close(
        &numbers(&i, "KE"),
        &[41.0 * pi / 12.0, 10.0 * pi / 3.0],
        "ke",
    );
}

#[test]
fn atom_values_thermo_keywords_and_computes_in_formulas() {
    let i = run(&format!(
        r#"{TWO}
variable mv atom mass*vx
compute r all reduce max x vx
compute p all reduce sum v_mv
compute zsum big reduce sum z
variable a1 equal x[1]
variable a2 equal vx[2]
variable a3 equal mass[1]
variable r1 equal c_r[1]
variable r2 equal c_r[2]
variable pp equal c_p
variable zz equal c_zsum
variable t1 equal step
variable t2 equal atoms
variable t3 equal vol
variable t4 equal step*dt+atoms/vol
print "AT ${{a1}} ${{a2}} ${{a3}}"
print "C ${{r1}} ${{r2}} ${{pp}} ${{zz}}"
print "T ${{t1}} ${{t2}} ${{t3}} ${{t4}}"
"#
    ));
    let pi = std::f64::consts::PI;
    assert_close(&numbers(&i, "AT"), &[0.2, 2.0, pi / 6.0], "atom values");
    // reduce max of x and vx: (0.6, 2); Σ m vx = m2 · 2 = 8π/3; z of atom 2 only.
    assert_close(
        &numbers(&i, "C "),
        &[0.6, 2.0, 8.0 * pi / 3.0, 0.4],
        "computes",
    );
    assert_close(
        &numbers(&i, "T "),
        &[25.0, 2.0, 1.0, 25.0 * 0.001 + 2.0],
        "thermo keywords",
    );
}

/// `v_name[i]`: atom i's value of an atom-style variable, in equal-style formulas and in
/// atom-style ones (the same number for every atom). LIGGGHTS 3.8 printed the same
/// thermo columns (8 digits) and `${e2}` (15 digits) for a three-sphere script with
/// `v_e[2]`, `2*v_e[3]+v_e[1]` and `v_e[3]*x` in a reduced atom-style variable.
#[test]
fn indexed_atom_style_variables() {
    let i = run(&format!(
        r#"{TWO}
variable mv atom mass*vx+z
variable a equal v_mv[2]
variable b equal 2*v_mv[1]-v_mv[2]
variable s atom v_mv[2]*x
compute r all reduce sum v_s
variable c equal c_r
print "IX ${{a}} ${{b}} ${{c}}"
"#
    ));
    let pi = std::f64::consts::PI;
    // vx1 = 0, z1 = 0.4; m2 = 4π/3, vx2 = 2, z2 = 0.4.
    let (e1, e2) = (0.4, 8.0 * pi / 3.0 + 0.4);
    assert_close(
        &numbers(&i, "IX"),
        &[e2, 2.0 * e1 - e2, e2 * (0.2 + 0.6)],
        "v_mv[i]",
    );
}

#[test]
fn bad_references_in_formulas_are_errors() {
    for (formula, message) in [
        ("c_r[3]", "c_r[3]"),
        ("x[7]", "no atom with ID 7"),
        ("count(nobody)", "no group 'nobody'"),
        ("v_mv", "atom-style variable 'mv'"),
        ("v_mv[7]", "v_mv[7]: no atom with ID 7"),
        ("v_e[1]", "'e' is not an atom-style variable"),
    ] {
        let r = common::try_run(
            "in.test",
            &format!(
                "{TWO}variable mv atom mass*vx\nvariable e equal 1\ncompute r all reduce max x vx\nprint \"$({formula})\"\n"
            ),
        )
        .map(|_| ());
        let e = r.expect_err(formula);
        assert!(e.contains(message), "{formula}: {e}");
    }
}

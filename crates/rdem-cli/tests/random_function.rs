//! `random(lo, hi, seed)` in equal-style formulas (LIGGGHTS_SEAICE's packing scripts draw
//! their diameters with it): one generator for the script, seeded by the first call's
//! seed, as LIGGGHTS. The printed values are those LIGGGHTS 3.8 printed for the same
//! script (stored below), digit for digit.

use crate::common;

const SCRIPT: &str = r#"variable lo equal 0.01
variable r equal random(v_lo,0.03,3124127)
variable s equal 2*(random(-1,1,93263)*0.2+1)
print "A ${r}"
print "B ${r}"
print "C ${s}"
variable k loop 5
label top
print "D $r $s"
next k
jump SELF top
"#;

/// LIGGGHTS 3.8's lines for SCRIPT.
const LIGGGHTS: &str = "A 0.0100539994239807
B 0.0109982979297638
C 1.68965401649475
D 0.0113439583778381 1.75966439247131
D 0.029107494354248 2.27555456161499
D 0.0184161019325256 1.83128347396851
D 0.0199832510948181 1.90778813362122
D 0.0246042621135712 2.15849280357361";

#[test]
fn random_draws_liggghts_numbers() {
    let out = common::run_script(SCRIPT, None);
    let got: Vec<&str> = out
        .lines()
        .filter(|l| l.len() > 2 && "ABCD".contains(&l[..1]) && &l[1..2] == " ")
        .collect();
    assert_eq!(got.join("\n"), LIGGGHTS);
}

#[test]
fn random_refuses_what_it_cannot_draw() {
    for (formula, want) in [
        ("random(0,1,0)", "positive integer"),
        ("random(0,1,2.5)", "positive integer"),
        ("random(0,1)", "3 arguments"),
        ("random(0,1,900000000)", "below 900000000"),
    ] {
        let out = common::run_script_raw(
            &format!("variable r equal {formula}\nprint \"${{r}}\"\n"),
            None,
        );
        assert!(!out.status.success(), "{formula}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(want), "{formula}: {err}");
    }
}

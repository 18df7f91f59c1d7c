//! `set ... x|y|z|vx|vy|vz|omegax|omegay|omegaz VALUE`, as the LIGGGHTS 3.8 manual lists
//! them: VALUE a number, or an equal- or atom-style variable evaluated per particle.

use rdem_script::Interpreter;

use crate::common;

/// Three particles on the x axis at 0.1, 0.2, 0.3; `tail` after them.
fn run(tail: &str) -> Result<Interpreter, String> {
    let src = format!(
        "units si
atom_style granular
boundary f f f
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
create_atoms 1 single 0.1 0 0 units box
create_atoms 1 single 0.2 0 0 units box
create_atoms 1 single 0.3 0 0 units box
set atom * diameter 0.02 density 2500
{tail}
"
    );
    common::try_run("in.set", &src)
}

#[test]
fn components_take_numbers_and_variables() {
    let i = run("variable a atom 10*x+1
variable e equal 2*3
set group all vx v_a omegaz 2.5 y -0.25 omegax v_e
set atom 2 z 0.5 vy -1")
    .unwrap();
    let p = &i.sim.world.as_ref().unwrap().particles;
    for (tag, x) in [(1u64, 0.1), (2, 0.2), (3, 0.3)] {
        let k = p.find_tag(tag).unwrap();
        assert!((p.v[k].x - (10.0 * x + 1.0)).abs() < 1e-12, "{:?}", p.v[k]);
        assert_eq!(p.omega[k].z, 2.5);
        assert_eq!(p.omega[k].x, 6.0);
        assert_eq!(p.x[k].y, -0.25);
        let (z, vy) = if tag == 2 { (0.5, -1.0) } else { (0.0, 0.0) };
        assert_eq!((p.x[k].z, p.v[k].y), (z, vy));
    }
}

#[test]
fn a_missing_value_or_variable_is_an_error() {
    let e = run("set group all omegay NULL").err().unwrap();
    assert!(e.contains("NULL is not a value"), "{e}");
    let e = run("set group all vx v_nope").err().unwrap();
    assert!(e.contains("no variable 'nope'"), "{e}");
}

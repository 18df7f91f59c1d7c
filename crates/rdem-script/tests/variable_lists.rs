//! `variable NAME file FILE`, `uloop N [pad]` and `universe v1 v2 ...` with `next` and
//! `jump`: the screen LIGGGHTS 3.8 printed for the same scripts (`liggghts -in in.x -log
//! none`, 2026-11-24), line for line.

use rdem_script::Interpreter;

use crate::common;

fn screen(i: &Interpreter) -> Vec<String> {
    let s = common::screen(i);
    s.lines().map(String::from).collect()
}

fn error(script: &str) -> String {
    let mut i = common::interpreter();
    let e = i.run_source("in.x", script).expect_err("must fail");
    e.to_string()
}

/// vals.txt is `# header comment`, ``, `alpha beta # trailing`, `   `, `  2.5e3`,
/// `#only comment`, `last`; v2.txt is `a b`, `\tt1 x`, `  # c`, ` x#y`. LIGGGHTS printed
/// `first [alpha]`, `after redefine [alpha]` (a defined file variable is not redefined,
/// even with a missing file), `f=alpha`, `f=  2.5e3`, `f=last`, `out of loop` (the
/// exhausted `next` skips the jump and deletes `f`), then for v2.txt `f=[a]`,
/// `f=[\tt1]`, `f=[ x]`.
#[test]
fn file_variables_read_lines_as_liggghts() {
    let d = common::scratch_dir("varlists-file");
    let vals = d.join("vals.txt");
    std::fs::write(
        &vals,
        "# header comment\n\nalpha beta # trailing\n   \n  2.5e3\n#only comment\nlast\n",
    )
    .unwrap();
    let v2 = d.join("v2.txt");
    std::fs::write(&v2, "a b\n\tt1 x\n  # c\n x#y\n").unwrap();
    let script = format!(
        "variable f file {}\n\
         print \"first [${{f}}]\"\n\
         variable f file {}\n\
         print \"after redefine [${{f}}]\"\n\
         label l1\n\
         print \"f=${{f}}\"\n\
         next f\n\
         jump SELF l1\n\
         print \"out of loop\"\n\
         variable g file {}\n\
         label l2\n\
         print \"f=[$g]\"\n\
         next g\n\
         jump SELF l2\n",
        vals.display(),
        d.join("other_missing.txt").display(),
        v2.display()
    );
    let i = common::run("in.x", &script);
    assert_eq!(
        screen(&i),
        [
            "first [alpha]",
            "after redefine [alpha]",
            "f=alpha",
            "f=  2.5e3",
            "f=last",
            "out of loop",
            "f=[a]",
            "f=[\tt1]",
            "f=[ x]",
        ]
    );
    assert!(i.sim.script.vars.get("f").is_none());
    assert!(i.sim.script.vars.get("g").is_none());

    // `next f g` advances both files.
    let script = format!(
        "variable f file {}\nvariable g file {}\nnext f g\nprint \"$f $g\"\n",
        vals.display(),
        v2.display()
    );
    assert_eq!(screen(&common::run("in.x", &script)), ["  2.5e3 \tt1"]);

    // LIGGGHTS: "Cannot open file variable file nofile.txt", "File variable could not
    // read value" (a file of blank and comment lines).
    let e = error(&format!(
        "variable f file {}\n",
        d.join("nofile.txt").display()
    ));
    assert!(e.contains("cannot open file variable file"), "{e}");
    let empty = d.join("empty.txt");
    std::fs::write(&empty, "\n# nothing\n").unwrap();
    let e = error(&format!("variable f file {}\n", empty.display()));
    assert!(e.contains("file variable could not read a value"), "{e}");
}

/// LIGGGHTS printed `u=1`, `Increment via next: value 2 on partition 0`, `u=2`, `...
/// value 3 ...`, `u=3`, `... value 4 ...`, `out`; with `uloop 12 pad`: `upad=01`, `...
/// value 2 ...`, `upad=02`.
#[test]
fn uloop_counts_as_loop_with_liggghts_lines() {
    let i = common::run(
        "in.x",
        "variable u uloop 3\n\
         label l2\n\
         print \"u=$u\"\n\
         next u\n\
         jump SELF l2\n\
         print \"out\"\n\
         variable p uloop 12 pad\n\
         print \"upad=$p\"\n",
    );
    let inc = |k: usize| format!("Increment via next: value {k} on partition 0");
    assert_eq!(
        screen(&i),
        [
            "u=1".to_string(),
            inc(2),
            "u=2".into(),
            inc(3),
            "u=3".into(),
            inc(4),
            "out".into(),
            "upad=01".into(),
        ]
    );
    // All universe/uloop variables have as many values (LIGGGHTS: "All universe/uloop
    // variables must have same # of values"); uloop takes N only ("Illegal variable
    // command" for `uloop 3 4`).
    let e = error("variable u uloop 2\nvariable v uloop 3\n");
    assert!(e.contains("same number of values"), "{e}");
    let e = error("variable u uloop 3 4\n");
    assert!(e.contains("style uloop takes N"), "{e}");
    let e = error("variable u uloop 0\n");
    assert!(e.contains("uloop 0 has no value"), "{e}");
}

/// LIGGGHTS printed `w=a`, `Increment via next: value 2 on partition 0`, `w=b`, `...
/// value 3 ...`, `w=c`, `... value 4 ...`, `jump skipped` (the redefinition `universe z`
/// is ignored; the exhausted `next` skips the jump to a label that does not exist); a
/// `next` of a uloop and a universe variable together prints one line:
/// `... value 2 ...`, `2 q`; `next i l` of an index and a loop variable stops with "All
/// variables in next command must be same style".
#[test]
fn universe_steps_as_index_with_liggghts_lines() {
    let i = common::run(
        "in.x",
        "variable w universe a b c\n\
         variable w universe z\n\
         print \"w=$w\"\n\
         next w\n\
         print \"w=$w\"\n\
         next w\n\
         print \"w=$w\"\n\
         next w\n\
         jump SELF nolabel\n\
         print \"jump skipped\"\n\
         variable u uloop 2\n\
         variable x universe p q\n\
         next u x\n\
         print \"$u $x\"\n",
    );
    let inc = |k: usize| format!("Increment via next: value {k} on partition 0");
    assert_eq!(
        screen(&i),
        [
            "w=a".to_string(),
            inc(2),
            "w=b".into(),
            inc(3),
            "w=c".into(),
            inc(4),
            "jump skipped".into(),
            inc(2),
            "2 q".into(),
        ]
    );
    let e = error("variable i index a b\nvariable l loop 3\nnext i l\n");
    assert!(e.contains("same style"), "{e}");
}

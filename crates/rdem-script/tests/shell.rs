//! `shell`: what it makes, removes and runs, compared with what LIGGGHTS 3.8 did for the
//! same script (`liggghts -in in.shell -log none` in an empty folder, 2026-11-24).
//!
//! `shell cd` changes the test process' working folder: one test holds every use of it,
//! and every path the test sets up itself is absolute.

use std::path::{Path, PathBuf};

use crate::common;
use common::screen;

fn tmpdir(name: &str) -> PathBuf {
    common::scratch_dir(&format!("shell-{name}"))
        .canonicalize()
        .unwrap()
}

/// Every file and folder under `d`, relative, sorted (as `find . | sort`).
fn tree(d: &Path) -> Vec<String> {
    fn walk(root: &Path, d: &Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            out.push(p.strip_prefix(root).unwrap().display().to_string());
            if p.is_dir() {
                walk(root, &p, out);
            }
        }
    }
    let mut out = Vec::new();
    walk(d, d, &mut out);
    out.sort();
    out
}

/// The script LIGGGHTS 3.8 ran, after a `shell cd` into the test folder. LIGGGHTS left
/// (`find . | sort`): `d1`, `d1/here.txt`, `d3`, `out.txt` — `d2/sub` is not made (no
/// parent), `mkdir d3 d3` and the failing `cd`, `rm`, `rmdir`, `mv`, `false`, `exit 3`
/// go on — `out.txt` holds `hello world quoted x` (the words joined by single spaces,
/// then split again by the shell) and the screen shows `in d1`, `FOO=bar`, `done`.
/// rdem prints a warning for each failure where LIGGGHTS says nothing.
#[test]
fn shell_acts_as_liggghts() {
    let d = tmpdir("acts");
    let script = format!(
        "shell cd {}\n\
         shell mkdir d1 d2/sub\n\
         shell mkdir d3 d3\n\
         shell cd d1\n\
         print \"in d1\" file here.txt\n\
         shell cd nonexist\n\
         shell cd ..\n\
         shell rm nofile\n\
         shell rmdir nodir\n\
         shell mv nofile2 other\n\
         shell putenv RDEM_SHELL_FOO=bar RDEM_SHELL_BAZ=q=u\n\
         variable f getenv RDEM_SHELL_FOO\n\
         variable g getenv RDEM_SHELL_BAZ\n\
         print \"FOO=${{f}} BAZ=${{g}}\"\n\
         shell echo hello   world \"quoted  x\" > out.txt\n\
         shell false\n\
         shell exit 3\n\
         print done\n",
        d.display()
    );
    let mut i = common::interpreter();
    i.run_source("in.shell", &script).unwrap();
    assert_eq!(tree(&d), ["d1", "d1/here.txt", "d3", "out.txt"]);
    assert_eq!(
        std::fs::read_to_string(d.join("d1/here.txt")).unwrap(),
        "in d1\n"
    );
    assert_eq!(
        std::fs::read_to_string(d.join("out.txt")).unwrap(),
        "hello world quoted x\n"
    );
    assert_eq!(std::env::current_dir().unwrap(), d);
    let out = screen(&i);
    let printed: Vec<&str> = out.lines().filter(|l| !l.starts_with("WARNING")).collect();
    assert_eq!(printed, ["in d1", "FOO=bar BAZ=q=u", "done"]);
    let warnings: Vec<&str> = out.lines().filter(|l| l.starts_with("WARNING")).collect();
    let expect = [
        "WARNING: line 2: shell mkdir: cannot create folder 'd2/sub'",
        "WARNING: line 6: shell cd: cannot change to 'nonexist'",
        "WARNING: line 8: shell rm: cannot remove 'nofile'",
        "WARNING: line 9: shell rmdir: cannot remove folder 'nodir'",
        "WARNING: line 10: shell mv: cannot move 'nofile2' to 'other'",
        "WARNING: line 16: shell command 'false' exited with status 1",
        "WARNING: line 17: shell command 'exit 3' exited with status 3",
    ];
    assert_eq!(warnings.len(), expect.len(), "{out}");
    for (w, e) in warnings.iter().zip(expect) {
        assert!(w.starts_with(e), "{w}\nwanted {e}...");
    }

    // mkdir -p makes parents and is quiet for existing folders; rm -f for missing files;
    // rm and rmdir act on each name; rm -r, -rf, -R, -fr remove folders with what they
    // hold; mv renames; putenv NAME removes NAME.
    let script = "shell mkdir -p a/b/c a\n\
         shell mkdir a\n\
         shell echo x > a/b/f1\n\
         shell echo y > a/b/f2\n\
         shell rm -f a/b/f1 a/b/none\n\
         shell mv a/b/f2 a/g\n\
         shell rmdir a/b/c a/b\n\
         shell mkdir -p r1/s r2/t r3 r4\n\
         shell echo z > r1/s/f\n\
         shell echo z > a/h\n\
         shell rm -r r1\n\
         shell rm -rf r2 r2 nothing\n\
         shell rm -R r3\n\
         shell rm -fr r4 a/h\n\
         shell putenv RDEM_SHELL_FOO\n\
         variable f getenv RDEM_SHELL_FOO\n\
         print \"[${f}]\"\n";
    let mut i = common::interpreter();
    i.run_source("in.shell2", script).unwrap();
    assert_eq!(tree(&d.join("a")), ["g"]);
    for gone in ["r1", "r2", "r3", "r4"] {
        assert!(!d.join(gone).exists(), "shell rm -r left {gone}");
    }
    assert_eq!(std::fs::read_to_string(d.join("a/g")).unwrap(), "y\n");
    assert_eq!(screen(&i), "[]\n");
    assert!(std::env::var_os("RDEM_SHELL_FOO").is_none());

    // `rdem -check`: cd and putenv act, nothing else does.
    let e = tmpdir("check");
    let script = format!(
        "shell putenv RDEM_SHELL_CHECK=1\n\
         shell cd {}\n\
         shell mkdir post\n\
         shell echo x > made.txt\n\
         shell rm keep.txt\n\
         shell mv keep.txt moved.txt\n",
        e.display()
    );
    std::fs::write(e.join("keep.txt"), "k").unwrap();
    let mut i = common::interpreter();
    let c = i.check_source("in.check", &script);
    assert!(c.problems.is_empty(), "{c:?}");
    assert_eq!(std::env::var("RDEM_SHELL_CHECK").as_deref(), Ok("1"));
    assert_eq!(std::env::current_dir().unwrap(), e);
    assert_eq!(tree(&e), ["keep.txt"]);
    assert_eq!(screen(&i), "");
}

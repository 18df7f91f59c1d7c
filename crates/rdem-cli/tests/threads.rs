//! `--threads N`: a LIGGGHTS tutorial case (cohesion, a hertz/history/sjkr bed poured into
//! a box, dumped every 800 steps) writes byte-identical dump files on 1, 2 and 4 threads.

use std::collections::BTreeMap;
use std::path::Path;

use crate::common;
use common::copy_dir;

const CASE: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/cohesion";

/// Runs the case on `threads` threads; returns the files of `post/` by name.
fn run(threads: usize) -> BTreeMap<String, Vec<u8>> {
    let d = common::scratch_dir(&format!("cli-threads-{threads}"));
    copy_dir(Path::new(CASE), &d);
    let post = d.join("post");
    let _ = std::fs::remove_dir_all(&post);
    std::fs::create_dir_all(&post).unwrap();
    let out = common::rdem_in(&d, "in.cohesion", None)
        .arg("--threads")
        .arg(threads.to_string())
        .output()
        .unwrap();
    let stdout = common::success(&format!("{threads} threads"), &out);
    let plural = if threads == 1 { "" } else { "s" };
    assert!(stdout.contains(&format!("using {threads} thread{plural}")));
    let files = std::fs::read_dir(&post)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    let _ = std::fs::remove_dir_all(&d);
    files
}

#[test]
fn cohesion_tutorial_dumps_are_byte_identical_on_1_2_and_4_threads() {
    let one = run(1);
    assert!(one.len() > 50, "{} dump files", one.len());
    for threads in [2, 4] {
        let other = run(threads);
        assert_eq!(
            other.keys().collect::<Vec<_>>(),
            one.keys().collect::<Vec<_>>(),
            "{threads} threads: other dump files"
        );
        for (name, bytes) in &one {
            assert!(
                other[name] == *bytes,
                "{threads} threads: {name} differs from the 1-thread run"
            );
        }
    }
}

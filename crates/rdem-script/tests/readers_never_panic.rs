//! The file readers never panic, hang or make a huge allocation, whatever the bytes: STL
//! (ASCII and binary), LAMMPS data files, rdem's restart files (framing and payload),
//! LIGGGHTS restart files, VTK tetrahedral meshes and multisphere template files. Each gets arbitrary bytes and mutations of a valid file
//! (bytes set, cut, repeated; text tokens swapped for awkward numbers and keywords), and
//! must return either a value or an error with a message.
//!
//! A counting allocator records the largest single allocation of each case: no input of
//! these sizes (under 100 KB) may ask for more than [`LIMIT`].
//!
//! The suite runs [`CASES`] cases per reader and strategy (21 strategies) with a fixed
//! seed; `RDEM_FUZZ_CASES=N` runs N instead and `RDEM_FUZZ_SEED=S` (0–255) another seed.
//! Run by hand on 2026-12-04: 50,000 per strategy (1,050,000 cases) with seed 7 and
//! 20,000 (420,000) with seeds 1 and 2. Those runs found a 34 GB request in the VTK
//! tetrahedra reader (a huge POINTS count) and a 69 MB one in the LIGGGHTS restart
//! reader (the pair_coeff flags of a huge type count), both now capped by the bytes
//! left to read.

use std::alloc::{GlobalAlloc, Layout, System};
use std::fmt::Display;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::common;

/// The largest allocation a reader may make for these inputs.
const LIMIT: usize = 64 << 20;

/// Cases per reader and strategy in the suite.
const CASES: u32 = 400;

/// The system allocator, recording the largest request since the last reset.
struct Counting;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Cases per strategy: [`CASES`], or `RDEM_FUZZ_CASES`.
fn cases() -> u32 {
    std::env::var("RDEM_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(CASES)
}

/// Runs `reader` on inputs from `strategy` (a fixed seed): each must give a value or an
/// error with a message, and allocate no more than [`LIMIT`] at once.
fn run<E: Display, T>(
    name: &str,
    strategy: impl Strategy<Value = Vec<u8>>,
    reader: impl Fn(&[u8]) -> Result<T, E>,
) {
    let config = Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    };
    let seed = std::env::var("RDEM_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(7u8);
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let result = runner.run(&strategy, |bytes| {
        LARGEST.store(0, Ordering::Relaxed);
        let outcome = reader(&bytes);
        let largest = LARGEST.load(Ordering::Relaxed);
        prop_assert!(
            largest <= LIMIT,
            "{name}: an allocation of {largest} bytes for {} input bytes",
            bytes.len()
        );
        if let Err(e) = outcome {
            prop_assert!(!e.to_string().trim().is_empty(), "{name}: an empty message");
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}");
    }
}

/// Words that make number and count parsers work: huge, negative, non-finite, empty.
const AWKWARD: &[&str] = &[
    "0",
    "-1",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "18446744073709551615",
    "4294967296",
    "999999999999",
    "1.5",
    "",
    "Atoms",
    "Velocities",
    "facet",
    "endsolid",
    "POINTS",
    "CELLS",
    "CELL_TYPES",
];

/// One change to a file.
#[derive(Debug, Clone)]
enum Edit {
    /// Sets byte `at` (modulo the length).
    Byte(usize, u8),
    /// Cuts the file at `at`.
    Cut(usize),
    /// Repeats the `len` bytes from `at`.
    Repeat(usize, usize),
    /// Replaces whitespace-separated word `at` (modulo the count) by an awkward word.
    Word(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(a, b)| Edit::Byte(a, b)),
        any::<usize>().prop_map(Edit::Cut),
        (any::<usize>(), 1usize..64).prop_map(|(a, n)| Edit::Repeat(a, n)),
        (any::<usize>(), 0..AWKWARD.len()).prop_map(|(a, w)| Edit::Word(a, w)),
    ]
}

/// Applies `edits` to `seed`.
fn apply(seed: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut b = seed.to_vec();
    for e in edits {
        if b.is_empty() {
            break;
        }
        match *e {
            Edit::Byte(at, v) => {
                let n = b.len();
                b[at % n] = v;
            }
            Edit::Cut(at) => b.truncate(at % (b.len() + 1)),
            Edit::Repeat(at, len) => {
                let at = at % b.len();
                let end = (at + len).min(b.len());
                let piece = b[at..end].to_vec();
                b.splice(at..at, piece);
            }
            Edit::Word(at, w) => {
                let words: Vec<(usize, usize)> = word_spans(&b);
                if let Some(&(s, e)) = words.get(at % words.len().max(1)) {
                    b.splice(s..e, AWKWARD[w].bytes());
                }
            }
        }
    }
    b
}

/// Byte ranges of the whitespace-separated words of `b`.
fn word_spans(b: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (k, c) in b.iter().enumerate() {
        match (c.is_ascii_whitespace(), start) {
            (false, None) => start = Some(k),
            (true, Some(s)) => {
                out.push((s, k));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, b.len()));
    }
    out
}

/// Arbitrary bytes, up to 4 KiB.
fn bytes() -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(any::<u8>(), 0..4096)
}

/// `seed` with 1 to 8 edits.
fn mutated(seed: Vec<u8>) -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(edit(), 1..8).prop_map(move |e| apply(&seed, &e))
}

fn repo(path: &str) -> Vec<u8> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path);
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// A binary STL of two triangles whose header begins with `solid`.
fn binary_stl() -> Vec<u8> {
    let mut b = b"solid but binary".to_vec();
    b.resize(80, b' ');
    b.extend_from_slice(&2u32.to_le_bytes());
    for t in 0..2 {
        for v in [
            0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, t as f32,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&[0, 0]);
    }
    b
}

const DATA: &str = "LAMMPS data file\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n\
    0 1 zlo zhi\n\nAtoms # granular\n\n1 1 0.1 2500 0.2 0.3 0.5 0 0 0\n\
    2 1 0.1 2500 0.6 0.3 0.5 0 0 0\n\nVelocities\n\n1 0 0 -1 0 0 0\n2 0 0 0 0 0 1\n";

#[test]
fn stl_reader() {
    let read = |b: &[u8]| rdem_io::stl::parse_stl_numbered(b, "f.stl");
    run("stl, bytes", bytes(), read);
    let ascii = repo("crates/rdem-cli/tests/data/heat/floor.stl");
    run("stl, ascii edits", mutated(ascii), read);
    run("stl, binary edits", mutated(binary_stl()), read);
    // A binary header whose count is huge, with the size of that count or not.
    run(
        "stl, binary counts",
        (any::<u32>(), 0usize..400).prop_map(|(n, extra)| {
            let mut b = binary_stl();
            b[80..84].copy_from_slice(&n.to_le_bytes());
            b.resize(84 + extra, 0);
            b
        }),
        read,
    );
}

#[test]
fn data_file_reader() {
    let read = |b: &[u8]| rdem_io::data_file::parse_data(&String::from_utf8_lossy(b));
    run("data, bytes", bytes(), read);
    run("data, edits", mutated(DATA.as_bytes().to_vec()), read);
}

#[test]
fn restart_framing() {
    let read = |b: &[u8]| rdem_io::restart_file::unframe(Path::new("f.restart"), b.to_vec());
    run("restart framing, bytes", bytes(), read);
    let framed = rdem_io::restart_file::frame(b"payload of a restart file");
    run("restart framing, edits", mutated(framed), read);
}

#[test]
fn liggghts_restart_reader() {
    let read =
        |b: &[u8]| rdem_io::liggghts_restart::parse_liggghts_restart(Path::new("f.restart"), b);
    run("liggghts restart, bytes", bytes(), read);
    for f in ["pa.restart", "bed2.restart"] {
        let seed = repo(&format!("crates/rdem-cli/tests/data/liggghts_restart/{f}"));
        run(&format!("liggghts restart {f}, edits"), mutated(seed), read);
    }
}

#[test]
fn tet_vtk_reader() {
    let read = |b: &[u8]| rdem_io::vtk_tets::parse_tet_vtk(b, "f.vtk");
    run("tet vtk, bytes", bytes(), read);
    let seed = repo("crates/rdem-cli/tests/data/mesh_tet/five.vtk");
    run("tet vtk, edits", mutated(seed), read);
}

/// An rdem restart file of two touching spheres, written by a script.
fn rdem_restart() -> Vec<u8> {
    let dir = std::env::temp_dir().join(format!("rdem_fuzz_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("two.restart");
    let script = format!(
        "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
         communicate single vel yes\nunits si\nregion reg block 0 1 0 1 0 1 units box\n\
         create_box 1 reg\nneighbor 0.01 bin\n\
         fix m1 all property/global youngsModulus peratomtype 5.e6\n\
         fix m2 all property/global poissonsRatio peratomtype 0.45\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 1e-5\n\
         create_atoms 1 single 0.5 0.5 0.5\ncreate_atoms 1 single 0.5 0.5 0.595\n\
         set atom * diameter 0.1 density 1000\nvelocity all set 0 0 0.1\n\
         fix i all nve/sphere\nrun 5\nwrite_restart {}\n",
        file.display()
    );
    common::run("in.r", &script);
    let bytes = std::fs::read(&file).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    bytes
}

#[test]
fn rdem_restart_payload() {
    let (_, payload) = rdem_io::restart_file::unframe(Path::new("r"), rdem_restart())
        .expect("a restart file rdem wrote");
    rdem_script::restart_state::decode(&payload).expect("it decodes");
    let read = rdem_script::restart_state::decode;
    run("rdem restart payload, bytes", bytes(), read);
    run("rdem restart payload, edits", mutated(payload), read);
}

#[test]
fn multisphere_template_reader() {
    let seed = b"# x y z r\n0 0 0 0.5\n0.4 0 0 0.5 # second\n\n0 0.4 0 0.3\n".to_vec();
    assert_eq!(
        rdem_script::fixes::parse_spheres(&seed, 3).unwrap().len(),
        3
    );
    for n in [3, 0, usize::MAX] {
        let read = move |b: &[u8]| rdem_script::fixes::parse_spheres(b, n);
        run(&format!("template, n {n}, bytes"), bytes(), read);
        run(
            &format!("template, n {n}, edits"),
            mutated(seed.clone()),
            read,
        );
    }
    // `spheres_different_types` (LIGGGHTS-INL): a type after each radius.
    let typed = b"# x y z r type\n0 0 0 0.5 2\n0.4 0 0 0.5 1 # second\n\n0 0.4 0 0.3 3\n".to_vec();
    let got = rdem_script::fixes::parse_typed_spheres(&typed, 3).unwrap();
    assert_eq!(got.iter().map(|s| s.1).collect::<Vec<_>>(), [2, 1, 3]);
    assert!(rdem_script::fixes::parse_typed_spheres(b"0 0 0 0.5 0\n", 1).is_err());
    assert!(rdem_script::fixes::parse_typed_spheres(b"0 0 0 0.5 1.5\n", 1).is_err());
    assert!(rdem_script::fixes::parse_typed_spheres(&seed, 3).is_err());
    for n in [3, 0, usize::MAX] {
        let read = move |b: &[u8]| rdem_script::fixes::parse_typed_spheres(b, n);
        run(&format!("typed template, n {n}, bytes"), bytes(), read);
        run(
            &format!("typed template, n {n}, edits"),
            mutated(typed.clone()),
            read,
        );
    }
}

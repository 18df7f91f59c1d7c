//! The LIGGGHTS 3.8 restart reader against files LIGGGHTS 3.8 wrote
//! (`crates/rdem-cli/tests/data/liggghts_restart`, see its README) and against every
//! kind of damaged file.

use std::path::{Path, PathBuf};

use rdem_io::liggghts_restart::{parse_liggghts_restart, read_liggghts_restart};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../rdem-cli/tests/data/liggghts_restart")
        .join(name)
}

/// The `ITEM: ATOMS` rows of a LIGGGHTS dump, as numbers.
fn dump_rows(name: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(data(name)).unwrap();
    text.lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

#[test]
fn settled_bed_file_is_read_exactly() {
    let f = read_liggghts_restart(&data("bed.restart")).unwrap();
    assert!(
        f.version.starts_with("Version LIGGGHTS-PUBLIC 3.8.0"),
        "{}",
        f.version
    );
    assert_eq!(
        (
            f.units.as_str(),
            f.step,
            f.dimension,
            f.nprocs,
            f.natoms,
            f.ntypes
        ),
        ("si", 30000, 3, 1, 200, 1)
    );
    assert_eq!(f.atom_style, "granular");
    assert_eq!(f.boundary, [['f'; 2]; 3]);
    assert_eq!((f.boxlo, f.boxhi), ([-0.03, -0.03, 0.0], [0.03, 0.03, 0.1]));
    assert_eq!(f.tilt, None);
    assert_eq!(f.groups[0].as_deref(), Some("all"));
    assert!(f.groups[1..].iter().all(Option::is_none));
    let pair = f.pair.as_ref().unwrap();
    assert_eq!(
        (pair.style.as_str(), pair.setflag.as_slice()),
        ("gran", &[1][..])
    );
    let ids: Vec<_> = f.fixes.iter().map(|x| x.id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "history_floor",
            "history_cyl",
            "pts",
            "pdd",
            "ins",
            "contacthistory"
        ]
    );
    let per: Vec<_> = f
        .peratom
        .iter()
        .map(|p| (p.id.as_str(), p.style.as_str()))
        .collect();
    assert_eq!(
        per,
        [
            ("history_floor", "property/atom"),
            ("history_cyl", "property/atom"),
            ("contacthistory", "contacthistory")
        ]
    );
    // Every value against LIGGGHTS' dump of the same step (17 digits: exact).
    let rows = dump_rows("bed.dump");
    assert_eq!(rows.len(), 200);
    let a = &f.atoms;
    let mut by_tag: Vec<usize> = (0..a.len()).collect();
    by_tag.sort_by_key(|&k| a.tag[k]);
    for (row, &k) in rows.iter().zip(&by_tag) {
        // id type x y z vx vy vz omegax omegay omegaz radius mass density
        let got = [
            a.tag[k] as f64,
            a.ty[k] as f64,
            a.x[k][0],
            a.x[k][1],
            a.x[k][2],
            a.v[k][0],
            a.v[k][1],
            a.v[k][2],
            a.omega[k][0],
            a.omega[k][1],
            a.omega[k][2],
            a.radius[k],
            a.rmass[k],
            a.density[k],
        ];
        assert_eq!(&got[..], &row[..], "particle {}", a.tag[k]);
        assert_eq!((a.mask[k], a.image[k]), (1, [0, 0, 0]));
    }
    // Contact histories: 405 pairs, each stored from both sides as mirror images.
    let h = f.contact_history().unwrap().unwrap();
    assert_eq!((h.width, h.entries.len() / 5), (3, 810));
    let mut seen = std::collections::BTreeMap::new();
    for c in h.entries.chunks_exact(5) {
        seen.insert((c[0] as u64, c[1] as u64), [c[2], c[3], c[4]]);
    }
    for (&(i, j), v) in &seen {
        assert_eq!(seen[&(j, i)], v.map(|x| -x), "pair {i} {j}");
    }
    // Wall histories: three values per particle; the floor holds some.
    let floor = &f.peratom[0];
    assert!((0..200).all(|k| floor.of(k).len() == 3));
    assert!((0..200).any(|k| floor.of(k).iter().any(|&x| x != 0.0)));
}

#[test]
fn two_processor_periodic_file_is_read_exactly() {
    let f = read_liggghts_restart(&data("bed2.restart")).unwrap();
    assert_eq!((f.step, f.nprocs, f.natoms, f.ntypes), (20000, 2, 120, 2));
    assert_eq!(f.boundary, [['p', 'p'], ['p', 'p'], ['f', 'f']]);
    assert_eq!(f.groups[1].as_deref(), Some("upper"));
    assert_eq!(f.pair.as_ref().unwrap().setflag, [1, 1, 1]);
    let rows = dump_rows("bed2.dump");
    let a = &f.atoms;
    let mut by_tag: Vec<usize> = (0..a.len()).collect();
    by_tag.sort_by_key(|&k| a.tag[k]);
    for (row, &k) in rows.iter().zip(&by_tag) {
        // id type ix iy iz x y z vx vy vz omegax omegay omegaz radius mass density
        let im = a.image[k].map(f64::from);
        let got = [
            a.tag[k] as f64,
            a.ty[k] as f64,
            im[0],
            im[1],
            im[2],
            a.x[k][0],
            a.x[k][1],
            a.x[k][2],
            a.v[k][0],
            a.v[k][1],
            a.v[k][2],
            a.omega[k][0],
            a.omega[k][1],
            a.omega[k][2],
            a.radius[k],
            a.rmass[k],
            a.density[k],
        ];
        assert_eq!(&got[..], &row[..], "particle {}", a.tag[k]);
    }
    // The particles flowed through the periodic faces: some image counts are not 0.
    assert!(a.image.iter().any(|i| i[0] != 0 && i[1] != 0));
    // LIGGGHTS: "27 atoms in group upper" (bit 1).
    assert_eq!(a.mask.iter().filter(|&&m| m & 2 != 0).count(), 27);
    assert!(a.mask.iter().all(|&m| m & 1 == 1));
}

fn err(bytes: &[u8]) -> String {
    parse_liggghts_restart(Path::new("x.restart"), bytes)
        .unwrap_err()
        .to_string()
}

fn check(bytes: &[u8], want: &str) {
    let e = err(bytes);
    assert!(e.contains("'x.restart'") && e.contains("at byte"), "{e}");
    assert!(e.contains(want), "wanted '{want}' in: {e}");
}

/// Offset of the atoms section of a one-processor file: the int count `n` of doubles
/// with the file ending right after them.
fn atoms_at(b: &[u8]) -> usize {
    (0..b.len() - 4)
        .find(|&o| {
            let n = i32::from_le_bytes(b[o..o + 4].try_into().unwrap());
            n > 0 && o + 4 + 8 * n as usize == b.len()
        })
        .unwrap()
}

#[test]
fn every_kind_of_bad_file_is_a_located_error() {
    let good = std::fs::read(data("bed.restart")).unwrap();
    // Truncated in the version string, the header, the groups, the fix list, the atoms.
    check(&good[..40], "truncated");
    check(&good[..300], "truncated");
    let at = atoms_at(&good);
    check(&good[..at + 2], "truncated");
    check(&good[..at + 4 + 8 * 100], "truncated");
    check(&good[..good.len() - 1], "truncated");
    // Truncated at every length: an error, never a panic.
    for n in (0..good.len()).step_by(61) {
        assert!(parse_liggghts_restart(Path::new("x"), &good[..n]).is_err());
    }
    // One more atom announced than the file holds.
    let mut more = good.clone();
    // The NATOMS item (flag 23) follows the atom style string.
    let natoms_at = good
        .windows(13)
        .position(|w| w == b"granular\0\x17\0\0\0")
        .unwrap()
        + 13;
    more[natoms_at..natoms_at + 8].copy_from_slice(&201i64.to_le_bytes());
    check(&more, "the header announces 201 atoms, the file holds 200");
    // A damaged atom length.
    let mut len = good.clone();
    len[at + 4..at + 12].copy_from_slice(&(1e6f64).to_le_bytes());
    check(&len, "atom 1 of the file: its length");
    // A fix block longer than its atom.
    let mut fixlen = good.clone();
    let first = at + 4 + 8 * 17;
    fixlen[first..first + 8].copy_from_slice(&(40.0f64).to_le_bytes());
    check(&fixlen, "the values of fix history_floor do not fit");
    // An unknown header item.
    let mut flag = good.clone();
    let units = good
        .windows(11)
        .position(|w| w == b"\x04\0\0\0\x03\0\0\0si\0")
        .unwrap();
    flag[units..units + 4].copy_from_slice(&77i32.to_le_bytes());
    check(&flag, "header item 77 is not one LIGGGHTS 3.8 writes");
    // A string length beyond the file.
    let mut s = good.clone();
    s[4..8].copy_from_slice(&4000i32.to_le_bytes());
    check(&s, "not a string");
    // Bytes after the last atom.
    let mut tail = good.clone();
    tail.extend_from_slice(&[0; 8]);
    check(&tail, "8 bytes follow the last processor's atoms");
    // A type beyond the file's types.
    let mut ty = good.clone();
    ty[at + 4 + 40..at + 4 + 48].copy_from_slice(&f64::from_bits(5).to_le_bytes());
    check(&ty, "its type is 5, the file has 1 types");
    // Not a LIGGGHTS file at all.
    check(
        b"rdem restart\n\0\0\0",
        "does not begin with LIGGGHTS' version string",
    );
}

#[test]
fn random_damage_never_panics() {
    let good = std::fs::read(data("bed2.restart")).unwrap();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..3000 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let mut b = good.clone();
        let k = (state % b.len() as u64) as usize;
        b[k] ^= 1 << (state >> 60 & 7);
        let _ = parse_liggghts_restart(Path::new("x"), &b);
    }
}

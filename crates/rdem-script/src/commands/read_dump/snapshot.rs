//! One snapshot of a native (text) dump file, as `dump custom` writes it.

use crate::error::Error;

/// A snapshot: its box and its per-atom columns.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Snapshot {
    /// Box lower corner.
    pub lo: [f64; 3],
    /// Box upper corner.
    pub hi: [f64; 3],
    /// Column labels (after `ITEM: ATOMS`).
    pub labels: Vec<String>,
    /// One row of numbers per atom.
    pub rows: Vec<Vec<f64>>,
}

impl Snapshot {
    /// The column labelled `label`.
    pub fn column(&self, label: &str) -> Option<usize> {
        self.labels.iter().position(|l| l == label)
    }
}

/// The first snapshot of step `nstep` in `text`.
pub(crate) fn find(text: &str, nstep: u64) -> Result<Snapshot, Error> {
    let mut lines = text.lines();
    let bad =
        |what: &str| Error::invalid(format!("the dump file is not a native dump file ({what})"));
    while let Some(l) = lines.next() {
        if l.trim_end() != "ITEM: TIMESTEP" {
            continue;
        }
        let step: u64 = lines
            .next()
            .and_then(|s| s.trim().parse().ok())
            .ok_or_else(|| bad("no step after ITEM: TIMESTEP"))?;
        if step != nstep {
            continue;
        }
        let mut n = None;
        let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
        loop {
            let l = lines.next().ok_or_else(|| bad("no ITEM: ATOMS"))?;
            if l.starts_with("ITEM: NUMBER OF ATOMS") {
                n = lines.next().and_then(|s| s.trim().parse::<usize>().ok());
                if n.is_none() {
                    return Err(bad("no atom count"));
                }
            } else if l.starts_with("ITEM: BOX BOUNDS") {
                if l.contains("xy") {
                    return Err("triclinic dump snapshots are not supported".into());
                }
                for a in 0..3 {
                    let v: Vec<f64> = lines
                        .next()
                        .unwrap_or("")
                        .split_whitespace()
                        .map(|w| w.parse())
                        .collect::<Result<_, _>>()
                        .map_err(|_| bad("a box bound is not a number"))?;
                    if v.len() < 2 {
                        return Err(bad("a box line has fewer than 2 numbers"));
                    }
                    (lo[a], hi[a]) = (v[0], v[1]);
                }
            } else if let Some(rest) = l.strip_prefix("ITEM: ATOMS") {
                let n = n.ok_or_else(|| bad("no ITEM: NUMBER OF ATOMS"))?;
                let labels: Vec<String> = rest.split_whitespace().map(String::from).collect();
                let mut rows = Vec::with_capacity(n);
                for k in 0..n {
                    let row: Vec<f64> = lines
                        .next()
                        .ok_or_else(|| bad(&format!("only {k} of {n} atom lines")))?
                        .split_whitespace()
                        .map(|w| w.parse())
                        .collect::<Result<_, _>>()
                        .map_err(|_| {
                            bad(&format!(
                                "atom line {} has a word that is not a number",
                                k + 1
                            ))
                        })?;
                    if row.len() < labels.len() {
                        return Err(bad(&format!(
                            "atom line {} has {} values for {} columns",
                            k + 1,
                            row.len(),
                            labels.len()
                        )));
                    }
                    rows.push(row);
                }
                return Ok(Snapshot {
                    lo,
                    hi,
                    labels,
                    rows,
                });
            }
        }
    }
    Err(format!("the dump file has no snapshot of step {nstep}").into())
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id x\n1 0.5\nITEM: TIMESTEP\n7\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff ff\n-1 2\n0 1\n0 3\nITEM: ATOMS id type x \n4 1 0.25 \n9 2 1.5 \n";

    #[test]
    fn finds_the_snapshot_of_a_step() {
        let s = find(TEXT, 7).unwrap();
        assert_eq!(s.lo, [-1.0, 0.0, 0.0]);
        assert_eq!(s.hi, [2.0, 1.0, 3.0]);
        assert_eq!(s.labels, ["id", "type", "x"]);
        assert_eq!(s.rows, vec![vec![4.0, 1.0, 0.25], vec![9.0, 2.0, 1.5]]);
        assert_eq!(s.column("x"), Some(2));
        assert_eq!(find(TEXT, 0).unwrap().rows, vec![vec![1.0, 0.5]]);
        assert!(find(TEXT, 3)
            .unwrap_err()
            .to_string()
            .contains("no snapshot of step 3"));
        assert!(find(&TEXT[..TEXT.len() - 10], 7)
            .unwrap_err()
            .to_string()
            .contains("only 1 of 2"));
    }
}

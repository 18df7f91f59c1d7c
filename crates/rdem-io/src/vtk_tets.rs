//! Tetrahedra from a legacy VTK file (`region mesh/tet file F`): an ASCII
//! `DATASET UNSTRUCTURED_GRID` with `POINTS`, `CELLS` and `CELL_TYPES`, as Gmsh writes
//! it. Cells of type 10 (tetrahedron) are kept; vertices, lines, triangles and other
//! cells in the same file are skipped, as LIGGGHTS does. Point and cell data after the
//! cells are not read. Not supported, each with an error that says so: binary files,
//! other data sets, and the `OFFSETS`/`CONNECTIVITY` cell arrays of VTK 5.

use std::path::Path;

use glam::DVec3;

/// VTK cell type number of a linear tetrahedron.
pub const VTK_TETRA: u32 = 10;

/// The points and tetrahedra of a VTK file.
#[derive(Debug, Clone, PartialEq)]
pub struct TetFile {
    /// Every point of the file, in its order.
    pub points: Vec<DVec3>,
    /// The cells of type 10, as indices into `points`, in the file's order.
    pub tets: Vec<[usize; 4]>,
    /// How many cells of other types were skipped.
    pub skipped: usize,
}

/// Why a VTK tetrahedral mesh could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TetVtkError {
    /// The file could not be opened or read.
    #[error("cannot read VTK file {path}: {source}")]
    Io {
        /// File name.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The contents are not what `region mesh/tet` reads.
    #[error("VTK file {path}, line {line}: {reason}")]
    Syntax {
        /// File name.
        path: String,
        /// Line number (1-based).
        line: usize,
        /// What is wrong.
        reason: String,
    },
}

/// Reads the tetrahedra of the legacy ASCII VTK file at `path`.
pub fn read_tet_vtk(path: &Path) -> Result<TetFile, TetVtkError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| TetVtkError::Io {
        path: name.clone(),
        source,
    })?;
    parse_tet_vtk(&bytes, &name)
}

/// Whitespace-separated words with their line numbers.
struct Words<'a> {
    words: Vec<(usize, &'a str)>,
    next: usize,
    /// Line of the last word read (or of the end of the file).
    line: usize,
    name: &'a str,
}

impl<'a> Words<'a> {
    /// Room for `n` values, no more than the words left can fill (a count in the file
    /// never makes a large allocation by itself).
    fn room<T>(&self, n: usize) -> Vec<T> {
        Vec::with_capacity(n.min(self.words.len() - self.next))
    }

    fn error(&self, line: usize, reason: impl Into<String>) -> TetVtkError {
        TetVtkError::Syntax {
            path: self.name.to_string(),
            line,
            reason: reason.into(),
        }
    }

    fn word(&mut self, what: &str) -> Result<&'a str, TetVtkError> {
        match self.words.get(self.next) {
            Some(&(line, w)) => {
                self.next += 1;
                self.line = line;
                Ok(w)
            }
            None => Err(self.error(self.line, format!("the file ends where {what} should be"))),
        }
    }

    fn count(&mut self, what: &str) -> Result<usize, TetVtkError> {
        let w = self.word(what)?;
        w.parse()
            .map_err(|_| self.error(self.line, format!("{what} must be a count, not '{w}'")))
    }

    fn number(&mut self, what: &str) -> Result<f64, TetVtkError> {
        let w = self.word(what)?;
        match w.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.error(
                self.line,
                format!("{what} must be a finite number, not '{w}'"),
            )),
        }
    }
}

/// Parses the VTK file `bytes` (`name` for messages).
pub fn parse_tet_vtk(bytes: &[u8], name: &str) -> Result<TetFile, TetVtkError> {
    let text = String::from_utf8_lossy(bytes);
    let lines: Vec<&str> = text.lines().collect();
    let err = |line: usize, reason: String| TetVtkError::Syntax {
        path: name.to_string(),
        line,
        reason,
    };
    // Header: version line, title, ASCII|BINARY, DATASET type.
    let header = |k: usize| lines.get(k).map_or("", |l| l.trim());
    if !header(0).starts_with("# vtk DataFile") {
        return Err(err(
            1,
            format!(
                "a legacy VTK file starts with '# vtk DataFile Version', not '{}'",
                header(0)
            ),
        ));
    }
    match header(2).to_ascii_uppercase().as_str() {
        "ASCII" => {}
        "BINARY" => {
            return Err(err(
                3,
                "binary VTK files are not supported; region mesh/tet reads ASCII VTK (write the mesh as ASCII)".into(),
            ))
        }
        other => return Err(err(3, format!("expected ASCII, found '{other}'"))),
    }
    let text_words = || {
        lines.iter().enumerate().skip(3).flat_map(|(i, l)| {
            let l = l.split('#').next().unwrap_or("");
            l.split_whitespace().map(move |w| (i + 1, w))
        })
    };
    let mut w = Words {
        words: text_words().collect(),
        next: 0,
        line: 4,
        name,
    };
    let kw = w.word("DATASET")?;
    let set = w.word("the data set type")?;
    if !kw.eq_ignore_ascii_case("DATASET") || !set.eq_ignore_ascii_case("UNSTRUCTURED_GRID") {
        return Err(w.error(
            w.line,
            format!(
                "expected 'DATASET UNSTRUCTURED_GRID', found '{kw} {set}'; region mesh/tet reads unstructured grids of tetrahedra only"
            ),
        ));
    }
    let mut points: Option<Vec<DVec3>> = None;
    let mut cells: Option<(usize, Vec<Vec<usize>>)> = None;
    let mut types: Option<(usize, Vec<u32>)> = None;
    while w.next < w.words.len() && (points.is_none() || cells.is_none() || types.is_none()) {
        let section = w.word("a section")?;
        let at = w.line;
        match section.to_ascii_uppercase().as_str() {
            "POINTS" => {
                let n = w.count("the number of points")?;
                let ty = w.word("the point type")?;
                if !matches!(ty.to_ascii_lowercase().as_str(), "float" | "double") {
                    return Err(w.error(
                        w.line,
                        format!("points must be float or double, not '{ty}'"),
                    ));
                }
                let mut p = w.room(n);
                for _ in 0..n {
                    p.push(DVec3::new(
                        w.number("a point's x")?,
                        w.number("a point's y")?,
                        w.number("a point's z")?,
                    ));
                }
                points = Some(p);
            }
            "CELLS" => {
                let n = w.count("the number of cells")?;
                let size = w.count("the size of the cell list")?;
                if matches!(w.words.get(w.next), Some((_, s)) if s.eq_ignore_ascii_case("OFFSETS"))
                {
                    return Err(w.error(
                        w.line,
                        "VTK 5 cell arrays (OFFSETS, CONNECTIVITY) are not supported; write the file in the VTK 4.2 legacy format",
                    ));
                }
                let mut list = w.room(n);
                let mut read = 0;
                for _ in 0..n {
                    let k = w.count("a cell's number of points")?;
                    let line = w.line;
                    let mut c = w.room(k);
                    for _ in 0..k {
                        c.push(w.count("a cell's point index")?);
                    }
                    if w.line != line {
                        return Err(w.error(
                            line,
                            format!("this cell should list {k} points on its line"),
                        ));
                    }
                    read += k + 1;
                    list.push(c);
                }
                if read != size {
                    return Err(w.error(
                        at,
                        format!("CELLS {n} {size}: the cells hold {read} numbers, not {size}"),
                    ));
                }
                cells = Some((at, list));
            }
            "CELL_TYPES" => {
                let n = w.count("the number of cell types")?;
                let mut t = w.room(n);
                for _ in 0..n {
                    let v = w.count("a cell type")?;
                    t.push(v as u32);
                }
                types = Some((w.line, t));
            }
            "POINT_DATA" | "CELL_DATA" | "FIELD" | "METADATA" => break,
            other => {
                return Err(w.error(
                    at,
                    format!(
                        "unexpected '{other}': expected POINTS, CELLS or CELL_TYPES of an unstructured grid"
                    ),
                ))
            }
        }
    }
    let end = w.line;
    let points = points.ok_or_else(|| err(end, "the file has no POINTS".into()))?;
    let (cells_line, cells) = cells.ok_or_else(|| err(end, "the file has no CELLS".into()))?;
    let (types_line, types) = types.ok_or_else(|| err(end, "the file has no CELL_TYPES".into()))?;
    if types.len() != cells.len() {
        return Err(err(
            types_line,
            format!(
                "CELL_TYPES lists {} types for {} cells",
                types.len(),
                cells.len()
            ),
        ));
    }
    let mut tets = Vec::new();
    let mut skipped = 0;
    for (k, (c, &t)) in cells.iter().zip(&types).enumerate() {
        if t != VTK_TETRA {
            skipped += 1;
            continue;
        }
        if c.len() != 4 {
            return Err(err(
                cells_line + 1 + k,
                format!(
                    "cell {k} is a tetrahedron (type 10) but lists {} points",
                    c.len()
                ),
            ));
        }
        if let Some(&i) = c.iter().find(|&&i| i >= points.len()) {
            return Err(err(
                cells_line + 1 + k,
                format!(
                    "cell {k} names point {i}, but there are {} points",
                    points.len()
                ),
            ));
        }
        tets.push([c[0], c[1], c[2], c[3]]);
    }
    if tets.is_empty() {
        return Err(err(
            types_line,
            "the file has no tetrahedra (cells of type 10)".into(),
        ));
    }
    Ok(TetFile {
        points,
        tets,
        skipped,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "# vtk DataFile Version 2.0\nmesh\nASCII\nDATASET UNSTRUCTURED_GRID\n\
        POINTS 5 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n\n\
        CELLS 3 10\n1 0\n2 0 1\n4 0 1 2 3\nCELL_TYPES 3\n1\n3\n10\nCELL_DATA 3\n";

    #[test]
    fn reads_tetrahedra_and_skips_other_cells() {
        let f = parse_tet_vtk(GOOD.as_bytes(), "t.vtk").unwrap();
        assert_eq!(f.points.len(), 5);
        assert_eq!(f.tets, vec![[0, 1, 2, 3]]);
        assert_eq!(f.skipped, 2);
    }

    fn message(text: &str) -> String {
        parse_tet_vtk(text.as_bytes(), "t.vtk")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn bad_files_name_their_line() {
        let m = message(&GOOD.replace("ASCII", "BINARY"));
        assert!(m.contains("line 3") && m.contains("binary"), "{m}");
        let m = message(&GOOD.replace("UNSTRUCTURED_GRID", "POLYDATA"));
        assert!(m.contains("line 4") && m.contains("POLYDATA"), "{m}");
        let m = message(&GOOD.replace("0 0 1\n", "0 zero 1\n"));
        assert!(m.contains("line 9") && m.contains("'zero'"), "{m}");
        let m = message(&GOOD.replace("4 0 1 2 3", "4 0 1 2 7"));
        assert!(m.contains("line 15") && m.contains("point 7"), "{m}");
        let m = message(&GOOD.replace("\n10\n", "\n5\n"));
        assert!(m.contains("no tetrahedra"), "{m}");
        let m = message(&GOOD.replace("CELLS 3 10", "CELLS 3 13"));
        assert!(m.contains("line 12") && m.contains("hold 10"), "{m}");
        let m = message("solid x\n");
        assert!(m.contains("line 1"), "{m}");
    }
}

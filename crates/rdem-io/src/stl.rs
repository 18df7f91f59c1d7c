//! STL files (`fix mesh/surface file F`): binary STL through the `stl_io` crate, and ASCII
//! STL read here in double precision, as LIGGGHTS reads it (`stl_io` parses ASCII
//! coordinates into `f32`, which would move a wall written as `0.05` by 7e-10 m, enough to
//! change a contact force in its sixth digit). The result is a triangle soup; merging and
//! topology are the engine's ([`rdem::mesh::TriMesh`]).

use std::path::Path;

use glam::DVec3;

/// A triangle of an STL file, corners in the file's order.
pub type Triangle = [DVec3; 3];

/// Why an STL file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum StlError {
    /// The file could not be opened or read.
    #[error("cannot read STL file {path}: {source}")]
    Io {
        /// File name.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The contents are not a valid STL file.
    #[error("STL file {path}, line {line}: {reason}")]
    Syntax {
        /// File name.
        path: String,
        /// Line number (1-based; 0 for a binary file).
        line: usize,
        /// What is wrong.
        reason: String,
    },
}

/// The triangles of an STL file, each with the number by which LIGGGHTS'
/// `element_exclusion_list` names it.
#[derive(Debug, Clone, PartialEq)]
pub struct NumberedStl {
    /// The triangles, in the file's order.
    pub tris: Vec<Triangle>,
    /// One number per triangle: in an ASCII file the 1-based line of its `facet` line
    /// (every line counts, blank and comment lines too), in a binary file its 1-based
    /// position (LIGGGHTS 3.8 numbers both so).
    pub numbers: Vec<usize>,
    /// Whether the file is binary.
    pub binary: bool,
}

/// Reads the triangles of the ASCII or binary STL file at `path`.
pub fn read_stl(path: &Path) -> Result<Vec<Triangle>, StlError> {
    read_stl_numbered(path).map(|s| s.tris)
}

/// Reads the STL file at `path` as [`read_stl`] does, with each triangle's number.
pub fn read_stl_numbered(path: &Path) -> Result<NumberedStl, StlError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| StlError::Io {
        path: name.clone(),
        source,
    })?;
    parse_stl_numbered(&bytes, &name)
}

/// Parses STL `bytes` (`name` for messages). A file whose size is exactly 84 + 50 n bytes
/// for the n its header gives is binary (a binary header may also begin with `solid`);
/// otherwise it must be ASCII.
pub fn parse_stl(bytes: &[u8], name: &str) -> Result<Vec<Triangle>, StlError> {
    parse_stl_numbered(bytes, name).map(|s| s.tris)
}

/// Parses STL `bytes` as [`parse_stl`] does, with each triangle's number.
pub fn parse_stl_numbered(bytes: &[u8], name: &str) -> Result<NumberedStl, StlError> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if bytes.len() == 84 + 50 * n {
            let tris = parse_binary(bytes, name)?;
            return Ok(NumberedStl {
                numbers: (1..=tris.len()).collect(),
                tris,
                binary: true,
            });
        }
    }
    let text = std::str::from_utf8(bytes).map_err(|_| StlError::Syntax {
        path: name.into(),
        line: 0,
        reason: "neither a binary STL file (size does not match its triangle count) nor ASCII text"
            .into(),
    })?;
    let (tris, numbers) = parse_ascii(text, name)?;
    Ok(NumberedStl {
        tris,
        numbers,
        binary: false,
    })
}

fn parse_binary(bytes: &[u8], name: &str) -> Result<Vec<Triangle>, StlError> {
    let mut cursor = std::io::Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| StlError::Syntax {
        path: name.into(),
        line: 0,
        reason: format!("binary STL: {e}"),
    })?;
    let mut out = Vec::new();
    for t in reader {
        let t = t.map_err(|e| StlError::Syntax {
            path: name.into(),
            line: 0,
            reason: format!("binary STL: {e}"),
        })?;
        out.push(
            t.vertices
                .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)),
        );
    }
    Ok(out)
}

/// The triangles of ASCII STL `text` and the line of each one's `facet` word (of its
/// `outer loop` line if it has none).
fn parse_ascii(text: &str, name: &str) -> Result<(Vec<Triangle>, Vec<usize>), StlError> {
    let err = |line: usize, reason: String| StlError::Syntax {
        path: name.into(),
        line,
        reason,
    };
    let mut out = Vec::new();
    let mut numbers = Vec::new();
    let mut facet_line = None;
    let mut corners: Vec<DVec3> = Vec::with_capacity(3);
    let mut in_solid = false;
    let mut in_loop = false;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let mut w = raw.split_whitespace();
        let Some(word) = w.next() else {
            continue;
        };
        match word {
            // A comment line (LIGGGHTS 3.8 reads files that have them, e.g. a header).
            _ if word.starts_with('#') => {}
            "solid" => {
                if in_solid {
                    return Err(err(line, "'solid' inside a solid".into()));
                }
                in_solid = true;
            }
            "endsolid" => in_solid = false,
            "facet" | "endfacet" => {
                if !in_solid {
                    return Err(err(line, format!("'{word}' outside 'solid ... endsolid'")));
                }
                facet_line = (word == "facet").then_some(line);
            }
            "outer" => {
                corners.clear();
                in_loop = true;
                facet_line = facet_line.or(Some(line));
            }
            "vertex" => {
                if !in_loop {
                    return Err(err(line, "'vertex' outside 'outer loop ... endloop'".into()));
                }
                let mut v = [0.0; 3];
                for c in &mut v {
                    let t = w
                        .next()
                        .ok_or_else(|| err(line, "'vertex' needs three numbers".into()))?;
                    *c = t
                        .parse()
                        .map_err(|_| err(line, format!("'{t}' is not a number")))?;
                }
                corners.push(DVec3::from_array(v));
            }
            "endloop" => {
                if corners.len() != 3 {
                    return Err(err(
                        line,
                        format!(
                            "a facet has {} vertices; STL facets are triangles",
                            corners.len()
                        ),
                    ));
                }
                out.push([corners[0], corners[1], corners[2]]);
                numbers.push(facet_line.take().unwrap_or(line));
                in_loop = false;
            }
            _ => {
                return Err(err(
                    line,
                    format!(
                        "unexpected '{word}' (an ASCII STL file has solid, facet normal, outer loop, vertex, endloop, endfacet, endsolid)"
                    ),
                ))
            }
        }
    }
    if in_loop {
        return Err(err(
            text.lines().count(),
            "the file ends inside a facet".into(),
        ));
    }
    if out.is_empty() {
        return Err(err(0, "no triangle in the file".into()));
    }
    Ok((out, numbers))
}

/// ASCII STL text of `tris` (with their unit normals `normals`) as one solid named
/// `LIGGGHTS_STL_EXPORT`, numbers in C's `%g`, laid out as LIGGGHTS' `dump mesh/stl`
/// writes it.
pub fn format_ascii_stl(tris: &[Triangle], normals: &[DVec3]) -> String {
    use std::fmt::Write as _;
    let g = crate::Printf::default_float();
    let f = |v: f64| g.format(crate::Value::Float(v));
    let mut s = String::from("solid LIGGGHTS_STL_EXPORT\n");
    for (t, n) in tris.iter().zip(normals) {
        let _ = writeln!(s, "  facet normal {} {} {}", f(n.x), f(n.y), f(n.z));
        s.push_str("    outer loop\n");
        for p in t {
            let _ = writeln!(s, "      vertex {} {} {}", f(p.x), f(p.y), f(p.z));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid LIGGGHTS_STL_EXPORT\n");
    s
}

/// Writes [`format_ascii_stl`] to `path` atomically (creating parent directories).
pub fn write_ascii_stl(
    path: &Path,
    tris: &[Triangle],
    normals: &[DVec3],
) -> Result<(), crate::IoError> {
    crate::write_atomic(path, format_ascii_stl(tris, normals).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &str = "solid test
  facet normal 0 0 1
    outer loop
      vertex 0 0 0.05
      vertex 1 0 0.05
      vertex 1 1 0.05
    endloop
  endfacet
endsolid test
";

    /// ASCII coordinates are read in double precision (0.05 exactly as `str::parse`).
    #[test]
    fn ascii_in_double_precision() {
        let t = parse_stl(ASCII.as_bytes(), "t.stl").unwrap();
        assert_eq!(t.len(), 1);
        assert_eq!(t[0][2], DVec3::new(1.0, 1.0, 0.05));
    }

    /// Lines starting with `#` are comments, before `solid` and between facets (LIGGGHTS
    /// 3.8 reads such files); any other unknown word is still an error.
    #[test]
    fn comment_lines_are_skipped() {
        let text = format!(
            "# ======\n#backwall.stl:\n{}",
            ASCII.replace("  endfacet", "  endfacet\n  # note")
        );
        let t = parse_stl(text.as_bytes(), "t.stl").unwrap();
        assert_eq!(t, parse_stl(ASCII.as_bytes(), "t.stl").unwrap());
        let bad = format!("% header\n{ASCII}");
        assert!(parse_stl(bad.as_bytes(), "t.stl").is_err());
    }

    /// A binary file written by `stl_io` reads back, also when its header starts with
    /// `solid`.
    #[test]
    fn binary_round_trip() {
        let tri = stl_io::Triangle {
            normal: stl_io::Normal::new([0.0, 0.0, 1.0]),
            vertices: [
                stl_io::Vertex::new([0.0, 0.0, 0.5]),
                stl_io::Vertex::new([1.0, 0.0, 0.5]),
                stl_io::Vertex::new([0.0, 1.0, 0.5]),
            ],
        };
        let mut bytes = Vec::new();
        stl_io::write_stl(&mut bytes, [tri, tri].iter()).unwrap();
        bytes[..5].copy_from_slice(b"solid");
        let t = parse_stl(&bytes, "b.stl").unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t[1][1], DVec3::new(1.0, 0.0, 0.5));
    }

    /// Broken files give the line and the reason.
    #[test]
    fn errors_name_the_line() {
        let bad = ASCII.replace("vertex 1 0 0.05", "vertex 1 zero 0.05");
        let e = parse_stl(bad.as_bytes(), "t.stl").unwrap_err().to_string();
        assert!(e.contains("line 5") && e.contains("'zero'"), "{e}");
        let quad = ASCII.replace(
            "      vertex 1 1 0.05\n",
            "      vertex 1 1 0.05\n      vertex 0 1 0.05\n",
        );
        let e = parse_stl(quad.as_bytes(), "t.stl").unwrap_err().to_string();
        assert!(e.contains("4 vertices"), "{e}");
        assert!(parse_stl(b"\xff\xfe", "x.stl").is_err());
    }

    /// Each triangle's number is the line of its `facet` word in an ASCII file (comment
    /// and blank lines count), its position in a binary one.
    #[test]
    fn numbered_by_facet_line_or_position() {
        let text = format!(
            "# header\n{}",
            ASCII.replace("  endfacet\n", "  endfacet\n\n  # x\n")
        );
        let two = text.replace(
            "endsolid",
            "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid",
        );
        let s = parse_stl_numbered(two.as_bytes(), "t.stl").unwrap();
        assert_eq!((s.numbers, s.binary), (vec![3, 12], false));
        let mut bytes = Vec::new();
        let tri = stl_io::Triangle {
            normal: stl_io::Normal::new([0.0, 0.0, 1.0]),
            vertices: [
                stl_io::Vertex::new([0.0, 0.0, 0.0]),
                stl_io::Vertex::new([1.0, 0.0, 0.0]),
                stl_io::Vertex::new([0.0, 1.0, 0.0]),
            ],
        };
        stl_io::write_stl(&mut bytes, [tri, tri, tri].iter()).unwrap();
        let s = parse_stl_numbered(&bytes, "b.stl").unwrap();
        assert_eq!((s.numbers, s.binary), (vec![1, 2, 3], true));
    }

    /// What dump mesh/stl writes reads back as the same triangles (to %g's 6 digits).
    #[test]
    fn ascii_export_reads_back() {
        let tris = vec![
            [
                DVec3::ZERO,
                DVec3::new(0.1, 0.0, 0.0),
                DVec3::new(0.0, 0.2, 0.0),
            ],
            [
                DVec3::new(0.1, 0.0, 0.0),
                DVec3::new(0.1, 0.2, 0.0),
                DVec3::new(0.0, 0.2, 1e-3),
            ],
        ];
        let normals = vec![DVec3::Z, DVec3::Z];
        let text = format_ascii_stl(&tris, &normals);
        assert!(text.starts_with("solid LIGGGHTS_STL_EXPORT\n  facet normal 0 0 1\n"));
        let back = parse_stl(text.as_bytes(), "export").unwrap();
        assert_eq!(back, tris);
    }
}

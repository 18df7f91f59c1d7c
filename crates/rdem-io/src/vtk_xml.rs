//! VTK XML files (`.vtu`, `.vtp`, `.vtr`) laid out as LIGGGHTS 3.8 writes them through
//! VTK 9's XML writers, written here without the VTK library:
//!
//! ```text
//! <?xml version="1.0"?>
//! <VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian" header_type="UInt32">
//!   <UnstructuredGrid>
//!     <Piece NumberOfPoints="2" NumberOfCells="2">
//!       <PointData>
//!         <DataArray type="Float64" Name="radii" format="ascii" RangeMin="0.001" RangeMax="0.002">
//!           0.001 0.002
//!         </DataArray>
//!         ...
//! ```
//!
//! * Data is inline (no `AppendedData` section), in one of four [`XmlEncoding`]s: `ascii`
//!   (6 values a line; doubles in the shortest form that reads back exactly, fixed
//!   notation for 1e-7 ≤ |x| < 1e21 and `8.4e-16` style outside, as VTK prints them;
//!   `Float32` values are printed as the double they widen to), `binary` (base64 of a
//!   UInt32 byte count followed by the little-endian values), and the two compressed
//!   forms, `compressor="vtkZLibDataCompressor"` / `"vtkLZ4DataCompressor"`: the values
//!   cut into 32 KiB blocks, each compressed on its own (zlib stream, resp. raw LZ4
//!   block), written as base64 of the UInt32 header `[blocks, 32768, size of the last
//!   block (0 = full), compressed size of each block…]` immediately followed by base64
//!   of the concatenated compressed blocks.
//! * Every array carries `RangeMin`/`RangeMax` (of the values, or of the vector norms
//!   for arrays of several components, which also get an `L2_NORM_RANGE` information
//!   key with the norms as `%.11g`); an empty array has the range `1e+299`/`-1e+299`.
//!
//! [`format_atom_vtu`] is `dump atom/vtk`; [`format_vtp`], [`format_custom_vtu`] and
//! [`format_bounding_box_vtr`] are `dump custom/vtk` with a `.vtp` or `.vtu` name.

use std::fmt::Write as _;
use std::io::Write as _;

use base64::engine::general_purpose::STANDARD as BASE64;
use base64::Engine as _;
use rdem::{Domain, Particles};

use crate::fields::Column;
use crate::printf::{Printf, Value};
use crate::vtk_legacy::{VtkArray, VtkSource};

/// How the values of the data arrays are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum XmlEncoding {
    /// `format="ascii"` (LIGGGHTS' default).
    #[default]
    Ascii,
    /// `format="binary"`, base64, uncompressed (`dump_modify binary yes`).
    Binary,
    /// Base64 of zlib-compressed blocks (`dump_modify compressor zlib`).
    Zlib,
    /// Base64 of LZ4-compressed blocks (`dump_modify compressor lz4`).
    Lz4,
}

impl XmlEncoding {
    /// The `compressor` attribute of the `VTKFile` element, if any.
    pub fn compressor(self) -> Option<&'static str> {
        match self {
            XmlEncoding::Zlib => Some("vtkZLibDataCompressor"),
            XmlEncoding::Lz4 => Some("vtkLZ4DataCompressor"),
            _ => None,
        }
    }
}

/// VTK's block size for compressed data.
const BLOCK: usize = 32768;

/// The values of one data array.
#[derive(Debug, Clone, PartialEq)]
pub enum XmlData {
    /// `Float64`.
    F64(Vec<f64>),
    /// `Float32`.
    F32(Vec<f32>),
    /// `Int32`.
    I32(Vec<i32>),
    /// `Int64`.
    I64(Vec<i64>),
    /// `UInt8`.
    U8(Vec<u8>),
}

impl XmlData {
    fn type_name(&self) -> &'static str {
        match self {
            XmlData::F64(_) => "Float64",
            XmlData::F32(_) => "Float32",
            XmlData::I32(_) => "Int32",
            XmlData::I64(_) => "Int64",
            XmlData::U8(_) => "UInt8",
        }
    }

    fn len(&self) -> usize {
        match self {
            XmlData::F64(v) => v.len(),
            XmlData::F32(v) => v.len(),
            XmlData::I32(v) => v.len(),
            XmlData::I64(v) => v.len(),
            XmlData::U8(v) => v.len(),
        }
    }

    fn get(&self, k: usize) -> f64 {
        match self {
            XmlData::F64(v) => v[k],
            XmlData::F32(v) => v[k] as f64,
            XmlData::I32(v) => v[k] as f64,
            XmlData::I64(v) => v[k] as f64,
            XmlData::U8(v) => v[k] as f64,
        }
    }

    fn bytes(&self) -> Vec<u8> {
        match self {
            XmlData::F64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            XmlData::F32(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            XmlData::I32(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            XmlData::I64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            XmlData::U8(v) => v.clone(),
        }
    }
}

/// One named data array.
#[derive(Debug, Clone, PartialEq)]
pub struct XmlArray {
    /// `Name`.
    pub name: String,
    /// `NumberOfComponents` (written when > 1).
    pub components: usize,
    /// The values, tuple by tuple.
    pub data: XmlData,
}

impl XmlArray {
    /// A named array.
    pub fn new(name: impl Into<String>, components: usize, data: XmlData) -> Self {
        Self {
            name: name.into(),
            components,
            data,
        }
    }
}

/// Writes `x` as VTK's XML writers print a double: the shortest digits that read back
/// exactly, in fixed notation when 1e-7 ≤ |x| < 1e21, else as `1.5e-16` / `1e+299`.
pub fn write_number(out: &mut String, x: f64) {
    if x == 0.0 {
        out.push_str(if x.is_sign_negative() { "-0" } else { "0" });
        return;
    }
    if !x.is_finite() {
        out.push_str(if x.is_nan() {
            "nan"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        });
        return;
    }
    // ryu prints the same shortest digits, in fixed notation for 1e-5 ≤ |x| < 1e16
    // (integers with a ".0" to drop), else as "1.5e-7" / "1e16".
    let mut buf = ryu::Buffer::new();
    let s = buf.format_finite(x);
    let Some(e) = s.find('e') else {
        out.push_str(s.strip_suffix(".0").unwrap_or(s));
        return;
    };
    let (mant, exp) = (&s[..e], &s[e + 1..]);
    let exp: i32 = exp.parse().expect("integer exponent");
    let (sign, mant) = match mant.strip_prefix('-') {
        Some(m) => ("-", m),
        None => ("", mant),
    };
    let mut digits = [0u8; 24];
    let mut k = 0;
    for &b in mant.as_bytes().iter().filter(|&&b| b != b'.') {
        digits[k] = b;
        k += 1;
    }
    let digits = std::str::from_utf8(&digits[..k]).expect("ASCII digits");
    out.push_str(sign);
    compose(out, digits, exp + 1);
}

/// Writes the decimal `digits` with the decimal point at position `n` (value =
/// 0.digits × 10^n) as JavaScript's `Number.prototype.toString` does.
fn compose(out: &mut String, digits: &str, n: i32) {
    let k = digits.len() as i32;
    if k <= n && n <= 21 {
        out.push_str(digits);
        out.extend(std::iter::repeat_n('0', (n - k) as usize));
    } else if 0 < n && n <= 21 {
        out.push_str(&digits[..n as usize]);
        out.push('.');
        out.push_str(&digits[n as usize..]);
    } else if -6 < n && n <= 0 {
        out.push_str("0.");
        out.extend(std::iter::repeat_n('0', (-n) as usize));
        out.push_str(digits);
    } else {
        out.push_str(&digits[..1]);
        if k > 1 {
            out.push('.');
            out.push_str(&digits[1..]);
        }
        out.push('e');
        out.push(if n - 1 < 0 { '-' } else { '+' });
        write_int(out, (n - 1).abs() as i64);
    }
}

/// [`write_number`] for any finite non-zero `x`, from Rust's own shortest digits (the
/// tests' oracle).
#[cfg(test)]
fn write_number_general(out: &mut String, x: f64) {
    // Rust's {:e} gives the shortest round-trip digits: "1.2345e-5".
    let s = format!("{:e}", x.abs());
    let (mant, exp) = s.split_once('e').expect("{:e} has an exponent");
    let exp: i32 = exp.parse().expect("integer exponent");
    let digits: String = mant.chars().filter(|c| *c != '.').collect();
    if x < 0.0 {
        out.push('-');
    }
    compose(out, &digits, exp + 1);
}

fn number(x: f64) -> String {
    let mut s = String::new();
    write_number(&mut s, x);
    s
}

/// The data of one array as VTK's binary formats store it.
fn encode_binary(out: &mut String, raw: &[u8], enc: XmlEncoding) {
    match enc {
        XmlEncoding::Ascii => unreachable!("ascii is not encoded"),
        XmlEncoding::Binary => {
            let mut buf = Vec::with_capacity(raw.len() + 4);
            buf.extend_from_slice(&(raw.len() as u32).to_le_bytes());
            buf.extend_from_slice(raw);
            BASE64.encode_string(&buf, out);
        }
        XmlEncoding::Zlib | XmlEncoding::Lz4 => {
            let blocks: Vec<Vec<u8>> = raw
                .chunks(BLOCK)
                .map(|b| {
                    if enc == XmlEncoding::Zlib {
                        let mut z = flate2::write::ZlibEncoder::new(
                            Vec::with_capacity(b.len() / 2 + 16),
                            flate2::Compression::new(5),
                        );
                        z.write_all(b).expect("writing to memory");
                        z.finish().expect("writing to memory")
                    } else {
                        lz4_flex::block::compress(b)
                    }
                })
                .collect();
            let mut header = vec![
                blocks.len() as u32,
                BLOCK as u32,
                (raw.len() % BLOCK) as u32,
            ];
            header.extend(blocks.iter().map(|b| b.len() as u32));
            let header: Vec<u8> = header.iter().flat_map(|h| h.to_le_bytes()).collect();
            BASE64.encode_string(&header, out);
            BASE64.encode_string(blocks.concat(), out);
        }
    }
}

/// Writes `values` 6 a line, each line indented by `indent`.
fn write_lines<T: Copy>(out: &mut String, values: &[T], indent: usize, f: impl Fn(&mut String, T)) {
    for line in values.chunks(6) {
        out.extend(std::iter::repeat_n(' ', indent));
        for (j, &v) in line.iter().enumerate() {
            if j > 0 {
                out.push(' ');
            }
            f(out, v);
        }
        out.push('\n');
    }
}

/// Writes all values of `data` in VTK's ASCII layout.
fn write_ascii_values(out: &mut String, data: &XmlData, indent: usize) {
    match data {
        XmlData::F64(v) => write_lines(out, v, indent, write_number),
        XmlData::F32(v) => write_lines(out, v, indent, |o, x| write_number(o, x as f64)),
        XmlData::I32(v) => write_lines(out, v, indent, |o, x| write_int(o, x as i64)),
        XmlData::I64(v) => write_lines(out, v, indent, write_int),
        XmlData::U8(v) => write_lines(out, v, indent, |o, x| write_int(o, x as i64)),
    }
}

/// Appends the decimal digits of `v`.
fn write_int(out: &mut String, v: i64) {
    let mut buf = [0u8; 20];
    let mut k = buf.len();
    let mut u = v.unsigned_abs();
    loop {
        k -= 1;
        buf[k] = b'0' + (u % 10) as u8;
        u /= 10;
        if u == 0 {
            break;
        }
    }
    if v < 0 {
        out.push('-');
    }
    out.push_str(std::str::from_utf8(&buf[k..]).expect("ASCII digits"));
}

/// Writes one `<DataArray>` element at `indent` spaces.
fn write_array(out: &mut String, indent: usize, a: &XmlArray, enc: XmlEncoding) {
    write_array_keyed(out, indent, a, enc, false);
}

/// [`write_array`]; with `key_if_empty`, an empty array of several components also gets
/// its `L2_NORM_RANGE` key (of `1e+299`, `-1e+299`), as in LIGGGHTS' force-chain files.
pub(crate) fn write_array_keyed(
    out: &mut String,
    indent: usize,
    a: &XmlArray,
    enc: XmlEncoding,
    key_if_empty: bool,
) {
    let pad = " ".repeat(indent);
    let n = a.data.len();
    let nc = a.components.max(1);
    let ntuples = n / nc;
    // Range: of the values, or of the tuple norms.
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for t in 0..ntuples {
        let v = if nc == 1 {
            a.data.get(t)
        } else {
            (0..nc)
                .map(|c| a.data.get(t * nc + c).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if ntuples == 0 {
        (lo, hi) = (1e299, -1e299);
    }
    let _ = write!(
        out,
        "{pad}<DataArray type=\"{}\" Name=\"{}\"",
        a.data.type_name(),
        xml_escape(&a.name)
    );
    if nc > 1 {
        let _ = write!(out, " NumberOfComponents=\"{nc}\"");
    }
    let format = if enc == XmlEncoding::Ascii {
        "ascii"
    } else {
        "binary"
    };
    let _ = writeln!(
        out,
        " format=\"{format}\" RangeMin=\"{}\" RangeMax=\"{}\">",
        number(lo),
        number(hi)
    );
    if enc == XmlEncoding::Ascii {
        write_ascii_values(out, &a.data, indent + 2);
    } else {
        out.push_str(&pad);
        out.push_str("  ");
        encode_binary(out, &a.data.bytes(), enc);
        out.push('\n');
    }
    if nc > 1 && (ntuples > 0 || key_if_empty) {
        let g = Printf::parse("%.11g").expect("valid");
        let _ = writeln!(
            out,
            "{pad}  <InformationKey name=\"L2_NORM_RANGE\" location=\"vtkDataArray\" length=\"2\">"
        );
        for (k, v) in [lo, hi].into_iter().enumerate() {
            let _ = write!(out, "{pad}    <Value index=\"{k}\">\n{pad}      ");
            g.write(out, Value::Float(v));
            let _ = writeln!(out, "\n{pad}    </Value>");
        }
        let _ = writeln!(out, "{pad}  </InformationKey>");
    }
    let _ = writeln!(out, "{pad}</DataArray>");
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The XML declaration and the `VTKFile` start tag of a `kind` file.
pub(crate) fn file_header(out: &mut String, kind: &str, enc: XmlEncoding) {
    let _ = write!(
        out,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{kind}\" version=\"0.1\" \
         byte_order=\"LittleEndian\" header_type=\"UInt32\""
    );
    if let Some(c) = enc.compressor() {
        let _ = write!(out, " compressor=\"{c}\"");
    }
    out.push_str(">\n");
}

/// The positions of `selection` as a `Float32` `Points` array.
fn float32_points(p: &Particles, selection: &[usize]) -> XmlArray {
    XmlArray::new(
        "Points",
        3,
        XmlData::F32(
            selection
                .iter()
                .flat_map(|&i| p.x[i].to_array())
                .map(|v| v as f32)
                .collect(),
        ),
    )
}

/// The points of `selection` as `Float32`, and their vertex cells.
fn points_and_vertices(p: &Particles, selection: &[usize]) -> (XmlArray, XmlArray, XmlArray) {
    let n = selection.len();
    let points = float32_points(p, selection);
    let conn = XmlArray::new("connectivity", 1, XmlData::I64((0..n as i64).collect()));
    let offsets = XmlArray::new("offsets", 1, XmlData::I64((1..=n as i64).collect()));
    (points, conn, offsets)
}

/// The point-data arrays of `dump atom/vtk`, in LIGGGHTS' order: `radii`, `id`, `type`,
/// `proc`, `mass`, `velocity_lin`, `velocity_ang`, `force`, with `rank` as `proc` of
/// every particle.
pub fn atom_vtk_arrays(p: &Particles, selection: &[usize], rank: i32) -> Vec<XmlArray> {
    atom_vtk_arrays_with(p, selection, &|_| rank)
}

/// [`atom_vtk_arrays`] with the owning rank of each particle: `procs[i]` is the `proc` of
/// particle index `i` (particles gathered from every rank onto the writing one).
pub fn atom_vtk_arrays_procs(p: &Particles, selection: &[usize], procs: &[i32]) -> Vec<XmlArray> {
    atom_vtk_arrays_with(p, selection, &|i| procs[i])
}

fn atom_vtk_arrays_with(
    p: &Particles,
    selection: &[usize],
    proc_of: &dyn Fn(usize) -> i32,
) -> Vec<XmlArray> {
    let f64s = |f: &dyn Fn(usize) -> f64| XmlData::F64(selection.iter().map(|&i| f(i)).collect());
    let vec3 = |v: &[rdem::DVec3]| {
        XmlData::F64(
            selection
                .iter()
                .flat_map(|&i| v[i].to_array())
                .collect::<Vec<f64>>(),
        )
    };
    vec![
        XmlArray::new("radii", 1, f64s(&|i| p.radius[i])),
        XmlArray::new(
            "id",
            1,
            XmlData::I32(selection.iter().map(|&i| p.tag[i] as i32).collect()),
        ),
        XmlArray::new(
            "type",
            1,
            XmlData::I32(selection.iter().map(|&i| p.ty[i] as i32).collect()),
        ),
        XmlArray::new(
            "proc",
            1,
            XmlData::I32(selection.iter().map(|&i| proc_of(i)).collect()),
        ),
        XmlArray::new("mass", 1, f64s(&|i| p.rmass[i])),
        XmlArray::new("velocity_lin", 3, vec3(&p.v)),
        XmlArray::new("velocity_ang", 3, vec3(&p.omega)),
        XmlArray::new("force", 3, vec3(&p.f)),
    ]
}

/// The data of one `dump atom/vtk` snapshot, copied out of the particles so that it can
/// be formatted and written while the simulation goes on.
#[derive(Debug, Clone, PartialEq)]
pub struct AtomVtu {
    /// The point data ([`atom_vtk_arrays`]).
    pub arrays: Vec<XmlArray>,
    /// The points, `Float32`.
    pub points: XmlArray,
}

impl AtomVtu {
    /// The snapshot of the particles `selection` (in this order; the dump sorts by id),
    /// with `rank` as `proc`.
    pub fn capture(p: &Particles, selection: &[usize], rank: i32) -> Self {
        Self {
            arrays: atom_vtk_arrays(p, selection, rank),
            points: float32_points(p, selection),
        }
    }

    /// [`AtomVtu::capture`] with the owning rank of each particle as `proc` (`procs[i]`
    /// for particle index `i`).
    pub fn capture_procs(p: &Particles, selection: &[usize], procs: &[i32]) -> Self {
        Self {
            arrays: atom_vtk_arrays_procs(p, selection, procs),
            points: float32_points(p, selection),
        }
    }

    /// The file text.
    pub fn format(&self, enc: XmlEncoding) -> String {
        let n = self.points.data.len() / 3;
        let conn = XmlArray::new("connectivity", 1, XmlData::I64((0..n as i64).collect()));
        let offsets = XmlArray::new("offsets", 1, XmlData::I64((1..=n as i64).collect()));
        let types = XmlArray::new("types", 1, XmlData::U8(vec![1; n]));
        let mut out = String::with_capacity(400 * n + 4096);
        file_header(&mut out, "UnstructuredGrid", enc);
        let _ = writeln!(
            out,
            "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">\n      <PointData>"
        );
        for a in &self.arrays {
            write_array(&mut out, 8, a, enc);
        }
        out.push_str("      </PointData>\n      <CellData>\n      </CellData>\n      <Points>\n");
        write_array(&mut out, 8, &self.points, enc);
        out.push_str("      </Points>\n      <Cells>\n");
        for a in [&conn, &offsets, &types] {
            write_array(&mut out, 8, a, enc);
        }
        out.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
        out
    }
}

/// A `dump atom/vtk` snapshot: an UnstructuredGrid with one vertex cell per particle of
/// `selection` (in this order; the dump sorts by id), with [`atom_vtk_arrays`] as point
/// data and `rank` as `proc`.
pub fn format_atom_vtu(p: &Particles, selection: &[usize], rank: i32, enc: XmlEncoding) -> String {
    AtomVtu::capture(p, selection, rank).format(enc)
}

/// The point-data arrays of a `dump custom/vtk` snapshot with the legacy `layout`
/// ([`crate::vtk_layout`]): `int` arrays as `Int32`, the rest as `Float64`.
pub fn custom_vtk_arrays(
    p: &Particles,
    d: &Domain,
    selection: &[usize],
    columns: &[Column],
    layout: &[VtkArray],
) -> Vec<XmlArray> {
    layout
        .iter()
        .map(|a| {
            let values = selection.iter().flat_map(|&i| {
                a.components.iter().map(move |s| match *s {
                    VtkSource::Field(f) => f.typed_value(p, d, i),
                    VtkSource::Custom(k) => columns[k].value(p, d, i),
                })
            });
            let data = if a.int {
                XmlData::I32(
                    values
                        .map(|v| match v {
                            Value::Int(k) => k as i32,
                            Value::Float(x) => x as i32,
                        })
                        .collect(),
                )
            } else {
                XmlData::F64(
                    values
                        .map(|v| match v {
                            Value::Int(k) => k as f64,
                            Value::Float(x) => x,
                        })
                        .collect(),
                )
            };
            XmlArray::new(a.name.clone(), a.components.len(), data)
        })
        .collect()
}

/// A `dump custom/vtk` snapshot with a `.vtp` name: PolyData, one vertex per particle of
/// `selection`, the same arrays as the legacy file ([`custom_vtk_arrays`]).
pub fn format_vtp(
    p: &Particles,
    d: &Domain,
    selection: &[usize],
    columns: &[Column],
    layout: &[VtkArray],
    enc: XmlEncoding,
) -> String {
    format_custom(p, d, selection, columns, layout, enc, false)
}

/// A `dump custom/vtk` snapshot with a `.vtu` name: an UnstructuredGrid of vertex cells
/// with the same arrays as the legacy file ([`custom_vtk_arrays`]).
pub fn format_custom_vtu(
    p: &Particles,
    d: &Domain,
    selection: &[usize],
    columns: &[Column],
    layout: &[VtkArray],
    enc: XmlEncoding,
) -> String {
    format_custom(p, d, selection, columns, layout, enc, true)
}

fn format_custom(
    p: &Particles,
    d: &Domain,
    selection: &[usize],
    columns: &[Column],
    layout: &[VtkArray],
    enc: XmlEncoding,
    unstructured: bool,
) -> String {
    let n = selection.len();
    let arrays = custom_vtk_arrays(p, d, selection, columns, layout);
    let (points, conn, offsets) = points_and_vertices(p, selection);
    let mut out = String::with_capacity(128 * n * (layout.len() + 1) + 4096);
    if unstructured {
        file_header(&mut out, "UnstructuredGrid", enc);
        let _ = writeln!(
            out,
            "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">\n      <PointData>"
        );
    } else {
        file_header(&mut out, "PolyData", enc);
        let _ = writeln!(
            out,
            "  <PolyData>\n    <Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"{n}\" NumberOfLines=\"0\" \
             NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n      <PointData>"
        );
    }
    for a in &arrays {
        write_array(&mut out, 8, a, enc);
    }
    out.push_str("      </PointData>\n      <CellData>\n      </CellData>\n      <Points>\n");
    write_array(&mut out, 8, &points, enc);
    out.push_str("      </Points>\n");
    if unstructured {
        out.push_str("      <Cells>\n");
        let types = XmlArray::new("types", 1, XmlData::U8(vec![1; n]));
        for a in [&conn, &offsets, &types] {
            write_array(&mut out, 8, a, enc);
        }
        out.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
        return out;
    }
    out.push_str("      <Verts>\n");
    write_array(&mut out, 8, &conn, enc);
    write_array(&mut out, 8, &offsets, enc);
    out.push_str("      </Verts>\n");
    for section in ["Lines", "Strips", "Polys"] {
        let _ = writeln!(out, "      <{section}>");
        for name in ["connectivity", "offsets"] {
            write_array(
                &mut out,
                8,
                &XmlArray::new(name, 1, XmlData::I64(vec![])),
                enc,
            );
        }
        let _ = writeln!(out, "      </{section}>");
    }
    out.push_str("    </Piece>\n  </PolyData>\n</VTKFile>\n");
    out
}

/// The bounding-box companion of a `.vtp`/`.vtu` dump: the box as a 2×2×2 RectilinearGrid
/// (`.vtr`).
pub fn format_bounding_box_vtr(d: &Domain, enc: XmlEncoding) -> String {
    let mut out = String::new();
    file_header(&mut out, "RectilinearGrid", enc);
    out.push_str(
        "  <RectilinearGrid WholeExtent=\"0 1 0 1 0 1\">\n  <Piece Extent=\"0 1 0 1 0 1\">\n    \
         <PointData>\n    </PointData>\n    <CellData>\n    </CellData>\n    <Coordinates>\n",
    );
    for (a, name) in ["x", "y", "z"].into_iter().enumerate() {
        write_array(
            &mut out,
            6,
            &XmlArray::new(
                format!("{name}_coordinates"),
                1,
                XmlData::F64(vec![d.boxlo[a], d.boxhi[a]]),
            ),
            enc,
        );
    }
    out.push_str("    </Coordinates>\n  </Piece>\n  </RectilinearGrid>\n</VTKFile>\n");
    out
}

/// The bounding-box file name pattern of a `.vtp`/`.vtu` dump: as for legacy files,
/// with the suffix `.vtr` (`post/a_*.vtp` → `post/a_boundingBox_*.vtr`), as LIGGGHTS
/// names them.
pub fn bounding_box_vtr_path(pattern: &str) -> String {
    let b = crate::vtk_legacy::bounding_box_path(pattern);
    match b.strip_suffix(".vtp").or_else(|| b.strip_suffix(".vtu")) {
        Some(stem) => format!("{stem}.vtr"),
        None => format!("{b}.vtr"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_as_vtk_prints_them() {
        for (x, s) in [
            (0.00001212262065203961, "0.00001212262065203961"),
            (8.465450562766819e-16, "8.465450562766819e-16"),
            (-0.5470094449285665, "-0.5470094449285665"),
            (1e299, "1e+299"),
            (-1e299, "-1e+299"),
            (36.0, "36"),
            (0.00105, "0.00105"),
            (1e21, "1e+21"),
            (123456789012345680000.0, "123456789012345680000"),
            (1.5e-7, "1.5e-7"),
            (0.0, "0"),
            (12.5, "12.5"),
            (0.001978050_2_f32 as f64, "0.0019780502188950777"),
        ] {
            assert_eq!(number(x), s, "{x:e}");
            let mut g = String::new();
            if x != 0.0 {
                write_number_general(&mut g, x);
                assert_eq!(g, s, "{x:e}");
            }
        }
        // The fast path agrees with the general one across magnitudes.
        let mut x = 1.234_567_890_123_456_7e-300_f64;
        while x < 1e300 {
            for y in [x, -x, x * 3.0, (x * 7.0).round()] {
                let (mut a, mut b) = (String::new(), String::new());
                write_number(&mut a, y);
                if y != 0.0 {
                    write_number_general(&mut b, y);
                    // Both are shortest; on an exact tie of the last digit they may
                    // round differently.
                    assert!(
                        a == b || (a.len() == b.len() && a.parse::<f64>() == b.parse::<f64>()),
                        "{y:e}: {a} {b}"
                    );
                }
            }
            x *= 1.37;
        }
    }

    #[test]
    fn binary_blocks() {
        // Uncompressed: UInt32 byte count then the bytes, one base64 string.
        let mut s = String::new();
        encode_binary(&mut s, &36i32.to_le_bytes(), XmlEncoding::Binary);
        assert_eq!(s, BASE64.encode([4, 0, 0, 0, 36, 0, 0, 0]));
        // Compressed: header [blocks, 32768, last, sizes...] then the blocks.
        let raw: Vec<u8> = (0..70000u32).map(|k| (k % 251) as u8).collect();
        for enc in [XmlEncoding::Zlib, XmlEncoding::Lz4] {
            let mut s = String::new();
            encode_binary(&mut s, &raw, enc);
            let header = BASE64.decode(&s[..BASE64.encode([0u8; 24]).len()]).unwrap();
            let h: Vec<u32> = header
                .chunks(4)
                .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
                .collect();
            assert_eq!(h[..3], [3, 32768, 70000 - 65536]);
        }
    }
}

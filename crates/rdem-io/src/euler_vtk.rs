//! `dump euler/vtk`: the cells of `fix ave/euler` as a legacy ASCII VTK POLYDATA file, laid
//! out as LIGGGHTS 3.8 writes it (SPEC §4, seed 001): one vertex per cell centre, then the
//! point data `v_avg` (vector), `volumefraction`, `radius` and `pressure` (scalars), every
//! number with C's `%f`, cells x fastest, then y, then z.
//!
//! ```text
//! # vtk DataFile Version 2.0
//! LIGGGHTS mesh/VTK export
//! ASCII
//! DATASET POLYDATA
//! POINTS n float
//! x y z                      (n lines)
//! VERTICES n 2n
//! 1 i                        (i = 0 .. n-1)
//! POINT_DATA n
//! VECTORS v_avg float
//! vx vy vz                   (n lines)
//! SCALARS volumefraction float 1
//! LOOKUP_TABLE default
//! ...                        (likewise radius, pressure)
//! ```

use std::path::Path;

use rdem::euler::EulerCells;

use crate::atomic::{write_atomic, IoError};
use crate::printf::{Printf, Value};

/// Checks a `dump euler/vtk` file name: it must contain `*` (one file per snapshot, the
/// timestep in its name); `%` (a file per process) and `.bin` (binary output) are not
/// available for this style.
pub fn check_euler_vtk_name(name: &str) -> Result<(), EulerVtkNameError> {
    let name = name.to_string();
    if name.contains('%') {
        Err(EulerVtkNameError::PerProcess(name))
    } else if name.ends_with(".bin") {
        Err(EulerVtkNameError::Binary(name))
    } else if !name.contains('*') {
        Err(EulerVtkNameError::NoStar(name))
    } else {
        Ok(())
    }
}

/// Why a `dump euler/vtk` file name is refused ([`check_euler_vtk_name`]); each holds the
/// name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EulerVtkNameError {
    /// It has `%` (a file per process).
    #[error("dump euler/vtk file '{0}': '%' (one file per process) is not allowed: rank 0 writes the whole grid")]
    PerProcess(String),
    /// It ends in `.bin` (binary output).
    #[error("dump euler/vtk file '{0}': binary output (.bin) is not available, only ASCII VTK")]
    Binary(String),
    /// It has no `*`.
    #[error("dump euler/vtk file '{0}' must contain '*' (replaced by the timestep: one file per snapshot)")]
    NoStar(String),
}

/// The text of a `dump euler/vtk` file for `cells`.
pub fn format_euler_vtk(cells: &EulerCells) -> String {
    let f = Printf::parse("%f").expect("valid format");
    let n = cells.len();
    let mut s = String::with_capacity(64 + n * 120);
    let num = |s: &mut String, v: f64| f.write(s, Value::Float(v));
    let vec3 = |s: &mut String, v: [f64; 3]| {
        num(s, v[0]);
        s.push(' ');
        num(s, v[1]);
        s.push(' ');
        num(s, v[2]);
        s.push('\n');
    };
    s.push_str("# vtk DataFile Version 2.0\nLIGGGHTS mesh/VTK export\nASCII\nDATASET POLYDATA\n");
    s.push_str(&format!("POINTS {n} float\n"));
    for c in &cells.centre {
        vec3(&mut s, c.to_array());
    }
    s.push_str(&format!("VERTICES {n} {}\n", 2 * n));
    for i in 0..n {
        s.push_str(&format!("1 {i}\n"));
    }
    s.push_str(&format!("POINT_DATA {n}\nVECTORS v_avg float\n"));
    for v in &cells.v_avg {
        vec3(&mut s, v.to_array());
    }
    for (name, vals) in [
        ("volumefraction", &cells.volume_fraction),
        ("radius", &cells.radius),
        ("pressure", &cells.pressure),
    ] {
        s.push_str(&format!("SCALARS {name} float 1\nLOOKUP_TABLE default\n"));
        for &v in vals {
            num(&mut s, v);
            s.push('\n');
        }
    }
    s
}

/// Writes `cells` to `path` (atomically, creating missing directories).
pub fn write_euler_vtk(path: &Path, cells: &EulerCells) -> Result<(), IoError> {
    write_atomic(path, format_euler_vtk(cells).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rdem::DVec3;

    #[test]
    fn layout_and_numbers() {
        let cells = EulerCells {
            centre: vec![DVec3::new(-0.004, 0.0, 0.0), DVec3::new(0.008, 0.0, 0.0)],
            v_avg: vec![DVec3::new(0.1, -0.05, 0.02), DVec3::ZERO],
            volume_fraction: vec![0.0069813, 0.0],
            radius: vec![0.002, 0.0],
            pressure: vec![82.5020981, -0.0],
        };
        let want =
            "# vtk DataFile Version 2.0\nLIGGGHTS mesh/VTK export\nASCII\nDATASET POLYDATA\n\
POINTS 2 float\n-0.004000 0.000000 0.000000\n0.008000 0.000000 0.000000\n\
VERTICES 2 4\n1 0\n1 1\nPOINT_DATA 2\nVECTORS v_avg float\n0.100000 -0.050000 0.020000\n\
0.000000 0.000000 0.000000\nSCALARS volumefraction float 1\nLOOKUP_TABLE default\n0.006981\n\
0.000000\nSCALARS radius float 1\nLOOKUP_TABLE default\n0.002000\n0.000000\n\
SCALARS pressure float 1\nLOOKUP_TABLE default\n82.502098\n-0.000000\n";
        assert_eq!(format_euler_vtk(&cells), want);
    }

    #[test]
    fn names() {
        assert!(check_euler_vtk_name("post/e_*.vtk").is_ok());
        assert!(check_euler_vtk_name("post/e.vtk").is_err());
        assert!(check_euler_vtk_name("post/e_*_%.vtk").is_err());
        assert!(check_euler_vtk_name("post/e_*.bin").is_err());
    }
}

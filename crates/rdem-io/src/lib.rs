//! rdem file formats: the writers and readers the LIGGGHTS script front end needs, written
//! so that LIGGGHTS 3.8 input scripts run unmodified and leave the same files behind.
//!
//! * [`fields`]: the per-particle quantities `dump custom` knows (`id`, `x`, `vx`, ...) and
//!   columns computed by the front end (`c_ID`, `f_ID[N]`, `v_name`).
//! * [`printf`]: the C `printf` subset that `dump_modify format` strings use.
//! * [`dump_text`]: `dump custom` text snapshots (`ITEM: TIMESTEP` ...).
//! * [`vtk_legacy`]: `dump custom/vtk` legacy VTK files, laid out as LIGGGHTS 3.8 writes
//!   them, plus the `_boundingBox` companion file.
//! * [`vtk_xml`]: VTK XML files as LIGGGHTS writes them: `dump atom/vtk` (`.vtu`),
//!   `dump custom/vtk` with a `.vtp` name; ASCII, base64 binary, zlib or LZ4.
//! * [`atom_vtk`]: the `dump atom/vtk` writer.
//! * [`pvd`]: ParaView `.pvd` collections beside every VTK dump series.
//! * [`data_file`]: LAMMPS data files for `atom_style granular` (`read_data`, `write_data`).
//! * [`filename`]: the `*` (timestep) and `%` (rank) wildcards of dump file names.
//! * [`atomic`]: every file is written under a temporary name and renamed into place.
//! * [`liggghts_restart`]: a reader of LIGGGHTS 3.8 binary restart files.
//! * [`restart_file`]: the framing of rdem's binary restart files (magic, format
//!   version, length, CRC-32).
//! * [`stl`]: STL triangle files (ASCII in double precision, binary) for `fix mesh/surface`.
//! * [`vtk_tets`]: tetrahedra from legacy ASCII VTK unstructured grids (`region mesh/tet`).
//!
//! Nothing here decides *when* to write; the front end calls the writers on the right
//! timesteps with the selection of particles (group, region) it has worked out.

#![warn(missing_docs)]

pub mod atom_vtk;
pub mod atomic;
pub mod chains_vtk;
pub mod data_file;
pub mod dump_text;
pub mod euler_vtk;
pub mod fields;
pub mod filename;
pub mod liggghts_restart;
pub mod mesh_vtk;
pub mod printf;
pub mod pvd;
pub mod restart_file;
pub mod stl;
pub mod vtk_legacy;
pub mod vtk_tets;
pub mod vtk_xml;

pub use atom_vtk::{AtomVtkDump, Compressor};
pub use atomic::{write_atomic, AppendFile, IoError};
pub use chains_vtk::ForceChains;
pub use data_file::{
    format_data, parse_data, parse_data_as, read_data, read_data_as, write_data, AtomLayout,
    DataAtom, DataBond, DataError, DataFile, DataVelocity, ReadDataError, SubStyle,
};
pub use dump_text::{
    format_text_snapshot, parse_line_format, Sort, SortError, TextDump, TextOptions,
};
pub use euler_vtk::{check_euler_vtk_name, format_euler_vtk, write_euler_vtk, EulerVtkNameError};
pub use fields::{Column, Field};
pub use filename::DumpFileName;
pub use printf::{FormatError, Printf, Value};
pub use pvd::{pvd_path, PvdEntry, PvdSeries};
pub use vtk_legacy::{
    bounding_box_path, format_bounding_box, format_bounding_box_binary, format_vtk,
    format_vtk_binary, vtk_layout, VtkArray, VtkDump, VtkSource,
};
pub use vtk_xml::{
    atom_vtk_arrays, atom_vtk_arrays_procs, custom_vtk_arrays, format_atom_vtu,
    format_bounding_box_vtr, format_custom_vtu, format_vtp, AtomVtu, XmlArray, XmlData,
    XmlEncoding,
};

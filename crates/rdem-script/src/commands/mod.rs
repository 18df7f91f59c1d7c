//! The command registry ([`REGISTRY`]): every command rdem runs, with its handler and the
//! help the command table of docs/commands.md shows, and the LIGGGHTS commands it does not run. The
//! handlers live in the files of this folder, grouped by what they act on. Flow-control
//! commands (`include`, `label`, `jump`, `next`, `if`, `print`, `variable`, `log`, `echo`,
//! `quit`, and `run`, whose `every` runs commands) are rows too; [`crate::input`], which owns the file stack, runs them.

mod atoms;
mod bonds;
mod compute;
mod create;
mod data_files;
mod displace;
mod group;
mod pair;
mod read_dump;
pub mod region;
pub mod restart;
mod settings;
mod shell;
mod thermo;

pub use crate::args::id_help;
use crate::args::{nearest, Args, CmdResult};
use crate::registry::{Registry, Row};
use crate::sim::Sim;
use crate::{dumps, fixes};

/// A command's handler.
pub type Handler = fn(&mut Sim, &mut Args) -> CmdResult;

/// How a command runs.
#[derive(Clone, Copy)]
pub enum Command {
    /// On the simulation state; with `atoi`, its integer words are read as LIGGGHTS 3.8
    /// reads them, with C's `atoi` (`run 10.` runs there: rdem reads 10, with a warning).
    Sim {
        /// The handler.
        handler: Handler,
        /// Integers read with `atoi` (see [`Args::read_integers_with_atoi`]).
        atoi: bool,
    },
    /// By the interpreter (flow control, variables, output): see [`crate::input`].
    Flow,
}

const fn sim(name: &'static str, handler: Handler, help: &'static str) -> Row<Command> {
    Row::runs(
        name,
        Command::Sim {
            handler,
            atoi: false,
        },
        help,
    )
}

/// A command row whose integers LIGGGHTS 3.8 reads with `atoi` (checked there: `run`
/// (read so by the interpreter, which runs it), `reset_timestep`, the IDs and types of `group id|type`: `group g id 1.` takes atom 1).
const fn sim_atoi(name: &'static str, handler: Handler, help: &'static str) -> Row<Command> {
    Row::runs(
        name,
        Command::Sim {
            handler,
            atoi: true,
        },
        help,
    )
}

const fn flow(name: &'static str, help: &'static str) -> Row<Command> {
    Row::runs(name, Command::Flow, help)
}

/// Every command, in the order of docs/commands.md, then the LIGGGHTS commands rdem does not run.
pub static REGISTRY: Registry<Command> = Registry {
    family: "command",
    readme_prefix: "",
    rows: &[
        sim("atom_style", settings::atom_style, "`granular`, `sphere` (the same), `sph` (see [SPH](#sph)), `bond/gran n_bondtypes N bonds_per_atom M [disableNormalContact 0\\|1]` alone or in `hybrid granular bond/gran ...` (see `bond_style`)"),
        sim("atom_modify", settings::atom_modify, "`map array\\|hash` (accepted), `sort N binsize`, `id`"),
        sim("boundary", settings::boundary, "`p f s m` per axis, one or two letters").notes("before the box. A periodic length may be shorter than twice the neighbor cutoff, or than the cutoff (as in LIGGGHTS 3.8, the ghosts then hold several images of a particle); it must be at least twice the largest contact distance (twice the largest radius, times the contact distance factor, or the longest bond), else `run` stops with an error: rdem does not support a particle touching two images of one partner"),
        sim("dimension", settings::dimension, "`3`, `2` (with `fix enforce2d`)").notes("before the box; in 2d, as in LIGGGHTS 3.8: the box must be periodic in z, z velocities must be 0, masses are discs' (π r² ρ) with a sphere's moment of inertia, `fix gravity` takes its direction in the xy plane, the temperature counts 2 degrees of freedom per particle, particle templates (insertion) stop with an error. rdem makes no z images (as LAMMPS in 2d) by giving the engine fixed z faces. `fix adapt` in 2d: not supported yet"),
        sim("clear", settings::clear, "everything back to the start, except variables, screen, log and `thermo_log`"),
        sim("units", settings::units, "`si`, `cgs`, `micro`, with their default `timestep` and skin")
            .notes("before the box; without `units` rdem works in `si` (LIGGGHTS' default is `lj`); `lj`, `real`, `metal`, `electron`, `nano`: an error. LIGGGHTS 3.8's `youngsModulus` range check (`si`, `cgs`) is not made"),
        sim("coarsegraining", crate::coarse_graining::command, "`cg [model_check error\\|warn]` (LIGGGHTS-PFM): particles cg times the size the script gives: `particletemplate/sphere` (`radius constant`), `particletemplate/multiplespheres` and `multisphere` (radii and positions), `set diameter` and the `neighbor` skin are multiplied by cg; `hooke/stiffness` takes kn·cg, gamman/cg, gamman_abs·cg²; `fix massflow/mesh` files give the diameter over cg")
            .notes("first in the script (before the box, `neighbor`, `pair_style` and any fix), as in LIGGGHTS-PFM. The fork's inconsistent models and commands (`model hooke`, `hooke/hysteresis`, `hooke/stiffness`, `hertz/stiffness`, `jkr`; `cohesion sjkr`, `sjkr2`, `hamaker`, `morse`; `rolling_friction cdt`, `epsd`, `epsd2`; `create_atoms`; `fix addforce`, `buoyancy`, `drag`, `efield`, `heat/gran`, `heat/gran/conduction`, `heat/gran/radiation`, `spring`, `spring/rg`, `spring/self`, `viscous`) stop the script with `model_check error` (the default), warn with `warn`; a radius distribution in `particletemplate/sphere` is an error. rdem's models that LIGGGHTS-PFM lacks are neither scaled nor checked"),
        sim("newton", settings::newton, "accepted").notes("tuning only"),
        sim("communicate", settings::communicate, "accepted").notes("tuning only"),
        sim("hard_particles", settings::hard_particles, "accepted").notes("tuning only"),
        sim("soft_particles", settings::hard_particles, "accepted").notes("tuning only"),
        sim("processors", settings::processors, "`Px Py Pz`: the MPI processor grid (count or `*` each); `grid onelevel\\|twolevel Nc Cx Cy Cz\\|numa`; `map cart\\|cart/reorder\\|xyz`")
            .notes("a grid that does not fit the number of processes is a warning (LIGGGHTS stops): rdem keeps the counts that fit and chooses the rest; ranks are placed in xyz order whatever `map` or `grid` says (only which rank holds which part changes, not the outcome): `twolevel` is read and its core grid checked against Nc, a process count that is not a multiple of Nc is a warning (LAMMPS stops); `grid custom`, other maps, `part`, `file`: not supported"),
        sim("package", settings::package, "`omp N\\|* [force/neigh\\|force] [thread-binding] [verbose]` (LIGGGHTS-PFM's hybrid parallelization): rdem runs on its own threads")
            .notes("the thread count is rdem's (`--threads`, `RDEM_THREADS`): an N that differs is a warning; results do not depend on it. `gpu`, `cuda`, `kokkos` are not granular LIGGGHTS packages: an error"),
        sim("partitioner_style", settings::partitioner_style, "`zoltan [KEY VALUE ...]` (LIGGGHTS-PFM): accepted with a warning").notes("rdem shares the work between its threads itself; the Zoltan options are not used"),
        sim("region", region::region, "the region styles below; `side in\\|out`; `units box\\|lattice` (default `box`, as LIGGGHTS 3.8); `volume_limit V` (LIGGGHTS 3.8's undocumented limit of its region-volume estimate; checked, no other effect); `move v_x v_y v_z` (`NULL` allowed) and `rotate v_theta Px Py Pz Rx Ry Rz`: a moving region is placed by its equal-style variables each time it is used (`group`, `set`, `delete_atoms`, `create_atoms`, the region forms of `count()`, `mass()`, ...); insertion fixes, `create_box` and `ave/euler` refuse it, as LIGGGHTS 3.8 refuses it in insertion")
            .notes("`move` displacements are not scaled by `units lattice` (only the `rotate` point is), as the LIGGGHTS 3.8 manual says; LAMMPS' `open` is not a LIGGGHTS 3.8 keyword"),
        sim("lattice", region::lattice_cmd, "`sc`, `bcc`, `fcc`, `hcp`, `diamond` with a lattice constant; `custom` with `a1 a2 a3` along x, y, z and `basis`; `origin`")
            .notes("no `orient`/`spacing`"),
        sim("create_box", create::create_box, "`N region`"),
        sim("create_atoms", create::create_atoms, "`single`, `region`, `box`")
            .notes("new atoms have diameter 1 and density 1, as in LIGGGHTS; use `set`"),
        sim("create_particles", create::create_particles, "`TEMPLATE single x y z` (LIGGGHTS-INL): one particle of a `particletemplate/sphere`, or the spheres of a `particletemplate/multiplespheres` with their bounding sphere's centre at the point; `units box\\|lattice` (default `box`), `velocity`, `omega` (each sphere's), `orientation q1 q2 q3 q4` (sets the turn), `rotate axis ax ay az angle deg` (turns further; repeatable); new tags follow the largest, in the template's order")
            .notes("a rigid `particletemplate/multisphere` is refused (LIGGGHTS-INL has none); a sphere of the template outside a fixed face is an error. The bounding sphere is grown as LIGGGHTS-INL grows it, but taking the farthest sphere first instead of random orders: the same centre where that finds the smallest sphere (measured on an L of three spheres and a cluster of five), not always on large templates (INL's voxel example of 114704 spheres: rdem places it 0.36 higher in z than the fork, 0.3 % of its bounding radius 122)"),
        sim("mass", crate::sph::mass, "`I value`: the mass of type I (`*`, `*n`, `n*`, `m*n` ranges)")
            .notes("atom_style sph only (per-type masses, as LIGGGHTS); granular particles have their own mass"),
        sim("read_data", data_files::read_data, "granular `Atoms` lines (`id type diameter density x y z [ix iy iz]`), `Velocities`; under `atom_style hybrid granular bond/gran`, `id type x y z diameter density molecule [ix iy iz]` (the sub-styles' values in their order), `N bonds`, `N bond types`, `N extra bond per atom` and `Bonds` (`id type atom1 atom2`)")
            .notes("no `add`/`offset`; a bond's length is taken at its first evaluation, as for bonds made by `fix bond/create/gran`; plain `atom_style bond/gran` (lines without a diameter) is refused"),
        sim("read_dump", read_dump::read_dump, "`file Nstep` fields `x y z vx vy vz ix iy iz radius` (radius required); `box`, `replace`, `purge`, `trim`, `add yes\\|no`, `label`, `scaled`, `wrapped`, `format native`")
            .notes("native text dumps (`dump custom`); as LIGGGHTS 3.8: replaced particles keep their mass, added ones get new IDs, the dump's type, density 1 and the mass of a radius-0.5 sphere (use `set density` after), added ones outside a fixed face are dropped. `format xyz`, gzipped files, triclinic boxes: not supported yet"),
        sim("write_data", data_files::write_data, "the particles and the box as a LAMMPS data file (`nocoeff`, `nofix` accepted), in the columns of the atom style")
            .notes("under `hybrid granular bond/gran` with the molecule IDs and the intact bonds turned on, which `read_data` (and LIGGGHTS-PFM's) reads back; their lengths and loads are not kept (LIGGGHTS-PFM stops at `write_data` with bond style gran; LIGGGHTS_Flexible_Fibers and LIGGGHTS_SEAICE write the bonds but no molecule column, a file their `read_data` refuses)"),
        sim("delete_atoms", atoms::delete_atoms, "`group`, `region`; `compress yes\\|no`"),
        sim("displace_atoms", displace::displace_atoms, "`group move dx dy dz`, `ramp ddim dlo dhi dim clo chi`, `random dx dy dz seed` (LAMMPS' per-particle seeding: the same moves on any number of ranks), `rotate Px Py Pz Rx Ry Rz theta`; `units box\\|lattice` (default box)")
            .notes("moves positions only (velocities and spins stay); the default units are `box`, as LIGGGHTS 3.8 does (its manual says `lattice`); a particle moved outside a fixed face stays there until the next run loses it, as in LIGGGHTS 3.8, with a warning; spheres of clumps are not moved, with a warning (LIGGGHTS 3.8 moves them and puts them back at the next step)"),
        sim("set", atoms::set, "`atom`, `type`, `group`, `region` with `type`, `diameter`, `density`, `mass`, `x y z`, `vx vy vz`, `omegax omegay omegaz` (numbers or equal-/atom-style `v_name`), `omega`, `property/atom`")
            .notes("the mass follows diameter and density"),
        sim("velocity", atoms::velocity, "`set` (numbers, equal- or atom-style `v_name`, NULL), `zero linear\\|angular`, `ramp`, `create`; `sum`")
            .notes("`units box` only"),
        sim_atoi("group", group::group, "`region`, `type` and `id` (values, sequences `a:b[:c]`, or one logical `<` `<=` `>` `>=` `==` `!=` `<>`), `variable` (atom-style), `union`, `subtract`, `intersect`, `delete`"),
        sim("neighbor", settings::neighbor, "`skin bin\\|nsq`").notes("the skin is multiplied by the `coarsegraining` factor"),
        sim("neigh_modify", settings::neigh_modify, "`delay`, `every`, `check`, `exclude type M N\\|group G1 G2\\|molecule G\\|none` (`molecule`: atom style bond/gran, whose bonded templates each get a molecule ID; as in LAMMPS, ID 0 counts as one molecule; excluded pairs are never bonded by `fix bond/create/gran`, as in the forks) `contact_distance_factor f` (pairs listed up to f (r_i + r_j) + skin, f >= 1; `surface multicontact` takes at least 2, as LIGGGHTS 3.8 does) (`one`, `page`, `binsize` accepted)"),
        sim("pair_style", pair::pair_style, "`gran` with `model hertz\\|hooke\\|hooke/hysteresis\\|hertz/stiffness\\|hooke/stiffness\\|jkr\\|jkr/pfm\\|hysteretic/nonlinear1\\|hysteretic/nonlinear2` (jkr LIGGGHTS_Flexible_Fibers' and PICI's adhesive law, with `workOfAdhesion` per type pair (0: Hertz's contact for the pair, as the forks) and `resolutionJKR`, its contact radius solved exactly; with `cohesionEnergyDensity` per type pair and no `workOfAdhesion`, `jkr` is LIGGGHTS-PFM's law, which rdem also names `jkr/pfm`: work of adhesion 2γ, acting only while the spheres overlap, Hertz's load for friction; the hysteretic laws LIGGGHTS-INL's elasto-plastic ones, with `alphaCustom`, `cinCustom`, `aoneCustom`, `atwoCustom`, `athreeCustom`, `kcinCustom`, `LoadingStiffness`, `UnloadingStiffness`, `coefficientAdhesionStiffness`, `coefficientPlasticityDepth`, `pullOffForce` per type pair and `limitForce` on by default), `tangential off\\|history\\|no_history\\|incremental_history` (`off`, LIGGGHTS 3.8's default when `tangential` is not given: no tangential force and no `coefficientFriction` needed, in `fix wall/gran` too; LIGGGHTS-PFM's default is `no_history`; `incremental_history` LIGGGHTS-PFM's: the stored force gains increments, as the fork measured), `cohesion off\\|sjkr\\|sjkr2\\|bond\\|bond/nonlinear\\|easo/capillary/viscous`, `rolling_friction off\\|cdt\\|cdtnonlinear2\\|epsd\\|epsd2\\|epsd3` (cdtnonlinear2 LIGGGHTS-INL's cdt on the whole normal force), `surface default\\|multicontact` (multicontact with `fix multicontact/halfspace`, one MPI rank), then `tangential_damping`, `limitForce`, `torsionTorque`, `tangential_reduce`, `absolute_damping` (hooke/stiffness), and with `cohesion bond` or `bond/nonlinear` their switches (see [Bonded particles](#bonded-particles)); the pre-3.0 styles `gran/hertz/history`, `gran/hooke/history`, `gran/hooke` with LIGGGHTS 1.x's `dampflag cohesionflag` or 2.x's `tangential_damping`, `cohesion off\\|sjkr`, `rolling_friction off\\|cdt`, `viscous off`, run as the 3.x model they mean (a note line gives it); `sph/artVisc/tensCorr KERNEL h [artVisc] [tensCorr]` with atom_style sph (kernels `cubicspline`, `cubicspline2d`, `wendland`, `wendland2d`, `spiky`, `spiky2d`)")
            .notes("SPH: the per-type `sl` (smoothing length), `speedOfSound`, `artViscAlpha`, `artViscBeta`, `tensCorrDeltaP` and the scalars `artViscEta`, `tensCorrEpsilon` come from fix property/global, as LIGGGHTS 3.8 reads them; the `h` of the line is not used (as LIGGGHTS with atom_style sph); values after artVisc/tensCorr are refused, as LIGGGHTS 3.8 refuses them. Granular: the model types must come in LIGGGHTS' order; a misplaced one gets an error stating it. The stiffness models read `kn`, `kt`, `gamman`, `gammat` (`gamman_abs`, `gammat_abs` with `absolute_damping on`) per type pair and need no E, ν or e. epsd3 reads its prefactor from `rollingStiffness` (scalar), the name LIGGGHTS 3.8 reads; its manual says `coeffRollingStiffness`. `cohesion easo/capillary/viscous` (liquid bridges) does what LIGGGHTS 3.8's code does where it differs from its manual: the liquid content is a volume fraction, the bridge volume takes ½(1 − √(1 − r_j²/(r_i+r_j)²)) of each particle's liquid, the effective contact angle is ½θ_iθ_j, the viscous gap is at least minSeparationDistanceRatio·R*; it defines the fixes `liquidtransfer`, `surfaceLiquidContent`, `liquidFlux`, `liquidSource` (values from the first run on); the bridges cannot be used in `fix wall/gran` (LIGGGHTS 3.8 runs them there as dry walls, with a warning; its manual forbids it). `washino/capillary/viscous` is not supported yet. Pre-3.0 syntax (LIGGGHTS 3.8 refuses it): the contact physics are 3.x's (with `cohesion sjkr` the Coulomb limit leaves the cohesion out, where 2.x subtracted it from the normal force); LAMMPS' `Kn Kt gamma_n gamma_t xmu dampflag` form and `viscous on` stop with an error"),
        sim("pair_coeff", pair::pair_coeff, "`* *`"),
        sim("timestep", settings::timestep, "the time step (s)"),
        sim("fix", fixes::fix, "the fix styles below"),
        sim("unfix", fixes::unfix, "`ID`"),
        sim("fix_modify", fixes::fix_modify, "`energy yes\\|no`, and a style's own keywords")
            .notes("`energy yes` on `gravity`/`addforce` warns: their energy is not added to a potential energy (no granular fix tallies one in LIGGGHTS 3.8); `temp`, `press`, `virial` stop as in LIGGGHTS 3.8 (no granular fix computes a temperature or pressure)"),
        sim("compute", compute::compute, "the compute styles below; the general keyword `update_on_run_end yes\\|no` after the style")
            .notes("rdem evaluates a compute from the current state whenever it is asked, so a value read after a run is always current (`no` only loses LIGGGHTS' \"not current\" error)"),
        sim("uncompute", compute::uncompute, "`ID`"),
        sim("compute_modify", compute::compute_modify, "`extra N` (also `extra/dof`), `dynamic yes\\|no` (also `dynamic/dof`), `thermo yes\\|no`; `thermo_temp` and user computes")
            .notes("`extra/dof`, `dynamic/dof` are later LAMMPS names LIGGGHTS 3.8 refuses; a keyword a style does not use is accepted with a warning"),
        sim("thermo", thermo::thermo, "`N`"),
        sim("thermo_style", thermo::thermo_style, "`custom` with keywords `step elapsed elaplong dt time cpu atoms ke temp pe etotal vol lx ly lz xlo xhi ylo yhi zlo zhi`, `c_ID`, `c_ID[i]`, `f_ID[i]`, `v_name`; `one` and `multi` (step atoms ke cpu, on one line or in the multi-line layout)")
            .notes("`pe` is 0 (granular contacts store no potential energy); `temp` is `c_thermo_temp` (LIGGGHTS 3.8 has no `temp` keyword); `ke` is Σ ½ m v² for any count, as LIGGGHTS 3.8; `one`/`multi` do not append `vol` when the box changes (LIGGGHTS' manual says they do)"),
        sim("thermo_log", thermo::thermo_log, "`FILE [append]`, `none`: thermo's lines also go to FILE")
            .notes("without a file name LIGGGHTS 3.8 writes to `log`; rdem asks for the name"),
        sim("thermo_modify", thermo::thermo_modify, "`lost error\\|warn\\|ignore`, `norm`, `line one\\|multi`, `format int\\|float\\|line\\|N`, `every`, `flush`")
            .notes("`lost`: LIGGGHTS' default is `ignore`, and the run goes on as there, but the first loss (only the first) gives a warning that names the particle, where it was found, its velocity, the wall and mesh triangle it last touched and at which step, and the wall its path crosses traced back; `error` stops with that report, `ignore` is silent; `norm yes` divides the printed extensive columns as LIGGGHTS does (`ke`, `etotal`, `c_` of ke/erotate/reduce sum, `f_` of check/timestep/gran); `line multi` prints LIGGGHTS 3.8's multi-line layout byte for byte (a banner with the step and CPU seconds, three `Label = value` items a line); `line yaml` is an error, as in LIGGGHTS 3.8 (a later LAMMPS layout); a new `thermo_style` goes back to `line one`, as LIGGGHTS"),
        flow("run", "`N`, `upto`, `start N1`, `stop N2`, `pre yes\\|no`, `post yes\\|no`, `every M \"c1\" \"c2\" ...` (or `NULL`): the run in chunks of M steps with the commands after each")
            .notes("`stop` is checked but changes nothing: no rdem style ramps over a run (no `ramp()`); `elaplong` counts from `start`; under `rdem -check` the chunks are one checked run and the commands run once"),
        sim_atoi("reset_timestep", settings::reset_timestep, "`N`"),
        sim("modify_timing", settings::modify_timing, "`on\\|off\\|verbose`: after each run, each fix's time (`Fix ID style time (%) = t (pct)`, the fix's stages in the script and the engine), the Modify line called `Modfy`, as LIGGGHTS 3.8 prints them; `verbose` adds each MPI rank's")
            .notes("while on, the post-force fixes act one at a time, each timed (the same forces, a slower run); LIGGGHTS also lists its internal fixes (`contacthistory`, ...), rdem the script's and those its commands define"),
        sim("dump", dumps::dump, "the dump styles below"),
        sim("dump_modify", dumps::dump_modify, "`sort`, `pad`, `format`, `every`, `first`, `region ID\\|none` (dump custom, custom/vtk), `binary`, `compressor`, `label L` (dump local)"),
        sim("undump", dumps::undump, "`ID`"),
        sim("write_dump", dumps::write_dump, "`custom`, `custom/vtk`, `atom/vtk` with `modify`"),
        sim("write_restart", data_files::write_restart, "file name (`*` = the step)")
            .notes("rdem's own binary format (versioned, with a checksum): particles with every per-particle value, contact histories (bonds, walls, meshes), groups, step, time, timestep and the state of the fixes that keep one; LIGGGHTS' restart files are not written"),
        sim("restart", restart::restart, "`0`, `N root` (`*` in the name replaced by the step, else `.STEP` appended), `N file1 file2` (in turn)")
            .notes("the files are `write_restart`'s; `v_name` for N, `%` in names, `fileper`, `nfile`: not supported yet"),
        sim("read_restart", data_files::read_restart, "file name")
            .notes("in place of `create_box`: box, boundary, units, particles, contact histories, groups, step, time and timestep; a fix defined again with the ID and style it had takes its state back (as LIGGGHTS); the older rdem restart files (data files) are refused with a note to use `read_data`; a LIGGGHTS 3.8 binary restart file (one file, written on any number of processors; atom_style granular) gives its box, boundary, units, step, groups and particles (tag, type, group mask, image flags, position, velocity, angular velocity, radius, density, mass), the pair contact histories of `tangential history` and the histories of primitive walls (`history_ID` of wall `ID`), all taken exactly; the values of a `fix property/atom` go to the fix defined again with its ID (as LIGGGHTS); its fix states, other fixes' per-particle values (mesh wall histories) and its pair style are not taken (one warning lists them: define the pair style, materials, walls and fixes again after read_restart, as LIGGGHTS scripts do; LIGGGHTS 3.8 also runs on with the file's pair style when none is defined again, rdem stops the first run with an error saying so); LIGGGHTS stores no timestep, and `time` starts at 0 at the file's step, as in LIGGGHTS; `*` and `%` in the name are not supported yet"),
        flow("variable", "the variable styles below"),
        flow("print", "text with `$x`, `${name}`, `$(formula)`; `file`, `append`, `screen`"),
        flow("include", "a script file, run in place"),
        flow("label", "`ID`"),
        flow("jump", "`FILE\\|SELF [label]`"),
        flow("next", "variables of `index`, `loop`, `file`, `universe`, `uloop` styles (one style per command, `universe` with `uloop`)"),
        flow("if", "`\"condition\" then \"command\" ... [elif ...] [else ...]`"),
        flow("log", "`FILE [append]`, `none`"),
        flow("echo", "`none\\|screen\\|log\\|both`"),
        flow("quit", "stops the script"),
        sim("shell", shell::shell, "`cd`, `mkdir [-p]`, `rm [-f]`, `rmdir`, `mv`, `putenv` done by rdem; any other command run by `/bin/sh -c`")
            .notes("a failed action or a non-zero exit status is a warning (LIGGGHTS 3.8 says nothing); `mkdir -p` makes parents (LIGGGHTS 3.8 makes a folder named `-p`); under `rdem -check` only `cd` and `putenv` act"),
        sim("bond_style", bonds::bond_style, "`gran` (LIGGGHTS_Flexible_Fibers' flexible-fiber bonds; needs `atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M`)"),
        sim("bond_coeff", bonds::bond_coeff, "`T ro ri Y G dstyle d... bstyle b...` (Flexible_Fibers' form): damping style `0 x` (none), `1 beta`, `2 beta0 beta1 beta2`; or `T ro ri lb Sn St Sben Stor damp bn bt bstyle b...` (LIGGGHTS-PFM's form: L₀ = lb (R₁ + R₂) prescribed, bending and twisting moduli of their own, damping ratio `damp`, normal force × (1 − L₀/bn)/(1 − r/bn)); break style `0 r_b` (apart beyond 2 r_b), `1 sigma_c tau_c` (by stress), `2 sigma_c tau_c T_break` (by stress, or the pair's mean `Temp` above T_break), `3`, `4` or `5 sigma_c tau_c` (Flexible_Fibers' form only: by stress; a bond broken while its spheres overlap pushes them apart until they separate, with 0.001 K_n × overlap, K_n × shortening, or Hertz)")
            .notes("damping and break style are one for all bond types, as in the forks (a second type with other styles is an error); `bt` is read and has no effect (none measured in LIGGGHTS-PFM); Flexible_Fibers' build stops with \"ERROR: broken\" where a style-0 bond breaks, rdem breaks it as LIGGGHTS-PFM does; style 2 needs a per-particle `Temp` (`fix property/atom Temp` or `fix heat/gran`); a separating bond (styles 3–5) leaves `numbonds` at once and `compute property/local btype` gives its type negative, as in the fork; with `disableNormalContact 1` the pair's contact resumes at the step after such a bond leaves, as in the fork (after other breaks, at the next re-neighboring); a bond breaks, whatever its style, when a sphere's centre comes within 0.75 radius (Flexible_Fibers' form) or within the neighbor skin (LIGGGHTS-PFM's form) of a non-periodic box face, as in the forks; in Flexible_Fibers' form two spheres of one molecule, one of which holds a bond, have no pair contact while closer than half their radii sum, as in the fork (the fork tests the bond of the pair's first sphere in its neighbor list, rdem of either)"),
        sim("delete_bonds", bonds::delete_bonds, "`group-ID multi|atom T|bond T|stats [any] [undo] [remove] [special]` (bond/gran bonds)")
            .notes("a bond is selected when both its spheres are in the group (one with `any`); a selected bond is turned off (no force; still counted by `numbonds` and keeping the contact off under `disableNormalContact 1`; left out of `compute property/local`, where LIGGGHTS-PFM lists it with its type negative, the force of the bond listed before it, and only when its partner is on the same rank) or on again with `undo`; `remove` then drops every turned-off bond; `bond 0` selects the bonds broken since the last re-neighboring; `special` changes nothing more, as rdem keeps no 1-2 neighbor list (its pair rules read the bonds as they are); prints the counts as LAMMPS does"),
        Row::not_yet("create_bonds", "bonds"),
        Row::not_yet("run_style", "run styles other than verlet"),
        Row::not_yet("minimize", "energy minimisation"),
    ],
};

/// Runs a simulation command: the name must be in [`REGISTRY`] (the interpreter looks it
/// up first and runs the flow-control rows itself).
pub fn execute(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let name = a.name();
    match REGISTRY.lookup_at(a, 0, name)? {
        (_, Command::Sim { handler, atoi }) => {
            if *atoi {
                a.read_integers_with_atoi();
            }
            handler(sim, a)
        }
        (name, Command::Flow) => Err(a.error_cmd(
            format!("internal error: {name} is run by the interpreter"),
            None,
        )),
    }
}

/// Help for an unknown command: the nearest known command.
pub fn unknown_command_help(name: &str, all: &[&str]) -> String {
    match nearest(name, all) {
        Some(n) => {
            format!("did you mean '{n}'? (rdem runs the LIGGGHTS commands listed in its README)")
        }
        None => "rdem runs the LIGGGHTS commands listed in its README".into(),
    }
}

/// The command tables of `docs/commands.md`, made from the registries: commands, then
/// the fix, compute, dump, region and variable styles (`tests/readme_registry.rs` checks
/// that the file holds exactly this).
pub fn readme_tables() -> String {
    let mut out = String::new();
    let mut table = |title: &str, head: &str, rows: Vec<String>| {
        out.push_str(&format!(
            "## {title}\n\n| {head} | rdem supports | notes |\n|---|---|---|\n"
        ));
        for r in rows {
            out.push_str(&r);
            out.push('\n');
        }
        out.push('\n');
    };
    table("Commands", "command", REGISTRY.readme_rows());
    table("Fix styles", "fix style", fixes::REGISTRY.readme_rows());
    table(
        "Compute styles",
        "compute style",
        crate::computes::REGISTRY.readme_rows(),
    );
    table("Dump styles", "dump style", dumps::REGISTRY.readme_rows());
    table(
        "Region styles",
        "region style",
        region::STYLES.readme_rows(),
    );
    table(
        "Variable styles",
        "variable style",
        crate::variables::STYLES.readme_rows(),
    );
    out
}

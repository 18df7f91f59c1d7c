//! `rdem._rdem`: rdem from Python (PyO3), the native part of the `rdem` package.
//!
//! A [`Simulation`] holds one interpreter, the same one the `rdem` command runs, so any
//! LIGGGHTS script works through `sim.file()`, `sim.command()` and `sim.commands()`. While
//! commands run the GIL is released; a run checks after every step whether Ctrl-C was
//! pressed (a SIGINT handler of its own, chained to Python's) and calls the Python
//! callback every N steps. Particle arrays come as numpy copies, or as read-only views
//! of rdem's own storage that no command may outlive (see [`Simulation::view`]).

use std::cell::{Cell, RefCell};
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

use glam::DVec3;
use numpy::ndarray::{Array2, ArrayView1, ArrayView2};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{
    PyException, PyKeyError, PyKeyboardInterrupt, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rdem_script::{Interpreter, Output, ScriptReport, Sim};

pyo3::create_exception!(
    _rdem,
    RdemError,
    PyException,
    "An rdem command failed. Attributes: `file`, `line`, `column` (1-based; None when the \
     error points at no source), `message`, and `report` (the rendered report with the \
     script excerpt and the caret, as the rdem command prints it)."
);

/// Set by the SIGINT handler; cleared before each command.
static INTERRUPTED: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The interrupt flag, with the SIGINT handler installed on first use. signal-hook
/// chains to the handler that was there before (Python's), so Python sees the signal
/// too and raises KeyboardInterrupt when it next checks.
fn interrupted() -> &'static Arc<AtomicBool> {
    INTERRUPTED.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        // Without the handler Ctrl-C still reaches Python, after the command.
        let _ = signal_hook::flag::register(signal_hook::consts::SIGINT, Arc::clone(&flag));
        flag
    })
}

/// A value moved to the thread pool's thread and back while the calling thread waits.
struct WhileWaiting<T>(T);

// SAFETY: the value is used on a pool thread only while the thread that owns it is
// blocked in `ThreadPool::install` (inside `Python::detach`), so no two threads touch
// it at once; nothing in the interpreter is tied to a thread.
unsafe impl<T> Send for WhileWaiting<T> {}

impl<T> WhileWaiting<T> {
    fn get(self) -> T {
        self.0
    }
}

/// What a command runs: a file, or text with a name for reports.
enum Source {
    File(String),
    Text(String, String),
}

/// The per-particle arrays by name: `(values per particle, reader)`.
fn vec3_of<'a>(sim: &'a Sim, name: &str) -> Option<&'a [DVec3]> {
    let p = &sim.world.as_ref()?.particles;
    let n = p.nlocal();
    Some(match name {
        "x" => &p.x[..n],
        "v" => &p.v[..n],
        "omega" => &p.omega[..n],
        "f" => &p.f[..n],
        "torque" => &p.torque[..n],
        _ => return None,
    })
}

fn scalar_of<'a>(sim: &'a Sim, name: &str) -> Option<&'a [f64]> {
    let p = &sim.world.as_ref()?.particles;
    let n = p.nlocal();
    Some(match name {
        "radius" => &p.radius[..n],
        "mass" => &p.rmass[..n],
        "density" => &p.density[..n],
        _ => return None,
    })
}

const ARRAYS: &str = "x, v, omega, f, torque (n×3), radius, mass, density, tag, type, or a \
                      named per-particle property";

fn world(sim: &Sim) -> PyResult<&rdem::World> {
    sim.world.as_ref().ok_or_else(|| {
        PyRuntimeError::new_err(
            "no simulation box yet (create_box, read_data or read_restart first)",
        )
    })
}

/// A copy of array `name` of the owned particles, in storage order (`tag` says which
/// particle each row is).
fn array_copy<'py>(py: Python<'py>, sim: &Sim, name: &str) -> PyResult<Bound<'py, PyAny>> {
    let w = world(sim)?;
    let p = &w.particles;
    let n = p.nlocal();
    if let Some(v) = vec3_of(sim, name) {
        let flat: Vec<f64> = v.iter().flat_map(|d| d.to_array()).collect();
        let a = Array2::from_shape_vec((n, 3), flat).expect("n×3 values");
        return Ok(a.into_pyarray(py).into_any());
    }
    if let Some(v) = scalar_of(sim, name) {
        return Ok(PyArray1::from_slice(py, v).into_any());
    }
    match name {
        "tag" => return Ok(PyArray1::from_slice(py, &p.tag[..n]).into_any()),
        "type" => return Ok(PyArray1::from_slice(py, &p.ty[..n]).into_any()),
        _ => {}
    }
    let id = p
        .property(name)
        .ok_or_else(|| PyKeyError::new_err(format!("no per-particle array '{name}': {ARRAYS}")))?;
    let prop = &p.props[id.0];
    let data = &prop.data[..n * prop.width];
    if prop.width == 1 {
        return Ok(PyArray1::from_slice(py, data).into_any());
    }
    let a = Array2::from_shape_vec((n, prop.width), data.to_vec()).expect("n×width values");
    Ok(a.into_pyarray(py).into_any())
}

/// The thermo rows of the last run as numpy columns by keyword.
fn thermo_dict<'py>(py: Python<'py>, sim: &Sim) -> PyResult<Bound<'py, PyDict>> {
    let t = &sim.outputs.thermo.table;
    let d = PyDict::new(py);
    for (k, c) in t.columns.iter().enumerate() {
        let col: Vec<f64> = t
            .rows
            .iter()
            .map(|r| r.get(k).copied().unwrap_or(f64::NAN))
            .collect();
        d.set_item(c, PyArray1::from_vec(py, col))?;
    }
    Ok(d)
}

fn variable_value<'py>(py: Python<'py>, sim: &Sim, name: &str) -> PyResult<Bound<'py, PyAny>> {
    use rdem_script::variables::Variable;
    match sim.script.vars.get(name) {
        None => Err(PyKeyError::new_err(format!("no variable '{name}'"))),
        Some(Variable::Atom(_)) => {
            let v =
                rdem_script::context::eval_atom(sim, &format!("v_{name}")).map_err(value_error)?;
            Ok(PyArray1::from_vec(py, v).into_any())
        }
        Some(Variable::Equal(_)) => {
            let v = rdem_script::context::eval_equal(sim, &format!("v_{name}"))
                .map_err(|e| PyValueError::new_err(e.to_string()))?;
            Ok(v.into_pyobject(py)?.into_any())
        }
        Some(_) => {
            let t = rdem_script::context::variable_text(sim, name).map_err(value_error)?;
            Ok(t.into_pyobject(py)?.into_any())
        }
    }
}

/// 1-based index as rdem's references take it.
fn index(i: Option<usize>) -> PyResult<Option<usize>> {
    match i {
        Some(0) => Err(PyValueError::new_err(
            "indices are 1-based, as in c_ID[i] and f_ID[i]",
        )),
        i => Ok(i),
    }
}

/// The simulation state the read accessors take, shared by [`Simulation`] and
/// [`StepView`].
macro_rules! readers {
    ($t:ty) => {
        #[pymethods]
        impl $t {
            /// Positions of the owned particles (n×3 copy, storage order).
            #[getter]
            fn x<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "x")
            }
            /// Velocities (n×3 copy).
            #[getter]
            fn v<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "v")
            }
            /// Angular velocities (n×3 copy).
            #[getter]
            fn omega<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "omega")
            }
            /// Forces of the last step (n×3 copy).
            #[getter]
            fn f<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "f")
            }
            /// Torques of the last step (n×3 copy).
            #[getter]
            fn torque<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "torque")
            }
            /// Radii (copy).
            #[getter]
            fn radius<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "radius")
            }
            /// Masses (copy).
            #[getter]
            fn mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "mass")
            }
            /// Particle IDs (copy, uint64).
            #[getter]
            fn tag<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "tag")
            }
            /// Particle types (copy, uint32).
            #[getter]
            fn r#type<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, "type")
            }
            /// A copy of any per-particle array by name, named properties included.
            fn array<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
                array_copy(py, self.sim()?, name)
            }
            /// The thermo rows of the current or last run: {keyword: column}.
            #[getter]
            fn thermo<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
                thermo_dict(py, self.sim()?)
            }
            /// The value of a variable: a float (equal style), an array (atom style) or
            /// the text (other styles).
            fn variable<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
                variable_value(py, self.sim()?, name)
            }
            /// A global value of a compute: its scalar, or value `index` (1-based).
            #[pyo3(signature = (id, index=None))]
            fn compute(&self, id: &str, index: Option<usize>) -> PyResult<f64> {
                rdem_script::context::compute_global(self.sim()?, id, crate::index(index)?)
                    .map_err(value_error)
            }
            /// A per-particle compute (or its column, 1-based), in storage order.
            #[pyo3(signature = (id, column=None))]
            fn compute_peratom<'py>(
                &self,
                py: Python<'py>,
                id: &str,
                column: Option<usize>,
            ) -> PyResult<Bound<'py, PyArray1<f64>>> {
                let v =
                    rdem_script::context::compute_peratom(self.sim()?, id, crate::index(column)?)
                        .map_err(value_error)?;
                Ok(PyArray1::from_vec(py, v))
            }
            /// A global value of a fix: its scalar, or value `index` (1-based).
            #[pyo3(signature = (id, index=None))]
            fn fix(&self, id: &str, index: Option<usize>) -> PyResult<f64> {
                rdem_script::fixes::fix_value(self.sim()?, id, crate::index(index)?)
                    .map_err(value_error)
            }
            /// A per-particle fix value (or its column, 1-based), in storage order.
            #[pyo3(signature = (id, column=None))]
            fn fix_peratom<'py>(
                &self,
                py: Python<'py>,
                id: &str,
                column: Option<usize>,
            ) -> PyResult<Bound<'py, PyArray1<f64>>> {
                let v = rdem_script::fixes::fix_peratom(self.sim()?, id, crate::index(column)?)
                    .map_err(value_error)?;
                Ok(PyArray1::from_vec(py, v))
            }
            /// The current step.
            #[getter]
            fn step(&self) -> PyResult<u64> {
                Ok(self.sim()?.world.as_ref().map_or(0, |w| w.step))
            }
            /// The simulated time.
            #[getter]
            fn time(&self) -> PyResult<f64> {
                Ok(self.sim()?.time())
            }
            /// The number of particles.
            #[getter]
            fn natoms(&self) -> PyResult<u64> {
                Ok(self.sim()?.natoms())
            }
        }
    };
}

/// A simulation: one rdem interpreter with its own thread pool.
#[pyclass(unsendable, module = "rdem._rdem")]
pub struct Simulation {
    interp: Interpreter,
    pool: rayon::ThreadPool,
    callback: Option<(u64, Py<PyAny>)>,
    /// Views alive (each one's guard counts itself while the array lives).
    views: Rc<Cell<usize>>,
}

impl Simulation {
    fn sim(&self) -> PyResult<&Sim> {
        Ok(&self.interp.sim)
    }

    /// Runs `src` with the GIL released, the callback and the interrupt check installed.
    fn run(&mut self, py: Python<'_>, src: Source) -> PyResult<()> {
        let alive = self.views.get();
        if alive > 0 {
            return Err(PyRuntimeError::new_err(format!(
                "{alive} view(s) of particle arrays are alive: a command may move the storage \
                 they look at; delete them first (del v) or take copies (sim.x, sim.array(name))"
            )));
        }
        let flag = interrupted();
        flag.store(false, Ordering::SeqCst);
        let raised: Rc<RefCell<Option<PyErr>>> = Rc::new(RefCell::new(None));
        self.interp.sim.outputs.step_hook = Some(step_hook(
            self.callback.as_ref().map(|(n, f)| (*n, f.clone_ref(py))),
            Rc::clone(&raised),
            Arc::clone(flag),
        ));
        let interp = WhileWaiting(&mut self.interp);
        let pool = &self.pool;
        let result = py.detach(move || {
            let interp = interp.get();
            let job = WhileWaiting(interp);
            pool.install(move || {
                let interp = job.get();
                let r = match src {
                    Source::File(p) => interp.run_file(&p),
                    Source::Text(name, text) => interp.run_source(&name, &text),
                };
                interp.sim.outputs.out.flush();
                WhileWaiting(r)
            })
            .get()
        });
        self.interp.sim.outputs.step_hook = None;
        if let Some(e) = raised.borrow_mut().take() {
            return Err(e);
        }
        if flag.swap(false, Ordering::SeqCst) {
            py.check_signals()?;
            return Err(PyKeyboardInterrupt::new_err("rdem run interrupted"));
        }
        result.map_err(|r| rdem_error(py, *r))
    }
}

/// A Python `ValueError` with the message of an error of the script crate.
fn value_error(e: rdem_script::error::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// The hook a run calls after every step: stops at Ctrl-C, calls the callback every
/// `n` steps.
fn step_hook(
    callback: Option<(u64, Py<PyAny>)>,
    raised: Rc<RefCell<Option<PyErr>>>,
    flag: Arc<AtomicBool>,
) -> rdem_script::sim::StepHook {
    Box::new(move |sim: &Sim, step: u64| {
        if flag.load(Ordering::Relaxed) {
            return Err("interrupted (Ctrl-C)".into());
        }
        let Some((every, f)) = &callback else {
            return Ok(true);
        };
        if step % every != 0 {
            return Ok(true);
        }
        Python::attach(|py| {
            let alive = Arc::new(AtomicBool::new(true));
            let view = StepView {
                sim: sim as *const Sim,
                alive: Arc::clone(&alive),
            };
            let r = Py::new(py, view).and_then(|v| f.call1(py, (v,)));
            alive.store(false, Ordering::SeqCst);
            match r {
                Ok(v) if v.is_none(py) => Ok(true),
                Ok(v) => match v.is_truthy(py) {
                    Ok(b) => Ok(b),
                    Err(e) => {
                        *raised.borrow_mut() = Some(e);
                        Err("the callback's result has no truth value".into())
                    }
                },
                Err(e) => {
                    let m = format!("the callback raised {e}");
                    *raised.borrow_mut() = Some(e);
                    Err(m.into())
                }
            }
        })
    })
}

fn rdem_error(py: Python<'_>, r: ScriptReport) -> PyErr {
    let message = r.message().to_string();
    let loc = r.location();
    let report = format!("{:?}", miette::Report::new(r));
    let e = RdemError::new_err(message.clone());
    let v = e.value(py);
    let (file, line, column) = match loc {
        Some((f, l, c)) => (Some(f), Some(l), Some(c)),
        None => (None, None, None),
    };
    let _ = v.setattr("file", file);
    let _ = v.setattr("line", line);
    let _ = v.setattr("column", column);
    let _ = v.setattr("message", message);
    let _ = v.setattr("report", report);
    e
}

/// Keeps a view's count while the numpy array that looks at rdem's storage lives.
#[pyclass(unsendable, module = "rdem._rdem")]
struct ViewGuard {
    views: Rc<Cell<usize>>,
}

impl Drop for ViewGuard {
    fn drop(&mut self) {
        self.views.set(self.views.get() - 1);
    }
}

#[pymethods]
impl Simulation {
    /// A new simulation. `threads`: threads of its force pass (default: all cores;
    /// results do not depend on it); `log`: a log file, as `-log` (default none);
    /// `screen`: print the output on standard output, as the rdem command does.
    #[new]
    #[pyo3(signature = (threads=None, log=None, screen=false))]
    fn new(threads: Option<usize>, log: Option<&str>, screen: bool) -> PyResult<Self> {
        let threads = match threads {
            Some(0) => return Err(PyValueError::new_err("threads must be at least 1")),
            Some(n) => n,
            None => std::thread::available_parallelism().map_or(1, |n| n.get()),
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start {threads} threads: {e}")))?;
        let mut out = Output::stdout();
        if !screen {
            out.set_screen(None);
        }
        if let Some(l) = log {
            out.set_log(Some(l), false)
                .map_err(|e| PyRuntimeError::new_err(format!("cannot open log file '{l}': {e}")))?;
        }
        let mut sim = Sim::new(out);
        sim.script.threads = threads;
        Ok(Self {
            interp: Interpreter::new(sim),
            pool,
            callback: None,
            views: Rc::new(Cell::new(0)),
        })
    }

    /// Runs the script file `path` (as `rdem -in path`, or LIGGGHTS' `include`).
    fn file(&mut self, py: Python<'_>, path: &str) -> PyResult<()> {
        self.run(py, Source::File(path.to_string()))
    }

    /// Runs one command line.
    fn command(&mut self, py: Python<'_>, line: &str) -> PyResult<()> {
        self.run(py, Source::Text("<command>".into(), format!("{line}\n")))
    }

    /// Runs several lines of script (continuation lines, loops and labels work).
    fn commands(&mut self, py: Python<'_>, text: &str) -> PyResult<()> {
        self.run(py, Source::Text("<commands>".into(), text.to_string()))
    }

    /// Calls `callback(view)` every `every` steps of the runs that follow (None: no
    /// more calls). `view` reads the state as the simulation does (x, thermo, variable(),
    /// ...) during the call only. Returning False ends the run after that step (the
    /// script goes on); an exception ends the run and is raised by the command.
    #[pyo3(signature = (callback, every=1))]
    fn set_callback(&mut self, callback: Option<Py<PyAny>>, every: u64) -> PyResult<()> {
        if every == 0 {
            return Err(PyValueError::new_err("every must be at least 1"));
        }
        self.callback = callback.map(|f| (every, f));
        Ok(())
    }

    /// A read-only numpy view of rdem's own storage of array `name` (x, v, omega, f,
    /// torque: n×3; radius, mass, density), without a copy. It cannot be written, and
    /// no command runs while a view is alive (a command may move the storage): delete
    /// views before the next command. Use the attributes (sim.x, ...) for copies.
    fn view<'py>(slf: &Bound<'py, Self>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let this = slf.borrow();
        let views = Rc::clone(&this.views);
        views.set(views.get() + 1);
        let guard = Bound::new(py, ViewGuard { views })?.into_any();
        let sim = this.sim()?;
        world(sim)?;
        if let Some(v) = vec3_of(sim, name) {
            const _: () = assert!(std::mem::size_of::<DVec3>() == 24);
            // SAFETY: DVec3 is #[repr(C)] with three f64 and no padding (checked above).
            let flat = unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<f64>(), v.len() * 3) };
            let a = ArrayView2::from_shape((v.len(), 3), flat).expect("n×3 values");
            // SAFETY: the storage is not reallocated while the guard (the array's base)
            // lives: every command refuses to run while a guard is alive.
            let arr = unsafe { PyArray2::borrow_from_array(&a, guard) };
            arr.readwrite().make_nonwriteable();
            return Ok(arr.into_any());
        }
        if let Some(v) = scalar_of(sim, name) {
            let a = ArrayView1::from(v);
            // SAFETY: as above.
            let arr = unsafe { PyArray1::borrow_from_array(&a, guard) };
            arr.readwrite().make_nonwriteable();
            return Ok(arr.into_any());
        }
        Err(PyKeyError::new_err(format!(
            "no view of '{name}': x, v, omega, f, torque, radius, mass, density (copies of \
             every array, tag, type and named properties included: sim.array(name))"
        )))
    }
}

readers!(Simulation);

/// The simulation as a callback sees it, during the call only. (Callbacks run on a
/// thread of the simulation's pool, and Python may drop the view on any thread.)
#[pyclass(module = "rdem._rdem")]
pub struct StepView {
    sim: *const Sim,
    alive: Arc<AtomicBool>,
}

// SAFETY: the pointer is read only while `alive` is set, that is while the hook that
// made the view runs with the `&Sim` borrowed and nothing changes the simulation (the
// thread that owns it waits for the command); reading a `&Sim` from several threads at
// once is fine, and an expired view reads nothing.
unsafe impl Send for StepView {}
unsafe impl Sync for StepView {}

impl StepView {
    fn sim(&self) -> PyResult<&Sim> {
        if !self.alive.load(Ordering::SeqCst) {
            return Err(PyRuntimeError::new_err(
                "this view of a running simulation was kept after its callback returned",
            ));
        }
        // SAFETY: while `alive` is set the hook that made the view is running with the
        // `&Sim` it points at borrowed, and nothing changes the simulation meanwhile.
        Ok(unsafe { &*self.sim })
    }
}

readers!(StepView);

/// The `rdem` command with these arguments (the package's `rdem` script); returns its
/// exit status.
#[pyfunction]
fn cli(py: Python<'_>, args: Vec<String>) -> i32 {
    let code = py.detach(|| rdem_cli::main(&args));
    // ExitCode has no accessor: the command returns 0, 1 or 2.
    if code == std::process::ExitCode::SUCCESS {
        0
    } else if code == std::process::ExitCode::from(2) {
        2
    } else {
        1
    }
}

#[pymodule]
fn _rdem(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Simulation>()?;
    m.add_class::<StepView>()?;
    m.add_function(wrap_pyfunction!(cli, m)?)?;
    m.add("RdemError", m.py().get_type::<RdemError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

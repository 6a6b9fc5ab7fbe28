//! `curvenet._curvenet`: the Python extension module (PyO3 + rust-numpy). Thin glue only:
//! arrays in and out, options by name (the library's table, [`curvenet::pipeline::OPTIONS`]),
//! [`curvenet::Error`] → `curvenet.Error` and its subclasses with the error's place as
//! attributes (`curve`, `sample`, `node`, `segment`, `patch`, `vertex`). The numerics are
//! the library's; the Python package `curvenet` (python/curvenet/__init__.py) wraps these
//! functions with the documented signatures and checks array shapes and dtypes first.
//!
//! The GIL is released (`Python::detach`) around every solve and evaluation.

use curvenet::geom::DVec3;
use curvenet::metrics::{evaluate, Reference, Truth};
use curvenet::{Options, Preset};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;

pyo3::create_exception!(
    _curvenet,
    Error,
    PyValueError,
    "Every error of curvenet: a ValueError with the place as attributes."
);
pyo3::create_exception!(
    _curvenet,
    InputError,
    Error,
    "The input is malformed or invalid (file position, curve, sample)."
);
pyo3::create_exception!(
    _curvenet,
    TopologyError,
    Error,
    "The curves do not bound an oriented 2-manifold (node, segment, patch)."
);
pyo3::create_exception!(_curvenet, NumericalError, Error, "A system is singular or ill-conditioned (patch, vertex).");
pyo3::create_exception!(_curvenet, UsageError, Error, "An option value or a file name cannot be used.");

/// The library's error as the Python class of its kind, with the message and the ids of its
/// place as attributes (`None` where unknown).
fn err(e: curvenet::Error) -> PyErr {
    Python::attach(|py| {
        let message = e.to_string();
        let pe = match &e {
            curvenet::Error::Parse { .. } | curvenet::Error::Input { .. } => InputError::new_err(message),
            curvenet::Error::Topology { .. } => TopologyError::new_err(message),
            curvenet::Error::Numerical { .. } => NumericalError::new_err(message),
            curvenet::Error::Usage { .. } => UsageError::new_err(message),
            curvenet::Error::Memory { .. } => pyo3::exceptions::PyMemoryError::new_err(message),
            _ => Error::new_err(message),
        };
        let value = pe.value(py);
        let at = e.at();
        let (line, column, path) = match &e {
            curvenet::Error::Parse { line, column, path, .. } => (Some(*line), Some(*column), Some(path.clone())),
            curvenet::Error::Io { path, .. } => (None, None, Some(path.clone())),
            _ => (None, None, None),
        };
        let set = || -> PyResult<()> {
            value.setattr("kind", e.kind())?;
            value.setattr("curve", at.curve)?;
            value.setattr("sample", at.sample)?;
            value.setattr("node", at.node)?;
            value.setattr("segment", at.segment)?;
            value.setattr("patch", at.patch)?;
            value.setattr("vertex", at.vertex)?;
            value.setattr("point", at.point.map(|p| (p[0], p[1], p[2])))?;
            value.setattr("path", path)?;
            value.setattr("line", line)?;
            value.setattr("column", column)
        };
        match set() {
            Ok(()) => pe,
            Err(other) => other,
        }
    })
}

/// An argument the glue cannot use (array shapes, indices): a `curvenet.UsageError`.
fn usage(msg: String) -> PyErr {
    UsageError::new_err(msg)
}

/// `obj` as a C-contiguous NumPy array of float64 (`integer`: int64) with `ndim` dimensions
/// and, when given, `cols` columns; a `TypeError` or `ValueError` naming `name`, the expected
/// shape and what was given otherwise. Lists and other real dtypes are converted.
fn checked<'py>(
    name: &str,
    obj: &Bound<'py, PyAny>,
    ndim: usize,
    cols: Option<usize>,
    integer: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let shape_text = match (ndim, cols) {
        (1, _) => "(n,)".to_string(),
        (_, Some(c)) => format!("(n, {c})"),
        _ => "(n, d)".to_string(),
    };
    let a = np.call_method1("asarray", (obj,))?;
    let kind: String = a.getattr("dtype")?.getattr("kind")?.extract()?;
    let dtype: String = a.getattr("dtype")?.str()?.extract()?;
    let ok = if integer { "iu".contains(kind.as_str()) } else { "fiu".contains(kind.as_str()) };
    if !ok {
        let want = if integer { "an integer array (int64)" } else { "a real array (float64)" };
        return Err(PyTypeError::new_err(format!("{name} must be {want} of shape {shape_text}, got dtype {dtype}")));
    }
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    if shape.len() != ndim || cols.is_some_and(|c| shape[1] != c) {
        return Err(usage(format!("{name} must have shape {shape_text}, got {shape:?}")));
    }
    let target = if integer { np.getattr("int64")? } else { np.getattr("float64")? };
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", target)?;
    np.call_method("ascontiguousarray", (a,), Some(&kwargs))
}

fn array2<'py>(name: &str, obj: &Bound<'py, PyAny>, cols: Option<usize>) -> PyResult<PyReadonlyArray2<'py, f64>> {
    checked(name, obj, 2, cols, false)?.extract()
}

fn index2<'py>(name: &str, obj: &Bound<'py, PyAny>) -> PyResult<PyReadonlyArray2<'py, i64>> {
    checked(name, obj, 2, Some(3), true)?.extract()
}

fn index1<'py>(name: &str, obj: &Bound<'py, PyAny>) -> PyResult<PyReadonlyArray1<'py, i64>> {
    checked(name, obj, 1, None, true)?.extract()
}

/// Rows of an `(n, 3)` array as points (the Python layer checked the shape; checked again).
fn points(name: &str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<DVec3>> {
    let v = a.as_array();
    if v.ncols() != 3 {
        return Err(usage(format!("{name} must have shape (n, 3), got {:?}", v.shape())));
    }
    Ok(v.rows().into_iter().map(|r| DVec3::new(r[0], r[1], r[2])).collect())
}

fn faces(a: &PyReadonlyArray2<'_, i64>) -> PyResult<Vec<[u32; 3]>> {
    let v = a.as_array();
    if v.ncols() != 3 {
        return Err(usage(format!("F must have shape (m, 3), got {:?}", v.shape())));
    }
    v.rows()
        .into_iter()
        .enumerate()
        .map(|(i, r)| {
            let mut f = [0u32; 3];
            for k in 0..3 {
                f[k] =
                    u32::try_from(r[k]).map_err(|_| usage(format!("F[{i}, {k}] = {} is not a vertex index", r[k])))?;
            }
            Ok(f)
        })
        .collect()
}

/// An `(n, 3)` float64 array and an `(m, 3)` int64 array owned by Python.
type Points<'py> = Bound<'py, numpy::PyArray2<f64>>;
type Indices<'py> = Bound<'py, numpy::PyArray2<i64>>;

fn to_array(p: &[DVec3]) -> Array2<f64> {
    Array2::from_shape_fn((p.len(), 3), |(i, c)| p[i][c])
}

/// A curve as Python gives it: `(points, normals or None, closed, boundary)`.
type CurveTuple<'py> = (Bound<'py, PyAny>, Option<Bound<'py, PyAny>>, bool, bool);
/// A crease curve: `(points, normals, closed, boundary, normals_right or None)`.
type CreaseTuple<'py> = (Bound<'py, PyAny>, Option<Bound<'py, PyAny>>, bool, bool, Option<Bound<'py, PyAny>>);

/// A curve's parts, from a tuple or a dict ([`curve_parts`]).
struct CurveParts<'py> {
    points: Bound<'py, PyAny>,
    normals: Option<Bound<'py, PyAny>>,
    closed: bool,
    boundary: bool,
    normals_right: Option<Bound<'py, PyAny>>,
    name: Option<String>,
}

/// The keys of a curve given as a dict (those of the network JSON).
const CURVE_KEYS: [&str; 6] = ["points", "normals", "closed", "boundary", "name", "normals_right"];

/// Curve `i` of a list: a `(points, normals or None, closed, boundary[, normals_right])`
/// tuple, a dict (a `curvenet.Curve`) with the JSON keys — `points` required, the others
/// optional; an unknown key is an error naming it and the closest known one — or a bare
/// polyline (a `(k, 3)` array or list of points: open, normals inferred).
fn curve_parts<'py>(i: usize, item: &Bound<'py, PyAny>) -> PyResult<CurveParts<'py>> {
    if let Ok(d) = item.cast::<PyDict>() {
        for key in d.keys() {
            let key: String =
                key.extract().map_err(|_| usage(format!("curve {i}: the keys of a curve dict are strings")))?;
            if !CURVE_KEYS.contains(&key.as_str()) {
                let hint = curvenet::io::closest_key(&key, &CURVE_KEYS)
                    .map(|k| format!(" — did you mean `{k}`?"))
                    .unwrap_or_default();
                return Err(usage(format!(
                    "curve {i}: unknown key `{key}`{hint} (the keys are {})",
                    CURVE_KEYS.join(", ")
                )));
            }
        }
        let get = |k: &str| d.get_item(k).map(|v| v.filter(|v| !v.is_none()));
        let flag = |k: &str| -> PyResult<bool> {
            get(k)?.map_or(Ok(false), |v| {
                v.extract::<bool>().map_err(|_| usage(format!("curve {i}: `{k}` must be True or False")))
            })
        };
        let points = get("points")?.ok_or_else(|| usage(format!("curve {i}: a curve dict needs `points`")))?;
        let name = get("name")?
            .map(|v| v.extract::<String>().map_err(|_| usage(format!("curve {i}: `name` must be a string"))))
            .transpose()?;
        return Ok(CurveParts {
            points,
            normals: get("normals")?,
            closed: flag("closed")?,
            boundary: flag("boundary")?,
            normals_right: get("normals_right")?,
            name,
        });
    }
    if item.cast::<pyo3::types::PyTuple>().is_err() {
        // Anything else is a polyline: a (k, 3) array or list of points, open, normals inferred.
        return Ok(CurveParts {
            points: item.clone(),
            normals: None,
            closed: false,
            boundary: false,
            normals_right: None,
            name: None,
        });
    }
    let (points, normals, closed, boundary, normals_right) = match item.extract::<CurveTuple<'_>>() {
        Ok((p, n, c, b)) => (p, n, c, b, None),
        Err(_) => item.extract::<CreaseTuple<'_>>().map_err(|_| {
            usage(format!(
                "curve {i}: expected a dict (curvenet.Curve) or a tuple (points, normals or None, closed, boundary[, normals_right or None])"
            ))
        })?,
    };
    Ok(CurveParts { points, normals, closed, boundary, normals_right, name: None })
}

/// `(message, curve, sample, node, patch)` of a warning.
type WarningTuple = (String, Option<usize>, Option<usize>, Option<usize>, Option<usize>);

/// A curve network: curves sampled with normals (`curvenet::Network`).
#[pyclass(module = "curvenet._curvenet", name = "Network")]
#[derive(Clone)]
struct PyNetwork {
    inner: curvenet::Network,
    /// The file it was read from: `method="cauchy"` reads its per-curve attributes from it (as
    /// the command line does, only for that method).
    source: Option<std::path::PathBuf>,
}

#[pymethods]
impl PyNetwork {
    /// `curves`: a list of dicts (`curvenet.Curve`) with the network JSON's keys — `points`
    /// (n,3) float64, and optionally `normals` (n,3) or None (unknown: inferred), `closed`,
    /// `boundary`, `name`, `normals_right` (n,3) (a crease: the surface's normal on the right
    /// of the curve) — or of `(points, normals or None, closed, boundary[, normals_right])`
    /// tuples.
    #[new]
    #[pyo3(signature = (curves, snap=None))]
    fn new(curves: Vec<Bound<'_, PyAny>>, snap: Option<f64>) -> PyResult<Self> {
        let mut out = Vec::with_capacity(curves.len());
        for (i, item) in curves.iter().enumerate() {
            let CurveParts { points: p, normals: n, closed, boundary, normals_right: r, name } = curve_parts(i, item)?;
            let (pn, nn, rn) =
                (format!("curve {i}: points"), format!("curve {i}: normals"), format!("curve {i}: normals_right"));
            let vectors = |name: &str, a: &Option<Bound<'_, PyAny>>| -> PyResult<Vec<DVec3>> {
                match a {
                    Some(a) => points(name, &array2(name, a, Some(3))?),
                    None => Ok(Vec::new()),
                }
            };
            out.push(curvenet::Curve {
                name,
                points: points(&pn, &array2(&pn, &p, Some(3))?)?,
                normals: vectors(&nn, &n)?,
                normals_right: vectors(&rn, &r)?,
                closed,
                boundary,
            });
        }
        Ok(PyNetwork { inner: curvenet::Network { curves: out, snap, cycles: None }, source: None })
    }

    /// Per curve, its crease normals `normals_right` (n,3), or `None` for a smooth curve.
    #[getter]
    fn normals_right<'py>(&self, py: Python<'py>) -> Vec<Option<Points<'py>>> {
        self.inner.curves.iter().map(|c| c.is_crease().then(|| to_array(&c.normals_right).into_pyarray(py))).collect()
    }

    /// The curves as `(points, normals, closed, boundary)` tuples (copies; `normals` is `None`
    /// where they are unknown).
    #[getter]
    fn curves<'py>(&self, py: Python<'py>) -> Vec<(Points<'py>, Option<Points<'py>>, bool, bool)> {
        self.inner
            .curves
            .iter()
            .map(|c| {
                let normals = c.has_normals().then(|| to_array(&c.normals).into_pyarray(py));
                (to_array(&c.points).into_pyarray(py), normals, c.closed, c.boundary)
            })
            .collect()
    }

    #[getter]
    fn snap(&self) -> Option<f64> {
        self.inner.snap
    }

    /// The patches' cycles given with the network (`curvenet.cycles`, docs/design.md §15): per
    /// patch a list of `(curve, first sample, last sample, forward)` segments; `None`: found
    /// by the run. Settable (a cycle removed leaves its patch open).
    #[getter]
    fn cycles(&self) -> Option<Vec<curvenet::network::CycleKey>> {
        self.inner.cycles.clone()
    }

    #[setter]
    fn set_cycles(&mut self, cycles: Option<Vec<curvenet::network::CycleKey>>) {
        self.inner.cycles = cycles;
    }

    /// Writes the network (`.json`, `.net`, `.obj`, as the CLI).
    fn write(&self, path: &str) -> PyResult<()> {
        curvenet::io::write_network(Path::new(path), &self.inner).map_err(err)
    }

    fn __len__(&self) -> usize {
        self.inner.curves.len()
    }

    fn __repr__(&self) -> String {
        format!("Network({} curves, {} samples)", self.inner.curves.len(), self.inner.num_samples())
    }
}

/// Reads a network file; what the file holds that was not read (an unknown JSON key, with its
/// line and the closest known one) is a `UserWarning`.
#[pyfunction]
fn read_network(py: Python<'_>, path: &str) -> PyResult<PyNetwork> {
    let (inner, warnings) = curvenet::io::read_network_with_warnings(Path::new(path)).map_err(err)?;
    for w in &warnings {
        let text = std::ffi::CString::new(w.to_string().replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &text, 1)?;
    }
    Ok(PyNetwork { inner, source: Some(Path::new(path).to_path_buf()) })
}

#[pyfunction]
fn example(name: &str) -> PyResult<PyNetwork> {
    let names: Vec<&str> = curvenet::network::examples::EXAMPLES.iter().map(|e| e.0).collect();
    match curvenet::network::examples::example(name) {
        Some(inner) => Ok(PyNetwork { inner, source: None }),
        None => Err(usage(format!("unknown example \"{name}\"; the examples are: {}", names.join(", ")))),
    }
}

/// A network from polyscope-style arrays: `nodes (N, 3)`, `edges (E, 2)` (0-based), optional
/// `normals (N, 3)` ([`curvenet::io::network_from_edges`]).
#[pyfunction]
#[pyo3(signature = (nodes, edges, normals=None))]
fn _network_from_edges(
    nodes: Bound<'_, PyAny>,
    edges: Bound<'_, PyAny>,
    normals: Option<Bound<'_, PyAny>>,
) -> PyResult<PyNetwork> {
    let nodes = points("nodes", &array2("nodes", &nodes, Some(3))?)?;
    let e: PyReadonlyArray2<'_, i64> = checked("edges", &edges, 2, Some(2), true)?.extract()?;
    let edges: Vec<[i64; 2]> = e.as_array().rows().into_iter().map(|r| [r[0], r[1]]).collect();
    let normals = normals.map(|n| points("normals", &array2("normals", &n, Some(3))?)).transpose()?;
    let inner = curvenet::io::network_from_edges(&nodes, &edges, normals.as_deref()).map_err(err)?;
    Ok(PyNetwork { inner, source: None })
}

#[pyfunction]
fn examples() -> Vec<(&'static str, &'static str)> {
    curvenet::network::examples::EXAMPLES.to_vec()
}

/// The library options: `preset` ("default", "fast", "paper"), then every option given as
/// `(name, text)` over it ([`Options::from_named`], the command line's path too).
#[pyfunction]
fn _options(preset: &str, given: Vec<(String, String)>) -> PyResult<PyOptions> {
    let preset = Preset::from_name(preset).map_err(err)?;
    let given: Vec<(&str, &str)> = given.iter().map(|(n, v)| (n.as_str(), v.as_str())).collect();
    Ok(PyOptions { inner: Options::from_named(preset, &given).map_err(err)? })
}

/// Surfaces the network file `input` into the mesh file `output` with the options `(preset,
/// [(name, value)])` (plain data, so that it travels to another process or a Dask worker):
/// the report as JSON text (`curvenet batch`'s report line). Never raises for the file's
/// faults: they are the report's. The GIL is released during the run.
#[pyfunction]
fn _surface_file(
    py: Python<'_>,
    input: &str,
    output: &str,
    preset: &str,
    given: Vec<(String, String)>,
) -> PyResult<String> {
    let preset = Preset::from_name(preset).map_err(err)?;
    let named: Vec<(&str, &str)> = given.iter().map(|(n, v)| (n.as_str(), v.as_str())).collect();
    let options = Options::from_named(preset, &named).map_err(err)?;
    let report = py.detach(|| {
        curvenet::pipeline::files::surface_file(std::path::Path::new(input), std::path::Path::new(output), &options)
    });
    serde_json::to_string(&report).map_err(|e| usage(e.to_string()))
}

/// The jobs of a batch (`curvenet batch`'s expansion and naming): files, folders and glob
/// patterns in `inputs`, each with its mesh `out_dir/STEM.FORMAT`, as `(input, output)`.
#[pyfunction]
fn _plan_files(inputs: Vec<String>, out_dir: &str, format: &str) -> PyResult<Vec<(String, String)>> {
    use curvenet::pipeline::files::{expand_inputs, plan_outputs};
    let files = expand_inputs(&inputs).map_err(err)?;
    let jobs = plan_outputs(&files, std::path::Path::new(out_dir), format);
    let mut outputs: Vec<std::path::PathBuf> = jobs.iter().map(|j| j.output.clone()).collect();
    outputs.push(std::path::Path::new(out_dir).join(curvenet::io::folder::LOCK_FILE));
    curvenet::io::folder::check_outputs_apart(&files, &outputs).map_err(err)?;
    Ok(jobs.into_iter().map(|j| (j.input.display().to_string(), j.output.display().to_string())).collect())
}

/// The lock of an output folder (`curvenet::io::folder::FolderLock`), held until `release()`
/// or until the object is collected; the process's end releases it too.
#[pyclass]
struct _FolderLock {
    inner: Option<curvenet::io::folder::FolderLock>,
}

#[pymethods]
impl _FolderLock {
    fn release(&mut self) {
        self.inner = None;
    }
}

/// Locks the existing folder `out_dir` for one batch (a `UsageError` when another run holds
/// it) and removes the temporary files that dead runs left in it; returns the lock and the
/// number of files removed.
#[pyfunction]
fn _lock_folder(out_dir: &str) -> PyResult<(_FolderLock, usize)> {
    let dir = std::path::Path::new(out_dir);
    let lock = curvenet::io::folder::FolderLock::acquire(dir).map_err(err)?;
    let removed = curvenet::io::folder::remove_stale_temporaries(dir).len();
    Ok((_FolderLock { inner: Some(lock) }, removed))
}

/// The option table: `(name, value_name, choices, help, default)` per option.
#[pyfunction]
fn _option_specs() -> Vec<(&'static str, &'static str, Vec<&'static str>, &'static str, String)> {
    curvenet::pipeline::OPTIONS
        .iter()
        .map(|s| (s.name, s.value_name, s.choices.to_vec(), s.help, s.default_text()))
        .collect()
}

/// Resolved surfacing options (built by `curvenet._options`).
#[pyclass(module = "curvenet._curvenet", name = "Options", frozen)]
#[derive(Clone)]
struct PyOptions {
    inner: Options,
}

#[pymethods]
impl PyOptions {
    fn __repr__(&self) -> String {
        format!("{:?}", self.inner)
    }
}

/// `(V, F, info)` of a surface: positions `(n,3)` float64, faces `(m,3)` int64, and a dict
/// with the statistics (as `--stats`), warnings and per-vertex arrays.
fn result<'py>(py: Python<'py>, s: curvenet::Surface) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
    let v = to_array(&s.mesh.positions).into_pyarray(py);
    let faces = &s.mesh.faces;
    let f = Array2::from_shape_fn((faces.len(), 3), |(i, c)| faces[i][c] as i64).into_pyarray(py);
    let info = PyDict::new(py);
    let stats = serde_json::to_string(&s.stats).map_err(|e| usage(e.to_string()))?;
    info.set_item("stats_json", stats)?;
    let warnings = warning_tuples(&s.warnings);
    info.set_item("warnings", warnings)?;
    info.set_item("num_curve", s.mesh.num_curve)?;
    info.set_item("curve", Array1::from(s.curve_flags.clone()).into_pyarray(py))?;
    info.set_item("normals", to_array(&s.normals).into_pyarray(py))?;
    info.set_item("mean_curvature", Array1::from(s.mean_curvature.clone()).into_pyarray(py))?;
    match &s.propagated_normals {
        Some(n) => info.set_item("propagated_normals", to_array(n).into_pyarray(py))?,
        None => info.set_item("propagated_normals", py.None())?,
    }
    pyo3::types::PyTuple::new(py, [v.into_any(), f.into_any(), info.into_any()])
}

/// `options` with the per-curve attributes of the network's file for `method="cauchy"` (as the
/// command line reads them from the same JSON file, for that method only).
fn with_attributes(network: &PyNetwork, options: &Options) -> PyResult<Options> {
    let mut o = options.clone();
    if let (curvenet::Method::Cauchy, None, Some(path)) = (o.method, &o.cauchy.attributes, &network.source) {
        o.cauchy.attributes =
            curvenet::methods::andrews2011::NetworkAttributes::read(path).map_err(err)?.map(std::sync::Arc::new);
    }
    Ok(o)
}

/// `progress`: a callable `(stage, seconds, detail)` called after each stage of the run (and
/// each 3D iteration), with the GIL; its first exception is raised after the run.
#[pyfunction]
#[pyo3(signature = (network, options, progress=None))]
fn _surface<'py>(
    py: Python<'py>,
    network: &PyNetwork,
    options: &PyOptions,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
    let opts = with_attributes(network, &options.inner)?;
    let net = &network.inner;
    let raised: std::sync::Mutex<Option<PyErr>> = std::sync::Mutex::new(None);
    let s = py
        .detach(|| match &progress {
            None => curvenet::surface(net, &opts),
            Some(callback) => curvenet::surface_with_progress(net, &opts, &mut |stage, seconds, detail| {
                Python::attach(|py| {
                    if let Err(e) = callback.call1(py, (stage, seconds, detail)) {
                        let mut slot = raised.lock().unwrap_or_else(|p| p.into_inner());
                        slot.get_or_insert(e);
                    }
                })
            }),
        })
        .map_err(err)?;
    if let Some(e) = raised.into_inner().unwrap_or_else(|p| p.into_inner()) {
        return Err(e);
    }
    result(py, s)
}

/// The network with the normals of its curves without inferred (`curvenet::infer_normals`):
/// `(network, report as JSON, warnings)`.
#[pyfunction]
fn _infer_normals(
    py: Python<'_>,
    network: &PyNetwork,
    options: &PyOptions,
) -> PyResult<(PyNetwork, String, Vec<WarningTuple>)> {
    let net = &network.inner;
    let opts = &options.inner;
    let inferred = py.detach(|| curvenet::infer_normals(net, opts)).map_err(err)?;
    let report = serde_json::to_string(&inferred.report).map_err(|e| usage(e.to_string()))?;
    Ok((
        PyNetwork { inner: inferred.network, source: network.source.clone() },
        report,
        warning_tuples(&inferred.warnings),
    ))
}

/// The network a surface run uses, with its patches' cycles (`curvenet::network_with_cycles`):
/// `(network, warnings)`.
#[pyfunction]
fn _cycles(py: Python<'_>, network: &PyNetwork, options: &PyOptions) -> PyResult<(PyNetwork, Vec<WarningTuple>)> {
    let (net, opts) = (&network.inner, &options.inner);
    let (out, warnings) = py.detach(|| curvenet::network_with_cycles(net, opts)).map_err(err)?;
    Ok((PyNetwork { inner: out, source: network.source.clone() }, warning_tuples(&warnings)))
}

/// `network` with patch `patch` left open (`curvenet::with_patch_left_open`).
#[pyfunction]
fn _open_patch(py: Python<'_>, network: &PyNetwork, options: &PyOptions, patch: usize) -> PyResult<PyNetwork> {
    let (net, opts) = (&network.inner, &options.inner);
    let out = py.detach(|| curvenet::with_patch_left_open(net, opts, patch)).map_err(err)?;
    Ok(PyNetwork { inner: out, source: network.source.clone() })
}

/// `network` with the open cycle along curve `curve` filled (`curvenet::with_cycle_filled`).
#[pyfunction]
fn _fill_cycle(py: Python<'_>, network: &PyNetwork, options: &PyOptions, curve: usize) -> PyResult<PyNetwork> {
    let (net, opts) = (&network.inner, &options.inner);
    let out = py.detach(|| curvenet::with_cycle_filled(net, opts, curve)).map_err(err)?;
    Ok(PyNetwork { inner: out, source: network.source.clone() })
}

/// The warnings of a stage as Python takes them.
fn warning_tuples(warnings: &[curvenet::Warning]) -> Vec<WarningTuple> {
    warnings.iter().map(|w| (w.message.clone(), w.at.curve, w.at.sample, w.at.node, w.at.patch)).collect()
}

/// The network with its raw strokes consolidated (`curvenet::topology::consolidate`):
/// `(network, report as JSON, warnings)`.
#[pyfunction]
fn _consolidate(
    py: Python<'_>,
    network: &PyNetwork,
    options: &PyOptions,
) -> PyResult<(PyNetwork, String, Vec<WarningTuple>)> {
    let net = &network.inner;
    let opts = &options.inner;
    let mut c = opts.consolidate;
    c.enabled = true;
    let done = py.detach(|| curvenet::topology::consolidate::consolidate(net, &c, opts.mesh.snap)).map_err(err)?;
    let report = serde_json::to_string(&done.report).map_err(|e| usage(e.to_string()))?;
    Ok((PyNetwork { inner: done.network, source: network.source.clone() }, report, warning_tuples(&done.warnings)))
}

/// A network prepared for repeated solves that keeps its mesh and factorisations
/// (`curvenet::Surfacer`).
#[pyclass(module = "curvenet._curvenet", name = "_Surfacer")]
struct PySurfacer {
    inner: curvenet::Surfacer,
}

#[pymethods]
impl PySurfacer {
    #[new]
    fn new(py: Python<'_>, network: &PyNetwork, options: &PyOptions) -> PyResult<Self> {
        let opts = with_attributes(network, &options.inner)?;
        let net = &network.inner;
        let inner = py.detach(|| curvenet::Surfacer::new(net, &opts)).map_err(err)?;
        Ok(PySurfacer { inner })
    }

    fn solve<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        let inner = &mut self.inner;
        let s = py.detach(|| inner.solve()).map_err(err)?;
        result(py, s)
    }

    fn update_normals(&mut self, curve: usize, normals: Bound<'_, PyAny>) -> PyResult<()> {
        let n = points("normals", &array2("normals", &normals, Some(3))?)?;
        self.inner.update_normals(curve, &n).map_err(err)
    }

    fn update_points(&mut self, curve: usize, points_: Bound<'_, PyAny>) -> PyResult<()> {
        let p = points("points", &array2("points", &points_, Some(3))?)?;
        self.inner.update_points(curve, &p).map_err(err)
    }

    #[getter]
    fn network(&self) -> PyNetwork {
        PyNetwork { inner: self.inner.network().clone(), source: None }
    }

    #[getter]
    fn is_factored(&self) -> bool {
        self.inner.is_factored()
    }
}

/// `Δᵏ X = 0` on the mesh with `X[b] = bc` (`curvenet::methods::harmonic::harmonic`).
#[pyfunction]
fn _harmonic<'py>(
    py: Python<'py>,
    v: Bound<'py, PyAny>,
    f: Bound<'py, PyAny>,
    b: Bound<'py, PyAny>,
    bc: Bound<'py, PyAny>,
    k: usize,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let positions = points("V", &array2("V", &v, Some(3))?)?;
    let faces = faces(&index2("F", &f)?)?;
    let b = index1("b", &b)?;
    let bc = array2("bc", &bc, None)?;
    let fixed: Vec<usize> = b
        .as_array()
        .iter()
        .enumerate()
        .map(|(i, &x)| usize::try_from(x).map_err(|_| usage(format!("b[{i}] = {x} is not a vertex index"))))
        .collect::<PyResult<_>>()?;
    let bcv = bc.as_array();
    if bcv.nrows() != fixed.len() {
        return Err(usage(format!("bc has {} rows for {} fixed vertices in b", bcv.nrows(), fixed.len())));
    }
    let columns = bcv.ncols();
    let values: Vec<f64> = bcv.iter().copied().collect();
    let x = py
        .detach(|| curvenet::methods::harmonic::harmonic(&positions, &faces, &fixed, &values, columns, k))
        .map_err(err)?;
    let out = Array2::from_shape_vec((positions.len(), columns), x).map_err(|e| usage(e.to_string()))?;
    Ok(out.into_pyarray(py))
}

/// Measures `(V, F)` against `truth` (a spec as `curvenet eval --truth`, or a mesh file), or
/// against the reference mesh `(ref_v, ref_f)`; returns the evaluation as JSON text.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (v, f, truth=None, ref_v=None, ref_f=None, exclude=None, normals=None))]
fn _eval(
    py: Python<'_>,
    v: Bound<'_, PyAny>,
    f: Bound<'_, PyAny>,
    truth: Option<&str>,
    ref_v: Option<Bound<'_, PyAny>>,
    ref_f: Option<Bound<'_, PyAny>>,
    exclude: Option<PyReadonlyArray1<'_, bool>>,
    normals: Option<Bound<'_, PyAny>>,
) -> PyResult<String> {
    let positions = points("V", &array2("V", &v, Some(3))?)?;
    let fcs = faces(&index2("F", &f)?)?;
    let n = positions.len();
    if let Some(i) = fcs.iter().flatten().find(|&&i| i as usize >= n) {
        return Err(usage(format!("F refers to vertex {i}, but V has {n} vertices")));
    }
    let exclude: Vec<bool> = match &exclude {
        Some(e) if e.as_array().len() != n => {
            return Err(usage(format!("exclude has {} entries for {n} vertices", e.as_array().len())))
        }
        Some(e) => e.as_array().to_vec(),
        None => vec![false; n],
    };
    let normals = match &normals {
        Some(a) => {
            let p = points("normals", &array2("normals", a, Some(3))?)?;
            if p.len() != n {
                return Err(usage(format!("normals has {} rows for {n} vertices", p.len())));
            }
            Some(p)
        }
        None => None,
    };
    let (ref_positions, ref_faces);
    let reference = match (truth, &ref_v, &ref_f) {
        (Some(spec), None, None) => match Truth::parse(spec) {
            Some(Ok(t)) => Reference::Analytic(t),
            Some(Err(e)) => return Err(usage(e)),
            None => {
                let m = curvenet::io::read_mesh(Path::new(spec)).map_err(err)?;
                (ref_positions, ref_faces) = (m.positions, m.faces);
                Reference::Mesh { positions: &ref_positions, faces: &ref_faces }
            }
        },
        (None, Some(rv), Some(rf)) => {
            (ref_positions, ref_faces) =
                (points("reference V", &array2("reference V", rv, Some(3))?)?, faces(&index2("reference F", rf)?)?);
            if let Some(i) = ref_faces.iter().flatten().find(|&&i| i as usize >= ref_positions.len()) {
                return Err(usage(format!("the reference F refers to vertex {i} out of range")));
            }
            Reference::Mesh { positions: &ref_positions, faces: &ref_faces }
        }
        _ => return Err(usage("give truth (a spec or a mesh file) or a reference mesh (V, F)".into())),
    };
    let e = py.detach(|| evaluate(&positions, &fcs, normals.as_deref(), &exclude, reference, None));
    serde_json::to_string(&e).map_err(|e| usage(e.to_string()))
}

/// Reads a mesh file (`.ply`, `.obj`, `.off`, as the CLI writes them): `(V, F)`.
#[pyfunction]
fn read_mesh<'py>(py: Python<'py>, path: &str) -> PyResult<(Points<'py>, Indices<'py>)> {
    let m = curvenet::io::read_mesh(Path::new(path)).map_err(err)?;
    let f = Array2::from_shape_fn((m.faces.len(), 3), |(i, c)| m.faces[i][c] as i64);
    Ok((to_array(&m.positions).into_pyarray(py), f.into_pyarray(py)))
}

#[pymodule]
fn _curvenet(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Under `ulimit -v`, as many threads as the matrix products' workspaces leave room for.
    curvenet::solve::memory::fit_thread_pool_to_address_space();
    m.add_class::<PyNetwork>()?;
    m.add_class::<PyOptions>()?;
    m.add_class::<PySurfacer>()?;
    m.add_function(wrap_pyfunction!(read_network, m)?)?;
    m.add_function(wrap_pyfunction!(read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(example, m)?)?;
    m.add_function(wrap_pyfunction!(examples, m)?)?;
    m.add_function(wrap_pyfunction!(_network_from_edges, m)?)?;
    m.add_function(wrap_pyfunction!(_options, m)?)?;
    m.add_function(wrap_pyfunction!(_option_specs, m)?)?;
    m.add("Error", m.py().get_type::<Error>())?;
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("TopologyError", m.py().get_type::<TopologyError>())?;
    m.add("NumericalError", m.py().get_type::<NumericalError>())?;
    m.add("UsageError", m.py().get_type::<UsageError>())?;
    m.add_function(wrap_pyfunction!(_surface, m)?)?;
    m.add_function(wrap_pyfunction!(_surface_file, m)?)?;
    m.add_function(wrap_pyfunction!(_plan_files, m)?)?;
    m.add_function(wrap_pyfunction!(_lock_folder, m)?)?;
    m.add_class::<_FolderLock>()?;
    m.add_function(wrap_pyfunction!(_infer_normals, m)?)?;
    m.add_function(wrap_pyfunction!(_consolidate, m)?)?;
    m.add_function(wrap_pyfunction!(_cycles, m)?)?;
    m.add_function(wrap_pyfunction!(_open_patch, m)?)?;
    m.add_function(wrap_pyfunction!(_fill_cycle, m)?)?;
    m.add_function(wrap_pyfunction!(_harmonic, m)?)?;
    m.add_function(wrap_pyfunction!(_eval, m)?)?;
    Ok(())
}

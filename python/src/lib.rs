//! `curvenet._curvenet`: the Python extension module (PyO3 + rust-numpy). Thin glue only:
//! arrays in and out, options by name, [`curvenet::Error`] → `ValueError`. The numerics are
//! the library's; the Python package `curvenet` (python/curvenet/__init__.py) wraps these
//! functions with the documented signatures and checks array shapes and dtypes first.
//!
//! The GIL is released (`Python::detach`) around every solve and evaluation.

use curvenet::geom::DVec3;
use curvenet::metrics::{evaluate, Reference, Truth};
use curvenet::{GuideArea, Method, Options, Patching, Weighting};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;

/// The library's error as a Python `ValueError` with its message.
fn err(e: curvenet::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

fn usage(msg: String) -> PyErr {
    PyValueError::new_err(msg)
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

/// A curve network: curves sampled with normals (`curvenet::Network`).
#[pyclass(module = "curvenet._curvenet", name = "Network")]
#[derive(Clone)]
struct PyNetwork {
    inner: curvenet::Network,
}

#[pymethods]
impl PyNetwork {
    /// `curves`: a list of `(points (n,3) float64, normals (n,3) float64, closed, boundary)`.
    #[new]
    #[pyo3(signature = (curves, snap=None))]
    fn new(curves: Vec<(Bound<'_, PyAny>, Bound<'_, PyAny>, bool, bool)>, snap: Option<f64>) -> PyResult<Self> {
        let mut out = Vec::with_capacity(curves.len());
        for (i, (p, n, closed, boundary)) in curves.iter().enumerate() {
            let (pn, nn) = (format!("curve {i}: points"), format!("curve {i}: normals"));
            out.push(curvenet::Curve {
                name: None,
                points: points(&pn, &array2(&pn, p, Some(3))?)?,
                normals: points(&nn, &array2(&nn, n, Some(3))?)?,
                closed: *closed,
                boundary: *boundary,
            });
        }
        Ok(PyNetwork { inner: curvenet::Network { curves: out, snap } })
    }

    /// The curves as `(points, normals, closed, boundary)` tuples (copies).
    #[getter]
    fn curves<'py>(&self, py: Python<'py>) -> Vec<(Points<'py>, Points<'py>, bool, bool)> {
        self.inner
            .curves
            .iter()
            .map(|c| {
                (to_array(&c.points).into_pyarray(py), to_array(&c.normals).into_pyarray(py), c.closed, c.boundary)
            })
            .collect()
    }

    #[getter]
    fn snap(&self) -> Option<f64> {
        self.inner.snap
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

#[pyfunction]
fn read_network(path: &str) -> PyResult<PyNetwork> {
    Ok(PyNetwork { inner: curvenet::io::read_network(Path::new(path)).map_err(err)? })
}

#[pyfunction]
fn example(name: &str) -> PyResult<PyNetwork> {
    let names: Vec<&str> = curvenet::network::examples::EXAMPLES.iter().map(|e| e.0).collect();
    match curvenet::network::examples::example(name) {
        Some(inner) => Ok(PyNetwork { inner }),
        None => Err(usage(format!("unknown example \"{name}\"; the examples are: {}", names.join(", ")))),
    }
}

#[pyfunction]
fn examples() -> Vec<(&'static str, &'static str)> {
    curvenet::network::examples::EXAMPLES.to_vec()
}

/// The library options: `preset` ("default", "fast", "paper"), then every option given
/// (not `None`) overrides it. Names as the CLI's flags.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (preset="default", method=None, spacing=None, vertices=None, soft=None, w1=None,
    patching=None, iterations=None, inner_steps=None, tolerance=None, normal_prior=None, energy=None,
    guide_area=None, guide_updates=None, snap=None))]
fn _options(
    preset: &str,
    method: Option<&str>,
    spacing: Option<f64>,
    vertices: Option<usize>,
    soft: Option<f64>,
    w1: Option<f64>,
    patching: Option<&str>,
    iterations: Option<usize>,
    inner_steps: Option<usize>,
    tolerance: Option<f64>,
    normal_prior: Option<f64>,
    energy: Option<&str>,
    guide_area: Option<&str>,
    guide_updates: Option<usize>,
    snap: Option<f64>,
) -> PyResult<PyOptions> {
    let mut o = match preset {
        "default" => Options::default(),
        "fast" => Options::fast(),
        "paper" => Options::paper(),
        _ => return Err(usage(format!("unknown preset \"{preset}\" (default, fast, paper)"))),
    };
    let bad = |what: &str, v: &str, all: &str| usage(format!("unknown {what} \"{v}\" ({all})"));
    if let Some(m) = method {
        let all: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        o.method = Method::from_name(m).ok_or_else(|| bad("method", m, &all.join(", ")))?;
    }
    if let Some(p) = patching {
        o.patching = match p {
            "planar" => Patching::Planar,
            "conformal" => Patching::Conformal,
            _ => return Err(bad("patching", p, "planar, conformal")),
        };
    }
    if let Some(e) = energy {
        o.energy = match e {
            "area" => Weighting::Area,
            "uniform" => Weighting::Uniform,
            _ => return Err(bad("energy", e, "area, uniform")),
        };
    }
    if let Some(g) = guide_area {
        o.guide_area = match g {
            "mass" => GuideArea::Mass,
            "surface" => GuideArea::Surface,
            _ => return Err(bad("guide_area", g, "mass, surface")),
        };
    }
    if spacing.is_some() && vertices.is_some() {
        return Err(usage("give spacing or vertices, not both".into()));
    }
    o.spacing = spacing.or(o.spacing);
    o.vertices = vertices.or(o.vertices);
    o.soft = soft.or(o.soft);
    o.w1 = w1.unwrap_or(o.w1);
    o.iterations = iterations.unwrap_or(o.iterations);
    o.inner_steps = inner_steps.unwrap_or(o.inner_steps);
    o.tolerance = tolerance.unwrap_or(o.tolerance);
    o.normal_prior = normal_prior.unwrap_or(o.normal_prior);
    o.guide_updates = guide_updates.unwrap_or(o.guide_updates);
    o.snap = snap.or(o.snap);
    Ok(PyOptions { inner: o })
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
    info.set_item("warnings", s.warnings.iter().map(|w| w.message.clone()).collect::<Vec<_>>())?;
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

#[pyfunction]
fn _surface<'py>(
    py: Python<'py>,
    network: &PyNetwork,
    options: &PyOptions,
) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
    let (net, opts) = (&network.inner, &options.inner);
    let s = py.detach(|| curvenet::surface(net, opts)).map_err(err)?;
    result(py, s)
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
        let (net, opts) = (&network.inner, &options.inner);
        let inner = py.detach(|| curvenet::Surfacer::new(net, opts)).map_err(err)?;
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

    #[getter]
    fn network(&self) -> PyNetwork {
        PyNetwork { inner: self.inner.network().clone() }
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
    let x = py.detach(|| curvenet::methods::harmonic::harmonic(&positions, &faces, &fixed, &values, columns, k)).map_err(err)?;
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
    m.add_class::<PyNetwork>()?;
    m.add_class::<PyOptions>()?;
    m.add_class::<PySurfacer>()?;
    m.add_function(wrap_pyfunction!(read_network, m)?)?;
    m.add_function(wrap_pyfunction!(read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(example, m)?)?;
    m.add_function(wrap_pyfunction!(examples, m)?)?;
    m.add_function(wrap_pyfunction!(_options, m)?)?;
    m.add_function(wrap_pyfunction!(_surface, m)?)?;
    m.add_function(wrap_pyfunction!(_harmonic, m)?)?;
    m.add_function(wrap_pyfunction!(_eval, m)?)?;
    Ok(())
}

//! The Python extension module `topoplex._core`: PyO3 classes over the core library, imported by
//! the pure-Python package `topoplex` (python/topoplex/__init__.py), which adds the array
//! checks, scipy matrices and the meshio, GUDHI and trimesh converters on top.
//!
//! Arrays leave Rust without a second copy: each answer is a `Vec` moved into a numpy array
//! (`PyArray::from_vec`), and 2-D answers are reshaped views of it. Arrays come in as
//! C-contiguous arrays of the exact dtype (the Python layer converts anything else once) and are
//! read in place. Every call that walks the complex releases the GIL (`Python::detach`), so
//! Python threads query one structure in parallel. Errors become the exceptions of
//! `topoplex._errors` with the library's message.

use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use numpy::{
    PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
    ndarray::Dim,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyType};
use topoplex::complex::{Attribute, Attributes, Coords, Location, Values};
use topoplex::live::{
    ACROSS_MANY, ACROSS_NONE, ContractMode, LiveComplex, Refusal, TopId, UndoRecord,
};
use topoplex::store::{ComplexSpans, Saved, Span};
use topoplex::{Budget, Complex, Navigate, Order, StructureKind, Topology, VertexId};

/// A failure on the Rust side, named by the Python exception class it becomes
/// (`topoplex._errors`), with the library's message.
#[derive(Debug)]
enum Fail {
    /// Bad input: arrays, ids, simplices not in the complex, a refused kind (`InputError`).
    Input(String),
    /// A structure's domain excludes the complex (`DomainError`).
    Domain(String),
    /// A live edit was refused, the mesh unchanged (`EditRefused`).
    Refused(String),
    /// A file could not be read (`ReadError`).
    Read(String),
    /// A file could not be written (`WriteError`).
    Write(String),
    /// Too large for memory or for 32-bit ids (`TopoplexMemoryError`).
    Memory(String),
    /// No attribute of that name (`KeyError`).
    Key(String),
}

impl From<Fail> for PyErr {
    fn from(f: Fail) -> PyErr {
        let (class, msg) = match f {
            Fail::Input(m) => ("InputError", m),
            Fail::Domain(m) => ("DomainError", m),
            Fail::Refused(m) => ("EditRefused", m),
            Fail::Read(m) => ("ReadError", m),
            Fail::Write(m) => ("WriteError", m),
            Fail::Memory(m) => ("TopoplexMemoryError", m),
            Fail::Key(m) => return pyo3::exceptions::PyKeyError::new_err(m),
        };
        Python::attach(|py| {
            match py
                .import("topoplex._errors")
                .and_then(|m| m.getattr(class))
                .and_then(|t| Ok(t.cast_into::<PyType>()?))
            {
                Ok(t) => PyErr::from_type(t, msg),
                Err(e) => e,
            }
        })
    }
}

fn query_fail(e: topoplex::QueryError) -> Fail {
    match e {
        topoplex::QueryError::TooLarge { .. } => Fail::Memory(e.to_string()),
        _ => Fail::Input(e.to_string()),
    }
}

fn build_fail(e: topoplex::BuildError) -> Fail {
    match e {
        topoplex::BuildError::TooLarge { .. } => Fail::Memory(e.to_string()),
        _ => Fail::Domain(e.to_string()),
    }
}

fn complex_fail(e: topoplex::ComplexError) -> Fail {
    use topoplex::ComplexError as E;
    match e {
        E::Read(_) => Fail::Read(e.to_string()),
        E::TooLarge { .. } | E::OutOfMemory { .. } => Fail::Memory(e.to_string()),
        _ => Fail::Input(e.to_string()),
    }
}

/// A file that cannot be opened or whose content is malformed is a `ReadError` (the message
/// names the file and line); only running out of memory is not.
fn open_fail(e: topoplex::store::OpenError) -> Fail {
    use topoplex::ComplexError as E;
    match e {
        topoplex::store::OpenError::Read(c @ (E::TooLarge { .. } | E::OutOfMemory { .. })) => {
            Fail::Memory(c.to_string())
        }
        other => Fail::Read(other.to_string()),
    }
}

/// A saved file that cannot be opened or is malformed is a `ReadError`; memory it asks for that
/// cannot be had (a mapping, a copy, a build) is a `TopoplexMemoryError`.
fn store_fail(e: topoplex::store::StoreError) -> Fail {
    use topoplex::ComplexError as C;
    use topoplex::store::StoreError as S;
    match &e {
        S::Complex {
            source: C::TooLarge { .. } | C::OutOfMemory { .. },
            ..
        }
        | S::Build {
            source: topoplex::BuildError::TooLarge { .. },
            ..
        } => Fail::Memory(e.to_string()),
        _ => Fail::Read(e.to_string()),
    }
}

fn kind_of(name: &str) -> Result<StructureKind, Fail> {
    StructureKind::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = StructureKind::NAMED.iter().map(|k| k.name()).collect();
        Fail::Input(format!(
            "unknown structure {name:?}: one of {}",
            names.join(", ")
        ))
    })
}

/// A `Vec` moved into a 1-D numpy array (no copy).
fn vec1<T: numpy::Element>(py: Python<'_>, v: Vec<T>) -> Bound<'_, PyArray1<T>> {
    PyArray1::from_vec(py, v)
}

/// A `Vec` of `rows × cols` moved into numpy and viewed as a 2-D C-contiguous array (no copy:
/// the view's base is the 1-D array that owns the `Vec`).
fn vec2<T: numpy::Element>(py: Python<'_>, v: Vec<T>, cols: usize) -> PyResult<Bound<'_, PyAny>> {
    let rows = v.len().checked_div(cols).unwrap_or(0);
    let a = PyArray1::from_vec(py, v);
    Ok(a.reshape(Dim([rows, cols]))?.into_any())
}

/// An immutable simplicial complex: the closure of the simplices given, with optional vertex
/// coordinates and attributes. Made by `topoplex.read`, `topoplex.open` or
/// `Complex.from_arrays`.
#[pyclass(module = "topoplex._core", name = "Complex", frozen, weakref)]
struct PyComplex {
    inner: Arc<Complex>,
    /// The incidence graph, built on the first call that needs every simplex.
    ig: OnceLock<Result<Box<dyn Topology>, String>>,
    /// For a complex opened from a saved file: the file mapped for Python, where its arrays
    /// are viewed rather than copied.
    lent: Option<Arc<Lent>>,
}

impl PyComplex {
    fn wrap(c: Complex) -> PyComplex {
        PyComplex::with_lent(Arc::new(c), None)
    }

    fn with_lent(inner: Arc<Complex>, lent: Option<Arc<Lent>>) -> PyComplex {
        PyComplex {
            inner,
            ig: OnceLock::new(),
            lent,
        }
    }

    fn ig(&self, py: Python<'_>) -> Result<&dyn Topology, Fail> {
        let got = py.detach(|| {
            self.ig.get_or_init(|| {
                topoplex::build(StructureKind::Ig, &self.inner).map_err(|e| e.to_string())
            })
        });
        match got {
            Ok(s) => Ok(s.as_ref()),
            Err(m) => Err(Fail::Memory(m.clone())),
        }
    }
}

/// A saved file mapped read-only by Python's `mmap` (a buffer numpy views without copying),
/// and where the arrays of its complex lie in it. Safe Rust only (the C ABI crate and the
/// core's `sys` are the only places for `unsafe`): numpy gets the bytes through the buffer
/// protocol of Python's own map, each view's `.base` chain (a memoryview of the map) keeping
/// the map alive however long the view outlives the complex; the map is read-only, so every
/// view is (`writeable` False, and cannot be set True).
struct Lent {
    map: Py<PyAny>,
    spans: ComplexSpans,
}

impl Lent {
    /// `count` elements of numpy type `dtype` at the span, viewed as `cols` columns when
    /// `cols > 1`.
    fn view<'py>(
        &self,
        py: Python<'py>,
        span: Span,
        dtype: &str,
        cols: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let np = py.import("numpy")?;
        let a = if span.count == 0 {
            // An empty section may sit at the file's very end, where frombuffer refuses the
            // offset; there is nothing to view anyway.
            let a = np.call_method1("empty", (0, dtype))?;
            let kw = PyDict::new(py);
            kw.set_item("write", false)?;
            a.call_method("setflags", (), Some(&kw))?;
            a
        } else {
            let kw = PyDict::new(py);
            kw.set_item("dtype", dtype)?;
            kw.set_item("count", span.count)?;
            kw.set_item("offset", span.offset)?;
            np.call_method("frombuffer", (self.map.bind(py),), Some(&kw))?
        };
        if cols > 1 {
            a.call_method1("reshape", (-1, cols))
        } else {
            Ok(a)
        }
    }
}

/// Opens a saved file for the binding: the core's [`Saved`] and, on Unix, the same open file
/// mapped again by Python's `mmap` (read-only), so the complex's arrays can be lent as views;
/// both maps are of one file whatever is renamed over `path` meanwhile.
fn open_saved(py: Python<'_>, path: &std::path::Path) -> PyResult<(Saved, Option<Py<PyAny>>)> {
    let (file, _) = topoplex::io::open_regular(path)
        .map_err(|e| Fail::Read(format!("{}: {e}", path.display())))?;
    let saved = py
        .detach(|| Saved::open_file(path, &file))
        .map_err(store_fail)?;
    #[cfg(unix)]
    let map = {
        use std::os::fd::AsRawFd;
        let mmap = py.import("mmap")?;
        let kw = PyDict::new(py);
        kw.set_item("access", mmap.getattr("ACCESS_READ")?)?;
        // Python's mmap duplicates the descriptor; ours is closed when `file` drops.
        Some(
            mmap.getattr("mmap")?
                .call((file.as_raw_fd(), 0), Some(&kw))?
                .unbind(),
        )
    };
    #[cfg(not(unix))]
    let map = None;
    Ok((saved, map))
}

/// The complex of an opened file, with its arrays lent from `map` when there is one.
fn saved_complex(
    py: Python<'_>,
    saved: &Saved,
    map: Option<Py<PyAny>>,
) -> PyResult<(Complex, Option<Arc<Lent>>)> {
    let (c, spans) = py.detach(|| saved.complex_spans()).map_err(store_fail)?;
    Ok((c, map.map(|map| Arc::new(Lent { map, spans }))))
}

fn dtype_of(v: &Values) -> &'static str {
    match v {
        Values::I32(_) => "int32",
        Values::I64(_) => "int64",
        Values::F32(_) => "float32",
        Values::F64(_) => "float64",
    }
}

fn location_name(l: Location) -> &'static str {
    match l {
        Location::Vertices => "vertices",
        Location::Listed => "listed",
    }
}

/// The attributes as a dict: name → (location, array of shape (n,) or (n, components)); views
/// into the saved file when `lent`, else copies.
fn attributes_dict<'py>(
    py: Python<'py>,
    attrs: &Attributes,
    lent: Option<&Lent>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for a in attrs.iter() {
        let c = a.components;
        let span = lent.and_then(|l| {
            l.spans
                .attributes
                .iter()
                .find(|(n, _)| *n == a.name)
                .map(|(_, s)| (l, *s))
        });
        if let Some((l, span)) = span {
            let arr = l.view(py, span, dtype_of(&a.values), c)?;
            d.set_item(&a.name, (location_name(a.location), arr))?;
            continue;
        }
        let arr = match &a.values {
            Values::I32(v) => vec2(py, v.clone(), c)?,
            Values::I64(v) => vec2(py, v.clone(), c)?,
            Values::F32(v) => vec2(py, v.clone(), c)?,
            Values::F64(v) => vec2(py, v.clone(), c)?,
        };
        let arr = if c == 1 {
            arr.call_method1("reshape", (-1,))?
        } else {
            arr
        };
        d.set_item(&a.name, (location_name(a.location), arr))?;
    }
    Ok(d)
}

/// The coordinates as an (n, dim) float64 array: a view into the saved file when `lent`, else
/// a copy.
fn coords_array<'py>(
    py: Python<'py>,
    c: Option<&Coords>,
    lent: Option<&Lent>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    match (c, lent.and_then(|l| l.spans.coords.map(|s| (l, s)))) {
        (Some(c), Some((l, span))) if c.dim > 0 => {
            // A 1-column view keeps its 2-D shape, as the copy does.
            let a = l.view(py, span, "float64", 1)?;
            Ok(Some(a.call_method1("reshape", (-1, c.dim))?))
        }
        (Some(c), _) if c.dim > 0 => Ok(Some(vec2(py, c.data.clone(), c.dim)?)),
        _ => Ok(None),
    }
}

/// The coordinates an (n, k) points array gives, copied (k numbers a vertex).
fn coords_of(points: Option<&PyReadonlyArray2<'_, f64>>) -> PyResult<Option<Coords>> {
    points
        .map(|p| {
            Ok(Coords {
                dim: p.shape()[1],
                data: p.as_slice()?.to_vec(),
            })
        })
        .transpose()
}

#[pymethods]
impl PyComplex {
    /// Builds from a CSR of simplices: simplex i is `ids[offsets[i]:offsets[i+1]]`.
    #[staticmethod]
    #[pyo3(signature = (n_vertices, ids, offsets, points=None))]
    fn _from_csr(
        py: Python<'_>,
        n_vertices: u32,
        ids: PyReadonlyArray1<'_, u32>,
        offsets: PyReadonlyArray1<'_, usize>,
        points: Option<PyReadonlyArray2<'_, f64>>,
    ) -> PyResult<PyComplex> {
        let ids = ids.as_slice()?;
        let offsets = offsets.as_slice()?;
        check_csr(ids, offsets)?;
        let coords = coords_of(points.as_ref())?;
        let c = py
            .detach(|| Complex::from_arrays(n_vertices, ids, offsets, coords))
            .map_err(complex_fail)?;
        Ok(PyComplex::wrap(c))
    }

    /// Builds from one block of simplices of `arity` vertices each: simplex i is
    /// `ids[i*arity:(i+1)*arity]` (an (n, arity) array, flat), without offsets.
    #[staticmethod]
    #[pyo3(signature = (n_vertices, arity, ids, points=None))]
    fn _from_uniform(
        py: Python<'_>,
        n_vertices: u32,
        arity: usize,
        ids: PyReadonlyArray1<'_, u32>,
        points: Option<PyReadonlyArray2<'_, f64>>,
    ) -> PyResult<PyComplex> {
        let ids = ids.as_slice()?;
        let coords = coords_of(points.as_ref())?;
        let c = py
            .detach(|| Complex::from_uniform(n_vertices, arity, ids, coords))
            .map_err(complex_fail)?;
        Ok(PyComplex::wrap(c))
    }

    /// Reads a mesh file (by extension) or a saved `.tpx` file (its arrays then lent as
    /// read-only views into the file).
    #[staticmethod]
    fn _read(py: Python<'_>, path: PathBuf) -> PyResult<PyComplex> {
        if topoplex::store::is_saved_path(&path) {
            let (saved, map) = open_saved(py, &path)?;
            let (c, lent) = saved_complex(py, &saved, map)?;
            return Ok(PyComplex::with_lent(Arc::new(c), lent));
        }
        let c = py
            .detach(|| topoplex::store::open_complex(&path, Budget::default()))
            .map_err(open_fail)?;
        Ok(PyComplex::wrap(c))
    }

    /// Number of vertices (ids are `0..vertex_count`).
    #[getter]
    fn vertex_count(&self) -> u32 {
        self.inner.vertex_count()
    }

    /// The dimension (the largest simplex's, 0 for vertices only).
    #[getter]
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }

    /// Vertex coordinates as a float64 array of shape (n, k), or None.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        coords_array(py, self.inner.coords(), self.lent.as_deref())
    }

    /// Attributes as a dict: name → (location, array); location is "vertices" or "listed".
    #[getter]
    fn attributes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        attributes_dict(py, self.inner.attributes(), self.lent.as_deref())
    }

    /// Whether the arrays (`points`, `attributes`, `listed()`) are read-only views into a
    /// saved file rather than copies.
    #[getter]
    fn mapped(&self) -> bool {
        self.lent.is_some()
    }

    /// Number of p-simplices.
    fn count(&self, py: Python<'_>, p: usize) -> PyResult<usize> {
        if p > self.inner.dimension() {
            return Ok(0);
        }
        Ok(self.ig(py)?.count(p))
    }

    /// Every p-simplex as rows of p+1 ascending ids, in ascending lexicographic order.
    fn simplices<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        let ig = self.ig(py)?;
        let mut out = Vec::new();
        if p <= self.inner.dimension() {
            py.detach(|| ig.simplices(p, &mut out));
        }
        vec2(py, out, p + 1)
    }

    /// The top p-simplices (faces of no other simplex), rows of ascending ids.
    fn tops<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        let mut out = Vec::new();
        if p <= self.inner.dimension() {
            let t = self.inner.tops(p);
            for i in 0..t.len() {
                out.extend_from_slice(t.get(i));
            }
        }
        vec2(py, out, p + 1)
    }

    /// Writes the complex (its simplices as listed, with their winding and data) to a file;
    /// the format by the extension or by `format` (off, obj, mesh, simplices, ply, stl, vtk,
    /// vtu, msh, ...).
    #[pyo3(signature = (path, format=None))]
    fn write(&self, py: Python<'_>, path: PathBuf, format: Option<&str>) -> PyResult<()> {
        let format = match format {
            Some(f) => Some(
                topoplex::io::write::Format::from_name(f)
                    .ok_or_else(|| Fail::Input(format!("unknown format {f:?}")))?,
            ),
            None => None,
        };
        py.detach(|| topoplex::io::write::write_complex(&self.inner, &path, format))
            .map_err(|e| Fail::Write(e.to_string()))?;
        Ok(())
    }

    /// Builds a structure of the survey by name (ig, sig, ia, iqm, nmia, ts, pe, le, de) or the
    /// live mesh (iastar).
    fn build(&self, py: Python<'_>, kind: &str) -> PyResult<PyStructure> {
        let kind = kind_of(kind)?;
        if kind == StructureKind::IaStar {
            return self.live(py);
        }
        let s = py
            .detach(|| topoplex::build(kind, &self.inner))
            .map_err(build_fail)?;
        Ok(PyStructure {
            inner: Inner::Fixed(s),
            complex: Some(self.inner.clone()),
            lent: self.lent.clone(),
        })
    }

    /// The live (editable) mesh of this complex.
    fn live(&self, py: Python<'_>) -> PyResult<PyStructure> {
        let l = py
            .detach(|| LiveComplex::try_from_complex(&self.inner))
            .map_err(build_fail)?;
        Ok(PyStructure {
            inner: Inner::Live(Box::new(l)),
            complex: None,
            lent: None,
        })
    }

    /// A copy with attribute `name` set (replacing one of that name).
    fn _with_attribute(
        &self,
        name: &str,
        location: &str,
        values: Bound<'_, PyAny>,
    ) -> PyResult<PyComplex> {
        let location = match location {
            "vertices" => Location::Vertices,
            "listed" => Location::Listed,
            other => {
                return Err(
                    Fail::Input(format!("location {other:?}: \"vertices\" or \"listed\"")).into(),
                );
            }
        };
        let (values, components) = values_of(&values)?;
        let mut c = (*self.inner).clone();
        let mut attrs = c.take_attributes();
        attrs.remove(name);
        attrs.insert(Attribute {
            name: name.to_string(),
            location,
            components,
            values,
        });
        c.set_attributes(attrs).map_err(complex_fail)?;
        Ok(PyComplex::wrap(c))
    }

    /// A copy without attribute `name` (KeyError when it has none).
    fn _without_attribute(&self, name: &str) -> PyResult<PyComplex> {
        let mut c = (*self.inner).clone();
        let mut attrs = c.take_attributes();
        if !attrs.remove(name) {
            return Err(pyo3::exceptions::PyKeyError::new_err(name.to_string()));
        }
        c.set_attributes(attrs).map_err(complex_fail)?;
        Ok(PyComplex::wrap(c))
    }

    /// Saves the complex, and `structure` when given, as a `.tpx` file.
    #[pyo3(signature = (path, structure=None))]
    fn _save(
        &self,
        py: Python<'_>,
        path: PathBuf,
        structure: Option<PyRef<'_, PyStructure>>,
    ) -> PyResult<()> {
        let s = structure.as_ref().map(|s| s.topo());
        py.detach(|| topoplex::store::save(&path, &self.inner, s))
            .map_err(|e| Fail::Write(e.to_string()))?;
        Ok(())
    }

    /// The simplices as listed (input order, each with its vertex order as given, repeats and
    /// faces included): a CSR pair `(offsets, ids)`. Attributes on "listed" are per row.
    fn listed<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        if let Some(l) = &self.lent {
            // The saved offsets are u64 from 0 to the ids' length: the same bytes as int64.
            let offsets = l.view(py, l.spans.listed_offsets, "int64", 1)?;
            let ids = l.view(py, l.spans.listed_ids, "uint32", 1)?;
            return Ok((offsets, ids));
        }
        let c = &self.inner;
        let n = c.input_count();
        let mut offsets = Vec::with_capacity(n + 1);
        let mut ids = Vec::new();
        offsets.push(0i64);
        for i in 0..n {
            ids.extend_from_slice(c.input_simplex(i));
            offsets.push(ids.len() as i64);
        }
        Ok((vec1(py, offsets).into_any(), vec1(py, ids).into_any()))
    }

    /// Census: dimension, vertex count, simplices and top simplices per dimension.
    fn census<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let ig = self.ig(py)?;
        census(py, ig)
    }

    fn __repr__(&self) -> String {
        format!(
            "<topoplex.Complex: {} vertices, dimension {}, tops {:?}>",
            self.inner.vertex_count(),
            self.inner.dimension(),
            self.inner.top_counts()
        )
    }
}

/// An attribute's values from a C-contiguous numpy array of int32, int64, float32 or float64,
/// shape (n,) or (n, c).
fn values_of(a: &Bound<'_, PyAny>) -> PyResult<(Values, usize)> {
    let shape: Vec<usize> = a.getattr("shape")?.extract()?;
    let comps = if shape.len() == 2 { shape[1] } else { 1 };
    let flat = a.call_method1("reshape", (-1,))?;
    if let Ok(v) = flat.extract::<PyReadonlyArray1<'_, i32>>() {
        return Ok((Values::I32(v.as_slice()?.to_vec()), comps));
    }
    if let Ok(v) = flat.extract::<PyReadonlyArray1<'_, i64>>() {
        return Ok((Values::I64(v.as_slice()?.to_vec()), comps));
    }
    if let Ok(v) = flat.extract::<PyReadonlyArray1<'_, f32>>() {
        return Ok((Values::F32(v.as_slice()?.to_vec()), comps));
    }
    if let Ok(v) = flat.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok((Values::F64(v.as_slice()?.to_vec()), comps));
    }
    Err(Fail::Input("attribute values: int32, int64, float32 or float64 array".into()).into())
}

fn census<'py>(py: Python<'py>, t: &dyn Topology) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let dim = t.dimension();
    d.set_item("dimension", dim)?;
    d.set_item("vertices", t.vertex_count())?;
    let counts: Vec<usize> = (0..=dim).map(|p| t.count(p)).collect();
    let tops: Vec<usize> = (0..=dim).map(|p| t.top_count(p)).collect();
    d.set_item("simplices", counts)?;
    d.set_item("tops", tops)?;
    Ok(d)
}

enum Inner {
    Fixed(Box<dyn Topology>),
    Live(Box<LiveComplex>),
}

/// A built structure (one of the survey's nine, by name) or the live editable mesh
/// (`iastar`). Every p-simplex has a dense index: its rank among the p-simplices in ascending
/// lexicographic order of its sorted vertex ids (a vertex: its id), as `simplices(p)` lists
/// them.
#[pyclass(module = "topoplex._core", name = "Structure")]
struct PyStructure {
    inner: Inner,
    /// The complex it was built on (None for the live mesh, whose complex changes).
    complex: Option<Arc<Complex>>,
    /// The complex's arrays in the saved file it was opened from, if any.
    lent: Option<Arc<Lent>>,
}

impl PyStructure {
    fn topo(&self) -> &dyn Topology {
        match &self.inner {
            Inner::Fixed(s) => s.as_ref(),
            Inner::Live(l) => l.as_ref(),
        }
    }

    fn nav(&self) -> Result<&dyn Navigate, Fail> {
        self.topo()
            .as_navigate()
            .ok_or_else(|| Fail::Input(format!("{} has no navigation", self.topo().kind())))
    }

    fn live_mut(&mut self) -> Result<&mut LiveComplex, Fail> {
        match &mut self.inner {
            Inner::Live(l) => Ok(l),
            Inner::Fixed(s) => Err(Fail::Input(format!(
                "structure `{}` is not editable: edit the live mesh (complex.live())",
                s.kind()
            ))),
        }
    }

    fn live_ref(&self) -> Result<&LiveComplex, Fail> {
        match &self.inner {
            Inner::Live(l) => Ok(l),
            Inner::Fixed(s) => Err(Fail::Input(format!(
                "structure `{}` is not the live mesh",
                s.kind()
            ))),
        }
    }

    /// The dense p-indices of every p-simplex, in the order of `simplices(p)`: `0..count(p)`,
    /// except for the vertices of the live mesh, which are named by their ids, removed ones
    /// skipped until `compact()`.
    fn all_indices(&self, p: usize) -> Vec<u32> {
        match &self.inner {
            Inner::Live(l) if p == 0 => l.vertices().map(|v| v.0).collect(),
            _ => (0..self.topo().count(p) as u32).collect(),
        }
    }

    /// Applies `edit` to each row of a CSR (ids, offsets) of simplices of the live mesh, in
    /// order, the GIL released; stops at the first refusal, naming its row (the rows before it
    /// stay edited). Returns the number of rows.
    fn edit_rows(
        &mut self,
        py: Python<'_>,
        ids: PyReadonlyArray1<'_, u32>,
        offsets: PyReadonlyArray1<'_, usize>,
        edit: fn(&mut LiveComplex, &[u32]) -> Result<(), Refusal>,
    ) -> PyResult<usize> {
        let ids = ids.as_slice()?;
        let offsets = offsets.as_slice()?;
        check_csr(ids, offsets)?;
        let l = self.live_mut()?;
        py.detach(|| {
            for (i, w) in offsets.windows(2).enumerate() {
                edit(l, &ids[w[0]..w[1]]).map_err(|e| Fail::Refused(format!("row {i}: {e}")))?;
            }
            Ok::<_, Fail>(offsets.len().saturating_sub(1))
        })
        .map_err(PyErr::from)
    }

    /// The dense p-indices `simplices` a query names, or all of them ([`Self::all_indices`]).
    fn selected<'a>(
        &self,
        p: usize,
        simplices: &'a Option<PyReadonlyArray1<'_, u32>>,
    ) -> PyResult<Cow<'a, [u32]>> {
        Ok(match simplices {
            Some(s) => Cow::Borrowed(s.as_slice()?),
            None => Cow::Owned(self.all_indices(p)),
        })
    }

    fn check_dim(&self, p: usize, q: usize) -> Result<(), Fail> {
        let dim = self.topo().dimension();
        if p > dim || q > dim {
            return Err(Fail::Input(format!(
                "relation R_{{{p},{q}}}: dimension {} is above the complex's dimension {dim}",
                p.max(q)
            )));
        }
        Ok(())
    }
}

/// Checks a CSR of simplices: offsets start at 0, never decrease and end at `ids.len()`.
fn check_csr(ids: &[u32], offsets: &[usize]) -> Result<(), Fail> {
    let ok = offsets.first() == Some(&0)
        && offsets.windows(2).all(|w| w[0] <= w[1])
        && offsets.last() == Some(&ids.len());
    if ok {
        Ok(())
    } else {
        Err(Fail::Input(format!(
            "CSR offsets must start at 0, not decrease and end at len(ids) = {}",
            ids.len()
        )))
    }
}

fn parse_mode(mode: &str) -> Result<ContractMode, Fail> {
    match mode {
        "topology" => Ok(ContractMode::PreserveTopology),
        "manifold" => Ok(ContractMode::PreserveManifold),
        "free" => Ok(ContractMode::Free),
        other => Err(Fail::Input(format!(
            "contract mode {other:?}: \"topology\", \"manifold\" or \"free\""
        ))),
    }
}

/// What `Structure.contract` returns per contraction: the record `Structure.split` undoes it
/// with.
#[pyclass(module = "topoplex._core", name = "Undo", frozen)]
struct PyUndo {
    record: UndoRecord,
}

#[pymethods]
impl PyUndo {
    /// The kept vertex a and the removed vertex b of the contraction.
    #[getter]
    fn edge(&self) -> (u32, u32) {
        (self.record.a.0, self.record.b.0)
    }

    fn __repr__(&self) -> String {
        format!(
            "<topoplex.Undo: {} contracted into {}>",
            self.record.b.0, self.record.a.0
        )
    }
}

#[pymethods]
impl PyStructure {
    /// The structure's name: ig, sig, ia, iqm, nmia, ts, pe, le, de or iastar.
    #[getter]
    fn kind(&self) -> &'static str {
        self.topo().kind().name()
    }

    /// The dimension of the complex.
    #[getter]
    fn dimension(&self) -> usize {
        self.topo().dimension()
    }

    /// Number of vertex ids (for the live mesh: slots, removed vertices included until
    /// `compact()`).
    #[getter]
    fn vertex_count(&self) -> u32 {
        self.topo().vertex_count()
    }

    /// Whether the structure can be edited (the live mesh).
    #[getter]
    fn editable(&self) -> bool {
        matches!(self.inner, Inner::Live(_))
    }

    /// Number of p-simplices.
    fn count(&self, p: usize) -> usize {
        if p > self.topo().dimension() {
            return 0;
        }
        self.topo().count(p)
    }

    /// Every p-simplex as an (n_p, p+1) uint32 array of ascending ids, in ascending
    /// lexicographic order (row i is the simplex of dense index i).
    fn simplices<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        let t = self.topo();
        let mut out = Vec::new();
        if p <= t.dimension() {
            py.detach(|| t.simplices(p, &mut out));
        }
        vec2(py, out, p + 1)
    }

    /// R_{p,q} as a CSR pair `(offsets, ids)` (int64, uint32): the answer of the i-th selected
    /// p-simplex is `ids[offsets[i]:offsets[i+1]]`, dense q-indices in ascending order
    /// (`order="natural"`: the structure's own walk order, cheaper).
    #[pyo3(signature = (p, q, simplices=None, order="sorted"))]
    fn _relation<'py>(
        &self,
        py: Python<'py>,
        p: usize,
        q: usize,
        simplices: Option<PyReadonlyArray1<'_, u32>>,
        order: &str,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        self.check_dim(p, q)?;
        let order = match order {
            "sorted" => Order::Lexicographic,
            "natural" => Order::Natural,
            o => return Err(Fail::Input(format!("order {o:?}: \"sorted\" or \"natural\"")).into()),
        };
        let nav = self.nav()?;
        let idx = self.selected(p, &simplices)?;
        let (offsets, ids) = py
            .detach(|| {
                let mut ids = Vec::new();
                let mut ends = Vec::with_capacity(idx.len());
                nav.related_batch(p, &idx, q, order, &mut ids, &mut ends)?;
                let mut offsets = Vec::with_capacity(ends.len() + 1);
                offsets.push(0i64);
                offsets.extend(ends.iter().map(|&e| e as i64));
                Ok((offsets, ids))
            })
            .map_err(query_fail)?;
        Ok((vec1(py, offsets).into_any(), vec1(py, ids).into_any()))
    }

    /// |R_{p,q}| of every p-simplex (or of the dense indices `simplices`) as uint32.
    #[pyo3(signature = (p, q, simplices=None))]
    fn _degree<'py>(
        &self,
        py: Python<'py>,
        p: usize,
        q: usize,
        simplices: Option<PyReadonlyArray1<'_, u32>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.check_dim(p, q)?;
        let nav = self.nav()?;
        let idx = self.selected(p, &simplices)?;
        let out = py
            .detach(|| {
                let mut out = vec![0u32; idx.len()];
                nav.degree_batch(p, &idx, q, &mut out)?;
                Ok(out)
            })
            .map_err(query_fail)?;
        Ok(vec1(py, out).into_any())
    }

    /// Dense indices of the simplices given as rows of vertex ids (any order within a row);
    /// -1 where a row is not a simplex of the complex when `missing_ok`, else InputError.
    fn _locate<'py>(
        &self,
        py: Python<'py>,
        rows: PyReadonlyArray2<'_, u32>,
        missing_ok: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nav = self.nav()?;
        let k = rows.shape()[1];
        let flat = rows.as_slice()?;
        let out = py
            .detach(|| {
                let mut out = Vec::with_capacity(flat.len() / k.max(1));
                for row in flat.chunks_exact(k.max(1)) {
                    match nav.locate(row).and_then(|h| nav.index_of(h)) {
                        Ok(i) => out.push(i64::from(i)),
                        Err(topoplex::QueryError::NotInComplex { .. }) if missing_ok => {
                            out.push(-1)
                        }
                        Err(e) => return Err(e),
                    }
                }
                Ok(out)
            })
            .map_err(query_fail)?;
        Ok(vec1(py, out).into_any())
    }

    /// +1 or -1 per p-simplex: the parity of the winding a top simplex was given with (its
    /// vertex order as listed against the ascending order); +1 for simplices that are not
    /// top (their orientation is the ascending order).
    fn winding<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        self.check_dim(p, p)?;
        let nav = self.nav()?;
        let all = self.all_indices(p);
        let out = py
            .detach(|| {
                let mut out = vec![1i8; all.len()];
                for (&i, o) in all.iter().zip(out.iter_mut()) {
                    let h = nav.handle(p, i)?;
                    if let Some(t) = nav.top_id(h)? {
                        let given = nav.top_as_given(t)?;
                        *o = parity(&given);
                    }
                }
                Ok(out)
            })
            .map_err(query_fail)?;
        Ok(vec1(py, out).into_any())
    }

    /// The fans around vertex `v`: a list of arrays, each the dense indices of the top
    /// simplices of one fan in cyclic order (dimension-2 complexes).
    fn fans<'py>(&self, py: Python<'py>, v: u32) -> PyResult<Bound<'py, PyList>> {
        let nav = self.nav()?;
        let mut fans = topoplex::Fans::default();
        let h = nav.vertex(VertexId(v)).map_err(query_fail)?;
        nav.fans_around(h, &mut fans).map_err(query_fail)?;
        fans_list(py, nav, &fans)
    }

    /// The q-simplices around edge (a, b) in radial order, grouped by cycle (a list of arrays
    /// of dense q-indices).
    #[pyo3(signature = (a, b, q=2))]
    fn radial<'py>(
        &self,
        py: Python<'py>,
        a: u32,
        b: u32,
        q: usize,
    ) -> PyResult<Bound<'py, PyList>> {
        let nav = self.nav()?;
        let mut fans = topoplex::Fans::default();
        let h = nav.locate(&[a, b]).map_err(query_fail)?;
        nav.around_edge(h, q, &mut fans).map_err(query_fail)?;
        fans_list(py, nav, &fans)
    }

    /// Storage and census as a dict: kind, dimension, vertices, simplices and tops per
    /// dimension, integers and bits the papers count, heap bytes, and the structure's own
    /// figures.
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let t = self.topo();
        let d = census(py, t)?;
        d.set_item("kind", t.kind().name())?;
        let s = t.storage();
        d.set_item("integers", s.integers)?;
        d.set_item("bits", s.bits)?;
        d.set_item("bytes", s.bytes)?;
        let more = PyDict::new(py);
        for (k, v) in t.summary() {
            more.set_item(k, v)?;
        }
        d.set_item("summary", more)?;
        Ok(d)
    }

    /// Census: dimension, vertex count, simplices and top simplices per dimension.
    fn census<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        census(py, self.topo())
    }

    /// Checks the structure's invariants; InputError naming the first broken one.
    fn validate(&self, py: Python<'_>) -> PyResult<()> {
        let t = self.topo();
        py.detach(|| t.validate()).map_err(Fail::Input)?;
        Ok(())
    }

    /// The complex the structure holds (for the live mesh: its current complex, vertices
    /// renumbered densely as `compact()` would).
    fn to_complex(&self, py: Python<'_>) -> PyComplex {
        match (&self.inner, &self.complex) {
            (_, Some(c)) => PyComplex::with_lent(c.clone(), self.lent.clone()),
            (Inner::Live(l), None) => PyComplex::wrap(py.detach(|| l.to_complex())),
            (Inner::Fixed(_), None) => unreachable!("a built structure keeps its complex"),
        }
    }

    // ---- the live mesh ----

    /// Vertex coordinates of the live mesh as a float64 (slots, k) array (removed vertices'
    /// rows included until `compact()`), or None.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        match &self.inner {
            Inner::Live(l) => {
                let k = l.coord_dim();
                if k == 0 {
                    return Ok(None);
                }
                Ok(Some(vec2(py, l.all_coords().to_vec(), k)?))
            }
            Inner::Fixed(_) => coords_array(
                py,
                self.complex.as_ref().and_then(|c| c.coords()),
                self.lent.as_deref(),
            ),
        }
    }

    /// Sets every vertex's coordinates from a float64 (slots, k) array.
    fn _set_points(&mut self, points: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let l = self.live_mut()?;
        l.set_all_coords(points.as_slice()?)
            .map_err(|e| Fail::Refused(e.to_string()))?;
        Ok(())
    }

    /// Sets the coordinates of the vertices `ids` (rows of `points`).
    fn _set_point_rows(
        &mut self,
        ids: PyReadonlyArray1<'_, u32>,
        points: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<()> {
        let l = self.live_mut()?;
        let k = points.shape()[1];
        for (v, xyz) in ids
            .as_slice()?
            .iter()
            .zip(points.as_slice()?.chunks_exact(k.max(1)))
        {
            l.set_coords(VertexId(*v), xyz)
                .map_err(|e| Fail::Refused(e.to_string()))?;
        }
        Ok(())
    }

    /// Inserts top simplices given as a CSR (ids, offsets); returns the number inserted.
    fn _insert(
        &mut self,
        py: Python<'_>,
        ids: PyReadonlyArray1<'_, u32>,
        offsets: PyReadonlyArray1<'_, usize>,
    ) -> PyResult<usize> {
        self.edit_rows(py, ids, offsets, |l, row| l.insert_top(row).map(drop))
    }

    /// Removes top simplices given as a CSR (ids, offsets); returns the number removed.
    fn _remove(
        &mut self,
        py: Python<'_>,
        ids: PyReadonlyArray1<'_, u32>,
        offsets: PyReadonlyArray1<'_, usize>,
    ) -> PyResult<usize> {
        self.edit_rows(py, ids, offsets, LiveComplex::remove_top)
    }

    /// Adds a vertex (isolated) with coordinates `xyz`; returns its id.
    fn _add_vertex(&mut self, xyz: PyReadonlyArray1<'_, f64>) -> PyResult<u32> {
        let l = self.live_mut()?;
        let v = l
            .add_vertex(xyz.as_slice()?)
            .map_err(|e| Fail::Refused(e.to_string()))?;
        Ok(v.0)
    }

    /// Whether contracting b into a is allowed in `mode` (nothing changes).
    #[pyo3(signature = (a, b, mode="topology"))]
    fn can_contract(&self, a: u32, b: u32, mode: &str) -> PyResult<bool> {
        let mode = parse_mode(mode)?;
        Ok(self
            .live_ref()?
            .can_contract(VertexId(a), VertexId(b), mode)
            .is_ok())
    }

    /// Contracts each pair (a, b) of `pairs` (b into a) in order; returns the undo records.
    #[pyo3(signature = (pairs, mode="topology", positions=None))]
    fn _contract(
        &mut self,
        py: Python<'_>,
        pairs: PyReadonlyArray2<'_, u32>,
        mode: &str,
        positions: Option<PyReadonlyArray2<'_, f64>>,
    ) -> PyResult<Vec<PyUndo>> {
        let mode = parse_mode(mode)?;
        let pairs = pairs.as_slice()?;
        let pos = match &positions {
            Some(p) if p.shape()[0] * 2 != pairs.len() => {
                return Err(Fail::Input(format!(
                    "positions: {} rows for {} pairs",
                    p.shape()[0],
                    pairs.len() / 2
                ))
                .into());
            }
            Some(p) => Some((p.as_slice()?, p.shape()[1])),
            None => None,
        };
        let l = self.live_mut()?;
        let undos = py.detach(|| {
            let mut undos = Vec::new();
            for (i, ab) in pairs.chunks_exact(2).enumerate() {
                let xyz = pos.map(|(d, k)| &d[i * k..(i + 1) * k]);
                let u = l
                    .contract(VertexId(ab[0]), VertexId(ab[1]), mode, xyz)
                    .map_err(|e| Fail::Refused(format!("pair {i}: {e}")))?;
                undos.push(u);
            }
            Ok::<_, Fail>(undos)
        })?;
        Ok(undos.into_iter().map(|record| PyUndo { record }).collect())
    }

    /// Undoes a contraction (vertex split), from its undo record.
    fn split(&mut self, py: Python<'_>, undo: PyRef<'_, PyUndo>) -> PyResult<()> {
        let l = self.live_mut()?;
        let r = &undo.record;
        py.detach(|| l.split(r))
            .map_err(|e| Fail::Refused(e.to_string()))?;
        Ok(())
    }

    /// Drops removed vertices and top simplices, renumbering densely; returns the remap
    /// `(vertices, tops)`: `vertices[old] = new` (uint32, 2**32-1 for a removed vertex) and
    /// `tops[p][old slot] = new slot`.
    fn _compact<'py>(
        &mut self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyList>)> {
        let l = self.live_mut()?;
        let maps = py.detach(|| l.compact());
        let tops = PyList::empty(py);
        for t in maps.tops {
            tops.append(vec1(py, t))?;
        }
        Ok((vec1(py, maps.vertices).into_any(), tops))
    }

    /// The live mesh's top simplices as given (with their winding): a list, per dimension, of
    /// (n, p+1) arrays.
    fn _live_tops<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let l = self.live_ref()?;
        let dim = l.dimension();
        let mut per: Vec<Vec<u32>> = vec![Vec::new(); dim + 1];
        for (_, vs) in l.tops() {
            per[vs.len() - 1].extend_from_slice(vs);
        }
        let out = PyList::empty(py);
        for (p, v) in per.into_iter().enumerate() {
            out.append(vec2(py, v, p + 1)?)?;
        }
        Ok(out)
    }

    /// The rows of vertex attribute `name` for the live vertices `vertices` (ids), as one
    /// array of the attribute's type, (n, components) (None for no vertex); KeyError without
    /// such an attribute.
    fn _vertex_values<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        vertices: PyReadonlyArray1<'_, u32>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let l = self.live_ref()?;
        let vs = vertices.as_slice()?;
        let rows = py.detach(|| {
            vs.iter()
                .map(|&v| {
                    l.vertex_values(name, VertexId(v))
                        .map_err(|e| Fail::Input(e.to_string()))
                })
                .collect::<Result<Vec<_>, Fail>>()
        })?;
        rows_array(py, name, rows)
    }

    /// Sets the rows of vertex attribute `name` of the live vertices `vertices` to the rows of
    /// `values` (float64, (n, components)); labels must be whole numbers of their type.
    /// Checks everything first: on an error nothing changes.
    fn _set_vertex_values(
        &mut self,
        py: Python<'_>,
        name: &str,
        vertices: PyReadonlyArray1<'_, u32>,
        values: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<()> {
        let vs = vertices.as_slice()?;
        let (data, c) = (values.as_slice()?, values.shape()[1]);
        let l = self.live_mut()?;
        py.detach(|| {
            check_rows(vs.len(), data, c)?;
            for (i, &v) in vs.iter().enumerate() {
                l.vertex_values(name, VertexId(v))
                    .map_err(|e| Fail::Input(format!("row {i}: {e}")))?;
            }
            let vs: Vec<VertexId> = vs.iter().map(|&v| VertexId(v)).collect();
            set_rows(
                l,
                (name, "vertices"),
                &vs,
                (data, c),
                LiveComplex::vertex_values,
                LiveComplex::set_vertex_values,
            )
        })?;
        Ok(())
    }

    /// The rows of listed attribute `name` for the live top p-simplices `rows` (row indices of
    /// `live_tops()[p]`), as `_vertex_values`.
    fn _top_values<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        p: usize,
        rows: PyReadonlyArray1<'_, u32>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let l = self.live_ref()?;
        let rows = rows.as_slice()?;
        let got = py.detach(|| {
            let tops = live_top_ids(l, p);
            rows.iter()
                .map(|&r| {
                    let t = top_at(&tops, p, r)?;
                    l.top_values(name, t)
                        .map_err(|e| Fail::Input(e.to_string()))
                })
                .collect::<Result<Vec<_>, Fail>>()
        })?;
        rows_array(py, name, got)
    }

    /// Sets the rows of listed attribute `name` of the live top p-simplices `rows` (row
    /// indices of `live_tops()[p]`) to the rows of `values`, as `_set_vertex_values`.
    fn _set_top_values(
        &mut self,
        py: Python<'_>,
        name: &str,
        p: usize,
        rows: PyReadonlyArray1<'_, u32>,
        values: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<()> {
        let rows = rows.as_slice()?;
        let (data, c) = (values.as_slice()?, values.shape()[1]);
        let l = self.live_mut()?;
        py.detach(|| {
            check_rows(rows.len(), data, c)?;
            let tops = live_top_ids(l, p);
            let ts = rows
                .iter()
                .map(|&r| top_at(&tops, p, r))
                .collect::<Result<Vec<_>, Fail>>()?;
            set_rows(
                l,
                (name, "listed simplices"),
                &ts,
                (data, c),
                LiveComplex::top_values,
                LiveComplex::set_top_values,
            )
        })?;
        Ok(())
    }

    /// The tops across each facet of every live top p-simplex: a uint32 (n, p+1) array, row i
    /// for row i of `live_tops()[p]`, entry j for its facet opposite its j-th vertex (as
    /// listed there): the row of the one other top p-simplex through that facet,
    /// `ACROSS_NONE` when there is none (of dimension p), `ACROSS_MANY` when several.
    fn _adjacency<'py>(&self, py: Python<'py>, p: usize) -> PyResult<Bound<'py, PyAny>> {
        let l = self.live_ref()?;
        if p == 0 || p > l.dimension() {
            return Err(Fail::Input(format!(
                "adjacency: p = {p} must be in 1..={}",
                l.dimension()
            ))
            .into());
        }
        let out = py.detach(|| {
            let adj = l.adjacency().map_err(build_fail)?;
            let entries = adj.rows[p];
            let w = p + 1;
            // Slot → row of live_tops()[p] (tombstoned slots skipped).
            let mut row_of = vec![ACROSS_NONE; entries.len() / w];
            let mut live = Vec::new();
            for (t, _) in l.tops().filter(|(t, _)| t.dim() == p) {
                row_of[t.slot() as usize] = live.len() as u32;
                live.push(t.slot() as usize);
            }
            let mut out = Vec::with_capacity(live.len() * w);
            for &slot in &live {
                for &e in &entries[slot * w..(slot + 1) * w] {
                    out.push(match e {
                        ACROSS_NONE | ACROSS_MANY => e,
                        // A packed top id of dimension p: its slot in the low 28 bits.
                        e => row_of[(e & ((1 << 28) - 1)) as usize],
                    });
                }
            }
            Ok::<_, Fail>(out)
        })?;
        vec2(py, out, p + 1)
    }

    /// Every vertex's one-ring, copied out: (offsets int64 of vertex_slots + 1, neighbours
    /// uint32, tops at each edge uint32), rows by vertex slot in the order the star first
    /// names them (`LiveComplex::rings`).
    #[allow(clippy::type_complexity)]
    fn _rings<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray1<i64>>,
        Bound<'py, PyArray1<u32>>,
        Bound<'py, PyArray1<u32>>,
    )> {
        let l = self.live_ref()?;
        let (offsets, ids, held) = py.detach(|| {
            let r = l.rings().map_err(build_fail)?;
            let offsets: Vec<i64> = r.offsets.iter().map(|&o| i64::from(o)).collect();
            Ok::<_, Fail>((offsets, r.neighbours.to_vec(), r.held.to_vec()))
        })?;
        Ok((vec1(py, offsets), vec1(py, ids), vec1(py, held)))
    }

    /// Keeps the facet adjacency across edits (built now, then repaired by each edit), or,
    /// with `keep=False`, builds it on request and drops it at each edit (the default).
    #[pyo3(signature = (keep=true))]
    fn keep_adjacency(&mut self, py: Python<'_>, keep: bool) -> PyResult<()> {
        let l = self.live_mut()?;
        py.detach(|| l.keep_adjacency(keep)).map_err(build_fail)?;
        Ok(())
    }

    /// Simplifies the live mesh in place to about `ratio` of its top simplices (quadric
    /// decimation); returns the statistics.
    #[pyo3(signature = (ratio, preserve_topology=false, keep_regions=None))]
    fn _simplify<'py>(
        &mut self,
        py: Python<'py>,
        ratio: f64,
        preserve_topology: bool,
        keep_regions: Option<String>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let l = self.live_mut()?;
        let mut o = topoplex::simplify::Options::new(ratio, preserve_topology);
        o.keep_regions = keep_regions;
        let stats = py
            .detach(|| topoplex::simplify::simplify_live(l, &o, &mut |_, _| {}))
            .map_err(simplify_fail)?;
        stats_dict(py, &stats)
    }

    /// Saves the structure with its complex as a `.tpx` file (the live mesh with its data).
    fn _save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let done = match (&self.inner, &self.complex) {
            (Inner::Live(l), _) => py.detach(|| l.save(&path)),
            (Inner::Fixed(s), Some(c)) => {
                py.detach(|| topoplex::store::save(&path, c, Some(s.as_ref())))
            }
            (Inner::Fixed(_), None) => unreachable!("a built structure keeps its complex"),
        };
        done.map_err(|e| Fail::Write(e.to_string()))?;
        Ok(())
    }

    fn __repr__(&self) -> String {
        let t = self.topo();
        let counts: Vec<usize> = (0..=t.dimension()).map(|p| t.count(p)).collect();
        format!("<topoplex.Structure {}: simplices {:?}>", t.kind(), counts)
    }
}

/// The live tops of dimension p, in the order of `live_tops()[p]` (slot order).
fn live_top_ids(l: &LiveComplex, p: usize) -> Vec<TopId> {
    l.tops()
        .filter(|(t, _)| t.dim() == p)
        .map(|(t, _)| t)
        .collect()
}

fn top_at(tops: &[TopId], p: usize, r: u32) -> Result<TopId, Fail> {
    tops.get(r as usize).copied().ok_or_else(|| {
        Fail::Input(format!(
            "top row {r}: the live mesh has {} top {p}-simplices",
            tops.len()
        ))
    })
}

fn no_attribute(name: &str, on: &str) -> Fail {
    Fail::Key(format!(
        "no attribute {} on the {on}",
        topoplex::error::echo(name)
    ))
}

/// `n` rows of `c` numbers in `data`.
fn check_rows(n: usize, data: &[f64], c: usize) -> Result<(), Fail> {
    if data.len() != n * c {
        return Err(Fail::Input(format!(
            "values: {} rows of {c} for {n} simplices",
            data.len() / c.max(1)
        )));
    }
    Ok(())
}

/// Sets attribute `name`'s rows of the live elements `keys` (vertices or tops, `on` naming
/// them for the KeyError) to the rows of `data`, `c` numbers each, once the first element's row
/// (`get`) has shown that the rows fit the attribute.
fn set_rows<K: Copy>(
    l: &mut LiveComplex,
    (name, on): (&str, &str),
    keys: &[K],
    (data, c): (&[f64], usize),
    get: fn(&LiveComplex, &str, K) -> Result<Option<Values>, Refusal>,
    set: fn(&mut LiveComplex, &str, K, &[f64]) -> Result<bool, Refusal>,
) -> Result<(), Fail> {
    if let Some(&k) = keys.first() {
        let row = get(l, name, k)
            .map_err(|e| Fail::Input(e.to_string()))?
            .ok_or_else(|| no_attribute(name, on))?;
        check_values(name, &row, data, c)?;
    }
    for (&k, row) in keys.iter().zip(data.chunks_exact(c.max(1))) {
        set(l, name, k, row).map_err(|e| Fail::Input(e.to_string()))?;
    }
    Ok(())
}

/// `data` (rows of `c`) fits attribute `name`, whose row `like` is: `c` is its components, and
/// for labels every number is a whole number of the type.
fn check_values(name: &str, like: &Values, data: &[f64], c: usize) -> Result<(), Fail> {
    if like.len() != c {
        return Err(Fail::Input(format!(
            "attribute {} has {} components, rows of {c} given",
            topoplex::error::echo(name),
            like.len()
        )));
    }
    let range = match like {
        Values::I32(_) => Some((f64::from(i32::MIN), f64::from(i32::MAX))),
        // 2^63 - 1024: the largest f64 below 2^63.
        Values::I64(_) => Some((-(2f64.powi(63)), 2f64.powi(63) - 1024.0)),
        _ => None,
    };
    if let Some((lo, hi)) = range
        && let Some(k) = data
            .iter()
            .position(|&y| y.fract() != 0.0 || !(lo..=hi).contains(&y))
    {
        return Err(Fail::Input(format!(
            "attribute {} holds {} labels: value {} (row {}) is not one",
            topoplex::error::echo(name),
            dtype_of(like),
            data[k],
            k / c.max(1)
        )));
    }
    Ok(())
}

/// Rows of one attribute (each `Some`, or KeyError naming it) as one array, (n,) for one
/// component, else (n, components); None for no row.
fn rows_array<'py>(
    py: Python<'py>,
    name: &str,
    rows: Vec<Option<Values>>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let mut it = rows.into_iter();
    let Some(first) = it.next() else {
        return Ok(None);
    };
    let mut all = first.ok_or_else(|| no_attribute(name, "simplices given"))?;
    let c = all.len();
    for r in it {
        all.append(&r.ok_or_else(|| no_attribute(name, "simplices given"))?);
    }
    let arr = match all {
        Values::I32(v) => vec2(py, v, c)?,
        Values::I64(v) => vec2(py, v, c)?,
        Values::F32(v) => vec2(py, v, c)?,
        Values::F64(v) => vec2(py, v, c)?,
    };
    Ok(Some(if c == 1 {
        arr.call_method1("reshape", (-1,))?
    } else {
        arr
    }))
}

fn parity(given: &[u32]) -> i8 {
    let mut inversions = 0usize;
    for i in 0..given.len() {
        for j in i + 1..given.len() {
            if given[i] > given[j] {
                inversions += 1;
            }
        }
    }
    if inversions.is_multiple_of(2) { 1 } else { -1 }
}

fn fans_list<'py>(
    py: Python<'py>,
    nav: &dyn Navigate,
    fans: &topoplex::Fans,
) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for k in 0..fans.len() {
        let mut idx = Vec::with_capacity(fans.group(k).len());
        for &h in fans.group(k) {
            idx.push(nav.index_of(h).map_err(query_fail)?);
        }
        out.append(vec1(py, idx))?;
    }
    Ok(out)
}

fn simplify_fail(e: topoplex::simplify::SimplifyError) -> Fail {
    use topoplex::simplify::SimplifyError as E;
    match e {
        E::Memory { .. } | E::TooLarge { .. } => Fail::Memory(e.to_string()),
        _ => Fail::Input(e.to_string()),
    }
}

fn stats_dict<'py>(py: Python<'py>, s: &topoplex::simplify::Stats) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("input_tops", s.input_tops)?;
    d.set_item("target_tops", s.target_tops)?;
    d.set_item("output_tops", s.output_tops)?;
    d.set_item("contractions", s.contractions)?;
    d.set_item("refused", s.refused)?;
    d.set_item("refills", s.refills)?;
    d.set_item("refused_regions", s.refused_regions)?;
    Ok(d)
}

/// Opens a saved `.tpx` file: its structure when it holds one of `kind` (mapped), else the
/// structure `kind` built from its complex; `kind=None` gives the saved structure, or the
/// complex when the file holds none.
#[pyfunction]
#[pyo3(signature = (path, kind=None))]
fn _open(py: Python<'_>, path: PathBuf, kind: Option<&str>) -> PyResult<Py<PyAny>> {
    let kind = kind.map(kind_of).transpose()?;
    let read = store_fail;
    let (saved, map) = open_saved(py, &path)?;
    let (complex, lent) = saved_complex(py, &saved, map)?;
    let structure = py.detach(|| {
        let s = match kind {
            Some(StructureKind::IaStar) => Some(Inner::Live(Box::new(
                LiveComplex::open_saved(&saved).map_err(read)?,
            ))),
            Some(k) => Some(Inner::Fixed(saved.structure_of(k).map_err(read)?)),
            None => match saved.kind() {
                Some(StructureKind::IaStar) => Some(Inner::Live(Box::new(
                    LiveComplex::open_saved(&saved).map_err(read)?,
                ))),
                Some(_) => saved.structure().map_err(read)?.map(Inner::Fixed),
                None => None,
            },
        };
        Ok::<_, Fail>(s)
    })?;
    Ok(match structure {
        Some(Inner::Live(l)) => Py::new(
            py,
            PyStructure {
                inner: Inner::Live(l),
                complex: None,
                lent: None,
            },
        )?
        .into_any(),
        Some(inner) => Py::new(
            py,
            PyStructure {
                inner,
                complex: Some(Arc::new(complex)),
                lent,
            },
        )?
        .into_any(),
        None => Py::new(py, PyComplex::with_lent(Arc::new(complex), lent))?.into_any(),
    })
}

/// Simplifies a complex to about `ratio` of its top simplices; returns (complex, stats).
#[pyfunction]
#[pyo3(signature = (complex, ratio, preserve_topology=false, keep_regions=None))]
fn _simplify<'py>(
    py: Python<'py>,
    complex: PyRef<'_, PyComplex>,
    ratio: f64,
    preserve_topology: bool,
    keep_regions: Option<String>,
) -> PyResult<(PyComplex, Bound<'py, PyDict>)> {
    let mut o = topoplex::simplify::Options::new(ratio, preserve_topology);
    o.keep_regions = keep_regions;
    let c = complex.inner.clone();
    let out = py
        .detach(|| topoplex::simplify::simplify(&c, &o, &mut |_, _| {}))
        .map_err(simplify_fail)?;
    let stats = stats_dict(py, &out.stats)?;
    Ok((PyComplex::wrap(out.complex), stats))
}

/// Cuts a complex into its IQM components and writes them, with `gluing.json`, into `out`;
/// returns the paths written (components first).
#[pyfunction]
#[pyo3(signature = (complex, out, format=None))]
fn _decompose(
    py: Python<'_>,
    complex: PyRef<'_, PyComplex>,
    out: PathBuf,
    format: Option<&str>,
) -> PyResult<Vec<PathBuf>> {
    let format = match format {
        Some(f) => Some(
            topoplex::io::write::Format::from_name(f)
                .ok_or_else(|| Fail::Input(format!("unknown format {f:?}")))?,
        ),
        None => None,
    };
    let c = complex.inner.clone();
    let paths = py.detach(|| {
        let iqm = topoplex::structures::iqm::Iqm::build(&c).map_err(build_fail)?;
        let dec = iqm.decomposition();
        topoplex::decompose::write_components_of(&dec, &c, &out, format)
            .map_err(|e| Fail::Write(e.to_string()))
    })?;
    Ok(paths)
}

/// The names of the structures, the survey's nine then the live mesh.
#[pyfunction]
fn structure_names() -> Vec<&'static str> {
    StructureKind::NAMED.iter().map(|k| k.name()).collect()
}

/// The extension module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyComplex>()?;
    m.add_class::<PyStructure>()?;
    m.add_class::<PyUndo>()?;
    m.add_function(wrap_pyfunction!(_open, m)?)?;
    m.add_function(wrap_pyfunction!(_simplify, m)?)?;
    m.add_function(wrap_pyfunction!(_decompose, m)?)?;
    m.add_function(wrap_pyfunction!(structure_names, m)?)?;
    m.add("ACROSS_NONE", ACROSS_NONE)?;
    m.add("ACROSS_MANY", ACROSS_MANY)?;
    Ok(())
}

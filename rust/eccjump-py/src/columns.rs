//! The one output convention of the bridge: struct-of-arrays by name. One numpy column per
//! field of a slice of per-point results ([`set_column`]), one Python list per field of a
//! run's records ([`Records`]), and the rows of a dense output evaluated at many times.
//! Every buffer whose size the caller chooses is allocated fallibly: too large a request is
//! a `MemoryError`, never an abort.

use crate::errors::to_py;
use eccjump_core::error::{short, try_filled};
use numpy::{Element, IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyMemoryError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};

/// Sets `d[name]` to the column `f(row)` of `rows`, allocated fallibly (a `MemoryError`
/// naming the field, not an abort, if it does not fit). `name` is a Python string made once
/// (`intern!`): a run's few points cost no more than its names.
pub fn set_column<'py, R, T: Element>(
    d: &Bound<'py, PyDict>,
    name: &Bound<'py, PyString>,
    rows: &[R],
    f: impl Fn(&R) -> T,
) -> PyResult<()> {
    let mut v = Vec::new();
    v.try_reserve_exact(rows.len()).map_err(|_| {
        PyMemoryError::new_err(format!(
            "the field {name} of {} points does not fit in memory",
            rows.len()
        ))
    })?;
    v.extend(rows.iter().map(f));
    d.set_item(name, v.into_pyarray(d.py()))
}

/// A run's records (events, transitions, flights, ...) as one Python list per field, by the
/// field names of the Python layer's named tuple, which it makes by name: the order of the
/// fields is written there only. Records hold Python values (floats, ints, bools, strings,
/// None), so lists, not numpy arrays.
pub struct Records<'py, 'r, R> {
    dict: Bound<'py, PyDict>,
    rows: &'r [R],
}

impl<'py, 'r, R> Records<'py, 'r, R> {
    /// No field yet.
    pub fn new(py: Python<'py>, rows: &'r [R]) -> Self {
        Self {
            dict: PyDict::new(py),
            rows,
        }
    }

    /// Adds the field `name` (a Python string made once, `intern!`): `f` of every record.
    pub fn field<T: IntoPyObject<'py>>(
        self,
        name: &Bound<'py, PyString>,
        f: impl Fn(&R) -> T,
    ) -> PyResult<Self> {
        let list = PyList::new(self.dict.py(), self.rows.iter().map(f))?;
        self.dict.set_item(name, list)?;
        Ok(self)
    }

    /// The fields, by name.
    pub fn into_dict(self) -> Bound<'py, PyDict> {
        self.dict
    }
}

/// A dense output evaluated at the times `t`: the (K, len(t)) array whose row k holds
/// component k of `at(t[i])`. The times come from the caller (a numpy array of any length),
/// so the K·len(t) values are allocated fallibly and before any evaluation: a `MemoryError`
/// naming `what` if they do not fit. `at` is None outside the output; the first such time
/// is a ValueError naming its index and the output's `range` [start, end].
pub fn dense_rows<'py, const K: usize>(
    py: Python<'py>,
    what: &'static str,
    t: &[f64],
    range: (f64, f64),
    at: impl Fn(f64) -> Option<[f64; K]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = t.len();
    // A product that overflows saturates, which `try_filled` refuses as too large.
    let mut flat = try_filled(what, n.saturating_mul(K), 0.0).map_err(to_py)?;
    for (i, &ti) in t.iter().enumerate() {
        let y = at(ti).ok_or_else(|| {
            PyValueError::new_err(format!(
                "t[{i}] = {} is outside the allowed range [{}, {}] of the dense output",
                short(ti),
                short(range.0),
                short(range.1)
            ))
        })?;
        for (k, v) in y.into_iter().enumerate() {
            flat[k * n + i] = v;
        }
    }
    PyArray1::from_vec(py, flat).reshape([K, n])
}

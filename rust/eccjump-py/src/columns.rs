//! Struct-of-arrays output: one numpy column per field of a slice of per-point results.

use numpy::{Element, IntoPyArray};
use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Sets `d[name]` to the column `f(row)` of `rows`, allocated fallibly (a `MemoryError`
/// naming the field, not an abort, if it does not fit).
pub fn set_column<'py, R, T: Element>(
    d: &Bound<'py, PyDict>,
    name: &str,
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

//! Python's record types (the `NamedTuple`s of `eccjump.motion` and `eccjump.rolling`),
//! made here from their fields. A short run returns a dozen records, and making each in Python from a plain
//! tuple (`tuple.__new__(cls, fields)` through `map`) cost 2 µs of a 45 µs `simulate`.

use pyo3::exceptions::PyTypeError;
use pyo3::ffi;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyTuple, PyType};

/// A `NamedTuple` class of the Python package, imported at first use.
pub struct RecordType {
    module: &'static str,
    name: &'static str,
    class: PyOnceLock<Py<PyType>>,
}

impl RecordType {
    /// The class `name` of the module `module`.
    pub const fn new(module: &'static str, name: &'static str) -> Self {
        Self {
            module,
            name,
            class: PyOnceLock::new(),
        }
    }

    /// The records of `fields`, each a tuple of a record's fields in their declaration
    /// order, as a tuple.
    pub fn tuple_of<'py, F>(
        &self,
        py: Python<'py>,
        fields: impl IntoIterator<Item = F>,
    ) -> PyResult<Bound<'py, PyTuple>>
    where
        F: IntoPyObject<'py, Target = PyTuple, Output = Bound<'py, PyTuple>>,
    {
        let class = self.class.get_or_try_init(py, || {
            let class = py
                .import(self.module)?
                .getattr(self.name)?
                .cast_into::<PyType>()?;
            if !class.is_subclass_of::<PyTuple>()? {
                return Err(PyTypeError::new_err(format!(
                    "{} is not a tuple",
                    self.name
                )));
            }
            Ok(class.unbind())
        })?;
        // tuple's own constructor, tuple_new: for a subclass it copies the fields into an
        // instance of it, as `tuple.__new__(cls, fields)` does, without the checks of that
        // call's wrapper (the class is a tuple subclass, checked above) and without the
        // class's Python `__new__`.
        // SAFETY: PyTuple_Type is a static type object, whose slots PyType_GetSlot may read
        // (Python ≥ 3.10); its tp_new is a `newfunc`, never null.
        let new: ffi::newfunc = unsafe {
            std::mem::transmute::<*mut std::ffi::c_void, ffi::newfunc>(ffi::PyType_GetSlot(
                &raw mut ffi::PyTuple_Type,
                ffi::Py_tp_new,
            ))
        };
        let records = fields
            .into_iter()
            .map(|f| {
                let args = PyTuple::new(py, [f.into_pyobject(py).map_err(Into::into)?])?;
                // SAFETY: a type and a tuple of arguments, both alive for the call; the
                // result is a new reference or null with an exception set.
                unsafe {
                    let record = new(class.as_ptr().cast(), args.as_ptr(), std::ptr::null_mut());
                    Bound::from_owned_ptr_or_err(py, record)
                }
            })
            .collect::<PyResult<Vec<_>>>()?;
        PyTuple::new(py, records)
    }
}

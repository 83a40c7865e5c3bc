//! Python's result types, made here from their fields: the record types (the `NamedTuple`s
//! of `eccjump.motion` and `eccjump.rolling`) and the frozen dataclasses holding a whole run
//! (`RollResult`, `MotionResult`). A short run returns a dozen records, and making each in
//! Python from a plain tuple (`tuple.__new__(cls, fields)` through `map`) cost 2 µs of a
//! 45 µs `simulate`; making a `RollResult` in Python cost 0.8 µs of a 9 µs `roll`.

use pyo3::exceptions::PyTypeError;
use pyo3::ffi;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyString, PyTuple, PyType};

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

/// A frozen dataclass of the Python package (`RollResult`, `MotionResult`), made here from
/// its fields' values without its `__init__` (whose `object.__setattr__` per field costs
/// more than a short run): an instance whose `__dict__` holds the fields in their
/// declaration order, the same object as the `__init__` makes. The dict is a copy of a
/// template (its table ready sized) with the values put in place; in Python, building the
/// 19-entry dict of a `RollResult` alone took 0.5 µs.
pub struct ResultType<const N: usize> {
    module: &'static str,
    name: &'static str,
    fields: [&'static str; N],
    made: PyOnceLock<Made<N>>,
}

/// What [`ResultType`] imports and makes once: the class, the template dict (every field
/// None) and the fields' names as interned strings.
struct Made<const N: usize> {
    class: Py<PyType>,
    template: Py<PyDict>,
    keys: [Py<PyString>; N],
}

impl<const N: usize> ResultType<N> {
    /// The class `name` of the module `module`, whose dataclass fields are `fields` in
    /// their declaration order (checked at first use: a TypeError if they are not).
    pub const fn new(module: &'static str, name: &'static str, fields: [&'static str; N]) -> Self {
        Self {
            module,
            name,
            fields,
            made: PyOnceLock::new(),
        }
    }

    fn made(&self, py: Python<'_>) -> PyResult<&Made<N>> {
        self.made.get_or_try_init(py, || {
            let class = py
                .import(self.module)?
                .getattr(self.name)?
                .cast_into::<PyType>()?;
            let names: Vec<String> = py
                .import("dataclasses")?
                .call_method1("fields", (&class,))?
                .try_iter()?
                .map(|f| f?.getattr("name")?.extract::<String>())
                .collect::<PyResult<_>>()?;
            if names != self.fields {
                // The first field where they part, for a short message.
                let i = (0..)
                    .find(|&i| names.get(i).map(String::as_str) != self.fields.get(i).copied())
                    .unwrap_or(0);
                let quoted = |n: Option<&str>| n.map_or("none".to_string(), |n| format!("'{n}'"));
                return Err(PyTypeError::new_err(format!(
                    "{}'s fields differ from the bridge's at field {i}: {} against {}",
                    self.name,
                    quoted(names.get(i).map(String::as_str)),
                    quoted(self.fields.get(i).copied()),
                )));
            }
            let keys = self.fields.map(|f| PyString::intern(py, f).unbind());
            let template = PyDict::new(py);
            for k in &keys {
                template.set_item(k.bind(py), py.None())?;
            }
            Ok(Made {
                class: class.unbind(),
                template: template.unbind(),
                keys,
            })
        })
    }

    /// An instance with the fields `values`, in their declaration order.
    pub fn make<'py>(
        &self,
        py: Python<'py>,
        values: [Bound<'py, PyAny>; N],
    ) -> PyResult<Bound<'py, PyAny>> {
        let made = self.made(py)?;
        let dict = made.template.bind(py).copy()?;
        for (k, v) in made.keys.iter().zip(values) {
            // The template's values are None already.
            if !v.is_none() {
                dict.set_item(k.bind(py), v)?;
            }
        }
        // object.__new__(cls), then object.__setattr__(result, "__dict__", dict): the
        // frozen class's own __setattr__ would refuse.
        // SAFETY: PyBaseObject_Type is a static type object, whose slots PyType_GetSlot may
        // read (Python ≥ 3.10); its tp_new is a `newfunc`, never null.
        let new: ffi::newfunc = unsafe {
            std::mem::transmute::<*mut std::ffi::c_void, ffi::newfunc>(ffi::PyType_GetSlot(
                &raw mut ffi::PyBaseObject_Type,
                ffi::Py_tp_new,
            ))
        };
        let args = PyTuple::empty(py);
        // SAFETY: a type and a tuple of arguments, alive for the call; a new reference or
        // null with an exception set.
        let result = unsafe {
            Bound::from_owned_ptr_or_err(
                py,
                new(
                    made.class.as_ptr().cast(),
                    args.as_ptr(),
                    std::ptr::null_mut(),
                ),
            )?
        };
        // SAFETY: an object, an interned name and a dict, all alive; 0 or −1 with an
        // exception set.
        let status = unsafe {
            ffi::PyObject_GenericSetAttr(
                result.as_ptr(),
                pyo3::intern!(py, "__dict__").as_ptr(),
                dict.as_ptr(),
            )
        };
        if status != 0 {
            return Err(PyErr::fetch(py));
        }
        Ok(result)
    }
}

//! The arguments of `roll` in their plain Python types only: float, int, bool, str or None.
//! The Python layer passes the arguments it was given; one of any other type (an int for a
//! float, a numpy scalar, …) makes `roll` return None, and the Python layer converts it by
//! its checks, which alone define what is accepted, and calls again. Testing the thirteen
//! exact types here costs nanoseconds; in Python it took 0.2 µs of a 9 µs call.
//! (`simulate`, whose runs take 45 µs and more, keeps that test in Python.)

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyInt, PyString};

/// A float's value.
#[inline]
pub fn float(x: &Bound<'_, PyAny>) -> Option<f64> {
    x.cast_exact::<PyFloat>().ok().map(|f| f.value())
}

/// None, or a float's value.
#[inline]
pub fn optional_float(x: &Bound<'_, PyAny>) -> Option<Option<f64>> {
    if x.is_none() {
        Some(None)
    } else {
        float(x).map(Some)
    }
}

/// An int from 1 to 2⁶⁴ − 1 (the Python layer's range for a count; the core checks its own).
#[inline]
pub fn count(x: &Bound<'_, PyAny>) -> Option<usize> {
    if !x.is_exact_instance_of::<PyInt>() {
        return None;
    }
    let v: u64 = x.extract().ok()?;
    usize::try_from(v).ok().filter(|&v| v >= 1)
}

/// A bool's value.
#[inline]
pub fn flag(x: &Bound<'_, PyAny>) -> Option<bool> {
    x.cast_exact::<PyBool>().ok().map(|b| b.is_true())
}

/// A str (or a subclass of it, as the Python layer's test `isinstance(x, str)`).
#[inline]
pub fn text<'a, 'py>(x: &'a Bound<'py, PyAny>) -> Option<&'a Bound<'py, PyString>> {
    x.cast::<PyString>().ok()
}

//! The core's names (modes, reasons, statuses, events) as Python strings made once. A run's
//! records repeat a handful of names dozens of times, and a new string for each costs as
//! much as the float beside it.

use eccjump_core::maps::motion::sequence_code as code_of;
use eccjump_core::modes::contact::{Mode, TransitionReason};
use eccjump_core::modes::rolling::events::ContactEvent;
use eccjump_core::motion::record::MotionStatus;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyString;

/// The Python strings of the `K` values of one of the core's enums, made at first use.
pub struct Names<T: 'static, const K: usize> {
    all: [T; K],
    name: fn(T) -> &'static str,
    strings: PyOnceLock<[Py<PyString>; K]>,
}

impl<T: Copy + PartialEq, const K: usize> Names<T, K> {
    const fn new(all: [T; K], name: fn(T) -> &'static str) -> Self {
        Self {
            all,
            name,
            strings: PyOnceLock::new(),
        }
    }

    /// (code, name) of every value: `all` is indexed by code (`named_enum!`'s `ALL`).
    fn table(&self) -> Vec<(u8, &'static str)> {
        (0..).zip(self.all.map(self.name)).collect()
    }

    /// The name of `value`, the same string object at every call.
    pub fn of<'py>(&self, py: Python<'py>, value: T) -> Bound<'py, PyString> {
        let strings = self.strings.get_or_init(py, || {
            self.all
                .map(|v| PyString::intern(py, (self.name)(v)).unbind())
        });
        // `all` holds every value of the enum; a value missing from it (an enum grown
        // without its `ALL`) still gets its own name, as a new string.
        match self.all.iter().position(|&v| v == value) {
            Some(i) => strings[i].bind(py).clone(),
            None => PyString::new(py, (self.name)(value)),
        }
    }
}

/// `Mode::name`.
pub static MODES: Names<Mode, 3> = Names::new(Mode::ALL, Mode::name);
/// `TransitionReason::name` (why a mode began).
pub static REASONS: Names<TransitionReason, 9> =
    Names::new(TransitionReason::ALL, TransitionReason::name);
/// `MotionStatus::name`.
pub static STATUSES: Names<MotionStatus, 7> = Names::new(MotionStatus::ALL, MotionStatus::name);
/// `ContactEvent::name` (the events of a rolling run).
pub static ROLL_EVENTS: Names<ContactEvent, 5> = Names::new(ContactEvent::ALL, ContactEvent::name);

// The tables the Python layer checks its copies against at import (`eccjump.motion`): a
// stale build whose codes moved would otherwise mislabel every record.

/// (code, name) of every mode of the full motion; a sequence code's digit is code + 1.
#[pyfunction]
pub fn mode_codes() -> Vec<(u8, &'static str)> {
    MODES.table()
}

/// (code, name) of every reason a mode of the full motion began.
#[pyfunction]
pub fn transition_reason_codes() -> Vec<(u8, &'static str)> {
    REASONS.table()
}

/// (code, name) of every way a full-motion run ends.
#[pyfunction]
pub fn status_codes() -> Vec<(u8, &'static str)> {
    STATUSES.table()
}

/// The sequence code a motion map stores for the modes `codes` (codes of [`mode_codes`],
/// the first `SEQUENCE_LEN` counted): the core's own formula, not a copy. ValueError for a
/// code that is no mode.
#[pyfunction]
pub fn sequence_code(codes: Vec<u8>) -> PyResult<u16> {
    let mode = |&c: &u8| {
        Mode::ALL.get(usize::from(c)).copied().ok_or_else(|| {
            PyValueError::new_err(format!(
                "codes: {c} is not a mode code (0 ... {})",
                Mode::ALL.len() - 1
            ))
        })
    };
    let modes = codes.iter().map(mode).collect::<PyResult<Vec<Mode>>>()?;
    Ok(code_of(modes.into_iter()))
}

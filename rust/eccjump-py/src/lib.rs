//! The pyo3 bridge: converts, validates and releases the GIL; no physics lives here.

use pyo3::prelude::*;

#[pymodule]
mod _core {
    #[pymodule_export]
    const VERSION: &str = env!("CARGO_PKG_VERSION");
}

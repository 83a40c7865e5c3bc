//! The impact law, exposed privately for the tests (`tests/test_impact_law.py` compares W
//! with a symbolic derivation): validation and physics live in the core.

use crate::errors::to_py;
use eccjump_core::mechanics::impact::{impact as resolve_impact, Ending, ImpactLaw};
use eccjump_core::Cylinder;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// One impact of the body (χ, k_m) at the state (θ, θ̇, l̇, ḃ) under the law (μ_s, μ_k, e): a
/// dict with W (wtt, wtn, wnn), the impulse (pt, pn), the contact velocity after it (ut,
/// un), whether it ends sticking, the velocities after it (omega, ldot, bdot) and the works.
/// Raises ValueError naming a bad parameter.
#[pyfunction]
pub fn impact<'py>(
    py: Python<'py>,
    chi: f64,
    km: f64,
    state: (f64, f64, f64, f64),
    law: (f64, f64, f64),
) -> PyResult<Bound<'py, PyDict>> {
    let body = Cylinder::new(chi, km).map_err(to_py)?;
    let (theta, omega, ldot, bdot) = state;
    let (mu_s, mu_k, restitution) = law;
    let law = ImpactLaw {
        mu_s,
        mu_k,
        restitution,
    };
    let r = resolve_impact(&body, &law, theta, omega, ldot, bdot).map_err(to_py)?;
    let i = r.impulse;
    let d = PyDict::new(py);
    for (key, value) in [
        ("wtt", r.w.tt()),
        ("wtn", r.w.tn()),
        ("wnn", r.w.nn()),
        ("pt", i.pt),
        ("pn", i.pn),
        ("ut", i.ut),
        ("un", i.un),
        ("omega", r.omega),
        ("ldot", r.ldot),
        ("bdot", r.bdot),
        ("compression_work", i.compression_work),
        ("normal_work", i.normal_work),
        ("friction_work", i.friction_work),
    ] {
        d.set_item(key, value)?;
    }
    d.set_item("sticking", i.ending == Ending::Sticking)?;
    Ok(d)
}

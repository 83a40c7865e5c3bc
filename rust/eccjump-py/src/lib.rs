//! The pyo3 bridge of eccjump: converts arguments, lets the core validate them, releases
//! the GIL around the numerical work and maps core errors to Python exceptions. No physics
//! lives here; the typed Python layer is `python/eccjump`.

// No unsafe code: the bridge returns plain values, which the Python layer makes into its
// result objects.
#![forbid(unsafe_code)]

mod body;
mod boundary;
mod closed_form;
mod columns;
mod derivatives;
mod errors;
mod impact;
mod jarm;
mod motion_map;
mod names;
mod options;
mod roll;
mod simulate;

use pyo3::prelude::*;

#[pymodule]
mod _core {
    #[pymodule_export]
    const VERSION: &str = env!("CARGO_PKG_VERSION");
    /// The parameters of a full-motion run, in the order of the sensitivities' last axis.
    #[pymodule_export]
    const MOTION_PARAMETERS: [&str; 8] = eccjump_core::motion::options::PARAMETERS;
    /// The largest `max_transitions` of a full-motion run.
    #[pymodule_export]
    const MAX_TRANSITIONS: usize = eccjump_core::motion::options::MAX_TRANSITIONS;
    /// The largest `max_steps` of an integration.
    #[pymodule_export]
    const MAX_STEPS: usize = eccjump_core::modes::rolling::run::MAX_STEPS;
    /// The modes a motion map's sequence code keeps.
    #[pymodule_export]
    const SEQUENCE_LEN: usize = eccjump_core::maps::motion::SEQUENCE_LEN;
    /// The `status` of a motion map's point whose parameters are invalid.
    #[pymodule_export]
    const INVALID: u8 = eccjump_core::maps::motion::INVALID;

    #[pymodule_export]
    use crate::body::{body_derived, body_from_inertia, body_from_shell_and_line};
    #[pymodule_export]
    use crate::boundary::{alpha_interval_around, alpha_intervals, mu_s_min_path};
    #[pymodule_export]
    use crate::closed_form::{
        alpha_min, gamma, green_turn, j_brackets, j_paper, jump_forces, liftoff_function, mu,
        mu_s_min, path_forces, theta_j_range, theta_nj,
    };
    #[pymodule_export]
    use crate::derivatives::jarm_derivatives;
    #[pymodule_export]
    use crate::impact::impact;
    #[pymodule_export]
    use crate::jarm::{jarm_grid, jarm_points, reason_codes};
    #[pymodule_export]
    use crate::motion_map::{landing_codes, motion_grid, motion_points};
    #[pymodule_export]
    use crate::names::{mode_codes, sequence_code, status_codes, transition_reason_codes};
    #[pymodule_export]
    use crate::options::{BoundaryOptions, ClassifyOptions, MotionMapOptions};
    #[pymodule_export]
    use crate::roll::{roll, DenseSolution};
    #[pymodule_export]
    use crate::simulate::{simulate, MotionDense};
}

//! The full motion of the body (the paper's "work in progress"): rolling, slipping, flight
//! and landing, one segment after another, as `docs/motion.md` specifies.
//!
//! - [`options`]: the inputs and their checks, the Zeno rule's threshold;
//! - [`simulate`](mod@simulate): the driver (one solver run per contact segment, exact flights, the impact
//!   law at every landing, the consistency test after every event);
//! - `landing`: the impact law and the Zeno rule as a map of the state;
//! - [`record`]: what a run records (points, transitions, flights, impacts, segments,
//!   energy ledger);
//! - [`solution`]: `sol(t)` across segments;
//! - [`sensitivities`]: the derivatives of a run's transitions with respect to its
//!   parameters (variational equations, saltation at events, the landing's Jacobian).

pub(crate) mod landing;
pub mod options;
pub mod record;
pub mod sensitivities;
pub mod simulate;
pub(crate) mod sliding;
pub mod solution;

pub use options::SimOptions;
pub use record::{MotionRun, MotionStatus};
pub use simulate::{simulate, simulate_until};

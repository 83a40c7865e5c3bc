//! The lift-off rule: when the rolling body is taken to leave the ramp. Shared by the
//! rolling runs (`roll`) and the JARM classification (`jarm`).

/// When the body leaves the ramp (see `docs/jarm.md` and the physics notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Rule {
    /// The paper's rule (and its reference [gomes]): lift-off at the first rising zero of the
    /// free-flight normal acceleration χ θ̇² cos θ − cos α. The default: it reproduces the paper.
    #[default]
    Paper,
    /// The classical unilateral-contact rule: keep rolling while F_y > 0 and |F_x| ≤ μ_s F_y;
    /// lift-off when F_y reaches 0, or at slip onset when no sliding contact is consistent.
    NormalForce,
}

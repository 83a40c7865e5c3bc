//! An accepted step seen from its two ends only: the states, their derivatives and the
//! tolerance the step met. From it the event scan can clear a step of events before (and
//! instead of) building the step's dense output, which costs DOP853 three more
//! evaluations of f ([`crate::ode::EventBounds::change_bounds_ends`]).

use super::{DenseStep, State};

/// The ends of an accepted step from t_old over h.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepEnds<const N: usize> {
    /// Start of the step.
    pub t_old: f64,
    /// End of the step.
    pub t_new: f64,
    /// Signed step size t_new − t_old.
    pub h: f64,
    /// State at t_old.
    pub y_old: State<N>,
    /// f(t_old, y_old).
    pub f_old: State<N>,
    /// State at t_old + h.
    pub y_new: State<N>,
    /// f(t_old + h, y_new).
    pub f_new: State<N>,
    /// The step's error scale atol + rtol max(|y_old|, |y_new|), per component: the size
    /// of the local error the step control allowed.
    pub scale: State<N>,
}

impl StepEnds<2> {
    /// For a second-order equation written as the state (x, v) with x' = v: the quintic
    /// Hermite interpolant of x from x, x' = v and x'' = v' at both ends (v being its
    /// derivative), as a dense-output step, and an estimate of its error per component.
    ///
    /// In σ = (t − t_old)/h, with m = h v and n = h² v' at the ends:
    ///   x(σ) = x0 + m0 σ + n0 σ²/2 + c3 σ³ + c4 σ⁴ + c5 σ⁵,
    ///   c3 = 10D0 − 4D1 + D2/2, c4 = −15D0 + 7D1 − D2, c5 = 6D0 − 3D1 + D2/2,
    /// D0 = x1 − x0 − m0 − n0/2, D1 = m1 − m0 − n0, D2 = n1 − n0 (the three conditions at
    /// σ = 1). Its error is O(h⁶) in x and O(h⁵) in v; the estimate is the largest
    /// difference (by the triangle inequality on the coefficients) from the cubic Hermite
    /// interpolants of x (from x, v) and of v (from v, v'), whose errors are O(h⁴): for
    /// the steps an accurate pair takes, a multiple of the quintic's own error.
    pub fn second_order_hermite(&self) -> (DenseStep<2>, [f64; 2]) {
        let h = self.h;
        let (x0, v0, a0) = (self.y_old[0], self.y_old[1], self.f_old[1]);
        let (x1, v1, a1) = (self.y_new[0], self.y_new[1], self.f_new[1]);
        let (m0, m1) = (h * v0, h * v1);
        let (n0, n1) = (h * h * a0, h * h * a1);
        let d0 = x1 - x0 - m0 - 0.5 * n0;
        let d1 = m1 - m0 - n0;
        let d2 = n1 - n0;
        let c3 = 10.0 * d0 - 4.0 * d1 + 0.5 * d2;
        let c4 = -15.0 * d0 + 7.0 * d1 - d2;
        let c5 = 6.0 * d0 - 3.0 * d1 + 0.5 * d2;
        // x(σ) = x0 + h Σ Q_j σ^(j+1); v(σ) = x'(σ)/h = v0 + h Σ Q'_j σ^(j+1).
        let q = [
            State::<2>::new(v0, a0),
            State::<2>::new(0.5 * h * a0, 3.0 * c3 / (h * h)),
            State::<2>::new(c3 / h, 4.0 * c4 / (h * h)),
            State::<2>::new(c4 / h, 5.0 * c5 / (h * h)),
            State::<2>::new(c5 / h, 0.0),
        ];
        let dense = DenseStep::from_powers(self.t_old, h, self.y_old, &q);
        // The cubic Hermite interpolants: x0 + m0 σ + (3Δ − 2m0 − m1) σ² + (m0 + m1 − 2Δ) σ³
        // with Δ = x1 − x0, and alike for v (slopes h v').
        let dx = x1 - x0;
        let err_x = (0.5 * n0 - (3.0 * dx - 2.0 * m0 - m1)).abs()
            + (c3 - (m0 + m1 - 2.0 * dx)).abs()
            + c4.abs()
            + c5.abs();
        let (dv, k0, k1) = (v1 - v0, h * a0, h * a1);
        let err_v = (3.0 * c3 / h - (3.0 * dv - 2.0 * k0 - k1)).abs()
            + (4.0 * c4 / h - (k0 + k1 - 2.0 * dv)).abs()
            + (5.0 * c5 / h).abs();
        (dense, [err_x, err_v])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x = sin(ωt + φ) (v = ω cos, v' = −ω² sin): the interpolant meets the ends, its error
    /// is O(h⁶) in x and O(h⁵) in v, and the estimate exceeds the true error.
    #[test]
    fn the_quintic_hermite_interpolates_a_second_order_solution() {
        for &(w, phi, h) in &[
            (1.0, 0.3, 0.5),
            (2.0, -1.0, 0.2),
            (0.7, 2.0, -0.4),
            (3.0, 0.1, 0.05),
        ] {
            let y = |t: f64| State::<2>::new((w * t + phi).sin(), w * (w * t + phi).cos());
            let f = |t: f64| State::<2>::new(y(t)[1], -w * w * y(t)[0]);
            let t_old = 1.25;
            let ends = StepEnds {
                t_old,
                t_new: t_old + h,
                h,
                y_old: y(t_old),
                f_old: f(t_old),
                y_new: y(t_old + h),
                f_new: f(t_old + h),
                scale: State::<2>::new(1e-12, 1e-12),
            };
            let (dense, [ex, ev]) = ends.second_order_hermite();
            let end = dense.eval(t_old + h);
            assert!((end - y(t_old + h)).abs().max() < 1e-14, "{end:?}");
            let mut worst = [0.0f64; 2];
            for i in 0..=200 {
                let t = t_old + h * i as f64 / 200.0;
                let d = dense.eval(t) - y(t);
                worst = [worst[0].max(d[0].abs()), worst[1].max(d[1].abs())];
            }
            let wh = (w * h).abs();
            assert!(worst[0] <= wh.powi(6) / 1000.0 + 1e-15, "{worst:?} {wh}");
            assert!(worst[1] <= w * wh.powi(5) / 100.0 + 1e-15, "{worst:?} {wh}");
            assert!(ex >= worst[0] && ev >= worst[1], "{ex} {ev} {worst:?}");
        }
    }
}

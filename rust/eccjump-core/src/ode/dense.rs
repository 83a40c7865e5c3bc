//! The dense output of one accepted step: a polynomial in σ = (t − t_old)/h, whatever pair
//! produced it (degree 4 for Dormand–Prince 5(4), as scipy's `RkDenseOutput`; degree 7 for
//! DOP853, converted from scipy's `Dop853DenseOutput` form into powers of σ; degree 8 for
//! Vern9).

use super::State;

/// Highest degree of a dense-output polynomial (Vern9's).
pub const MAX_DEGREE: usize = 8;

/// Dense output on [t_old, t_old + h]: y(t_old + σh) = y_old + h Σ_j Q_j σ^(j+1),
/// j = 0..degree − 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseStep<const N: usize> {
    /// Start time of the step.
    pub t_old: f64,
    /// Signed step size (negative when integrating backwards).
    pub h: f64,
    /// State at the start of the step.
    pub y_old: State<N>,
    /// The coefficients Q_j of σ^(j+1); those at j ≥ `degree` are zero and unused.
    pub q: [State<N>; MAX_DEGREE],
    /// Degree of the polynomial (1..=MAX_DEGREE).
    pub degree: usize,
}

impl<const N: usize> DenseStep<N> {
    /// The polynomial y_old + h Σ_j q_j σ^(j+1) of the given degree.
    #[inline]
    pub fn from_powers(t_old: f64, h: f64, y_old: State<N>, q: &[State<N>]) -> Self {
        let degree = q.len().clamp(1, MAX_DEGREE);
        let mut all = [State::<N>::zeros(); MAX_DEGREE];
        all[..degree].copy_from_slice(&q[..degree]);
        Self {
            t_old,
            h,
            y_old,
            q: all,
            degree,
        }
    }

    /// The interpolated state at t (meaningful for t in [t_old, t_old + h]).
    #[inline]
    pub fn eval(&self, t: f64) -> State<N> {
        let s = (t - self.t_old) / self.h;
        // Horner in σ: y_old + h σ (Q0 + σ (Q1 + σ (Q2 + …))).
        let mut acc = self.q[self.degree - 1];
        for j in (0..self.degree - 1).rev() {
            acc = self.q[j] + acc * s;
        }
        self.y_old + acc * (self.h * s)
    }
}

/// Componentwise bounds of a dense-output step over the whole step, from the triangle
/// inequality on its coefficients: for σ ∈ [0, 1],
/// |y(σ)| ≤ |y_old| + |h| Σ_j |Q_j|, |dy/dt| = |Σ_j (j+1) Q_j σ^j| ≤ Σ_j (j+1) |Q_j| and
/// |d²y/dt²| = |Σ_j (j+1) j Q_j σ^(j−1)| / |h| ≤ Σ_j (j+1) j |Q_j| / |h|.
/// They hold for the exact polynomial; computed in floating point they may be low by a
/// few ulps relative, which callers cover with a safety margin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseBounds<const N: usize> {
    /// Upper bound of |y_i| over the step.
    pub value: State<N>,
    /// Upper bound of |dy_i/dt| over the step.
    pub rate: State<N>,
    /// Upper bound of |d²y_i/dt²| over the step.
    pub accel: State<N>,
}

impl<const N: usize> DenseStep<N> {
    /// Bounds of the interpolant and its time derivative over the step (see
    /// [`DenseBounds`]).
    #[inline]
    pub fn bounds(&self) -> DenseBounds<N> {
        let mut spread = State::<N>::zeros();
        let mut rate = State::<N>::zeros();
        let mut bend = State::<N>::zeros();
        for (j, qj) in self.q[..self.degree].iter().enumerate() {
            let a = qj.abs();
            spread += a;
            rate += a * (j + 1) as f64;
            bend += a * ((j + 1) * j) as f64;
        }
        DenseBounds {
            value: self.y_old.abs() + spread * self.h.abs(),
            rate,
            accel: bend / self.h.abs(),
        }
    }
}

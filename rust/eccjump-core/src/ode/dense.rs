//! The 4th-order dense output of one Dormand–Prince step (scipy's `RkDenseOutput`).

use super::tableau::P;
use super::State;

/// Dense output on [t_old, t_old + h]: y(t_old + σh) = y_old + h Σ_j Q_j σ^(j+1), j = 0..3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseStep<const N: usize> {
    /// Start time of the step.
    pub t_old: f64,
    /// Signed step size (negative when integrating backwards).
    pub h: f64,
    /// State at the start of the step.
    pub y_old: State<N>,
    /// Q = K^T P of scipy's RK45, one column per power of σ.
    pub q: [State<N>; 4],
}

impl<const N: usize> DenseStep<N> {
    /// The interpolant of the step of size h from (t_old, y_old) with the 7 stages K
    /// (the last being the FSAL derivative at the step end): Q_j = Σ_i K_i P_ij, as
    /// scipy's `K.T.dot(P)`.
    #[inline]
    pub fn from_stages(t_old: f64, h: f64, y_old: State<N>, k: &[State<N>; 7]) -> Self {
        let mut q = [State::<N>::zeros(); 4];
        for (j, qj) in q.iter_mut().enumerate() {
            for (ki, pi) in k.iter().zip(P.iter()) {
                *qj += ki * pi[j];
            }
        }
        Self { t_old, h, y_old, q }
    }

    /// The interpolated state at t (meaningful for t in [t_old, t_old + h]).
    #[inline]
    pub fn eval(&self, t: f64) -> State<N> {
        let s = (t - self.t_old) / self.h;
        // Horner in σ: y_old + h σ (Q0 + σ (Q1 + σ (Q2 + σ Q3))).
        let mut acc = self.q[3];
        for j in (0..3).rev() {
            acc = self.q[j] + acc * s;
        }
        self.y_old + acc * (self.h * s)
    }
}

/// Componentwise bounds of a dense-output step over the whole step, from the triangle
/// inequality on its coefficients: for σ ∈ [0, 1],
/// |y(σ)| ≤ |y_old| + |h| Σ_j |Q_j| and |dy/dt| = |Σ_j (j+1) Q_j σ^j| ≤ Σ_j (j+1) |Q_j|.
/// They hold for the exact polynomial; computed in floating point they may be low by a
/// few ulps relative, which callers cover with a safety margin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseBounds<const N: usize> {
    /// Upper bound of |y_i| over the step.
    pub value: State<N>,
    /// Upper bound of |dy_i/dt| over the step.
    pub rate: State<N>,
}

impl<const N: usize> DenseStep<N> {
    /// Bounds of the interpolant and its time derivative over the step (see
    /// [`DenseBounds`]).
    #[inline]
    pub fn bounds(&self) -> DenseBounds<N> {
        let mut spread = State::<N>::zeros();
        let mut rate = State::<N>::zeros();
        for (j, qj) in self.q.iter().enumerate() {
            let a = qj.abs();
            spread += a;
            rate += a * (j + 1) as f64;
        }
        DenseBounds {
            value: self.y_old.abs() + spread * self.h.abs(),
            rate,
        }
    }
}

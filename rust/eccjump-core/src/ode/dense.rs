//! The 4th-order dense output of one Dormand–Prince step (scipy's `RkDenseOutput`).

use super::State;

/// Dense output on [t_old, t_old + h]: y(t_old + σh) = y_old + h Σ_j Q_j σ^(j+1), j = 0..3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseStep<const N: usize> {
    pub t_old: f64,
    pub h: f64,
    pub y_old: State<N>,
    /// Q = K^T P of scipy's RK45, one column per power of σ.
    pub q: [State<N>; 4],
}

impl<const N: usize> DenseStep<N> {
    /// The interpolated state at t (meaningful for t in [t_old, t_old + h]).
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

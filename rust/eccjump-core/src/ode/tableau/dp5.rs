//! The Dormand–Prince 5(4) Butcher tableau and dense-output matrix, copied from scipy's
//! `RK45` (`scipy/integrate/_ivp/rk.py`) fraction by fraction.
//!
//! Every entry is written as the same quotient of integers as in scipy, so that Rust's
//! correctly rounded `f64` division gives bit-identical coefficients to Python's: this is
//! what makes step-for-step agreement with scipy possible.

/// Number of stages (the FSAL stage f(t + h, y_new) is stored as an extra, 7th stage).
pub const N_STAGES: usize = 6;

/// Order of the propagated (5th-order) solution.
pub const ORDER: i32 = 5;

/// Order of the embedded error estimator; step control uses the exponent −1/(4 + 1).
pub const ERROR_ESTIMATOR_ORDER: i32 = 4;

/// Step-size exponent −1/(error_estimator_order + 1), as scipy's `error_exponent`.
pub const ERROR_EXPONENT: f64 = -1.0 / (ERROR_ESTIMATOR_ORDER as f64 + 1.0);

/// Nodes c_i: stage i is evaluated at t + c_i h.
pub const C: [f64; N_STAGES] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0];

/// Stage coupling a_ij (row i, column j < i), zero-padded like scipy's `A`.
pub const A: [[f64; N_STAGES - 1]; N_STAGES] = [
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
];

/// Weights b_i of the 5th-order solution (equal to the last row of A extended: FSAL).
pub const B: [f64; N_STAGES] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];

/// Error weights over the 7 stages (including FSAL): err = h Σ E_i K_i.
pub const E: [f64; N_STAGES + 1] = [
    -71.0 / 57600.0,
    0.0,
    71.0 / 16695.0,
    -71.0 / 1920.0,
    17253.0 / 339200.0,
    -22.0 / 525.0,
    1.0 / 40.0,
];

/// Stages kept: the 6 and the FSAL one (the dense output needs no extra stages).
pub const N_STAGES_EXTENDED: usize = N_STAGES + 1;

/// No extra stages.
pub const A_EXTRA: [[f64; 0]; 0] = [];

/// Dense-output matrix (7 stages × 4 powers of σ): Q = Kᵀ P. Shampine's optimal c_6
/// variant, as scipy.
pub const P: [[f64; 4]; N_STAGES + 1] = [
    [
        1.0,
        -8048581381.0 / 2820520608.0,
        8663915743.0 / 2820520608.0,
        -12715105075.0 / 11282082432.0,
    ],
    [0.0, 0.0, 0.0, 0.0],
    [
        0.0,
        131558114200.0 / 32700410799.0,
        -68118460800.0 / 10900136933.0,
        87487479700.0 / 32700410799.0,
    ],
    [
        0.0,
        -1754552775.0 / 470086768.0,
        14199869525.0 / 1410260304.0,
        -10690763975.0 / 1880347072.0,
    ],
    [
        0.0,
        127303824393.0 / 49829197408.0,
        -318862633887.0 / 49829197408.0,
        701980252875.0 / 199316789632.0,
    ],
    [
        0.0,
        -282668133.0 / 205662961.0,
        2019193451.0 / 616988883.0,
        -1453857185.0 / 822651844.0,
    ],
    [
        0.0,
        40617522.0 / 29380423.0,
        -110615467.0 / 29380423.0,
        69997945.0 / 29380423.0,
    ],
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_of_a_sum_to_c() {
        for (row, c) in A.iter().zip(C) {
            let s: f64 = row.iter().sum();
            assert!((s - c).abs() < 1e-14, "{s} vs {c}");
        }
    }

    #[test]
    fn weights_are_consistent() {
        // Σ b = 1; Σ E = 0 (both orders integrate constants exactly); P's first column
        // gives σ-linear term = f(t_old) and the row sums of P reproduce b at σ = 1.
        assert!((B.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(E.iter().sum::<f64>().abs() < 1e-15);
        for i in 0..N_STAGES {
            let at_one: f64 = P[i].iter().sum();
            assert!(
                (at_one - B[i]).abs() < 1e-14,
                "row {i}: {at_one} vs {}",
                B[i]
            );
        }
        assert!(P[N_STAGES].iter().sum::<f64>().abs() < 1e-14);
    }
}

//! The full motion, to the first landing, at a list of points: one column per parameter
//! (α, χ, k_m, μ_s, μ_k, e, θ0, θ̇0), each point's values given, as a Monte Carlo sample
//! needs them. A second source of points for the driver of a motion map
//! ([`motion_map`](crate::maps::motion::motion_map)), so every point is exactly
//! [`motion_point`](crate::maps::motion::motion_point) there, for any thread count.

use crate::error::Result;
use crate::maps::motion::MotionPoints;
use crate::maps::parallel::check_len;

/// The parameters of each point, one column per parameter, all of one length (`mu_k` may
/// be empty: μ_k = μ_s at every point). Unlike a map's k_m fraction, `km` is the body's k_m.
#[derive(Debug, Clone, Copy)]
pub struct MotionColumns<'a> {
    /// Ramp angles α (rad).
    pub alpha: &'a [f64],
    /// χ = d/R.
    pub chi: &'a [f64],
    /// The bodies' k_m ∈ [0, 1 − χ].
    pub km: &'a [f64],
    /// Static friction coefficients.
    pub mu_s: &'a [f64],
    /// Kinetic friction coefficients (empty: μ_k = μ_s).
    pub mu_k: &'a [f64],
    /// Stronge's coefficients of restitution.
    pub restitution: &'a [f64],
    /// Initial angles θ0.
    pub theta0: &'a [f64],
    /// Initial angular velocities θ̇0.
    pub omega0: &'a [f64],
}

impl MotionPoints for MotionColumns<'_> {
    /// The number of points: the length of `alpha`, which every other column (and `mu_k`
    /// unless empty) must have; an error naming the first column that does not.
    fn count(&self) -> Result<usize> {
        let n = self.alpha.len();
        let columns = [
            ("chi", self.chi),
            ("km", self.km),
            ("mu_s", self.mu_s),
            ("restitution", self.restitution),
            ("theta0", self.theta0),
            ("omega0", self.omega0),
        ];
        for (name, c) in columns {
            check_len(name, c.len(), n)?;
        }
        if !self.mu_k.is_empty() {
            check_len("mu_k", self.mu_k.len(), n)?;
        }
        Ok(n)
    }

    /// Point `i`: row `i` of the columns.
    fn values(&self, i: usize) -> [f64; 8] {
        let c = self;
        let mu_s = c.mu_s[i];
        [
            c.alpha[i],
            c.chi[i],
            c.km[i],
            mu_s,
            c.mu_k.get(i).copied().unwrap_or(mu_s),
            c.restitution[i],
            c.theta0[i],
            c.omega0[i],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::motion::{
        motion_map, motion_point, point_from, MotionAxes, MotionMapOptions, MotionSummary, INVALID,
    };
    use crate::mechanics::Rule;
    use crate::motion::MotionStatus;
    use crate::ode::{Integrator, SolverOptions};

    /// Points of every kind: JARM and slip-first bodies, moving starts, bounces, invalid
    /// points (k_m > 1 − χ, μ_k > μ_s).
    fn sample(n: usize) -> [Vec<f64>; 8] {
        // A deterministic spread (a Weyl sequence per parameter), no random crate needed.
        let frac = |k: usize, a: f64| ((k as f64 + 0.5) * a).fract();
        let alpha = (0..n).map(|k| 0.1 + 1.3 * frac(k, 0.618_034)).collect();
        let chi: Vec<f64> = (0..n).map(|k| 0.05 + 0.9 * frac(k, 0.414_214)).collect();
        let km = (0..n)
            .map(|k| 1.02 * (1.0 - chi[k]) * frac(k, 0.732_051))
            .collect();
        let mu_s: Vec<f64> = (0..n).map(|k| 0.2 + 1.2 * frac(k, 0.236_068)).collect();
        let mu_k = (0..n)
            .map(|k| mu_s[k] * 1.05 * frac(k, 0.645_751))
            .collect();
        let e = (0..n).map(|k| frac(k, 0.316_625)).collect();
        let theta0 = (0..n).map(|k| 6.0 * frac(k, 0.123_106)).collect();
        let omega0 = (0..n).map(|k| 2.0 * frac(k, 0.872_983)).collect();
        [alpha, chi, km, mu_s, mu_k, e, theta0, omega0]
    }

    fn columns(c: &[Vec<f64>; 8]) -> MotionColumns<'_> {
        MotionColumns {
            alpha: &c[0],
            chi: &c[1],
            km: &c[2],
            mu_s: &c[3],
            mu_k: &c[4],
            restitution: &c[5],
            theta0: &c[6],
            omega0: &c[7],
        }
    }

    #[test]
    fn each_point_is_motion_point_there_for_any_thread_count() {
        let c = sample(600);
        let cols = columns(&c);
        for method in Integrator::ALL {
            let opts = MotionMapOptions {
                rule: Rule::Paper,
                t_max: 30.0,
                max_transitions: 30,
                solver: SolverOptions {
                    method,
                    ..SolverOptions::default()
                },
            };
            let mut one = vec![MotionSummary::invalid(); 600];
            motion_map(&cols, &opts, 1, &mut one, &|| false).unwrap();
            let mut two = one.clone();
            two.fill(MotionSummary::invalid());
            motion_map(&cols, &opts, 2, &mut two, &|| false).unwrap();
            let base = opts.base();
            for (i, (a, b)) in one.iter().zip(&two).enumerate() {
                assert_eq!(format!("{a:?}"), format!("{b:?}"), "point {i}");
                let alone = match point_from(cols.values(i), &base) {
                    Some((ramp, o)) => motion_point(&ramp, &o),
                    None => MotionSummary::invalid(),
                };
                assert_eq!(format!("{a:?}"), format!("{alone:?}"), "point {i}");
            }
            let count = |f: &dyn Fn(&MotionSummary) -> bool| one.iter().filter(|s| f(s)).count();
            assert!(count(&|s| s.status == INVALID) > 20);
            assert!(count(&|s| s.status == MotionStatus::Landed as u8) > 100);
            assert!(count(&|s| s.slipped_first) > 20);
        }
    }

    #[test]
    fn a_grid_and_its_points_as_columns_are_one_map() {
        // Two sources of points for one driver: the grid's points, given as columns, have
        // the grid's summaries (invalid points and μ_k = μ_s included).
        let axes = MotionAxes {
            alpha: &[0.4, 0.7],
            chi: &[0.15, 0.5],
            frac: &[0.0, 0.3, 0.9],
            mu_s: &[0.4, 1.0],
            mu_k: &[],
            restitution: &[0.0, 0.6],
            theta0: &[0.0],
            omega0: &[0.0, 1.0],
        };
        let n = axes.count().unwrap();
        let rows: Vec<[f64; 8]> = (0..n).map(|g| axes.values(g)).collect();
        let c: [Vec<f64>; 8] = std::array::from_fn(|k| rows.iter().map(|r| r[k]).collect());
        let opts = MotionMapOptions {
            rule: Rule::Paper,
            t_max: 30.0,
            max_transitions: 30,
            solver: SolverOptions::default(),
        };
        let mut grid = vec![MotionSummary::invalid(); n];
        motion_map(&axes, &opts, 2, &mut grid, &|| false).unwrap();
        let mut points = vec![MotionSummary::invalid(); n];
        motion_map(&columns(&c), &opts, 1, &mut points, &|| false).unwrap();
        assert_eq!(format!("{grid:?}"), format!("{points:?}"));
        assert!(
            grid.iter().any(|s| s.status == INVALID),
            "k_m = 0 is invalid"
        );
        assert!(grid.iter().any(|s| s.status == MotionStatus::Landed as u8));
    }

    #[test]
    fn columns_of_unequal_lengths_are_an_error_naming_the_column() {
        let c = sample(4);
        let short = [0.5; 3];
        let cols = MotionColumns {
            theta0: &short,
            ..columns(&c)
        };
        let opts = MotionMapOptions {
            rule: Rule::Paper,
            t_max: 10.0,
            max_transitions: 10,
            solver: SolverOptions::default(),
        };
        let mut out = vec![MotionSummary::invalid(); 4];
        let err = motion_map(&cols, &opts, 1, &mut out, &|| false).unwrap_err();
        assert!(err.to_string().contains("theta0"), "{err}");
        let none = MotionColumns {
            mu_k: &[],
            ..columns(&c)
        };
        motion_map(&none, &opts, 1, &mut out, &|| false).unwrap();
        for (i, s) in out.iter().enumerate() {
            // μ_k = μ_s everywhere: only a k_m beyond 1 − χ makes a point invalid.
            assert_eq!(s.status == INVALID, c[2][i] > 1.0 - c[1][i], "point {i}");
        }
    }
}

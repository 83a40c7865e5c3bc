//! The order conditions of every tableau, checked in f64 from its constants as compiled: one
//! condition per rooted tree t, Σ_i b_i Φ_i(t) = 1/γ(t) (Butcher; Hairer, Nørsett & Wanner I,
//! Sec. II.2). A mistyped coefficient breaks some of them by far more than rounding (the
//! generators check the same in 50 digits before writing the Rust files).

use super::{dop853, dp5, vern9};

/// A rooted tree as the keys (order, index in `Trees::by_order[order]`) of its subtrees,
/// in non-increasing order.
type Tree = Vec<(usize, usize)>;

/// All rooted trees up to an order.
struct Trees {
    by_order: Vec<Vec<Tree>>,
}

impl Trees {
    fn up_to(max: usize) -> Self {
        let mut by_order: Vec<Vec<Tree>> = vec![Vec::new(), vec![Vec::new()]];
        for n in 2..=max {
            let mut found = Vec::new();
            // Multisets of subtrees whose orders add up to n − 1, each listed once: keys
            // chosen in non-increasing order.
            fn grow(
                by_order: &[Vec<Tree>],
                rest: usize,
                largest: (usize, usize),
                kids: &mut Tree,
                found: &mut Vec<Tree>,
            ) {
                if rest == 0 {
                    found.push(kids.clone());
                    return;
                }
                for order in (1..=rest.min(largest.0)).rev() {
                    for index in 0..by_order[order].len() {
                        if (order, index) > largest {
                            continue;
                        }
                        kids.push((order, index));
                        grow(by_order, rest - order, (order, index), kids, found);
                        kids.pop();
                    }
                }
            }
            grow(&by_order, n - 1, (n, 0), &mut Vec::new(), &mut found);
            by_order.push(found);
        }
        Self { by_order }
    }

    /// γ(t) = ρ(t) Π γ(subtrees).
    fn gamma(&self, (order, index): (usize, usize)) -> f64 {
        let kids = &self.by_order[order][index];
        order as f64 * kids.iter().map(|&k| self.gamma(k)).product::<f64>()
    }

    /// Φ_i(t) per stage i: Π over the subtrees s of (A Φ(s))_i.
    fn phi(&self, (order, index): (usize, usize), a: &[Vec<f64>]) -> Vec<f64> {
        let mut v = vec![1.0; a.len()];
        for &kid in &self.by_order[order][index] {
            let w = self.phi(kid, a);
            for (vi, row) in v.iter_mut().zip(a) {
                *vi *= row.iter().zip(&w).map(|(x, y)| x * y).sum::<f64>();
            }
        }
        v
    }

    /// The largest |Σ_i w_i Φ_i(t) − scale(ρ)/γ(t)| over the trees of orders 1 … p.
    fn worst(&self, a: &[Vec<f64>], w: &[f64], p: usize, scale: impl Fn(usize) -> f64) -> f64 {
        let mut worst = 0.0f64;
        for order in 1..=p {
            for index in 0..self.by_order[order].len() {
                let phi = self.phi((order, index), a);
                let sum: f64 = w.iter().zip(&phi).map(|(x, y)| x * y).sum();
                worst = worst.max((sum - scale(order) / self.gamma((order, index))).abs());
            }
        }
        worst
    }
}

/// A square matrix of `n` stages from rows of any length (missing entries 0).
fn square<R: AsRef<[f64]>>(rows: &[R], n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let r = rows.get(i).map_or(&[][..], |r| r.as_ref());
            (0..n).map(|j| r.get(j).copied().unwrap_or(0.0)).collect()
        })
        .collect()
}

#[test]
fn there_are_as_many_trees_as_butcher_counts() {
    let t = Trees::up_to(8);
    let counts: Vec<usize> = t.by_order[1..].iter().map(Vec::len).collect();
    assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48, 115]);
    // γ of the bushy tree of order 4 (three leaves) is 4, of the tall one 24.
    let gammas: Vec<f64> = (0..4).map(|i| t.gamma((4, i))).collect();
    assert!(
        gammas.contains(&4.0) && gammas.contains(&24.0),
        "{gammas:?}"
    );
}

#[test]
fn dormand_prince_5_4_has_orders_5_and_4() {
    let t = Trees::up_to(6);
    // The embedded solution uses the FSAL stage (its row of A is b).
    let mut rows: Vec<Vec<f64>> = dp5::A.iter().map(|r| r.to_vec()).collect();
    rows.push(dp5::B.to_vec());
    let a = square(&rows, dp5::N_STAGES + 1);
    let b: Vec<f64> = dp5::B.iter().copied().chain([0.0]).collect();
    let b_hat: Vec<f64> = b.iter().zip(&dp5::E).map(|(x, e)| x - e).collect();
    assert!(t.worst(&a, &b, 5, |_| 1.0) < 1e-14);
    assert!(t.worst(&a, &b_hat, 4, |_| 1.0) < 1e-14);
    // Not one order more: the conditions are not met by accident.
    assert!(t.worst(&a, &b, 6, |_| 1.0) > 1e-4);
}

#[test]
fn dop853_has_order_8() {
    let t = Trees::up_to(9);
    let a = square(&dop853::A, dop853::N_STAGES);
    assert!(t.worst(&a, &dop853::B, 8, |_| 1.0) < 1e-12);
    assert!(t.worst(&a, &dop853::B, 9, |_| 1.0) > 1e-6);
}

/// A Verner pair's tableau as slices: its main stages' A and its B and E = b − b̂, the extra
/// stages' A and c, the interpolant's R (row j: the weights of σ^(j+1)).
struct Verner<'a> {
    a: Vec<&'a [f64]>,
    b: &'a [f64],
    e: &'a [f64],
    a_extra: Vec<&'a [f64]>,
    c_extra: &'a [f64],
    r: Vec<&'a [f64]>,
}

impl Verner<'_> {
    /// b of order q and b̂ of order q − 1, exactly, and neither one order more; the
    /// interpolant over all stages (the stage after the main ones is f at y_new: its row is
    /// b) of order p exactly, Σ_i b_i(σ) Φ_i(t) = σ^ρ/γ(t) within `exact` for ρ ≤ p, and
    /// within `near` for ρ = p + 1 (as Verner published it); each extra row sums to its node.
    fn check(&self, q: usize, p: usize, exact: f64, near: f64) {
        let t = Trees::up_to(q + 1);
        let n = self.b.len();
        let a = square(&self.a, n);
        let b_hat: Vec<f64> = self.b.iter().zip(self.e).map(|(x, e)| x - e).collect();
        assert!(t.worst(&a, self.b, q, |_| 1.0) < 1e-12);
        assert!(t.worst(&a, &b_hat, q - 1, |_| 1.0) < 1e-12);
        assert!(t.worst(&a, self.b, q + 1, |_| 1.0) > 1e-7);
        assert!(t.worst(&a, &b_hat, q, |_| 1.0) > 1e-7);
        let mut rows = self.a.clone();
        rows.push(self.b);
        rows.extend(&self.a_extra);
        let extended = rows.len();
        let a = square(&rows, extended);
        for sigma in [0.0f64, 0.3, 0.7, 1.0] {
            let w: Vec<f64> = (0..extended)
                .map(|i| {
                    self.r
                        .iter()
                        .enumerate()
                        .map(|(j, r)| r[i] * sigma.powi(j as i32 + 1))
                        .sum()
                })
                .collect();
            let at = |rho: usize| sigma.powi(rho as i32);
            assert!(t.worst(&a, &w, p, at) < exact, "{sigma}");
            assert!(t.worst(&a, &w, p + 1, at) < near, "{sigma}");
        }
        for (row, c) in self.a_extra.iter().zip(self.c_extra) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14);
        }
    }
}

/// A Verner tableau module's constants as a [`Verner`].
macro_rules! verner {
    ($tab:ident) => {
        Verner {
            a: $tab::A.iter().map(|r| &r[..]).collect(),
            b: &$tab::B,
            e: &$tab::E,
            a_extra: $tab::A_EXTRA.iter().map(|r| &r[..]).collect(),
            c_extra: &$tab::C_EXTRA,
            r: $tab::R.iter().map(|r| &r[..]).collect(),
        }
    };
}

#[test]
fn verner_9_8_has_orders_9_and_8_and_an_interpolant_of_order_8() {
    // The interpolant's order-9 conditions hold within 1e-5 (4.8e-6 in 50 digits); its
    // weights reach 1e4, so the f64 sums of the exact conditions err by ~1e-12.
    verner!(vern9).check(9, 8, 1e-10, 1e-5);
}

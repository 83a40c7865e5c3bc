//! Forward-mode differentiation: a number carrying its partial derivatives with respect to
//! N independent variables, so that a formula is written once, as in the physics notes, and
//! its partials follow by the chain rule of each operation (exact up to rounding, no step
//! size). The exact derivatives of the jump (`jarm::derivatives`, N = 4: θ, α, χ, k_m) and
//! the sensitivities of a full motion (`motion::sensitivities`, N = 9: eight parameters and
//! time) use it. [`Number`] lets one formula serve f64 and `Dual` alike.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its partial derivatives with respect to N variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// The value.
    pub v: f64,
    /// Its partials.
    pub d: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant (all partials 0).
    pub fn constant(v: f64) -> Self {
        Self { v, d: [0.0; N] }
    }

    /// The independent variable number `i` at value `v`.
    pub fn variable(v: f64, i: usize) -> Self {
        let mut d = [0.0; N];
        d[i] = 1.0;
        Self { v, d }
    }

    /// `k` times this number, for a constant `k`.
    pub fn scale(self, k: f64) -> Self {
        Self {
            v: k * self.v,
            d: self.d.map(|x| k * x),
        }
    }
}

/// (sin x, cos x), with d sin = cos dx and d cos = −sin dx (free functions, as in
/// [`crate::trig`], whose one implementation they use).
pub fn sin_cos<const N: usize>(x: Dual<N>) -> (Dual<N>, Dual<N>) {
    let (s, c) = crate::trig::sin_cos(x.v);
    (
        Dual {
            v: s,
            d: x.d.map(|dx| c * dx),
        },
        Dual {
            v: c,
            d: x.d.map(|dx| -s * dx),
        },
    )
}

/// sin x.
pub fn sin<const N: usize>(x: Dual<N>) -> Dual<N> {
    sin_cos(x).0
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d: std::array::from_fn(|i| self.d[i] + o.d[i]),
        }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d: std::array::from_fn(|i| self.d[i] - o.d[i]),
        }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self.scale(-1.0)
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    /// d(ab) = b da + a db.
    #[allow(clippy::suspicious_arithmetic_impl)] // the product rule
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d: std::array::from_fn(|i| self.d[i] * o.v + self.v * o.d[i]),
        }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    /// d(a/b) = (da − (a/b) db)/b.
    #[allow(clippy::suspicious_arithmetic_impl)] // the quotient rule
    fn div(self, o: Self) -> Self {
        let q = self.v / o.v;
        Self {
            v: q,
            d: std::array::from_fn(|i| (self.d[i] - q * o.d[i]) / o.v),
        }
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    fn add(self, k: f64) -> Self {
        Self {
            v: self.v + k,
            ..self
        }
    }
}

impl<const N: usize> Sub<Dual<N>> for f64 {
    type Output = Dual<N>;
    fn sub(self, x: Dual<N>) -> Dual<N> {
        -x + self
    }
}

/// A number a formula can be written for once: f64, or a [`Dual`] carrying partials.
pub trait Number:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A constant.
    fn of(v: f64) -> Self;
    /// (sin x, cos x), by the kernels' one implementation ([`crate::trig`]).
    fn sin_cos(self) -> (Self, Self);
}

impl Number for f64 {
    #[inline(always)]
    fn of(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        crate::trig::sin_cos(self)
    }
}

impl<const N: usize> Number for Dual<N> {
    fn of(v: f64) -> Self {
        Self::constant(v)
    }
    fn sin_cos(self) -> (Self, Self) {
        sin_cos(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each operation against a central difference of the same expression in f64.
    #[test]
    fn partials_match_central_differences() {
        let f = |x: [Dual<3>; 2]| {
            let (s, c) = sin_cos(x[0]);
            (s * x[1] + c.scale(3.0)) / (x[1] * x[1] + 1.0) - sin(2.0 - x[0])
        };
        let g = |x: [f64; 2]| {
            (x[0].sin() * x[1] + 3.0 * x[0].cos()) / (x[1] * x[1] + 1.0) - (2.0 - x[0]).sin()
        };
        let at = [0.7, -1.3];
        let y = f([Dual::variable(at[0], 0), Dual::variable(at[1], 1)]);
        assert!((y.v - g(at)).abs() < 1e-15);
        for i in 0..2 {
            let h = 1e-6;
            let (mut up, mut down) = (at, at);
            up[i] += h;
            down[i] -= h;
            let fd = (g(up) - g(down)) / (2.0 * h);
            assert!((y.d[i] - fd).abs() < 1e-9, "{i}: {} {fd}", y.d[i]);
        }
        assert_eq!(y.d[2..], [0.0, 0.0]);
    }
}

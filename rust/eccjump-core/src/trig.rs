//! The elementary functions of the kernels, from one pure-Rust implementation (the `libm`
//! crate, a port of musl's): the same bits on every machine and C library (the platform's
//! `sin`/`cos`/`pow` are accurate to an ulp but not bit-identical between C libraries), so
//! results are reproducible to the last bit across platforms. About as fast as glibc's.

/// (sin x, cos x).
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// A one-entry memo of (sin θ, cos θ), keyed on the bits of θ. Each accepted step of the
/// integrator ends with the FSAL evaluation at the new state, where the event scan (and an
/// observer) then look again: they find sin_cos in the memo. A pure function, so hits and
/// misses give identical bits.
#[derive(Debug, Clone, PartialEq)]
pub struct SinCosMemo(std::cell::Cell<(f64, f64, f64)>);

impl Default for SinCosMemo {
    fn default() -> Self {
        // θ = NaN never matches: the first lookup computes.
        Self(std::cell::Cell::new((f64::NAN, f64::NAN, f64::NAN)))
    }
}

impl SinCosMemo {
    /// (sin θ, cos θ), from the memo when θ is the last one asked for.
    #[inline]
    pub fn get(&self, theta: f64) -> (f64, f64) {
        let (th, s, c) = self.0.get();
        if th.to_bits() == theta.to_bits() {
            return (s, c);
        }
        let (s, c) = sin_cos(theta);
        self.0.set((theta, s, c));
        (s, c)
    }

    /// The entry (θ, sin θ, cos θ); θ is NaN before the first lookup.
    #[inline]
    pub fn entry(&self) -> (f64, f64, f64) {
        self.0.get()
    }
}

/// x^y.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_the_platform_to_an_ulp() {
        for i in 0..100_000 {
            let x = -50.0 + i as f64 * 1e-3;
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!((s - s0).abs() <= 2.0 * f64::EPSILON * s0.abs().max(1e-300) + 1e-300);
            assert!((c - c0).abs() <= 2.0 * f64::EPSILON * c0.abs().max(1e-300) + 1e-300);
            let p = pow(1.0 + i as f64 * 1e-4, -0.2);
            assert!((p - (1.0 + i as f64 * 1e-4).powf(-0.2)).abs() <= 2.0 * f64::EPSILON * p);
        }
    }
}

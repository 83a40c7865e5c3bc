//! (sin x, cos x) of [`LANES`] angles at once, bit for bit [`super::sin_cos`] (musl's
//! `sincos`, through the `libm` crate): the integrator of many trajectories side by side
//! ([`crate::ode::lanes`]) evaluates the right-hand sides of all its lanes together, and a
//! call per lane would serialise their longest dependency chain.
//!
//! The same operations as musl in the same order, with every branch turned into a choice
//! between values computed for all lanes, so that the compiler can keep the lanes in vector
//! registers:
//! - |x| ≤ π/4 (high word ≤ 0x3fe921fb): the kernels at x itself (`k_sin(x, 0, 0)`,
//!   `k_cos(x, 0)`);
//! - π/4 < |x| ≤ 9π/4: musl's `rem_pio2` subtracts n·π/2 with n = 1 … 4 chosen by the high
//!   word (one round: z = x − nπ/2₁, y0 = z − nπ/2₁ₜ, y1 = (z − y0) − nπ/2₁ₜ);
//! - 9π/4 < |x| < 2²⁰π/2: its medium case, n = rint(2x/π) by the 1.5·2⁵² trick, the same
//!   round;
//! - then `k_sin(y0, y1, 1)`, `k_cos(y0, y1)` and the quadrant n mod 4.
//!
//! Lanes that musl treats otherwise are recomputed by [`super::sin_cos`] itself: tiny |x|
//! (< 2⁻²⁷√2), the neighbourhoods of π/2, π, 3π/2 and 2π that musl sends to its medium
//! case, a medium reduction that needs musl's second round (heavy cancellation), |x| ≥
//! 2²⁰π/2, ∞ and NaN. The tests compare every lane with `libm::sincos` on millions of
//! angles of every size.

/// Angles per call (two AVX2 registers, or four SSE2 ones).
pub const LANES: usize = 8;

/// Values, one per lane.
pub type Lane = [f64; LANES];

// musl's constants (k_sin.c, k_cos.c, rem_pio2.c), by their bits.
const S1: f64 = f64::from_bits(0xBFC5_5555_5555_5549);
const S2: f64 = f64::from_bits(0x3F81_1111_1110_F8A6);
const S3: f64 = f64::from_bits(0xBF2A_01A0_19C1_61D5);
const S4: f64 = f64::from_bits(0x3EC7_1DE3_57B1_FE7D);
const S5: f64 = f64::from_bits(0xBE5A_E5E6_8A2B_9CEB);
const S6: f64 = f64::from_bits(0x3DE5_D93A_5ACF_D57C);
const C1: f64 = f64::from_bits(0x3FA5_5555_5555_554C);
const C2: f64 = f64::from_bits(0xBF56_C16C_16C1_5177);
const C3: f64 = f64::from_bits(0x3EFA_01A0_19CB_1590);
const C4: f64 = f64::from_bits(0xBE92_7E4F_809C_52AD);
const C5: f64 = f64::from_bits(0x3E21_EE9E_BDB4_B1C4);
const C6: f64 = f64::from_bits(0xBDA8_FAE9_BE88_38D4);
const INV_PIO2: f64 = f64::from_bits(0x3FE4_5F30_6DC9_C883);
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5440_0000);
const PIO2_1T: f64 = f64::from_bits(0x3DD0_B461_1A62_6331);
const TO_INT: f64 = 1.5 / f64::EPSILON;

/// (sin x, cos x) lane by lane, each bit for bit [`super::sin_cos`].
#[inline(always)]
#[allow(clippy::needless_range_loop)] // lane loops index several arrays in step
pub fn sin_cos_lanes(x: &Lane) -> (Lane, Lane) {
    let (mut s, mut c) = ([0.0; LANES], [0.0; LANES]);
    let mut other = [false; LANES];
    for i in 0..LANES {
        let xi = x[i];
        let ix = ((xi.to_bits() >> 32) as u32) & 0x7fff_ffff;
        let negative = xi.to_bits() >> 63 != 0;
        let small = ix <= 0x3fe9_21fb;
        // rem_pio2: n by the high word up to 9π/4, else rint(2x/π).
        let fixed = ix <= 0x401c_463b;
        let n_fixed = if ix <= 0x4002_d97c {
            1.0
        } else if ix <= 0x400f_6a7a {
            2.0
        } else if ix <= 0x4015_fdbc {
            3.0
        } else {
            4.0
        };
        let n_fixed = if negative { -n_fixed } else { n_fixed };
        let f_n = if fixed {
            n_fixed
        } else {
            (xi * INV_PIO2 + TO_INT) - TO_INT
        };
        let r = xi - f_n * PIO2_1;
        let w = f_n * PIO2_1T;
        let y0 = r - w;
        let y1 = (r - y0) - w;
        let cancelled = ix as i32 >> 20 > ((y0.to_bits() >> 52) & 0x7ff) as i32 + 16;
        let near_axis = (ix <= 0x400f_6a7a && (ix & 0xf_ffff) == 0x9_21fb)
            || ix == 0x4012_d97c
            || ix == 0x4019_21fb;
        other[i] = !(0x3e46_a09e..0x4139_21fb).contains(&ix)
            || (!small && (near_axis || (!fixed && cancelled)));
        let (y0, y1) = if small { (xi, 0.0) } else { (y0, y1) };
        // k_sin (iy = 0 for the small case, 1 after a reduction) and k_cos.
        let z = y0 * y0;
        let zz = z * z;
        let rs = S2 + z * (S3 + z * S4) + z * zz * (S5 + z * S6);
        let v = z * y0;
        let sin_k = if small {
            y0 + v * (S1 + z * rs)
        } else {
            y0 - ((z * (0.5 * y1 - v * rs) - y1) - v * S1)
        };
        let rc = z * (C1 + z * (C2 + z * C3)) + zz * zz * (C4 + z * (C5 + z * C6));
        let hz = 0.5 * z;
        let one = 1.0 - hz;
        let cos_k = one + (((1.0 - one) - hz) + (z * rc - y0 * y1));
        // The quadrant n mod 4 (n = 0 in the small case): (s, c), (c, −s), (−s, −c), (−c, s).
        let n = if small { 0 } else { (f_n as i32) & 3 };
        let (a, b) = if n & 1 == 1 {
            (cos_k, sin_k)
        } else {
            (sin_k, cos_k)
        };
        s[i] = if n >= 2 { -a } else { a };
        c[i] = if n == 1 || n == 2 { -b } else { b };
    }
    for i in 0..LANES {
        if other[i] {
            (s[i], c[i]) = super::sin_cos(x[i]);
        }
    }
    (s, c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(x: Lane) {
        let (s, c) = sin_cos_lanes(&x);
        for i in 0..LANES {
            let (s0, c0) = libm::sincos(x[i]);
            let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
            assert!(same(s[i], s0) && same(c[i], c0), "x = {:e}", x[i]);
        }
    }

    #[test]
    fn every_lane_is_libm_sincos_bit_for_bit() {
        let mut rng = crate::testing::Lcg(5);
        let mut u = || rng.next();
        // Uniform over many scales, both signs.
        for round in 0..250_000 {
            let scale = [1e-9, 0.8, 3.0, 8.0, 50.0, 1e3, 1e5, 1.7e6][round % 8];
            check(std::array::from_fn(|_| (2.0 * u() - 1.0) * scale));
        }
        // Next to the multiples of π/2 (musl's special cases and its second round), across
        // the thresholds of the high word, and the edges of every range.
        let half_pi = std::f64::consts::FRAC_PI_2;
        for k in 1..2000 {
            for e in [0.0, 1e-16, 1e-12, 1e-9, 3e-7, 1e-5, 1e-3] {
                let m = k as f64 * half_pi;
                check(std::array::from_fn(|i| {
                    let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                    sign * (m + e * (i as f64 - 3.5))
                }));
            }
        }
        for hw in [
            0x3e46_a09e_u64,
            0x3fe9_21fb,
            0x4002_d97c,
            0x400f_6a7a,
            0x4012_d97c,
            0x4015_fdbc,
            0x4019_21fb,
            0x401c_463b,
            0x4139_21fb,
        ] {
            check(std::array::from_fn(|i| {
                let bits = (hw << 32) + (i as u64 * 0x2000_0001) - 0x8000_0000;
                f64::from_bits(bits)
            }));
        }
        check([
            0.0,
            -0.0,
            1e-300,
            f64::MIN_POSITIVE / 3.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e300,
        ]);
    }
}

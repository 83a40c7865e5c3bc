//! The elementary functions of the kernels, from one pure-Rust implementation (the `libm`
//! crate, a port of musl's): the same bits on every machine and C library (the platform's
//! `sin`/`cos`/`pow` are accurate to an ulp but not bit-identical between C libraries), so
//! results are reproducible to the last bit across platforms. About as fast as glibc's.
//! [`lanes`] computes sin_cos of several angles at once, bit for bit as [`sin_cos`].

pub mod lanes;

/// The elementary functions of the kernels: `libm`'s own (`sin_cos` is its `sincos`).
pub use libm::{acos, asin, cbrt, cos, pow, sin, sincos as sin_cos, tan};

/// An angle θ with its (sin θ, cos θ), computed once where a state's right-hand side needs
/// them and handed on explicitly by the integrator to whatever looks at the same state next
/// (the event scan, the change bounds, the observer: [`crate::ode::OdeSystem::rhs_with_trig`]).
/// `sin_cos` is a pure function, so using the handed-on values or computing them again gives
/// identical bits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SinCos {
    /// θ.
    pub theta: f64,
    /// sin θ.
    pub sin: f64,
    /// cos θ.
    pub cos: f64,
}

impl SinCos {
    /// θ with its sine and cosine.
    #[inline]
    pub fn of(theta: f64) -> Self {
        let (sin, cos) = sin_cos(theta);
        Self { theta, sin, cos }
    }

    /// θ with its sine and cosine: `known` when it is of this θ (the same bits), else
    /// computed.
    #[inline]
    pub fn reuse(theta: f64, known: Option<SinCos>) -> Self {
        match known {
            Some(k) if k.theta.to_bits() == theta.to_bits() => k,
            _ => Self::of(theta),
        }
    }

    /// (sin θ, cos θ) of [`Self::reuse`].
    #[inline]
    pub fn at(theta: f64, known: Option<SinCos>) -> (f64, f64) {
        let k = Self::reuse(theta, known);
        (k.sin, k.cos)
    }
}

/// x^(−1/5), the step-size factor err^(−1/5) of the 5(4) pair, without `pow` (61 ns of
/// latency in the libm crate, a sixth of a motion map): x = m·2^e with m ∈ [1, 2) and
/// e = 5q + r gives 2^(−q)·2^(−r/5)·m^(−1/5), and m^(−1/5) takes two Newton steps
/// y ← y(6 − m y⁵)/5 from a quartic fit (relative error 1.9e-5, then ~1e-9, then rounding).
/// Within 4 ulp of x^(−1/5); `pow(x, −0.2)` (and scipy's `err ** -0.2`) differs from that by
/// the rounding of −0.2, 1e-16 relative for the error norms of a step (tested). 0, subnormal,
/// ∞ and NaN go to `pow` itself.
#[inline]
pub fn inv_fifth_root(x: f64) -> f64 {
    // 2^(−r/5), r = 0 … 4.
    const ROOT2: [f64; 5] = [
        1.0,
        0.870_550_563_296_124_1,
        0.757_858_283_255_199,
        0.659_753_955_386_447_1,
        0.574_349_177_498_517_5,
    ];
    const FIT: [f64; 5] = [
        0.999_980_730_183_848_9,
        -0.198_959_359_686_662_98,
        0.110_609_191_521_070_57,
        -0.055_623_152_120_730_206,
        0.014_557_430_005_373_31,
    ];
    inverse_root(x, -0.2, (&ROOT2, FIT), |y, m| {
        let y2 = y * y;
        y * (6.0 - m * (y2 * y2 * y)) * 0.2
    })
}

/// x^(−1/9), the step-size factor err^(−1/9) of Verner's 9(8) pair, to a relative 9.3e-6:
/// x = m·2^e, e = 9q + r, m^(−1/9) by a quartic fit alone. A step-size factor needs no
/// more (the safety factor 0.75 moves it by a quarter), and it lies on the path from one
/// step to the next, where Newton steps to make it exact would cost time for nothing.
/// 0, subnormal, ∞ and NaN go to `pow`.
#[inline]
pub fn inv_ninth_root(x: f64) -> f64 {
    // 2^(−r/9), r = 0 … 8.
    const ROOT2: [f64; 9] = [
        1.0,
        0.925_874_712_287_290_5,
        0.857_243_982_853_072_8,
        0.793_700_525_984_099_8,
        0.734_867_246_137_799_4,
        0.680_395_000_087_188_5,
        0.629_960_524_947_436_6,
        0.583_264_519_788_058_3,
        0.540_029_869_446_153,
    ];
    const FIT: [f64; 5] = [
        0.999_990_691_264_867_3,
        -0.110_609_055_211_727_92,
        0.057_208_138_337_770_02,
        -0.027_915_619_540_688_427,
        0.007_207_490_241_227_687,
    ];
    coarse_inverse_root(x, -1.0 / 9.0, (&ROOT2, FIT))
}

/// x^power for power = −1/k, k = `root2.len()`, without `pow`: x = m·2^e with m ∈ [1, 2) and
/// e = k q + r gives 2^(−q)·2^(−r/k)·m^(−1/k), with m^(−1/k) from the quartic `fit` in m − 1
/// refined by two `newton` steps y ← newton(y, m). 0, subnormal, ∞ and NaN go to `pow`.
#[inline(always)]
fn inverse_root(
    x: f64,
    power: f64,
    (root2, fit): (&[f64], [f64; 5]),
    newton: impl Fn(f64, f64) -> f64,
) -> f64 {
    let Some((m, y, r, two_q)) = root_fit(x, (root2, fit)) else {
        return pow(x, power);
    };
    let mut y = y;
    for _ in 0..2 {
        y = newton(y, m);
    }
    y * r * two_q
}

/// [`inverse_root`] without the Newton steps: to the relative error of `fit`.
#[inline(always)]
fn coarse_inverse_root(x: f64, power: f64, (root2, fit): (&[f64], [f64; 5])) -> f64 {
    match root_fit(x, (root2, fit)) {
        Some((_, y, r, two_q)) => y * r * two_q,
        None => pow(x, power),
    }
}

/// For a normal x > 0 (else None): m ∈ [1, 2), `fit`'s m^(−1/k), 2^(−r/k) and 2^(−q), where
/// x = m·2^e, e = k q + r, k = `root2.len()`.
#[inline(always)]
fn root_fit(x: f64, (root2, fit): (&[f64], [f64; 5])) -> Option<(f64, f64, f64, f64)> {
    if !(x.is_normal() && x > 0.0) {
        return None;
    }
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let k = root2.len() as i64;
    let (q, r) = (e.div_euclid(k), e.rem_euclid(k) as usize);
    let t = m - 1.0;
    let y = fit[0] + t * (fit[1] + t * (fit[2] + t * (fit[3] + t * fit[4])));
    // |q| ≤ 205: 2^(−q) is a normal number.
    Some((m, y, root2[r], f64::from_bits(((1023 - q) as u64) << 52)))
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
            let close = |a: f64, b: f64| (a - b).abs() <= 2.0 * f64::EPSILON * b.abs() + 1e-300;
            assert!(close(sin(x), x.sin()) && close(cos(x), x.cos()));
            assert!(close(tan(0.03 * x), (0.03 * x).tan()) && close(cbrt(x), x.cbrt()));
            let u = x / 50.0;
            assert!(close(asin(u), u.asin()) && close(acos(u), u.acos()));
        }
    }

    /// `root(x)` against pow(x, `power`) over 1e-300 … 1e300 and at the special values.
    /// pow raises to the double nearest the power, e.g. 1.11e-17 below −1/5: its result
    /// is smaller than the exact root by up to 7.6e-15 at 1e±300 (scipy's err ** -0.2 does
    /// the same), so the tolerance carries that term.
    /// `root` is x^power within `ulps` ulp (plus the rounding of power, growing with |ln x|)
    /// and the relative error `rel` over 10^-300 … 10^300; at 0, ∞, NaN, negative and
    /// subnormal x it is `pow` itself.
    fn check_inverse_root(root: fn(f64) -> f64, power: f64, ulps: f64, rel: f64) {
        let mut worst = 0.0f64;
        for i in 0..400_000 {
            // 10^-300 … 10^300, and the powers of two among them.
            let x = pow(10.0, -300.0 + 600.0 * i as f64 / 400_000.0);
            for y in [x, f64::from_bits(x.to_bits() & !0x000f_ffff_ffff_ffff)] {
                let (a, b) = (root(y), pow(y, power));
                let tol = ulps * f64::EPSILON + 1.2e-17 * libm::log(y).abs() + rel;
                worst = worst.max(((a - b) / b).abs() / tol);
            }
        }
        assert!(worst <= 1.0, "{worst}");
        for x in [
            0.0,
            -0.0,
            -1.0,
            f64::INFINITY,
            f64::NAN,
            1e-310,
            f64::MIN_POSITIVE,
        ] {
            let (a, b) = (root(x), pow(x, power));
            // NaN is NaN whatever its sign bit, which an optimised build may fold
            // differently for the two calls.
            let same = a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
            assert!(same || (a - b).abs() <= (1e-14 + rel) * b, "{x}");
        }
    }

    #[test]
    fn inv_ninth_root_is_pow_within_its_fit() {
        check_inverse_root(inv_ninth_root, -1.0 / 9.0, 0.0, 9.4e-6);
    }

    #[test]
    fn inv_fifth_root_is_pow_within_4_ulp() {
        check_inverse_root(inv_fifth_root, -0.2, 4.0, 0.0);
    }

    /// Every elementary function of the library's code comes from this module (one pure-Rust
    /// implementation), never from the platform's `f64` methods, whose last bits differ
    /// between C libraries: each file's lines outside its `#[cfg(test)]` items are searched
    /// for them (a file `tests.rs` is a module of tests alone, declared
    /// `#[cfg(test)] mod tests;`).
    #[test]
    fn no_platform_elementary_functions_outside_this_module() {
        let forbidden = [
            ".sin()",
            ".cos()",
            ".tan()",
            ".asin()",
            ".acos()",
            ".atan()",
            ".atan2(",
            ".exp()",
            ".exp_m1()",
            ".ln()",
            ".ln_1p()",
            ".log10()",
            ".log2()",
            ".powf(",
            ".cbrt()",
            ".hypot(",
            ".sinh()",
            ".cosh()",
            ".tanh()",
            ".sin_cos()",
        ];
        let mut dirs = vec![std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")];
        let mut files = 0;
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    dirs.push(path);
                    continue;
                }
                let here = path.parent().is_some_and(|d| d.ends_with("trig"));
                let tests = path.file_name().is_some_and(|n| n == "tests.rs");
                if path.extension().is_none_or(|e| e != "rs") || here || tests {
                    continue;
                }
                files += 1;
                let text = std::fs::read_to_string(&path).unwrap();
                for (number, line) in library_lines(&text) {
                    let line = line.split("//").next().unwrap_or("");
                    for f in forbidden {
                        assert!(!line.contains(f), "{}:{number}: {f}", path.display());
                    }
                }
            }
        }
        assert!(files > 40, "{files}");
    }

    /// The lines of `text` outside its `#[cfg(test)]` items, with their numbers from 1: a
    /// test module or a test-only function, type or impl may sit between the library's items
    /// (`jarm/path/mod.rs` declares its tests on line 41 of 369), so the scan goes on after
    /// each (the rule of `scripts/core_lines.py`).
    fn library_lines(text: &str) -> Vec<(usize, &str)> {
        let lines: Vec<&str> = text.lines().collect();
        let mut kept = Vec::new();
        let mut i = 0;
        while i < lines.len() {
            let Some(rest) = lines[i].trim_start().strip_prefix("#[cfg(test)]") else {
                kept.push((i + 1, lines[i]));
                i += 1;
                continue;
            };
            // The item the attribute applies to: after any other attributes and comments.
            let mut start = i;
            if rest.trim().is_empty() {
                start += 1;
                while lines.get(start).is_some_and(|l| {
                    l.trim_start().starts_with("#[") || l.trim_start().starts_with("//")
                }) {
                    start += 1;
                }
            }
            i = item_end(&lines, start) + 1;
        }
        kept
    }

    /// The index of the last line of the item starting at `lines[start]`: the line of its `;`
    /// if it has no body, else the line where its braces close. Comments, strings and
    /// character literals do not count (`'{'` opens nothing).
    fn item_end(lines: &[&str], start: usize) -> usize {
        let mut depth = 0_i32; // of (), [] and {} together: `[f64; K]` ends nothing
        for (i, line) in lines.iter().enumerate().skip(start) {
            let chars: Vec<char> = line.chars().collect();
            let mut k = 0;
            while k < chars.len() {
                match chars[k] {
                    '/' if chars.get(k + 1) == Some(&'/') => break,
                    '"' => {
                        k += 1;
                        while k < chars.len() && chars[k] != '"' {
                            k += if chars[k] == '\\' { 2 } else { 1 };
                        }
                    }
                    '\'' if chars.get(k + 2) == Some(&'\'') => k += 2,
                    '\'' if chars.get(k + 1) == Some(&'\\') => {
                        while k + 1 < chars.len() && chars[k + 1] != '\'' {
                            k += 1;
                        }
                        k += 1;
                    }
                    '(' | '[' | '{' => depth += 1,
                    ')' | ']' | '}' => {
                        depth -= 1;
                        if depth == 0 && chars[k] == '}' {
                            return i;
                        }
                    }
                    ';' if depth == 0 => return i,
                    _ => {}
                }
                k += 1;
            }
        }
        lines.len().saturating_sub(1)
    }

    #[test]
    fn library_lines_go_on_after_each_test_item() {
        let text = "\
fn a() {}
#[cfg(test)]
mod tests;
fn b() { x.sin() }
#[cfg(test)]
#[allow(dead_code)]
fn helper() {
    let c = '{';
    let s = \"}\";
}
#[cfg(test)] impl Foo { fn f(&self) -> [f64; 2] { [0.0; 2] } }
fn c() {}
#[cfg(test)]
mod tests {
    fn t() {}
}
fn d() {}";
        let kept: Vec<usize> = library_lines(text).iter().map(|&(n, _)| n).collect();
        assert_eq!(kept, [1, 4, 12, 17]);
    }
}

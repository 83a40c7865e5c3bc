//! What the integration tests share (a module of each test file that declares it).

/// A small deterministic generator (Knuth's MMIX LCG), uniform in [0, 1): reproducible
/// random test points (the same as the unit tests' `crate::testing::Lcg`).
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number, uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

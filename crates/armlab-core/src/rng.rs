//! A tiny seeded random generator (SplitMix64). The core needs reproducible random
//! numbers (tests, IK restarts, benchmarks) on every target, wasm included, without a
//! dependency that reaches for the operating system's entropy.

/// SplitMix64 (Steele, Lea & Flood 2014): 64 bits of state, passes BigCrush, and any
/// seed (including 0) is fine.
#[derive(Debug, Clone)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform number in [lo, hi].
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// A joint vector drawn uniformly within the robot's limits.
    pub fn joint_vector(&mut self, robot: &super::robot::Robot) -> Vec<f64> {
        robot
            .joints
            .iter()
            .map(|j| self.uniform(j.limits.min, j.limits.max))
            .collect()
    }
}

//! The project's seeded random generator: SplitMix64 (Steele, Lea & Flood 2014, "Fast
//! splittable pseudorandom number generators"; the C reference is Vigna's `splitmix64.c`),
//! used both as a sequential generator and as a counter-based hash.
//!
//! The algorithm, exactly (all arithmetic wrapping modulo 2⁶⁴):
//!
//! ```text
//! state += 0x9E3779B97F4A7C15                      // γ, the golden-ratio increment
//! z = state
//! z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9
//! z = (z ^ (z >> 27)) * 0x94D049BB133111EB
//! return z ^ (z >> 31)                             // = mix64(state)
//! ```
//!
//! `mix64` (the last three lines) is a bijection of u64, so the i-th output of a SplitMix64
//! stream seeded with `s` is `mix64(s + i·γ)`, i = 1, 2, …
//!
//! Random wave amplitudes are keyed, not drawn in sequence: the two Gaussians of mode (n, m)
//! come from the stream whose state is
//!
//! ```text
//! state(seed, n, m) = mix64(mix64(seed) ^ lane(n, m)),
//! lane(n, m) = ((n as i32 as u32) << 32) | (m as i32 as u32)
//! ```
//!
//! `lane` is injective for |n|, |m| < 2³¹ and `x ↦ mix64(mix64(seed) ^ x)` is a bijection, so
//! within one seed distinct modes get distinct streams. The numbers of a mode therefore do not
//! depend on the order in which modes are visited nor on the grid size: a larger grid keeps the
//! low modes' amplitudes.
//!
//! Gaussians (Box–Muller, Box & Muller 1958), from the first two outputs `a`, `b` of the stream:
//!
//! ```text
//! u1 = ((a >> 11) + 1) · 2⁻⁵³     // top 53 bits → uniform on (0, 1]: never 0, so ln is finite
//! u2 = ((b >> 11) + 1) · 2⁻⁵³     // same; 2π·u2 ∈ (0, 2π]
//! r = sqrt(−2 ln u1), θ = 2π u2
//! (ξ_r, ξ_i) = (r cos θ, r sin θ) // both branches are used: one pair per mode
//! ```
//!
//! Both u are exact in f64 (53-bit integers times a power of two). |ξ| ≤ sqrt(2·53 ln 2) ≈ 8.6.
//! `ln`, `sqrt`, `cos` and `sin` are the platform's libm: bit-identical across runs on one
//! platform; the GPU receives these numbers as computed on the CPU, it never recomputes them.

use std::f64::consts::TAU;

/// The SplitMix64 increment γ = 2⁶⁴/φ, odd.
pub const SPLITMIX64_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// 2⁻⁵³, the spacing of the 53-bit uniforms.
const INV_2_POW_53: f64 = 1.0 / (1u64 << 53) as f64;

/// SplitMix64's output function (Stafford's "Mix13" variant of the MurmurHash3 finaliser):
/// a bijection of u64 with full avalanche.
#[inline]
pub fn mix64(state: u64) -> u64 {
    let mut z = state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A SplitMix64 stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A stream whose first output is `mix64(seed + γ)`, as in the reference implementation.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The stream of mode (n, m) for `seed` (see the module documentation).
    pub fn for_mode(seed: u64, n: i32, m: i32) -> Self {
        let lane = (u64::from(n as u32) << 32) | u64::from(m as u32);
        Self::new(mix64(mix64(seed) ^ lane))
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(SPLITMIX64_GAMMA);
        mix64(self.state)
    }

    /// A uniform on (0, 1]: the top 53 bits plus one, times 2⁻⁵³. Exact in f64; never 0.
    #[inline]
    pub fn next_open_closed(&mut self) -> f64 {
        ((self.next_u64() >> 11) + 1) as f64 * INV_2_POW_53
    }

    /// Two independent standard normal deviates by Box–Muller (cos branch first).
    pub fn next_gaussian_pair(&mut self) -> (f64, f64) {
        let u1 = self.next_open_closed();
        let u2 = self.next_open_closed();
        // u1 ∈ (0, 1] so ln u1 ∈ [−36.8, 0] and r is finite; −2 ln 1 = −0 would give
        // sqrt(−0) = −0, harmless (r·cos θ = ∓0).
        let r = (-2.0 * u1.ln()).sqrt();
        let theta = TAU * u2;
        (r * theta.cos(), r * theta.sin())
    }
}

/// The pair of standard Gaussians (ξ_r, ξ_i) of mode (n, m): the first Box–Muller pair of
/// [`SplitMix64::for_mode`]. Independent of any traversal order.
pub fn mode_gaussians(seed: u64, n: i32, m: i32) -> (f64, f64) {
    SplitMix64::for_mode(seed, n, m).next_gaussian_pair()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Vigna's `splitmix64.c`, transcribed independently of the code above.
    fn reference_splitmix64(x: &mut u64) -> u64 {
        *x = x.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = *x;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        z ^ (z >> 31)
    }

    #[test]
    fn known_answers_for_seed_1234567() {
        // The widely published first outputs of SplitMix64 seeded with 1234567.
        let published: [u64; 5] = [
            6457827717110365317,
            3203168211198807973,
            9817491932198370423,
            4593380528125082431,
            16408922859458223821,
        ];
        let mut ours = SplitMix64::new(1234567);
        let mut reference = 1234567u64;
        for &p in &published {
            let r = reference_splitmix64(&mut reference);
            assert_eq!(r, p, "reference transcription disagrees with the published value");
            assert_eq!(ours.next_u64(), p);
        }
        // And further along the stream.
        for _ in 0..1000 {
            assert_eq!(ours.next_u64(), reference_splitmix64(&mut reference));
        }
    }

    #[test]
    fn uniforms_are_in_the_half_open_interval() {
        // Extreme bit patterns: all-zero top bits gives 2⁻⁵³, all-one gives exactly 1.
        let all_zero_top_bits = 0x7ffu64; // only the 11 discarded low bits set
        assert_eq!(((all_zero_top_bits >> 11) + 1) as f64 * INV_2_POW_53, INV_2_POW_53);
        assert_eq!(((u64::MAX >> 11) + 1) as f64 * INV_2_POW_53, 1.0);
        let mut g = SplitMix64::new(7);
        for _ in 0..10_000 {
            let u = g.next_open_closed();
            assert!(u > 0.0 && u <= 1.0);
        }
    }

    #[test]
    fn mode_streams_are_order_independent_and_distinct() {
        let a = mode_gaussians(42, 3, -5);
        let _ = mode_gaussians(42, 0, 0);
        assert_eq!(a, mode_gaussians(42, 3, -5));
        assert_ne!(a, mode_gaussians(42, -5, 3));
        assert_ne!(a, mode_gaussians(42, -3, 5));
        assert_ne!(a, mode_gaussians(43, 3, -5));
    }
}

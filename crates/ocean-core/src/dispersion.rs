//! The dispersion relation of linear gravity waves, ω² = g k tanh(k h), and the phase ω·t
//! evaluated so that it stays accurate at any time.
//!
//! Looping (seed 000 §2.1: "these samples are played cyclically"): with a loop period T > 0
//! every ω is rounded down to a multiple of ω₀ = 2π/T (Tessendorf 2001, §3.3), so that
//! h(t + T) = h(t) exactly. Times are reduced modulo T in f64 *before* any phase is formed, and
//! the phase itself is reduced modulo 2π in f64, so that `phase(…) as f32` is as accurate at
//! t = 10⁹ s as at t = 0.

use std::f64::consts::TAU;

use crate::{Error, Result};

/// The dispersion relation of the scene's water.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dispersion {
    /// Gravitational acceleration, m/s².
    pub gravity: f64,
    /// Water depth h, metres; `f64::INFINITY` for deep water.
    pub depth_m: f64,
    /// Loop period T, seconds; 0 means no looping (no quantisation).
    pub loop_period_s: f64,
}

/// Above this k·h, tanh(k h) equals 1 in f64 (tanh(19.1) = 1 − 5.5e-17), so the deep-water
/// branch is taken; it also keeps `depth_m = ∞` free of `inf · 0`.
const DEEP_KH: f64 = 20.0;

impl Dispersion {
    /// A dispersion relation; errors on a non-positive or NaN depth or gravity, or a negative
    /// or non-finite loop period.
    pub fn new(gravity: f64, depth_m: f64, loop_period_s: f64) -> Result<Self> {
        if !(gravity > 0.0 && gravity.is_finite()) {
            return Err(Error::InvalidParameter {
                name: "gravity",
                value: gravity,
                reason: "must be finite and > 0".into(),
            });
        }
        // NaN fails both tests.
        if depth_m.is_nan() || depth_m <= 0.0 {
            return Err(Error::InvalidParameter {
                name: "depth_m",
                value: depth_m,
                reason: "must be > 0 (use inf for deep water)".into(),
            });
        }
        if !(loop_period_s >= 0.0 && loop_period_s.is_finite()) {
            return Err(Error::InvalidParameter {
                name: "loop_period_s",
                value: loop_period_s,
                reason: "must be finite and ≥ 0 (0 = no looping)".into(),
            });
        }
        Ok(Self { gravity, depth_m, loop_period_s })
    }

    /// Deep water, no looping.
    pub fn deep(gravity: f64) -> Self {
        Self { gravity, depth_m: f64::INFINITY, loop_period_s: 0.0 }
    }

    /// Whether the relation is quantised to a loop period.
    pub fn is_looping(&self) -> bool {
        self.loop_period_s > 0.0
    }

    /// The fundamental angular frequency ω₀ = 2π/T of the loop, if looping.
    pub fn loop_omega0(&self) -> Option<f64> {
        self.is_looping().then(|| TAU / self.loop_period_s)
    }

    /// ω(k) = sqrt(g k tanh(k h)), unquantised. ω(0) = 0; negative k is treated as |k|.
    pub fn omega_continuous(&self, k: f64) -> f64 {
        let k = k.abs();
        // Deep water is tested on the depth itself: k·h would be ∞·0 = NaN at k = 0.
        let tanh_kh = if self.depth_m.is_infinite() || k * self.depth_m > DEEP_KH {
            1.0
        } else {
            (k * self.depth_m).tanh()
        };
        (self.gravity * k * tanh_kh).sqrt()
    }

    /// dω/dk, the group velocity, unquantised. At k = 0 this is sqrt(g h) (shallow-water
    /// speed) in finite depth and +∞ in deep water (ω = sqrt(g k) has an infinite slope there).
    pub fn group_velocity(&self, k: f64) -> f64 {
        let k = k.abs();
        let g = self.gravity;
        let h = self.depth_m;
        if k == 0.0 {
            return if h.is_finite() { (g * h).sqrt() } else { f64::INFINITY };
        }
        let kh = k * h;
        if kh > DEEP_KH {
            // ω = sqrt(g k): dω/dk = ω / (2k).
            return 0.5 * (g / k).sqrt();
        }
        if kh < 1e-8 {
            // Shallow-water limit: ω = k sqrt(g h) (1 − (kh)²/6 + …), so dω/dk = sqrt(g h) to
            // 1e-16; the general form below would divide by an ω that underflows to 0 for
            // k < 1e-150.
            return (g * h).sqrt();
        }
        // 2ω dω/dk = g (tanh(kh) + kh sech²(kh)).
        let t = kh.tanh();
        let sech2 = 1.0 - t * t;
        let omega = (g * k * t).sqrt();
        g * (t + kh * sech2) / (2.0 * omega)
    }

    /// The integer multiple m of ω₀ that ω(k) is quantised to when looping (m = ⌊ω/ω₀⌋),
    /// or `None` without looping.
    pub fn loop_harmonic(&self, k: f64) -> Option<u64> {
        let omega0 = self.loop_omega0()?;
        Some((self.omega_continuous(k) / omega0).floor() as u64)
    }

    /// ω(k) as the synthesis uses it: quantised to ⌊ω/ω₀⌋·ω₀ when looping, else continuous.
    pub fn omega(&self, k: f64) -> f64 {
        match (self.loop_harmonic(k), self.loop_omega0()) {
            (Some(m), Some(omega0)) => m as f64 * omega0,
            _ => self.omega_continuous(k),
        }
    }

    /// The time that enters the phases: t reduced modulo T when looping (in f64, so that
    /// h(t + T) = h(t) holds to round-off however large t is), else t itself.
    pub fn reduced_time(&self, t: f64) -> f64 {
        if self.is_looping() { t.rem_euclid(self.loop_period_s) } else { t }
    }

    /// The phase ω(k)·t reduced to [0, 2π), computed in f64.
    ///
    /// Looping: ω = m·ω₀, so ω t = 2π · frac(m · (t mod T) / T); forming frac() of the
    /// integer multiple first keeps the result exact to f64 round-off of (t mod T)/T.
    /// Not looping: ω·t is formed in f64 (relative error 1e-16, i.e. 1e-7 rad at ω t = 1e9)
    /// and reduced modulo 2π.
    pub fn phase(&self, k: f64, t: f64) -> f64 {
        match self.loop_harmonic(k) {
            Some(m) => {
                let tau = self.reduced_time(t) / self.loop_period_s;
                TAU * (m as f64 * tau).fract()
            }
            None => (self.omega_continuous(k) * t).rem_euclid(TAU),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = crate::GRAVITY;

    #[test]
    fn deep_and_finite_depth_agree_with_closed_forms() {
        let deep = Dispersion::deep(G);
        let shallow = Dispersion::new(G, 5.0, 0.0).unwrap();
        for &k in &[1e-6, 1e-3, 0.01, 0.1, 1.0, 10.0, 1e3] {
            let w_deep = (G * k).sqrt();
            assert!((deep.omega(k) - w_deep).abs() <= 1e-15 * w_deep);
            let w_finite = (G * k * (k * 5.0_f64).tanh()).sqrt();
            assert!((shallow.omega(k) - w_finite).abs() <= 1e-15 * w_finite);
        }
        // Shallow-water limit: ω → k sqrt(g h).
        let k = 1e-6;
        let c = shallow.omega(k) / k;
        assert!((c - (G * 5.0).sqrt()).abs() < 1e-9);
        assert_eq!(deep.omega(0.0), 0.0);
        assert_eq!(shallow.omega(0.0), 0.0);
    }

    #[test]
    fn group_velocity_matches_a_central_difference() {
        for d in [Dispersion::deep(G), Dispersion::new(G, 5.0, 0.0).unwrap()] {
            for &k in &[0.01, 0.1, 0.5, 2.0, 30.0] {
                let h = 1e-6 * k;
                let fd = (d.omega(k + h) - d.omega(k - h)) / (2.0 * h);
                let cg = d.group_velocity(k);
                assert!((fd - cg).abs() < 1e-7 * cg, "k={k} fd={fd} cg={cg}");
            }
        }
    }

    #[test]
    fn group_velocity_is_finite_for_tiny_k() {
        let d = Dispersion::new(G, 5.0, 0.0).unwrap();
        for k in [1e-300, 1e-160, 1e-12, 1e-9] {
            let cg = d.group_velocity(k);
            assert!((cg - (G * 5.0).sqrt()).abs() < 1e-9, "k={k}: {cg}");
        }
    }

    #[test]
    fn looping_quantises_and_repeats() {
        let d = Dispersion::new(G, f64::INFINITY, 20.0).unwrap();
        let omega0 = TAU / 20.0;
        for &k in &[0.01, 0.1, 1.0, 7.0] {
            let w = d.omega(k);
            assert!(w <= d.omega_continuous(k) && d.omega_continuous(k) - w < omega0);
            let m = (w / omega0).round();
            assert!((w - m * omega0).abs() < 1e-12);
            for &t in &[0.0, 3.7, 1e6, 1e9] {
                let a = d.phase(k, t);
                let b = d.phase(k, t + 20.0);
                let diff = (a - b).abs();
                let diff = diff.min(TAU - diff);
                // t + T is itself rounded in f64: at t = 1e9 its ulp is 1.2e-7 s.
                let ulp_t = (t + 20.0) * f64::EPSILON;
                assert!(diff <= w * ulp_t + 1e-12, "k={k} t={t}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn phase_is_reduced_and_finite_at_huge_time() {
        let d = Dispersion::deep(G);
        for &t in &[0.0, 1.0, 1e6, 1e9, 1e15] {
            let p = d.phase(1.0, t);
            assert!((0.0..TAU).contains(&p), "t={t}: {p}");
        }
    }

    #[test]
    fn bad_parameters_are_errors() {
        assert!(Dispersion::new(G, 0.0, 0.0).is_err());
        assert!(Dispersion::new(G, f64::NAN, 0.0).is_err());
        assert!(Dispersion::new(G, 1.0, -1.0).is_err());
        assert!(Dispersion::new(G, 1.0, f64::INFINITY).is_err());
        assert!(Dispersion::new(0.0, 1.0, 0.0).is_err());
        assert!(Dispersion::new(G, f64::INFINITY, 0.0).is_ok());
    }
}

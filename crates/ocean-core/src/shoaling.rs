//! Waves entering shallow water (issue 15, groundwork of waves technique `coastal` and of the
//! depth damping of every sea near a shore): linear theory's wavenumber, speed and height at a
//! local depth, and where the waves break.
//!
//! A wave keeps its angular frequency ω as the depth h under it changes; its wavenumber
//! follows the dispersion relation ω² = g k tanh(k h) (shorter and slower in shallow water),
//! and with no energy lost its energy flux E·c_g is conserved, so its height grows by the
//! **shoaling coefficient** K_s = √(c_g,deep / c_g(h)) (c_g,deep = g/(2ω)): K_s falls from 1
//! to its minimum 0.913 near k h = 1.2, then rises without bound, as (4 k₀ h)^(−1/4) in the
//! shallow limit (Green's law; k₀ = ω²/g the deep-water wavenumber). Linear theory stops where
//! the wave breaks: a **depth-limited** height H ≤ γ h with γ = 0.78 (McCowan 1894's solitary
//! wave limit, the usual breaker index of surf-zone models), so the height a shoaling wave
//! reaches is min(K_s H₀, γ h) and goes to 0 with the depth: waves run out on the sand.
//!
//! Everything is f64 and total: non-finite or non-positive inputs give documented values
//! (h ≤ 0: dry, height 0; h = ∞: deep water), never NaN.

/// McCowan's breaker index γ: a wave breaks where its height exceeds γ times the depth.
pub const BREAKER_INDEX: f64 = 0.78;

/// The wavenumber k (rad/m) of a wave of angular frequency `omega` (rad/s) in water `depth_m`
/// deep under gravity `g`: the root of ω² = g k tanh(k h). Newton's method from Fenton &
/// McKee (1990)'s explicit approximation, to round-off (a few iterations). Deep water
/// (h = ∞, or k h beyond 20 where tanh is 1 in f64): ω²/g. h ≤ 0, NaN, or ω ≤ 0: 0.
pub fn wavenumber(omega: f64, g: f64, depth_m: f64) -> f64 {
    // NaN fails every comparison, so it lands here too.
    let valid = omega > 0.0 && g > 0.0 && depth_m > 0.0 && omega.is_finite() && g.is_finite();
    if !valid {
        return 0.0;
    }
    let k0 = omega * omega / g;
    if depth_m.is_infinite() || k0 * depth_m > 20.0 {
        return k0;
    }
    // Fenton & McKee: k ≈ k₀ / tanh((k₀ h)^{3/4})^{2/3}, within 1.5 % everywhere.
    let x = k0 * depth_m;
    let mut k = k0 / x.powf(0.75).tanh().powf(2.0 / 3.0);
    // Newton on ω(k)² − ω² with the scene's own relation: its derivative is 2 ω(k) c_g(k).
    let d = relation(g, depth_m);
    for _ in 0..8 {
        let w = d.omega_continuous(k);
        let f = w * w - omega * omega;
        let df = 2.0 * w * d.group_velocity(k);
        let next = k - f / df;
        if next.is_nan() || next <= 0.0 || next.is_infinite() {
            break;
        }
        if (next - k).abs() <= 1e-15 * k {
            return next;
        }
        k = next;
    }
    k
}

/// The dispersion relation ω² = g k tanh(k h) of `crate::dispersion`, unquantised, for a
/// depth and gravity already checked positive.
fn relation(g: f64, depth_m: f64) -> crate::dispersion::Dispersion {
    crate::dispersion::Dispersion { gravity: g, depth_m, loop_period_s: 0.0 }
}

/// The group velocity c_g = dω/dk (m/s) of a wave of angular frequency `omega` at depth
/// `depth_m` (`Dispersion::group_velocity` at its [`wavenumber`]). Deep water: g/(2ω);
/// h ≤ 0 or ω ≤ 0: 0.
pub fn group_velocity(omega: f64, g: f64, depth_m: f64) -> f64 {
    let k = wavenumber(omega, g, depth_m);
    if k <= 0.0 {
        return 0.0;
    }
    relation(g, depth_m).group_velocity(k)
}

/// The shoaling coefficient K_s = √(c_g,deep / c_g(h)) of a wave of angular frequency `omega`
/// over `depth_m` (module docs). 1 in deep water; h ≤ 0: 0 (no water, no wave).
pub fn shoaling_coefficient(omega: f64, g: f64, depth_m: f64) -> f64 {
    let cg = group_velocity(omega, g, depth_m);
    if cg.is_nan() || cg <= 0.0 || omega.is_nan() || omega <= 0.0 {
        return 0.0;
    }
    (g / (2.0 * omega) / cg).sqrt()
}

/// The height (m, crest to trough) that a wave of deep-water height `deep_height_m` and angular
/// frequency `omega` has over `depth_m`: min(K_s H₀, γ h), the depth-limited breaker
/// (module docs). 0 where there is no water.
pub fn shoaled_height(deep_height_m: f64, omega: f64, g: f64, depth_m: f64) -> f64 {
    if depth_m.is_nan() || depth_m <= 0.0 || deep_height_m.is_nan() || deep_height_m <= 0.0 {
        return 0.0;
    }
    let h = deep_height_m * shoaling_coefficient(omega, g, depth_m);
    h.min(BREAKER_INDEX * depth_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;

    #[test]
    fn the_wavenumber_solves_the_dispersion_relation() {
        for omega in [0.2, 0.63, 1.0, 3.0, 10.0] {
            for h in [0.01, 0.3, 2.0, 10.0, 100.0, 1e4] {
                let k = wavenumber(omega, G, h);
                let residual = (G * k * (k * h).tanh() - omega * omega).abs() / (omega * omega);
                assert!(residual < 1e-13, "ω {omega} h {h}: residual {residual}");
                // The scene's own dispersion relation gives the same ω back.
                let d = crate::dispersion::Dispersion::new(G, h, 0.0).expect("valid");
                assert!((d.omega_continuous(k) - omega).abs() < 1e-12 * omega);
            }
        }
        assert_eq!(wavenumber(2.0, G, f64::INFINITY), 4.0 / G);
        assert_eq!(wavenumber(2.0, G, 0.0), 0.0);
        assert_eq!(wavenumber(f64::NAN, G, 3.0), 0.0);
    }

    #[test]
    fn shoaling_has_its_published_minimum_and_greens_law() {
        let omega = 1.0;
        let k0 = omega * omega / G;
        // The minimum over depth, 0.913 near k h = 1.2: the standard result of linear shoaling
        // (Dean & Dalrymple 1991, "Water Wave Mechanics for Engineers and Scientists").
        let (mut min, mut at) = (f64::INFINITY, 0.0);
        for i in 1..20_000 {
            let h = f64::from(i) * 1e-3 / k0;
            let ks = shoaling_coefficient(omega, G, h);
            if ks < min {
                (min, at) = (ks, wavenumber(omega, G, h) * h);
            }
        }
        assert!((min - 0.9129).abs() < 5e-4, "minimum K_s {min}");
        assert!((at - 1.2).abs() < 0.1, "at k h = {at}");
        // Deep water: 1; the shallow limit: (4 k₀ h)^(−1/4), to the first correction in k h.
        assert!((shoaling_coefficient(omega, G, 1e3 / k0) - 1.0).abs() < 1e-12);
        let h = 1e-6 / k0;
        let green = (4.0 * k0 * h).powf(-0.25);
        let ks = shoaling_coefficient(omega, G, h);
        assert!((ks / green - 1.0).abs() < 1e-5, "{ks} against Green's {green}");
        // Negative control: Green's law is wrong in deep water.
        assert!((shoaling_coefficient(omega, G, 1.0 / k0) - (4.0f64).powf(-0.25)).abs() > 0.1);
    }

    #[test]
    fn waves_break_at_the_depth_limit_and_vanish_on_the_sand() {
        let omega = std::f64::consts::TAU / 8.0; // an 8 s swell
        let deep = 1.5;
        // Offshore the height follows K_s; near the shore γ h caps it, down to 0 at h = 0.
        assert!((shoaled_height(deep, omega, G, 200.0) - deep).abs() < 1e-3);
        let mut last = f64::INFINITY;
        for i in 0..=400 {
            let h = 2.0 - f64::from(i) * 0.005;
            let height = shoaled_height(deep, omega, G, h);
            assert!(height <= BREAKER_INDEX * h.max(0.0) + 1e-15, "h {h}: {height}");
            assert!(height <= last + 1e-15, "the broken wave grows at h {h}");
            last = height;
        }
        assert_eq!(shoaled_height(deep, omega, G, 0.0), 0.0);
        assert_eq!(shoaled_height(deep, omega, G, -1.0), 0.0);
        assert_eq!(shoaled_height(deep, omega, G, f64::NAN), 0.0);
        assert!(shoaled_height(deep, omega, G, f64::INFINITY) == deep);
    }
}

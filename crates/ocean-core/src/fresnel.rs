//! The Fresnel reflectance of a smooth dielectric interface for unpolarised light.
//!
//! - [`fresnel_exact`] is eq. 2 of Hu et al. 2004 (seed 000, §4.1, after Cook & Torrance 1982),
//!   written so that it stays accurate as η → 1 and total for every finite input. It is the
//!   function the renderer uses (directly on the CPU, through the 2D texture of
//!   [`crate::tables`] on the GPU), in `f32` or `f64`.
//! - [`fresnel_schlick`] is Schlick's (1994) approximation, under its own name; the tests bound
//!   its error against [`fresnel_exact`].
//! - [`fresnel_dielectric_sp`] and [`fresnel_dielectric_polarized`] are an independent
//!   formulation (Snell's law for cos θₜ, then the s- and p-amplitude coefficients, as pbrt-v4's
//!   `FrDielectric`), kept in `f64` as the reference that eq. 2 is tested against.
//!
//! Conventions (the same in every function here):
//! - `cos_theta_i` = c = cos θᵢ is the cosine between the incident (or view) direction and the
//!   surface normal, both pointing away from the surface. By reciprocity the reflectance for the
//!   view vector V equals the one for the light vector L = reflect(V), which is why seed 000 can
//!   write c = L·N = V·N.
//! - `eta` = η = ηₜ/ηᵢ, the index of refraction on the far side of the surface (the side the
//!   normal does not point to) over the index on the near side: air → water is η ≈ 1.333.
//! - c < 0 means the direction is on the far side of the surface, i.e. the ray arrives from
//!   inside the other medium. As pbrt's `FrDielectric` does, the interface is then seen from the
//!   other side: c → −c and η → 1/η.
//! - c is clamped to [−1, 1]: a dot product of two vectors normalised in floating point can be
//!   a few ulp above 1 in magnitude, which would make sin²θᵢ = 1 − c² negative.

use num_traits::Float;

/// The conventions both Fresnel functions share: NaN propagates; c is clamped to [−1, 1]; a
/// negative c means the ray comes from the far side (c → −c, η → 1/η, as pbrt's
/// FrDielectric); η ≤ 0 and η = +∞ reflect everything; η = 1 is no interface. `Err` holds the
/// result of such a special case, `Ok` the oriented (c ∈ [0, 1], η) to evaluate.
fn orient<T: Float>(cos_theta_i: T, eta: T) -> Result<(T, T), T> {
    let zero = T::zero();
    let one = T::one();
    if cos_theta_i.is_nan() || eta.is_nan() {
        return Err(T::nan());
    }
    let mut c = cos_theta_i.max(-one).min(one);
    let mut eta = eta;
    if c < zero {
        // The ray comes from the far side: look at the interface from there.
        c = -c;
        eta = one / eta;
    }
    // Non-physical η ≤ 0 (also 1/(−0) = −∞ above) and η = +∞ both reflect everything.
    if eta <= zero || eta.is_infinite() {
        return Err(one);
    }
    if eta == one {
        // No interface, no reflection; also avoids 0/0 at c = 0.
        return Err(zero);
    }
    Ok((c, eta))
}

/// The unpolarised Fresnel reflectance F(c, η) of eq. 2 (seed 000, §4.1):
///
/// F = ½ (g−c)²/(g+c)² · (1 + (c(g+c)−1)²/(c(g−c)+1)²), g² = η² + c² − 1,
///
/// where g = η cos θₜ. See the [module documentation](self) for the conventions on c and η.
///
/// Evaluation, and why it is not the formula as printed:
/// - g − c is formed as (η² − 1)/(g + c) with η² − 1 = (η − 1)(η + 1): (g − c)(g + c) = η² − 1
///   exactly, and η − 1 is exact in floating point near 1, so nothing cancels as η → 1. The
///   printed g − c loses all digits there (for η = 1.00001 in f32 the printed form is wrong in
///   the second significant digit; this form is good to a few ulp).
/// - The second factor uses c(g+c) − 1 = cg − sin²θᵢ and c(g−c) + 1 = cg + sin²θᵢ with
///   sin²θᵢ = (1 − c)(1 + c): the denominator is then a sum of non-negative terms and is never
///   formed by cancellation (the numerator does cancel at Brewster's angle, where it is 0, as
///   the p-reflectance it measures is).
/// - For η > 2, g = η·sqrt(1 − sin²θᵢ/η²), so that η² is never formed and does not overflow
///   for huge η; there g ≥ √3 > c and g − c does not cancel.
///
/// Results, for every input that is not NaN, are finite and in [0, 1]:
/// - total internal reflection (g² < 0, only for η < 1 beyond the critical angle asin η):
///   exactly 1;
/// - c = 0 (grazing) with η ≠ 1: exactly 1, the limit of eq. 2;
/// - c = ±1 (normal incidence): ((η − 1)/(η + 1))², eq. 2's value there, formed directly;
/// - η = 1 exactly: exactly 0 for every c, because there is no interface. At c = 0 eq. 2 is
///   0/0 there, and the limit depends on the order: η → 1 at fixed c > 0 gives 0, c → 0 at fixed
///   η ≠ 1 gives 1. 0 is returned because an index-matched boundary reflects nothing;
/// - η = +∞: 1 (the limit of a perfect mirror);
/// - η ≤ 0 (not a physical index ratio; it is the caller's bug): 1, the limit η → 0⁺ (an
///   infinitely dense medium on the near side totally reflects every direction). No panic, so
///   that a shader port can do the same.
///
/// NaN in either argument propagates to a NaN result: it is a bug of the caller, and hiding it
/// behind a plausible reflectance would make it harder to find.
///
/// The final `min(1)` only removes round-off: near the critical angle the computed
/// ((g − c)/(g + c))² can exceed 1 by an ulp.
pub fn fresnel_exact<T: Float>(cos_theta_i: T, eta: T) -> T {
    let zero = T::zero();
    let one = T::one();
    let two = one + one;
    let half = one / two;
    let (c, eta) = match orient(cos_theta_i, eta) {
        Ok(oriented) => oriented,
        Err(special) => return special,
    };
    if c == zero {
        // Grazing incidence reflects everything (for η < 1 this is inside the TIR range too).
        return one;
    }
    if c == one {
        // Normal incidence: g = η, and eq. 2 reduces to ((η − 1)/(η + 1))². Forming it directly
        // also keeps 0/0 out of the second factor when η is so small that g rounds to 0.
        let r = (eta - one) / (eta + one);
        return r * r;
    }
    let sin2_theta_i = (one - c) * (one + c);
    let (g, g_minus_c) = if eta <= two {
        // g² = η² − sin²θᵢ = (η − 1)(η + 1) + c².
        let eta2_minus_1 = (eta - one) * (eta + one);
        let g2 = eta2_minus_1 + c * c;
        if g2 < zero {
            // Total internal reflection: no real transmitted direction.
            return one;
        }
        let g = g2.sqrt();
        (g, eta2_minus_1 / (g + c))
    } else {
        let g = eta * (one - sin2_theta_i / eta / eta).sqrt();
        (g, g - c)
    };
    // (g − c)/(g + c): the s-polarised amplitude ratio, up to sign.
    let r_s = g_minus_c / (g + c);
    // (c(g+c) − 1)/(c(g−c) + 1): the ratio of the p- to the s-polarised amplitude, up to sign.
    // The denominator is > 0: c > 0 here, and sin²θᵢ > 0 because c < 1.
    let cg = c * g;
    let p_over_s = (cg - sin2_theta_i) / (cg + sin2_theta_i);
    (half * r_s * r_s * (one + p_over_s * p_over_s)).min(one)
}

/// Schlick's (1994) approximation of the unpolarised Fresnel reflectance:
/// F ≈ F₀ + (1 − F₀)(1 − cos θ)⁵ with F₀ = ((η − 1)/(η + 1))², the reflectance at normal
/// incidence.
///
/// The cosine in the fifth power is the one on the optically thinner side of the interface:
/// cos θᵢ when η ≥ 1, and the transmitted cos θₜ = sqrt(1 − sin²θᵢ/η²) when η < 1, which is the
/// usual way to use Schlick's formula from inside the denser medium (F₀ is the same for η and
/// 1/η; evaluating with cos θᵢ there would ignore the critical angle). Beyond the critical
/// angle the result is exactly 1, and it is continuous there (cos θₜ → 0 gives F → 1).
///
/// The conventions on c (sign, clamp) and the special values are those of [`fresnel_exact`]:
/// η = 1 gives 0 (the literal formula would give (1 − c)⁵, a reflection from no interface),
/// η ≤ 0 and η = +∞ give 1, NaN propagates.
pub fn fresnel_schlick<T: Float>(cos_theta_i: T, eta: T) -> T {
    let one = T::one();
    let (c, eta) = match orient(cos_theta_i, eta) {
        Ok(oriented) => oriented,
        Err(special) => return special,
    };
    let cos_theta = if eta > one {
        c
    } else {
        // Divided by η twice rather than by η²: η² underflows to 0 for tiny η (0/0 at c = 1).
        let sin2_theta_t = (one - c) * (one + c) / eta / eta;
        if sin2_theta_t >= one {
            return one;
        }
        (one - sin2_theta_t).sqrt()
    };
    let r0 = (eta - one) / (eta + one);
    let f0 = r0 * r0;
    f0 + (one - f0) * (one - cos_theta).powi(5)
}

/// The reflectances of the two linear polarisations, from [`fresnel_dielectric_polarized`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolarizedReflectance {
    /// R_s = r_⊥²: electric field perpendicular to the plane of incidence ("s", TE).
    pub r_s: f64,
    /// R_p = r_∥²: electric field in the plane of incidence ("p", TM); 0 at Brewster's angle.
    pub r_p: f64,
}

impl PolarizedReflectance {
    /// The unpolarised reflectance, the mean of the two: (R_s + R_p)/2.
    pub fn unpolarized(&self) -> f64 {
        0.5 * (self.r_s + self.r_p)
    }
}

/// The s- and p-polarised Fresnel reflectances, computed the way pbrt-v4's `FrDielectric`
/// does, as a reference that is independent of eq. 2: Snell's law gives sin²θₜ = sin²θᵢ/η²,
/// then cos θₜ, then the amplitude coefficients
///
/// r_∥ = (η cos θᵢ − cos θₜ)/(η cos θᵢ + cos θₜ),  r_⊥ = (cos θᵢ − η cos θₜ)/(cos θᵢ + η cos θₜ).
///
/// Same conventions as [`fresnel_exact`] for c (clamped to [−1, 1]; c < 0 flips the
/// interface). Total internal reflection (sin²θₜ ≥ 1) gives R_s = R_p = 1. This form is not
/// rearranged for accuracy: near η = 1 both numerators cancel, so its relative accuracy there is
/// about ε/|η − 1| (2e-11 for η = 1.00001 in f64), which is ample for a reference used at
/// 1e-6. Meant for 0 < η < ∞; other η are not given a meaning.
pub fn fresnel_dielectric_polarized(cos_theta_i: f64, eta: f64) -> PolarizedReflectance {
    let mut cos_theta_i = cos_theta_i.clamp(-1.0, 1.0);
    let mut eta = eta;
    if cos_theta_i < 0.0 {
        eta = 1.0 / eta;
        cos_theta_i = -cos_theta_i;
    }
    let sin2_theta_i = 1.0 - cos_theta_i * cos_theta_i;
    let sin2_theta_t = sin2_theta_i / (eta * eta);
    if sin2_theta_t >= 1.0 {
        return PolarizedReflectance { r_s: 1.0, r_p: 1.0 };
    }
    // sin²θₜ < 1 here, so the argument is positive; max(0) is not needed.
    let cos_theta_t = (1.0 - sin2_theta_t).sqrt();
    let r_parl = (eta * cos_theta_i - cos_theta_t) / (eta * cos_theta_i + cos_theta_t);
    let r_perp = (cos_theta_i - eta * cos_theta_t) / (cos_theta_i + eta * cos_theta_t);
    PolarizedReflectance { r_s: r_perp * r_perp, r_p: r_parl * r_parl }
}

/// The unpolarised Fresnel reflectance from the s/p formulation
/// ([`fresnel_dielectric_polarized`]): (R_s + R_p)/2. The independent reference for
/// [`fresnel_exact`].
pub fn fresnel_dielectric_sp(cos_theta_i: f64, eta: f64) -> f64 {
    fresnel_dielectric_polarized(cos_theta_i, eta).unpolarized()
}

/// Brewster's angle θ_B = atan η, in radians: the angle of incidence at which the
/// p-polarised reflectance vanishes (the reflected and transmitted rays are perpendicular).
/// Exists on both sides of an interface (η and 1/η give complementary angles). Meaningful for
/// η > 0; other values are returned as atan gives them.
pub fn brewster_angle(eta: f64) -> f64 {
    eta.atan()
}

/// The critical angle θ_c = asin η in radians, beyond which light is totally internally
/// reflected; it exists only when the far side is optically thinner, 0 < η < 1. `None` for
/// η ≥ 1 (no total internal reflection), for η ≤ 0 and for NaN.
pub fn critical_angle(eta: f64) -> Option<f64> {
    (eta > 0.0 && eta < 1.0).then(|| eta.asin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_is_f0() {
        for eta in [1.333_f64, 1.5, 2.5, 1.0 / 1.333] {
            let r = (eta - 1.0) / (eta + 1.0);
            assert_eq!(fresnel_exact(1.0, eta), r * r);
            assert!((fresnel_dielectric_sp(1.0, eta) - r * r).abs() < 1e-16);
        }
    }

    #[test]
    fn special_values() {
        assert_eq!(fresnel_exact(0.0_f64, 1.333), 1.0);
        assert_eq!(fresnel_exact(0.0_f32, 1.333), 1.0);
        assert_eq!(fresnel_exact(0.0_f64, 1.0), 0.0);
        assert_eq!(fresnel_exact(0.7_f64, 1.0), 0.0);
        assert_eq!(fresnel_exact(0.7_f64, 0.0), 1.0);
        assert_eq!(fresnel_exact(0.7_f64, -1.5), 1.0);
        assert_eq!(fresnel_exact(0.7_f64, f64::INFINITY), 1.0);
        assert_eq!(fresnel_exact(-1.0_f64, f64::INFINITY), 1.0);
        assert!(fresnel_exact(f64::NAN, 1.333).is_nan());
        assert!(fresnel_exact(0.5, f32::NAN).is_nan());
        assert!(fresnel_schlick(f64::NAN, 1.333).is_nan());
        assert_eq!(fresnel_schlick(0.3_f64, 1.0), 0.0);
        assert_eq!(critical_angle(1.0), None);
        assert_eq!(critical_angle(0.0), None);
        assert_eq!(critical_angle(0.5), Some(0.5_f64.asin()));
    }

    #[test]
    fn huge_and_tiny_eta_stay_finite() {
        for eta in [1e-30_f64, 1e-300, 5e-324, 1e30, 1e300, f64::MAX] {
            for c in [-1.0, -0.5, -1e-300, 0.0, 1e-300, 0.3, 0.999_999, 1.0] {
                let f = fresnel_exact(c, eta);
                assert!((0.0..=1.0).contains(&f), "F({c}, {eta}) = {f}");
            }
        }
        for eta in [1e-30_f32, 1e-45, 1e30, f32::MAX] {
            for c in [-1.0_f32, -0.5, 0.0, 0.3, 0.999_999, 1.0] {
                let f = fresnel_exact(c, eta);
                assert!((0.0..=1.0).contains(&f), "F({c}, {eta}) = {f}");
            }
        }
    }
}

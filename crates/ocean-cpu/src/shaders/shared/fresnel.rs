//! Mirror of `shaders/shared/fresnel.wgsl`: eq. 2 in f32, over any [`Real`].

use crate::envelope::{Real, choose};

/// `fresnel_exact(cos_theta_i, eta)`: eq. 2 for cos θ_i clamped to [0, 1] and η > 0, as the WGSL
/// writes out ocean-core's `fresnel::fresnel_exact` (same branches, same order). A NaN argument
/// gives NaN, as ocean-core's does (WGSL leaves it undefined).
pub fn fresnel_exact(cos_theta_i: f32, eta: f32) -> f32 {
    if cos_theta_i.is_nan() || eta.is_nan() {
        return f32::NAN;
    }
    fresnel_exact_r(cos_theta_i, eta)
}

/// [`fresnel_exact`] over any [`Real`]: each branch the bounds cannot decide is taken both ways.
pub fn fresnel_exact_r<R: Real>(cos_theta_i: R, eta: R) -> R {
    let l = R::lit;
    let (zero, one) = (l(0.0), l(1.0));
    let c = cos_theta_i.clamp(zero, one);
    choose(
        eta.eq(one),
        || zero,
        || {
            choose(
                c.eq(zero),
                || one,
                || {
                    choose(
                        c.eq(one),
                        || {
                            let r = (eta - one) / (eta + one);
                            r * r
                        },
                        || oblique(c, eta),
                    )
                },
            )
        },
    )
}

/// Eq. 2 for 0 < c < 1: the stable form for η ≤ 2 (total internal reflection where g² < 0),
/// the direct one above.
fn oblique<R: Real>(c: R, eta: R) -> R {
    let l = R::lit;
    let one = l(1.0);
    let sin2_theta_i = (one - c) * (one + c);
    let tail = |g: R, g_minus_c: R| {
        let r_s = g_minus_c / (g + c);
        let cg = c * g;
        let p_over_s = (cg - sin2_theta_i) / (cg + sin2_theta_i);
        (l(0.5) * r_s * r_s * (one + p_over_s * p_over_s)).min(one)
    };
    choose(
        eta.le(l(2.0)),
        || {
            let eta2_minus_1 = (eta - one) * (eta + one);
            let g2 = eta2_minus_1 + c * c;
            choose(
                g2.lt(l(0.0)),
                || one,
                || {
                    let g = g2.sqrt();
                    tail(g, eta2_minus_1 / (g + c))
                },
            )
        },
        || {
            let g = eta * (one - sin2_theta_i / eta / eta).sqrt();
            tail(g, g - c)
        },
    )
}

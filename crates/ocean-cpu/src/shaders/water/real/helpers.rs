//! `water.wgsl`'s small functions over [`Real`] that the stage and its shading techniques
//! share: the normal CDF, integer powers, the LOD's log2, and the filtered reflection (the
//! Fresnel term, the sun's lobe and the sky over the footprint's slope variance). The f32
//! mirror ([`crate::shaders::water`]) calls these at `f32`.

use ocean_core::frame::FrameUniforms;

use super::inputs::{Inputs, Tex};
use crate::envelope::{Real, choose, choose_n, dot3};
use crate::shaders::shared::optics::exp_arith_r;

/// `normal_cdf(a)`.
pub fn normal_cdf<R: Real>(a: R) -> R {
    let l = R::lit;
    let x = a.abs() * l(std::f32::consts::FRAC_1_SQRT_2);
    let t = l(1.0) / (l(1.0) + l(0.327_591_1) * x);
    let poly = ((((l(1.061_405_4) * t - l(1.453_152)) * t + l(1.421_413_8)) * t - l(0.284_496_74))
        * t
        + l(0.254_829_6))
        * t;
    let erf = l(1.0) - poly * exp_arith_r(-(x.sq()));
    choose(a.lt(l(0.0)), || l(0.5) - l(0.5) * erf, || l(0.5) + l(0.5) * erf)
}

/// `pow_int(x, n)`.
pub fn pow_int<R: Real>(x: R, n: u32) -> R {
    let mut result = R::lit(1.0);
    let mut base = x;
    let mut e = n;
    loop {
        if e & 1 == 1 {
            result = result * base;
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        base = base.sq();
    }
    result
}

/// `lod_log2(x)` for x > 0: each binade x may lie in, united.
pub fn lod_log2<R: Real>(x: R) -> R {
    let l = R::lit;
    let at = |e: i32, fract: R| {
        let m = fract * l(2.0) - l(1.0);
        l((e - 1) as f32) + m * (l(1.442_544_9) + m * (l(-0.718_145_2) + m * l(0.275_600_3)))
    };
    match x.frexp_cases() {
        Some([Some((e, f)), None]) => at(e, f),
        Some([Some((e0, f0)), Some((e1, f1))]) => at(e0, f0).hull(at(e1, f1)),
        _ => l(f32::NEG_INFINITY).hull(l(f32::INFINITY)),
    }
}

/// `subtexel(lod)`.
pub fn subtexel<R: Real>(lod: R) -> R {
    let l = R::lit;
    choose(l(0.0).le(lod), || l(1.0), || exp_arith_r(lod * l(2.0 * std::f32::consts::LN_2)))
}

/// `unit(v)`.
pub(super) fn unit<R: Real>(v: [R; 3]) -> [R; 3] {
    let len = (v[0].sq() + v[1].sq() + v[2].sq()).sqrt();
    v.map(|c| c / len)
}

/// `grazing_square_axis(a, b)`.
pub fn grazing_square_axis<R: Real>(a: R, b: R) -> R {
    let l = R::lit;
    let s2 = l(std::f32::consts::SQRT_2);
    let plus = (s2 + a - b) * (s2 + a + b);
    let minus = (s2 - a - b) * (s2 - a + b);
    l(0.5) * (plus.max(l(0.0)).sqrt() - minus.max(l(0.0)).sqrt())
}

/// `fresnel_st(u_bumped)`.
pub(super) fn fresnel_st<R: Real>(u: [R; 2], frame: &FrameUniforms) -> [R; 2] {
    let l = R::lit;
    let (x, y) = (u[0], u[1]);
    let r2 = x.sq() + y.sq();
    let z = (l(1.0) - r2).max(l(0.0)).sqrt();
    let den = (l(1.0) + z).sqrt().max(r2.sqrt());
    let d = [x / den, y / den];
    let a = [grazing_square_axis(d[0], d[1]), grazing_square_axis(d[1], d[0])];
    a.map(|c| c * l(frame.hu.fresnel_scale) + l(0.5))
}

/// `fresnel_filtered(u_bumped, variance)`.
pub(super) fn fresnel_filtered<R: Real>(u: [R; 2], variance: R, inp: &Inputs<'_, R>) -> R {
    let l = R::lit;
    let far = &inp.frame.far;
    let r = (u[0].sq() + u[1].sq()).sqrt();
    let t = (variance.sqrt() * l(far.inv_sigma_max)).sqrt();
    let uv = [
        r * l(far.filter_r_scale) + l(far.filter_r_offset),
        t * l(far.filter_t_scale) + l(far.filter_t_offset),
    ];
    (inp.sample)(Tex::FresnelFilter, uv, l(0.0))[0].clamp(l(0.0), l(1.0))
}

/// `lobe_side(ur, c, v, a)`.
pub(super) fn lobe_side<R: Real>(ur: R, c: R, v: R, a: R) -> [R; 3] {
    let l = R::lit;
    let d = ur - c;
    let m = (ur * a + c * v) / (a + v);
    let w = (v * a / (v + a)).sqrt().max(l(1e-30));
    [(a / (a + v)).sqrt() * exp_arith_r(l(-0.5) * d.sq() / (a + v)), m, w]
}

/// `sun_lobe_filtered(u, variance)`.
pub(super) fn sun_lobe_filtered<R: Real>(u: [R; 2], variance: R, frame: &FrameUniforms) -> R {
    let l = R::lit;
    let far = &frame.far;
    let sun = frame.sun.direction;
    let rh = [-l(sun[0]), -l(sun[2])];
    let len = (rh[0].sq() + rh[1].sq()).sqrt();
    let rho = choose_n(
        l(1e-6).lt(len),
        || {
            let inv = l(1.0) / len;
            [rh[0] * inv, rh[1] * inv]
        },
        || [l(1.0), l(0.0)],
    );
    let ur = u[0] * rho[0] + u[1] * rho[1];
    let ut = u[1] * rho[0] - u[0] * rho[1];
    let v = variance;
    let at = l(far.sun_tangential);
    let across = (at / (at + v)).sqrt() * exp_arith_r(l(-0.5) * ut.sq() / (at + v));
    let beyond = l(far.sun_rim) * normal_cdf((ur - l(1.0)) / v.sqrt());
    let c = l(far.sun_centre);
    let above = lobe_side(ur, c, v, l(far.sun_above));
    let below = lobe_side(ur, c, v, l(far.sun_below));
    let p_above = above[0] * normal_cdf((c - above[1]) / above[2]);
    let p_below = below[0]
        * (normal_cdf((l(1.0) - below[1]) / below[2]) - normal_cdf((c - below[1]) / below[2]));
    across * (beyond + p_above + p_below)
}

/// `reflect`ed sky along `n` seen along `view`: sky_radiance(unit(r + (0, 1e-6, 0))) with
/// r = n·2(v·n) − v, r.y ≥ 0.
pub(super) fn sky_reflected<R: Real>(view: [R; 3], n: [R; 3], inp: &Inputs<'_, R>) -> [R; 3] {
    let l = R::lit;
    let vn = dot3(view, n);
    let mut r: [R; 3] = std::array::from_fn(|c| n[c] * (l(2.0) * vn) - view[c]);
    r[1] = r[1].max(l(0.0));
    (inp.sky)(unit([r[0] + l(0.0), r[1] + l(1e-6), r[2] + l(0.0)]))
}

/// `sky_filtered(view, slopes, variance)`.
pub(super) fn sky_filtered<R: Real>(
    view: [R; 3],
    slopes: [R; 3],
    variance: R,
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let sigma = variance.sqrt();
    let mut sum_fl = [l(0.0); 3];
    let mut sum_f = l(0.0);
    let mut skies = [[l(0.0); 3]; 4];
    let mut fs = [l(0.0); 4];
    for (i, (slot, f_slot)) in skies.iter_mut().zip(fs.iter_mut()).enumerate() {
        let mut o = [l(0.0); 2];
        match i {
            0 => o[0] = sigma,
            1 => o[0] = -sigma,
            2 => o[1] = sigma,
            _ => o[1] = -sigma,
        }
        let ni = unit([-(slopes[0] + o[0]), l(1.0), -(slopes[1] + o[1])]);
        let st = fresnel_st([view[0] - ni[0], view[2] - ni[2]], inp.frame);
        let fi = (inp.sample)(Tex::FresnelAbove, st, l(0.0))[3];
        let sky = sky_reflected(view, ni, inp);
        *slot = sky;
        *f_slot = fi;
        sum_fl = std::array::from_fn(|c| sum_fl[c] + sky[c] * fi);
        sum_f = sum_f + fi;
    }
    let den = sum_f.max(l(1e-30));
    let out = sum_fl.map(|c| c / den);
    // The premise: every weight ≥ 0, and the divisor Σfᵢ itself (not its floor 1e-30).
    if !R::INTERVAL || fs.iter().any(|f| f.least() < 0.0) || sum_f.least() < f64::from(1e-30f32) {
        return out;
    }
    // Σ fᵢLᵢ / Σ fᵢ with every fᵢ > 0 is a convex combination of the Lᵢ: between the least
    // and the greatest, but for the rounding of its 4 products, 3 sums and one division
    // (allowed 16 ULP of the greatest).
    std::array::from_fn(|c| {
        let (lo, hi) = skies.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
            (a.min(s[c].least()), b.max(s[c].most()))
        });
        let slack = 16.0 * crate::envelope::f32_ulp(lo.abs().max(hi.abs()));
        out[c].within(lo - slack, hi + slack)
    })
}

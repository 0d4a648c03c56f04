//! `shaders/water.wgsl` over any [`Real`], for the techniques the envelope carries
//! ([`carried`]): waves `fft` (with eq. 1's scales), `gerstner` and `coastal`; surfaces
//! `hu_patches`, `projected_grid`, `shore_grid` and `clipmap` (not under waves `coastal`); far
//! fields `none`, `mip` and `variance`; shadings `hu`, `ggx` (with its detail map), `chiu` and
//! `coastal` (`real::shading`); every foam (`real::foam`); the terrain's wave damping. At `f32`
//! it is the exact mirror's arithmetic, operation for operation (a test holds the two to the
//! bit); over [`crate::envelope::Iv`] or [`crate::envelope::Af`] the envelope's, over
//! [`crate::envelope::Jitter`] one random conformant GPU's.
//!
//! Every texture read goes through [`Inputs::sample`] (the envelope reads the GPU's own
//! inputs through the filter's envelope), the environment through [`Inputs::sky`]. A
//! comparison the bounds cannot decide takes both branches; inside a branch what its
//! condition says of a value is kept ([`Real::at_least`]): the filtered BRDF's variance is
//! positive there, and the visible facets' spread is at least 10⁻⁴ of their mean.

pub mod clipmap;
mod coastal;
mod floor;
mod foam;
pub mod helpers;
mod inputs;
mod shading;

pub use foam::Foam;
pub use inputs::{Inputs, Tex, Varyings};

use helpers::{fresnel_st, lod_log2, normal_cdf, subtexel, unit};
use inputs::LEAST_POSITIVE;
use ocean_core::switch::SWITCH_ON;

use ocean_core::far_field::{FAR_NONE, FAR_VARIANCE};
use ocean_core::foam::FOAM_NONE;
use ocean_core::frame::FrameUniforms;

use crate::envelope::{Cond, Real, choose_n, dot3, mat4_mul_vec4};
use crate::shaders::shared::gerstner::gerstner_cis_r;
use crate::shaders::shared::optics::exp_arith_r;
use crate::shaders::shared::trig::{TAU, cis_reduced_r};

/// The shading techniques (`technique/shading`'s `shade_above`): the envelope carries each.
pub use ocean_core::plan::Shading;

/// Why the stage's configuration is not carried over [`Real`] yet (`None`: it is): every
/// shading and foam technique is, on every surface but waves `coastal` on a clipmap.
pub fn carried(frame: &FrameUniforms) -> Option<&'static str> {
    if frame.coastal.shape[0] == SWITCH_ON && frame.clip.vertex_count() > 0 {
        return Some("the water pass's envelope does not carry waves `coastal` on a clipmap");
    }
    None
}

/// `water_vertex(pos, mesh_weight)` under waves `fft`: the clip position and the varyings.
pub fn water_vertex<R: Real>(
    pos: [R; 2],
    mesh_weight: R,
    inp: &Inputs<'_, R>,
) -> ([R; 4], Varyings<R>) {
    let l = R::lit;
    let f = inp.frame;
    let uv = map_uvs(pos, f);
    let off = f.tiling.mesh_offset;
    let plane = [pos[0] + l(off[0]), pos[1] + l(off[1])];
    let weight = mesh_weight * floor::shore_weight(plane[0], plane[1], f.terrain.top[2], inp);
    if f.coastal.shape[0] == SWITCH_ON {
        // Waves `coastal`: their height at the vertex, faded to the screen grids' spacing.
        let sp = coastal::grid_spacing(pos, f);
        let z = l(0.0);
        let h = coastal::wave(pos, [sp[0], sp[1]], [z, z], [sp[2], sp[3]], inp)[0] * weight;
        return displaced_vertex(pos, [z, h, z, z], uv, weight, f);
    }
    let d = if f.gerstner.count > 0.0 {
        // Waves `gerstner`: the sum of the waves at the vertex, no maps to fetch.
        gerstner_displacement(pos, f).map(|c| c * weight)
    } else {
        let s = if f.scales.count > 0.0 {
            multi_scale_displacement(pos, inp)
        } else {
            (inp.sample)(Tex::Displacement, uv[0], l(0.0))
        };
        s.map(|c| c * (weight * l(f.passes.waves)))
    };
    displaced_vertex(pos, d, uv, weight, f)
}

/// `map_uvs(pos)`: the displacement and bump maps' (u, v) at `pos`.
fn map_uvs<R: Real>(pos: [R; 2], f: &FrameUniforms) -> [[R; 2]; 2] {
    let l = R::lit;
    let t = &f.tiling;
    let uv_d = [0, 1].map(|c| {
        (pos[c] + l(t.displacement_origin[c])) * l(t.inv_displacement_size)
            + l(t.displacement_half_texel)
    });
    let uv_b =
        [0, 1].map(|c| (pos[c] + l(t.bump_origin[c])) * l(t.inv_bump_size) + l(t.bump_half_texel));
    [uv_d, uv_b]
}

/// `displaced_vertex(pos, d, uv, weight)`: the vertex at `pos` moved by `d`, its clip position
/// and varyings.
fn displaced_vertex<R: Real>(
    pos: [R; 2],
    d: [R; 4],
    [uv_d, uv_b]: [[R; 2]; 2],
    weight: R,
    f: &FrameUniforms,
) -> ([R; 4], Varyings<R>) {
    let l = R::lit;
    let off = f.tiling.mesh_offset;
    let plane = [pos[0] + l(off[0]), pos[1] + l(off[1])];
    let rel = [plane[0] + d[0], d[1] - l(f.view.eye_height), plane[1] + d[2]];
    let clip = mat4_mul_vec4(&f.view.view_proj, [rel[0], rel[1], rel[2], l(1.0)]);
    (clip, [rel[0], rel[1], rel[2], uv_d[0], uv_d[1], uv_b[0], uv_b[1], weight, pos[0], pos[1]])
}

/// `vs_projected_grid` of surface `projected_grid` (not `shore_grid`) at the grid's lattice
/// point (i, j) = (quad % cols + di, quad / cols + dj): every vertex index naming that point
/// computes the same values from the same integers.
pub fn grid_vertex<R: Real>(i: u32, j: u32, inp: &Inputs<'_, R>) -> ([R; 4], Varyings<R>) {
    let l = R::lit;
    let g = &inp.frame.grid;
    if g.shore > 0.0 {
        // Surface `shore_grid`: rows at growing distances ahead of the eye.
        return water_vertex(coastal::shore_point(i, j, inp.frame), l(1.0), inp);
    }
    // The weights' complements from the integers (`vs_projected_grid` says why).
    let u = l(i as f32) / l(g.cols);
    let v = l(j as f32) / l(g.rows);
    let u1 = l((g.cols as u32 - i) as f32) / l(g.cols);
    let v1 = l((g.rows as u32 - j) as f32) / l(g.rows);
    let c = g.corners;
    let h: [R; 4] = std::array::from_fn(|k| {
        (l(c[0][k]) * u1 + l(c[1][k]) * u) * v1 + (l(c[2][k]) * u1 + l(c[3][k]) * u) * v
    });
    let inv_w = l(1.0) / h[3];
    let off = inp.frame.tiling.mesh_offset;
    water_vertex([h[0] * inv_w - l(off[0]), h[2] * inv_w - l(off[1])], l(1.0), inp)
}

/// `Footprint` with its number of taps decided (`taps_log2`).
#[derive(Clone, Copy, Debug)]
pub struct Footprint<R> {
    /// LODs on the displacement map (0) and the bump map (1).
    pub lods: [R; 2],
    /// log2 of the number of taps: a whole number.
    pub taps_log2: f32,
    /// Metres between two taps (x, z).
    pub step: [R; 2],
    /// Unit horizontal direction towards the eye.
    pub h: [R; 2],
    /// |rel.y| / dist.
    pub vy: R,
    /// horizontal / dist.
    pub vh: R,
    /// The distance to the eye.
    pub dist: R,
    /// log2 of the footprint's length.
    pub l_long: R,
}

/// `footprint(rel)`: one footprint for each number of taps `ceil(l_long − l_short)` may give
/// (`None` past two).
pub fn footprints<R: Real>(rel: [R; 3], frame: &FrameUniforms) -> Option<Vec<Footprint<R>>> {
    let l = R::lit;
    let far = &frame.far;
    if far.mode == FAR_NONE {
        let z = l(0.0);
        return Some(vec![Footprint {
            lods: [z; 2],
            taps_log2: 0.0,
            step: [z; 2],
            h: [z; 2],
            vy: z,
            vh: z,
            dist: z,
            l_long: z,
        }]);
    }
    let dist = (rel[0].sq() + rel[1].sq() + rel[2].sq()).sqrt();
    let cos_view = rel[1].abs() / dist.max(l(1e-30));
    let short = (dist * l(far.pixel_angle)).clamp(l(1e-30), l(1e30));
    let long = (short / cos_view.max(l(1e-4))).clamp(l(1e-30), l(1e30));
    let l_short = lod_log2(short);
    let l_long = lod_log2(long);
    // ceil(x) = −floor(−x).
    let cases = (-(l_long - l_short)).floor_cases()?;
    let horizontal = (rel[0].sq() + rel[2].sq()).sqrt();
    let mut out = Vec::with_capacity(2);
    for (kf, _) in cases.into_iter().flatten() {
        let k = (-kf).clamp(0.0, far.max_aniso_log2);
        let lv = l_short.max(l_long - l(k)) + l(far.lod_bias);
        let spacing = long * l(crate::shaders::wgsl::ldexp(1.0, -(k as i32)));
        let sh = spacing / horizontal.max(l(1e-30));
        let inv_h = l(1.0) / horizontal.max(l(1e-30));
        out.push(Footprint {
            lods: [lv + l(far.lod_offset_d), lv + l(far.lod_offset_b)],
            taps_log2: k,
            step: [rel[0] * sh, rel[2] * sh],
            h: [-rel[0] * inv_h, -rel[2] * inv_h],
            vy: rel[1].abs() / dist.max(l(1e-30)),
            vh: horizontal / dist.max(l(1e-30)),
            dist,
            l_long,
        });
    }
    Some(out)
}

/// `mesh_share(fp)`.
pub fn mesh_share<R: Real>(fp: &Footprint<R>, frame: &FrameUniforms) -> R {
    let l = R::lit;
    let k = fp.taps_log2;
    if k <= 0.0 {
        return l(0.0);
    }
    let leg = (l(frame.far.mesh_leg_scale) * fp.dist).max(l(frame.far.mesh_leg_min));
    ((fp.l_long - lod_log2(leg).max(fp.l_long - l(k))) / l(k)).clamp(l(0.0), l(1.0))
}

/// `sample_footprint(chain, uv, step_uv, lod, taps_log2, h)`: (mean, along_sq), and the
/// taps' mean [`Inputs::spread_floor`] (the mean of the taps' E\[s²\] − E\[s\]² is at most
/// the mean's: the taps' own spread only adds).
fn sample_footprint<R: Real>(
    inp: &Inputs<'_, R>,
    chain: Tex,
    uv: [R; 2],
    step_uv: [R; 2],
    lod: R,
    taps_log2: f32,
    h: [R; 2],
) -> ([R; 4], R, [f64; 2]) {
    let l = R::lit;
    let n = crate::shaders::wgsl::ldexp(1.0, taps_log2 as i32);
    let centre = 0.5 * (n - 1.0);
    let mut partial = [[l(0.0); 4]; 5];
    let mut sq_partial = [l(0.0); 5];
    let mut floor = [0.0f64; 2];
    let mut i = 0.0f32;
    while i < n {
        let at = [0, 1].map(|c| uv[c] + step_uv[c] * l(i - centre));
        let f = (inp.spread_floor)(chain, at, lod);
        floor = [floor[0] + f[0] / f64::from(n), floor[1] + f[1] / f64::from(n)];
        let mut t = (inp.sample)(chain, at, lod);
        let a = t[0] * h[0] + t[1] * h[1];
        let mut q = a.sq();
        let mut carry = i as u32;
        let mut j = 0;
        while carry & 1 == 1 {
            t = std::array::from_fn(|c| partial[j][c] + t[c]);
            q = q + sq_partial[j];
            carry >>= 1;
            j += 1;
        }
        partial[j] = t;
        sq_partial[j] = q;
        i += 1.0;
    }
    let k = taps_log2 as usize;
    let inv = l(crate::shaders::wgsl::ldexp(1.0, -(taps_log2 as i32)));
    (partial[k].map(|c| c * inv), sq_partial[k] * inv, floor)
}

/// `multi_scale_displacement(pos)`: eq. 1's Σ_i a_i·D at the scales' points.
fn multi_scale_displacement<R: Real>(pos: [R; 2], inp: &Inputs<'_, R>) -> [R; 4] {
    let l = R::lit;
    let m = &inp.frame.scales;
    let mut sum = [l(0.0); 4];
    for i in 0..m.count as usize {
        let uv = scale_uv(pos, i, inp.frame);
        let t = (inp.sample)(Tex::Displacement, uv, l(0.0));
        sum = std::array::from_fn(|c| sum[c] + t[c] * l(m.weight[i]));
    }
    sum
}

/// Scale `i`'s point in the displacement map (`multi_scale_*`'s `uv`).
fn scale_uv<R: Real>(pos: [R; 2], i: usize, frame: &FrameUniforms) -> [R; 2] {
    let l = R::lit;
    let m = &frame.scales;
    let origin = [m.origin_x[i], m.origin_z[i]];
    [0, 1].map(|c| {
        (pos[c] + l(origin[c])) * l(m.inv_size[i]) + l(frame.tiling.displacement_half_texel)
    })
}

/// `multi_scale_taps(pos, fp, h)`: the slope chain's taps summed over eq. 1's scales. Its
/// spread has cross terms between the scales, so no floor is known for it (−∞).
fn multi_scale_taps<R: Real>(
    pos: [R; 2],
    fp: &Footprint<R>,
    h: [R; 2],
    inp: &Inputs<'_, R>,
) -> ([R; 4], R, [f64; 2]) {
    let l = R::lit;
    let frame = inp.frame;
    let m = &frame.scales;
    let mut mean = [l(0.0); 4];
    let mut along_sq = l(0.0);
    for i in 0..m.count as usize {
        let uv = scale_uv(pos, i, frame);
        let step = fp.step.map(|c| c * l(m.inv_size[i]));
        let lod = fp.lods[0] + l(m.lod_offset[i]);
        let (t, t_sq, _) =
            sample_footprint(inp, Tex::DisplacementSlopes, uv, step, lod, fp.taps_log2, h);
        let c = l(m.weight[i]) * (l(m.inv_size[i]) / l(frame.tiling.inv_displacement_size));
        let c2 = c * c;
        mean = [mean[0] + t[0] * c, mean[1] + t[1] * c, mean[2] + t[2] * c2, mean[3] + t[3] * c2];
        along_sq = along_sq + t_sq * c2;
    }
    (mean, along_sq, [f64::NEG_INFINITY; 2])
}

/// `visible_slopes(mu, var_geo, vy, vh)`.
fn visible_slopes<R: Real>(mu: R, var_geo: R, vy: R, vh: R) -> [R; 2] {
    use crate::shaders::water::{VISIBLE_A_MAX, VISIBLE_A_MIN};
    let l = R::lit;
    let mt = vy - vh * mu;
    let st = vh * var_geo.sqrt();
    let skip = st.le(l(0.0)).or((l(VISIBLE_A_MAX) * st).le(mt));
    choose_n(
        skip,
        || [mu, var_geo],
        || {
            // Here st > 0 and 10⁴·st > mt (rounded): st is at least mt's least / 10⁴.
            let bound = mt.least() / (f64::from(VISIBLE_A_MAX) * (1.0 + 1e-6));
            let st = st.at_least(bound.max(LEAST_POSITIVE));
            let a = (mt / st).max(l(VISIBLE_A_MIN));
            let pdf = l(0.398_942_3) * exp_arith_r(l(-0.5) * a.sq());
            let cdf = normal_cdf(a);
            let w0 = a * cdf + pdf;
            let mean_u = cdf / w0;
            let var_u = ((a * cdf + l(2.0) * pdf) / w0 - mean_u.sq()).max(l(0.0));
            let out = [(vy - st * (a + mean_u)) / vh, var_u * (st.sq()) / (vh.sq())];
            if R::INTERVAL { visible_bounds(out, mu, mt, st, vy, vh) } else { out }
        },
    )
}

/// [`visible_slopes`]' branch over intervals, cut to what its exact value is known to be:
/// with mt > 0 (a = mt/st > 0, unclamped), (vy − st(a + mean_u))/vh = mu − g/vh with
/// g = st·mean_u(mt/st) ≥ 0, increasing in st and decreasing in mt (mean_u = Φ/(aΦ + φ)
/// decreases in a), so g lies between its values at two corners; and var_u ∈ [0, 1].
/// Interval arithmetic alone loses that st·a = mt (its bound on st·a grows as 1/st.lo).
/// The rounding of the branch's ~30 operations is allowed 2⁻¹⁴ of its terms' magnitudes
/// (an assumption, generous against f32's 2⁻²⁴ an operation).
fn visible_bounds<R: Real>(out: [R; 2], mu: R, mt: R, st: R, vy: R, vh: R) -> [R; 2] {
    let (st_lo, st_hi, mt_lo, mt_hi) = (st.least(), st.most(), mt.least(), mt.most());
    let (vh_lo, vh_hi) = (vh.least(), vh.most());
    if !(mt_lo > 0.0 && st_lo > 0.0 && vh_lo > 0.0 && st_hi.is_finite() && mt_hi.is_finite()) {
        return out;
    }
    let g = |st: f64, mt: f64| {
        let a = mt / st;
        let x = a * std::f64::consts::FRAC_1_SQRT_2;
        let t = 1.0 / (1.0 + 0.327_591_1 * x);
        let poly = ((((1.061_405_4 * t - 1.453_152) * t + 1.421_413_8) * t - 0.284_496_74) * t
            + 0.254_829_6)
            * t;
        let cdf = 0.5 + 0.5 * (1.0 - poly * (-(x * x)).exp());
        let pdf = 0.398_942_3 * (-0.5 * a * a).exp();
        st * cdf / (a * cdf + pdf)
    };
    let (g_lo, g_hi) = (g(st_lo, mt_hi), g(st_hi, mt_lo));
    let mu_m = mu.least().abs().max(mu.most().abs());
    let vy_m = vy.least().abs().max(vy.most().abs());
    let e = 2f64.powi(-14);
    let slack = e * ((vy_m + mt_hi + g_hi) / vh_lo + mu_m);
    let x = out[0].within(mu.least() - g_hi / vh_lo - slack, mu.most() - g_lo / vh_hi + slack);
    let y = out[1].within(0.0, st_hi * st_hi / (vh_lo * vh_lo) * (1.0 + e));
    [x, y]
}

/// `gerstner_displacement(pos)`.
fn gerstner_displacement<R: Real>(pos: [R; 2], frame: &FrameUniforms) -> [R; 4] {
    let l = R::lit;
    let mut d = [l(0.0); 4];
    for i in 0..frame.gerstner.count as usize {
        let cs = gerstner_cis_r(i, pos, frame);
        let (a, b) = (frame.gerstner.waves[2 * i], frame.gerstner.waves[2 * i + 1]);
        let w = [l(b[0]) * cs[0], l(a[3]) * cs[1], l(b[1]) * cs[0], l(0.0)];
        d = std::array::from_fn(|c| d[c] + w[c]);
    }
    d
}

/// The damping g = e^{−½((k·h)σ_long)² − ½((k·h⊥)σ_short)²} of a wave of wave vector
/// (kx, kz) over the footprint, and its share ½(1 − g⁴) + c²(g⁴ − g²) of the variance the
/// average removes (far field `variance`; 0 otherwise): the Gerstner waves' and the detail
/// map's common step.
fn damped<R: Real>(k: [R; 2], c: R, h: [R; 2], sigma: [R; 2], variance: bool) -> (R, R) {
    let l = R::lit;
    let k_long = (k[0] * h[0] + k[1] * h[1]) * sigma[0];
    let k_short = (k[1] * h[0] - k[0] * h[1]) * sigma[1];
    let g = exp_arith_r(l(-0.5) * (k_long.sq() + k_short.sq()));
    if !variance {
        return (g, l(0.0));
    }
    let g2 = g.sq();
    (g, l(0.5) * (l(1.0) - g2.sq()) + c.sq() * (g2.sq() - g2))
}

/// `gerstner_filtered_slopes(pos, fp, weight)`.
fn gerstner_filtered_slopes<R: Real>(
    pos: [R; 2],
    fp: &Footprint<R>,
    weight: R,
    frame: &FrameUniforms,
) -> [R; 3] {
    let l = R::lit;
    let short = fp.dist * l(frame.far.pixel_angle);
    let sigma = [l(0.5) * short / fp.vy.max(l(1e-4)), l(0.5) * short];
    let mut s = [l(0.0); 2];
    let mut variance = l(0.0);
    for i in 0..frame.gerstner.count as usize {
        let (a, b) = (frame.gerstner.waves[2 * i], frame.gerstner.waves[2 * i + 1]);
        let c = gerstner_cis_r(i, pos, frame)[0];
        let k = [l(TAU) * l(a[0]), l(TAU) * l(a[1])];
        let (g, v) = damped(k, c, fp.h, sigma, frame.far.mode == FAR_VARIANCE);
        let cg = c * g;
        s = [s[0] + l(b[2]) * cg, s[1] + l(b[3]) * cg];
        if frame.far.mode == FAR_VARIANCE {
            variance = variance + l(0.5) * (l(b[2]).sq() + l(b[3]).sq()) * v;
        }
    }
    [s[0] * weight, s[1] * weight, variance * weight.sq()]
}

/// `detail_slopes(pos, h, sigma_long, sigma_short)` (shared/detail.wgsl): shading `ggx`'s
/// detail normal map.
fn detail_slopes<R: Real>(pos: [R; 2], h: [R; 2], sigma: [R; 2], frame: &FrameUniforms) -> [R; 3] {
    let l = R::lit;
    let mut s = [l(0.0); 2];
    let mut variance = l(0.0);
    for w in &frame.detail.waves[..frame.detail.count as usize] {
        let terms = [l(w[0]) * pos[0], l(w[2]), l(w[1]) * pos[1]];
        let p = R::sum_as_written(&terms, |t| (t[0] + t[1]) + t[2]);
        let c = cis_reduced_r(p)[0];
        let k = [l(TAU) * l(w[0]), l(TAU) * l(w[1])];
        let (g, v) = damped(k, c, h, sigma, frame.far.mode == FAR_VARIANCE);
        let a = l(w[3]) * (c * g);
        s = [s[0] + l(w[0]) * a, s[1] + l(w[1]) * a];
        if frame.far.mode == FAR_VARIANCE {
            variance = variance + l(0.5) * l(w[3]).sq() * (l(w[0]).sq() + l(w[1]).sq()) * v;
        }
    }
    [s[0], s[1], variance]
}

/// `filtered_slopes(in)`: the waves' slopes plus shading `ggx`'s detail map over the same
/// footprint.
fn filtered_slopes<R: Real>(v: &Varyings<R>, fp: &Footprint<R>, inp: &Inputs<'_, R>) -> [R; 3] {
    let l = R::lit;
    let s = wave_slopes(v, fp, inp);
    let frame = inp.frame;
    if frame.detail.count <= 0.0 {
        return s;
    }
    let short = fp.dist * l(frame.far.pixel_angle);
    let sigma = [l(0.5) * short / fp.vy.max(l(1e-4)), l(0.5) * short];
    let d = detail_slopes([v[8], v[9]], fp.h, sigma, frame);
    [s[0] + d[0], s[1] + d[1], s[2] + d[2]]
}

/// `wave_slopes(in, fp)` under waves `fft` on one scale or `gerstner`: (s_x, s_z, variance).
fn wave_slopes<R: Real>(v: &Varyings<R>, fp: &Footprint<R>, inp: &Inputs<'_, R>) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    if frame.coastal.shape[0] == SWITCH_ON {
        // Waves `coastal`: their own slopes over the footprint (no variance from them).
        let short = fp.dist * l(frame.far.pixel_angle);
        let sigma = [l(0.5) * short / fp.vy.max(l(1e-4)), l(0.5) * short];
        let z = l(0.0);
        let w = coastal::wave([v[8], v[9]], fp.h, sigma, [z, z], inp);
        return [w[1] * v[7], w[2] * v[7], z];
    }
    if frame.gerstner.count > 0.0 {
        return gerstner_filtered_slopes([v[8], v[9]], fp, v[7], frame);
    }
    let t = &frame.tiling;
    let rel_y = v[1];
    let (uv_d, uv_b, weight) = ([v[3], v[4]], [v[5], v[6]], v[7]);
    let wd = weight * l(frame.passes.waves);
    let plane = [0, 1].map(|c| v[8 + c] + l(t.mesh_offset[c]));
    let wb =
        l(frame.passes.waves) * floor::shore_weight(plane[0], plane[1], frame.terrain.top[3], inp);
    let h = fp.h;
    let sd_uv = fp.step.map(|c| c * l(t.inv_displacement_size));
    let sb_uv = fp.step.map(|c| c * l(t.inv_bump_size));
    let (d, along_sq, d_floor) = if frame.scales.count > 0.0 {
        multi_scale_taps([v[8], v[9]], fp, h, inp)
    } else {
        sample_footprint(inp, Tex::DisplacementSlopes, uv_d, sd_uv, fp.lods[0], fp.taps_log2, h)
    };
    let (b, _, b_floor) =
        sample_footprint(inp, Tex::Bump, uv_b, sb_uv, fp.lods[1], fp.taps_log2, h);
    let sd = [d[0] * wd, d[1] * wd];
    let sb = [b[0] * wb, b[1] * wb];
    let s = [sd[0] + sb[0], sd[1] + sb[1]];
    if frame.far.mode != FAR_VARIANCE {
        return [s[0], s[1], l(0.0)];
    }
    let spread = |m: [R; 4], floor: [f64; 2]| {
        (m[2] - m[0].sq()).max(l(0.0)).at_least(floor[0])
            + (m[3] - m[1].sq()).max(l(0.0)).at_least(floor[1])
    };
    let vd = spread(d, d_floor) * subtexel(fp.lods[0]);
    let vb = spread(b, b_floor) * subtexel(fp.lods[1]);
    let variance = l(0.5) * (vd * (wd.sq()) + vb * (wb.sq()));
    choose_n(
        rel_y.lt(l(0.0)),
        || {
            let mu_raw = d[0] * h[0] + d[1] * h[1];
            let mu = mu_raw * wd;
            let var_geo = (along_sq - mu_raw.sq()).max(l(0.0)) * (wd.sq()) * mesh_share(fp, frame);
            let vis = visible_slopes(mu, var_geo, fp.vy, fp.vh);
            let shift = vis[0] - mu;
            [
                s[0] + h[0] * shift,
                s[1] + h[1] * shift,
                (variance + l(0.5) * (vis[1] - var_geo)).max(l(0.0)),
            ]
        },
        || [s[0], s[1], variance],
    )
}

/// `fs_main(in)` at the pixel whose centre is `frag` (x + ½, y + ½): the colour it writes
/// (before the target's storage), the union over the footprint's cases.
pub fn fs_main<R: Real>(frag: [f32; 2], v: &Varyings<R>, inp: &Inputs<'_, R>) -> [R; 4] {
    let l = R::lit;
    let full = [l(f32::NEG_INFINITY).hull(l(f32::INFINITY)); 4];
    let Some(fps) = footprints([v[0], v[1], v[2]], inp.frame) else { return full };
    let mut out: Option<[R; 4]> = None;
    for fp in &fps {
        let c = fragment(frag, v, fp, inp);
        out = Some(match out {
            None => c,
            Some(o) => std::array::from_fn(|i| o[i].hull(c[i])),
        });
    }
    out.unwrap_or(full)
}

/// [`fs_main`] for one footprint.
fn fragment<R: Real>(
    frag: [f32; 2],
    v: &Varyings<R>,
    fp: &Footprint<R>,
    inp: &Inputs<'_, R>,
) -> [R; 4] {
    let l = R::lit;
    let frame = inp.frame;
    let rel = [v[0], v[1], v[2]];
    let slopes = filtered_slopes(v, fp, inp);
    let n = unit([-slopes[0], l(1.0), -slopes[1]]);
    let view = unit(rel.map(|c| -c));
    let u_bumped = [view[0] - n[0], view[2] - n[2]];
    let ivs = frame.view.inv_viewport_size;
    let screen = [l(frag[0]) * l(ivs[0]), l(frag[1]) * l(ivs[1])];
    let c = choose_n(
        l(0.0).le(view[1]),
        || {
            let pos = [v[8], v[9]];
            let coastal = if frame.coastal.shape[0] == SWITCH_ON {
                let short = fp.dist * l(frame.far.pixel_angle);
                coastal::shore(pos, fp.h, [short / fp.vy.max(l(1e-4)), short], inp)
            } else {
                [l(0.0), l(0.0), l(1.0)]
            };
            let c = match inp.shading {
                Shading::Hu => shading::shade_above_hu(rel, slopes, n, view, u_bumped, screen, inp),
                Shading::Ggx => shading::shade_above_ggx(rel, slopes, n, view, screen, inp),
                Shading::Chiu => {
                    let depth = floor::floor_depth(rel, inp);
                    shading::shade_above_chiu(rel, n, view, screen, depth, inp)
                }
                Shading::Coastal => {
                    let p = shading::Point { n, view, u_bumped, screen, coastal };
                    shading::shade_above_coastal(rel, &p, inp)
                }
            };
            let mut cover = foam::coverage(v, slopes, inp);
            if frame.coastal.shape[0] == SWITCH_ON && frame.foam.mode != FOAM_NONE {
                cover = foam::shore_cover(cover, coastal[1], pos, frame);
            }
            foam::over(c, cover, n, rel, inp)
        },
        || {
            let st = fresnel_st(u_bumped, frame);
            let f = (inp.sample)(Tex::FresnelBelow, st, l(0.0))[3];
            let eta = l(frame.water.eta);
            let i = view.map(|c| -c);
            let cos_i = dot3(i, n);
            let k = l(1.0) - eta.sq() * (l(1.0) - cos_i.sq());
            let sky_t = choose_n(
                l(0.0).lt(k),
                || {
                    let s = k.at_least(LEAST_POSITIVE).sqrt() - eta * cos_i;
                    let t: [R; 3] = std::array::from_fn(|c| i[c] * eta + n[c] * s);
                    (inp.sky)(unit([t[0], t[1].max(l(0.0)) + l(1e-6), t[2]]))
                },
                || [l(0.0); 3],
            );
            std::array::from_fn(|c| l(frame.water.color[c]) * f + sky_t[c] * (l(1.0) - f))
        },
    );
    [c[0], c[1], c[2], l(1.0)]
}

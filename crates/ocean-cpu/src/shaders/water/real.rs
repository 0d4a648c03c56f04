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
mod shading;

pub use foam::Foam;

use ocean_core::far_field::{FAR_NONE, FAR_VARIANCE};
use ocean_core::foam::FOAM_NONE;
use ocean_core::frame::FrameUniforms;

use crate::envelope::{Cond, Real, choose, choose_n, dot3, mat4_mul_vec4};
use crate::shaders::shared::gerstner::gerstner_cis_r;
use crate::shaders::shared::optics::exp_arith_r;
use crate::shaders::shared::trig::{TAU, cis_reduced_r};

/// A texture the stage reads, as [`Inputs::sample`] names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tex {
    /// Binding 1, repeat.
    Displacement,
    /// Binding 2 (a chain under far fields `mip` and `variance`), repeat.
    DisplacementSlopes,
    /// Binding 3 (likewise), repeat.
    Bump,
    /// Binding 4, clamp.
    FresnelAbove,
    /// Binding 5, clamp.
    FresnelBelow,
    /// Binding 6, clamp.
    ReflectionMap,
    /// Binding 7, clamp.
    RefractionMap,
    /// Binding 11, clamp.
    FresnelFilter,
    /// `floor_map` (binding 12), clamp.
    FloorMap,
    /// Binding 13 (foam `accumulated`'s field), repeat.
    FoamField,
}

/// The shading techniques (`technique/shading`'s `shade_above`): the envelope carries each.
pub use ocean_core::plan::Shading;

/// What the stage reads, over a [`Real`].
pub struct Inputs<'a, R> {
    /// The frame's uniforms.
    pub frame: &'a FrameUniforms,
    /// The shading technique.
    pub shading: Shading,
    /// The foam technique.
    pub foam: Foam,
    /// `textureSampleLevel(texture, sampler, uv, lod)` with the texture's sampler.
    pub sample: &'a (dyn Fn(Tex, [R; 2], R) -> [R; 4] + Sync),
    /// For a slope chain's sample, the least t₂ − t₀² and t₃ − t₁² (E\[s²\] − E\[s\]² per
    /// axis) any conformant filter gives there (−∞ where nothing is known beyond `sample`:
    /// always, for a scalar), `crate::envelope::filter::spread_floor`.
    pub spread_floor: &'a (dyn Fn(Tex, [R; 2], R) -> [f64; 2] + Sync),
    /// The sky technique's `sky_radiance(sky, dir)`.
    pub sky: &'a (dyn Fn([R; 3]) -> [R; 3] + Sync),
    /// The shadow map's size.
    pub shadow_dims: [u32; 2],
    /// The shadow map's texel (x, y).
    pub occluder: &'a (dyn Fn(u32, u32) -> R + Sync),
}

/// Why the stage's configuration is not carried over [`Real`] yet (`None`: it is): every
/// shading and foam technique is, on every surface but waves `coastal` on a clipmap.
pub fn carried(frame: &FrameUniforms) -> Option<&'static str> {
    if frame.coastal.shape[0] > 0.0 && frame.clip.vertex_count() > 0 {
        return Some("the water pass's envelope does not carry waves `coastal` on a clipmap");
    }
    None
}

/// The varyings of `VertexOut` in declaration order: rel (3), uv_d (2), uv_b (2), weight,
/// pos (2).
pub type Varyings<R> = [R; 10];

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
    if f.coastal.shape[0] > 0.0 {
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
    let u = l(i as f32) / l(g.cols);
    let v = l(j as f32) / l(g.rows);
    let c = g.corners;
    let h: [R; 4] = std::array::from_fn(|k| {
        (l(c[0][k]) * (l(1.0) - u) + l(c[1][k]) * u) * (l(1.0) - v)
            + (l(c[2][k]) * (l(1.0) - u) + l(c[3][k]) * u) * v
    });
    let inv_w = l(1.0) / h[3];
    let off = inp.frame.tiling.mesh_offset;
    water_vertex([h[0] * inv_w - l(off[0]), h[2] * inv_w - l(off[1])], l(1.0), inp)
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

/// `subtexel(lod)`.
pub fn subtexel<R: Real>(lod: R) -> R {
    let l = R::lit;
    choose(l(0.0).le(lod), || l(1.0), || exp_arith_r(lod * l(2.0 * std::f32::consts::LN_2)))
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
    if frame.coastal.shape[0] > 0.0 {
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

/// `unit(v)`.
fn unit<R: Real>(v: [R; 3]) -> [R; 3] {
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
fn fresnel_st<R: Real>(u: [R; 2], frame: &FrameUniforms) -> [R; 2] {
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
fn fresnel_filtered<R: Real>(u: [R; 2], variance: R, inp: &Inputs<'_, R>) -> R {
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
fn lobe_side<R: Real>(ur: R, c: R, v: R, a: R) -> [R; 3] {
    let l = R::lit;
    let d = ur - c;
    let m = (ur * a + c * v) / (a + v);
    let w = (v * a / (v + a)).sqrt().max(l(1e-30));
    [(a / (a + v)).sqrt() * exp_arith_r(l(-0.5) * d.sq() / (a + v)), m, w]
}

/// `sun_lobe_filtered(u, variance)`.
fn sun_lobe_filtered<R: Real>(u: [R; 2], variance: R, frame: &FrameUniforms) -> R {
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
fn sky_reflected<R: Real>(view: [R; 3], n: [R; 3], inp: &Inputs<'_, R>) -> [R; 3] {
    let l = R::lit;
    let vn = dot3(view, n);
    let mut r: [R; 3] = std::array::from_fn(|c| n[c] * (l(2.0) * vn) - view[c]);
    r[1] = r[1].max(l(0.0));
    (inp.sky)(unit([r[0] + l(0.0), r[1] + l(1e-6), r[2] + l(0.0)]))
}

/// `sky_filtered(view, slopes, variance)`.
fn sky_filtered<R: Real>(view: [R; 3], slopes: [R; 3], variance: R, inp: &Inputs<'_, R>) -> [R; 3] {
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

/// The least positive f32 (a subnormal): what a positive value is at least.
const LEAST_POSITIVE: f64 = 1.401_298_464_324_817e-45;

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
            let coastal = if frame.coastal.shape[0] > 0.0 {
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
            if frame.coastal.shape[0] > 0.0 && frame.foam.mode != FOAM_NONE {
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

//! CPU mirror of `shaders/water.wgsl`: the sea surface (its shading from above is the
//! shading technique's, [`super::shading`]).

use ocean_core::far_field::{FAR_NONE, FAR_VARIANCE};
use ocean_core::foam::FOAM_NONE;
use ocean_core::frame::FrameUniforms;
use ocean_core::switch::SWITCH_ON;

mod clipmap;
pub mod envelope;
pub mod real;
pub use clipmap::vs_clipmap;

use super::shared::coastal::{coastal_shore, coastal_wave};
use super::shared::floor::shore_weight;
use super::shared::foam::{foam_mix, foam_over, foam_texture_at};
use super::shared::frame::{dot3, transform_point, unit};
use super::shared::gerstner::{gerstner_cis, gerstner_displacement, gerstner_jacobian};
use super::shared::trig::TAU;
use super::wgsl::{
    Vec2, Vec3, Vec4, abs, clamp, ldexp, max, sqrt, texture_sample_level, vec2, vec3, vec4,
};
use crate::mip::{MipChain, texture_sample_level_mip};
use crate::sampler::Texture2D;

pub use crate::sampler::{CLAMP_LINEAR, WRAP_LINEAR};

/// A shading technique's `shade_above(in, p)`: the radiance of the water seen from above
/// (what the stage calls of `technique/shading`; [`super::shading`] holds the mirrors).
pub type ShadeAbove = fn(&VertexOut, &SurfacePoint, &Bindings<'_>) -> Vec3;

/// A foam technique's `foam_coverage(in, p)` (what the stage calls of `technique/foam`;
/// [`super::foam`] holds the mirrors).
pub type FoamCoverage = fn(&VertexOut, &SurfacePoint, &Bindings<'_>) -> f32;

/// The stage's bindings (group 0 in binding order, then the sky function of
/// `shared/preetham.wgsl` with its uniforms).
pub struct Bindings<'a> {
    /// binding 0.
    pub frame: &'a FrameUniforms,
    /// binding 1: (disp_x, height, disp_z, jacobian).
    pub displacement: &'a Texture2D,
    /// binding 2: (slope_x, slope_z, 0, 0), or with far field `mip`/`variance` the chain of
    /// (slope_x, slope_z, slope_x², slope_z²).
    pub displacement_slopes: &'a MipChain,
    /// binding 3: (slope_x, slope_z, height, jacobian), or its chain likewise.
    pub bump: &'a MipChain,
    /// binding 4.
    pub fresnel_above: &'a Texture2D,
    /// binding 5.
    pub fresnel_below: &'a Texture2D,
    /// binding 6.
    pub reflection_map: &'a Texture2D,
    /// binding 7.
    pub refraction_map: &'a Texture2D,
    /// binding 8.
    pub shadow_map: &'a Texture2D,
    /// binding 11: the filtered Fresnel table.
    pub fresnel_filter: &'a Texture2D,
    /// binding 12: the sea floor's relief (shared/floor.wgsl).
    pub floor_map: &'a Texture2D,
    /// binding 13: foam `accumulated`'s field (one zero texel otherwise).
    pub foam_field: &'a Texture2D,
    /// `sky_radiance(dir)`.
    pub sky_radiance: &'a (dyn Fn([f32; 3]) -> [f32; 3] + Sync),
    /// The shading technique's `shade_above` (`technique/shading`).
    pub shade_above: ShadeAbove,
    /// The foam technique's `foam_coverage` (`technique/foam`).
    pub foam_coverage: FoamCoverage,
}

/// What a caller that runs the stage's vertex entry points alone (a test, a tool) binds in
/// place of the textures it does not have: one zero texel, as a texture and as a chain.
#[derive(Clone, Debug)]
pub struct Unbound {
    texture: Texture2D,
    chain: MipChain,
}

impl Default for Unbound {
    fn default() -> Self {
        let texture = Texture2D::new(1, 1, vec![[0.0; 4]]);
        Self { chain: MipChain::single(texture.clone()), texture }
    }
}

/// A sky that sends no light (the vertex stage does not look at the sky).
fn black_sky(_: [f32; 3]) -> [f32; 3] {
    [0.0; 3]
}

/// No light from above: the vertex stage's stand-in for a shading technique.
fn unshaded(_: &VertexOut, _: &SurfacePoint, _: &Bindings<'_>) -> Vec3 {
    vec3(0.0, 0.0, 0.0)
}

/// No white water: the vertex stage's stand-in for a foam technique (what foam `none` is).
fn no_foam(_: &VertexOut, _: &SurfacePoint, _: &Bindings<'_>) -> f32 {
    0.0
}

impl<'a> Bindings<'a> {
    /// Bindings for the vertex entry points: `frame` and the `displacement` map, every other
    /// texture `unbound`'s zero texel, a black sky, no shading and no foam. A caller that
    /// shades fragments overrides what it needs (a shading technique's `shade_above` included) (`Bindings { bump: …, ..vertex_stage(…) }`).
    pub fn vertex_stage(
        frame: &'a FrameUniforms,
        displacement: &'a Texture2D,
        unbound: &'a Unbound,
    ) -> Self {
        let (t, c) = (&unbound.texture, &unbound.chain);
        Self {
            frame,
            displacement,
            displacement_slopes: c,
            bump: c,
            fresnel_above: t,
            fresnel_below: t,
            reflection_map: t,
            refraction_map: t,
            shadow_map: t,
            fresnel_filter: t,
            floor_map: t,
            foam_field: t,
            sky_radiance: &black_sky,
            shade_above: unshaded,
            foam_coverage: no_foam,
        }
    }
}

/// `WaterVertex`: the vertex format is defined once, in ocean-core.
pub use ocean_core::geometry::WaterVertex;

/// `VertexOut`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub clip: Vec4,
    /// `@location(0)`.
    pub rel: Vec3,
    /// `@location(1)`.
    pub uv_d: Vec2,
    /// `@location(2)`.
    pub uv_b: Vec2,
    /// `@location(3)`.
    pub weight: f32,
    /// `@location(4)`: the undisplaced point relative to the mesh's reference point.
    pub pos: Vec2,
}

/// Number of f32 varyings of [`VertexOut`].
pub const VARYINGS: usize = 10;

impl VertexOut {
    /// The varyings in declaration order.
    pub fn varyings(&self) -> [f32; VARYINGS] {
        let (r, d, b, p) = (self.rel, self.uv_d, self.uv_b, self.pos);
        [r.x, r.y, r.z, d.x, d.y, b.x, b.y, self.weight, p.x, p.y]
    }

    /// The fragment stage's input: `clip` is the fragment's position (frag_coord).
    pub fn from_fragment(frag_coord: [f32; 4], v: &[f32; VARYINGS]) -> Self {
        Self {
            clip: frag_coord.into(),
            rel: vec3(v[0], v[1], v[2]),
            uv_d: vec2(v[3], v[4]),
            uv_b: vec2(v[5], v[6]),
            weight: v[7],
            pos: vec2(v[8], v[9]),
        }
    }
}

/// `sky_radiance(sky, dir)` of the bindings (the sky function takes and gives arrays).
pub fn sky_radiance(b: &Bindings<'_>, dir: Vec3) -> Vec3 {
    (b.sky_radiance)(dir.into()).into()
}

/// `vs_main`.
pub fn vs_main(v: &WaterVertex, b: &Bindings<'_>) -> VertexOut {
    water_vertex(Vec2::from(v.pos), v.weight, b)
}

/// `vs_projected_grid(k)`: vertex k of surface `projected_grid`'s (or `shore_grid`'s) triangle
/// list.
pub fn vs_projected_grid(k: u32, b: &Bindings<'_>) -> VertexOut {
    let g = &b.frame.grid;
    let cols = g.cols as u32;
    let quad = k / 6;
    let corner = (k % 6) as usize;
    let di = [0u32, 1, 1, 0, 1, 0];
    let dj = [0u32, 0, 1, 0, 1, 1];
    if g.shore > 0.0 {
        let [a, s, w, _] = g.corners;
        let d = s[0] * (1.0 / (1.0 - (quad / cols + dj[corner]) as f32 / s[1]) - 1.0) - s[2];
        let x =
            ((quad % cols + di[corner]) as f32 / g.cols * 2.0 - 1.0) * (w[0] + w[1] * (d + s[2]));
        let rel = vec2(a[0] * d + a[2] * x, a[1] * d + a[3] * x);
        return water_vertex(rel - Vec2::from(b.frame.tiling.mesh_offset), 1.0, b);
    }
    let (iu, iv) = (quad % cols + di[corner], quad / cols + dj[corner]);
    let (u, v) = (iu as f32 / g.cols, iv as f32 / g.rows);
    let (u1, v1) = ((cols - iu) as f32 / g.cols, (g.rows as u32 - iv) as f32 / g.rows);
    let c = g.corners.map(Vec4::from);
    let h = (c[0] * u1 + c[1] * u) * v1 + (c[2] * u1 + c[3] * u) * v;
    let inv_w = 1.0 / h.w;
    water_vertex(vec2(h.x * inv_w, h.z * inv_w) - Vec2::from(b.frame.tiling.mesh_offset), 1.0, b)
}

/// `map_uvs(pos)`: (uv_d, uv_b).
pub fn map_uvs(pos: Vec2, frame: &FrameUniforms) -> (Vec2, Vec2) {
    let uv_d = (pos + Vec2::from(frame.tiling.displacement_origin))
        * frame.tiling.inv_displacement_size
        + frame.tiling.displacement_half_texel;
    let uv_b = (pos + Vec2::from(frame.tiling.bump_origin)) * frame.tiling.inv_bump_size
        + frame.tiling.bump_half_texel;
    (uv_d, uv_b)
}

/// `grid_spacing(pos)`: (h, along, across) of the screen grids' vertices.
pub fn grid_spacing(pos: Vec2, frame: &FrameUniforms) -> Vec4 {
    let plane = pos + vec2(frame.tiling.mesh_offset[0], frame.tiling.mesh_offset[1]);
    let horizontal = (plane.x * plane.x + plane.y * plane.y).sqrt();
    let e = frame.view.eye_height;
    let dist = (horizontal * horizontal + e * e).sqrt();
    let across = frame.grid.cell_angle * dist;
    let along = across / max(e.abs() / max(dist, 1e-30), 1e-4);
    let h = plane * (-1.0 / max(horizontal, 1e-30));
    vec4(h.x, h.y, along, across)
}

/// `water_vertex(pos, weight)`.
pub fn water_vertex(pos: Vec2, mesh_weight: f32, b: &Bindings<'_>) -> VertexOut {
    let frame = b.frame;
    let uv = map_uvs(pos, frame);
    let plane = pos + vec2(frame.tiling.mesh_offset[0], frame.tiling.mesh_offset[1]);
    let weight =
        mesh_weight * shore_weight(plane.x, plane.y, frame.terrain.top[2], frame, b.floor_map);
    if frame.coastal.shape[0] == SWITCH_ON {
        let sp = grid_spacing(pos, frame);
        let h = coastal_wave(
            pos,
            vec2(sp.x, sp.y),
            vec2(0.0, 0.0),
            vec2(sp.z, sp.w),
            frame,
            b.floor_map,
        )
        .x * weight;
        return displaced_vertex(pos, vec4(0.0, h, 0.0, 0.0), uv, weight, frame);
    }
    if frame.gerstner.count > 0.0 {
        return displaced_vertex(
            pos,
            gerstner_displacement(pos, frame) * weight,
            uv,
            weight,
            frame,
        );
    }
    let mut d = texture_sample_level(b.displacement, &WRAP_LINEAR, uv.0, 0.0)
        * (weight * frame.passes.waves);
    if frame.scales.count > 0.0 {
        d = multi_scale_displacement(pos, b) * (weight * frame.passes.waves);
    }
    displaced_vertex(pos, d, uv, weight, frame)
}

/// `displaced_vertex(pos, d, uv, weight)`.
pub fn displaced_vertex(
    pos: Vec2,
    d: Vec4,
    (uv_d, uv_b): (Vec2, Vec2),
    weight: f32,
    frame: &FrameUniforms,
) -> VertexOut {
    let plane = pos + Vec2::from(frame.tiling.mesh_offset);
    let rel = vec3(plane.x + d.x, d.y - frame.view.eye_height, plane.y + d.z);
    VertexOut { clip: transform_point(&frame.view.view_proj, rel), rel, uv_d, uv_b, weight, pos }
}

/// `multi_scale_displacement(pos)`: eq. 1's Σ_i a_i·D at the scales' points.
pub fn multi_scale_displacement(pos: Vec2, b: &Bindings<'_>) -> Vec4 {
    let m = &b.frame.scales;
    let mut sum = Vec4::from([0.0; 4]);
    for i in 0..m.count as usize {
        let uv = (pos + vec2(m.origin_x[i], m.origin_z[i])) * m.inv_size[i]
            + b.frame.tiling.displacement_half_texel;
        sum = sum + texture_sample_level(b.displacement, &WRAP_LINEAR, uv, 0.0) * m.weight[i];
    }
    sum
}

/// `multi_scale_taps(pos, fp, h)`: the slope chain's taps summed over eq. 1's scales.
pub fn multi_scale_taps(pos: Vec2, fp: &Footprint, h: Vec2, b: &Bindings<'_>) -> Taps {
    let m = &b.frame.scales;
    let mut mean = Vec4::from([0.0; 4]);
    let mut along_sq = 0.0;
    for i in 0..m.count as usize {
        let uv = (pos + vec2(m.origin_x[i], m.origin_z[i])) * m.inv_size[i]
            + b.frame.tiling.displacement_half_texel;
        let t = sample_footprint(
            b.displacement_slopes,
            uv,
            fp.step * m.inv_size[i],
            fp.lods.x + m.lod_offset[i],
            fp.taps_log2,
            h,
        );
        let c = m.weight[i] * (m.inv_size[i] / b.frame.tiling.inv_displacement_size);
        mean =
            mean + Vec4::from([t.mean.x * c, t.mean.y * c, t.mean.z * (c * c), t.mean.w * (c * c)]);
        along_sq += t.along_sq * (c * c);
    }
    Taps { mean, along_sq }
}

/// `pow_int(x, n)`: x^n by binary exponentiation, multiplications in the WGSL's order.
pub fn pow_int(x: f32, n: u32) -> f32 {
    real::helpers::pow_int(x, n)
}

/// `sun_visibility(rel)` (shared/shadow.wgsl) with this stage's `shadow_map`.
pub fn sun_visibility(rel: Vec3, b: &Bindings<'_>) -> f32 {
    super::shared::shadow::sun_visibility(rel, b.frame, b.shadow_map)
}

/// `lod_log2(x)`.
pub fn lod_log2(x: f32) -> f32 {
    real::helpers::lod_log2(x)
}

/// `Footprint`: where the pixel's taps on the slope maps lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// LOD of every tap on the displacement map (x) and the bump map (y).
    pub lods: Vec2,
    /// log2 of the number of taps along the footprint's long axis (a whole number).
    pub taps_log2: f32,
    /// Metres between two taps along the long axis, as a vector on the sea plane (x, z).
    pub step: Vec2,
    /// Unit horizontal direction from the point towards the eye (x, z); 0 for `none`.
    pub h: Vec2,
    /// The view vector's vertical and horizontal parts, |rel.y|/dist and horizontal/dist.
    pub vy: f32,
    /// See `vy`.
    pub vh: f32,
    /// The distance to the eye.
    pub dist: f32,
    /// log2 of the footprint's length.
    pub l_long: f32,
}

/// `footprint(rel)`.
pub fn footprint(rel: Vec3, frame: &FrameUniforms) -> Footprint {
    let far = &frame.far;
    if far.mode == FAR_NONE {
        let zero = vec2(0.0, 0.0);
        return Footprint {
            lods: zero,
            taps_log2: 0.0,
            step: zero,
            h: zero,
            vy: 0.0,
            vh: 0.0,
            dist: 0.0,
            l_long: 0.0,
        };
    }
    let dist = sqrt(rel.x * rel.x + rel.y * rel.y + rel.z * rel.z);
    let cos_view = abs(rel.y) / max(dist, 1e-30);
    let short = clamp(dist * far.pixel_angle, 1e-30, 1e30);
    let long = clamp(short / max(cos_view, 1e-4), 1e-30, 1e30);
    let l_short = lod_log2(short);
    let l_long = lod_log2(long);
    let k = clamp((l_long - l_short).ceil(), 0.0, far.max_aniso_log2);
    let l = max(l_short, l_long - k) + far.lod_bias;
    let horizontal = sqrt(rel.x * rel.x + rel.z * rel.z);
    let spacing = long * ldexp(1.0, -(k as i32));
    Footprint {
        lods: vec2(l + far.lod_offset_d, l + far.lod_offset_b),
        taps_log2: k,
        step: vec2(rel.x, rel.z) * (spacing / max(horizontal, 1e-30)),
        h: vec2(-rel.x, -rel.z) * (1.0 / max(horizontal, 1e-30)),
        vy: abs(rel.y) / max(dist, 1e-30),
        vh: horizontal / max(dist, 1e-30),
        dist,
        l_long,
    }
}

/// `mesh_share(fp)`: the share of the taps' lengthwise slope spread the water mesh resolves
/// (0 with one tap).
pub fn mesh_share(fp: &Footprint, frame: &FrameUniforms) -> f32 {
    let k = fp.taps_log2;
    if k <= 0.0 {
        return 0.0;
    }
    let leg = max(frame.far.mesh_leg_scale * fp.dist, frame.far.mesh_leg_min);
    clamp((fp.l_long - max(lod_log2(leg), fp.l_long - k)) / k, 0.0, 1.0)
}

/// `textureSampleLevel` on a chain (a one-level chain is a plain texture).
fn sample_chain(chain: &MipChain, coords: Vec2, lod: f32) -> Vec4 {
    texture_sample_level_mip(chain, &WRAP_LINEAR, coords.into(), lod).into()
}

/// `Taps`: a chain averaged over the footprint's taps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Taps {
    /// The mean of the taps' samples.
    pub mean: Vec4,
    /// The mean of the squared slope along `h`, (x·h.x + y·h.y)², over the taps.
    pub along_sq: f32,
}

/// `sample_footprint(chain, uv, step_uv, lod, taps_log2, h)`: the taps summed pairwise (tap
/// i into the partial sums by the binary counter of i), so equal taps sum exactly.
pub fn sample_footprint(
    chain: &MipChain,
    uv: Vec2,
    step_uv: Vec2,
    lod: f32,
    taps_log2: f32,
    h: Vec2,
) -> Taps {
    let n = ldexp(1.0, taps_log2 as i32);
    let centre = 0.5 * (n - 1.0);
    let mut partial = [Vec4::from([0.0; 4]); 5];
    let mut sq_partial = [0.0f32; 5];
    let mut i = 0.0;
    while i < n {
        let mut t = sample_chain(chain, uv + step_uv * (i - centre), lod);
        let a = t.x * h.x + t.y * h.y;
        let mut q = a * a;
        let mut carry = i as u32;
        let mut j = 0;
        while carry & 1 == 1 {
            t = partial[j] + t;
            q += sq_partial[j];
            carry >>= 1;
            j += 1;
        }
        partial[j] = t;
        sq_partial[j] = q;
        i += 1.0;
    }
    let k = taps_log2 as usize;
    let inv = ldexp(1.0, -(taps_log2 as i32));
    Taps { mean: partial[k] * inv, along_sq: sq_partial[k] * inv }
}

pub use super::shared::optics::{EXP_MIN, exp_arith};

/// `normal_cdf(a)`: Φ(a) by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7).
pub fn normal_cdf(a: f32) -> f32 {
    real::helpers::normal_cdf(a)
}

/// `VISIBLE_A_MIN`: below this standardised mean the facets' weights are clamped.
pub const VISIBLE_A_MIN: f32 = -2.0;

/// `VISIBLE_A_MAX`: above it the reweighting is below f32's resolution and skipped.
pub const VISIBLE_A_MAX: f32 = 1e4;

/// `visible_slopes(mu, var_geo, vy, vh)`: (mean, variance) of the slope along `h` over the
/// facets the eye sees.
pub fn visible_slopes(mu: f32, var_geo: f32, vy: f32, vh: f32) -> Vec2 {
    let mt = vy - vh * mu;
    let st = vh * sqrt(var_geo);
    if st <= 0.0 || mt >= VISIBLE_A_MAX * st {
        return vec2(mu, var_geo);
    }
    let a = max(mt / st, VISIBLE_A_MIN);
    let pdf = 0.398_942_3 * exp_arith(-0.5 * a * a);
    let cdf = normal_cdf(a);
    let w0 = a * cdf + pdf;
    let mean_u = cdf / w0;
    let var_u = max((a * cdf + 2.0 * pdf) / w0 - mean_u * mean_u, 0.0);
    vec2((vy - st * (a + mean_u)) / vh, var_u * (st * st) / (vh * vh))
}

/// `subtexel(lod)`: the share of level 0's E\[s²\] − E\[s\]² a footprint of LOD `lod` < 0 holds.
pub fn subtexel(lod: f32) -> f32 {
    real::helpers::subtexel(lod)
}

/// `gerstner_filtered_slopes(pos, fp, weight)`.
pub fn gerstner_filtered_slopes(
    pos: Vec2,
    fp: &Footprint,
    weight: f32,
    frame: &FrameUniforms,
) -> Vec3 {
    let short = fp.dist * frame.far.pixel_angle;
    let sigma_long = 0.5 * short / max(fp.vy, 1e-4);
    let sigma_short = 0.5 * short;
    let mut s = vec2(0.0, 0.0);
    let mut variance = 0.0;
    for i in 0..frame.gerstner.count as usize {
        let (a, b) = (frame.gerstner.waves[2 * i], frame.gerstner.waves[2 * i + 1]);
        let c = gerstner_cis(i, pos, frame)[0];
        let kx = TAU * a[0];
        let kz = TAU * a[1];
        let k_long = (kx * fp.h.x + kz * fp.h.y) * sigma_long;
        let k_short = (kz * fp.h.x - kx * fp.h.y) * sigma_short;
        let g = exp_arith(-0.5 * (k_long * k_long + k_short * k_short));
        s = s + vec2(b[2], b[3]) * (c * g);
        if frame.far.mode == FAR_VARIANCE {
            let g2 = g * g;
            let v = 0.5 * (1.0 - g2 * g2) + c * c * (g2 * g2 - g2);
            variance += 0.5 * (b[2] * b[2] + b[3] * b[3]) * v;
        }
    }
    vec3(s.x * weight, s.y * weight, variance * (weight * weight))
}

/// `filtered_slopes(in)`: (s_x, s_z, unresolved variance per axis).
pub fn filtered_slopes(input: &VertexOut, b: &Bindings<'_>) -> Vec3 {
    let frame = b.frame;
    let fp = footprint(input.rel, frame);
    let s = wave_slopes(input, &fp, b);
    if frame.detail.count > 0.0 {
        let short = fp.dist * frame.far.pixel_angle;
        return s + super::shared::detail::detail_slopes(
            input.pos,
            fp.h,
            0.5 * short / max(fp.vy, 1e-4),
            0.5 * short,
            frame,
        );
    }
    s
}

/// `wave_slopes(in, fp)`.
pub fn wave_slopes(input: &VertexOut, fp: &Footprint, b: &Bindings<'_>) -> Vec3 {
    let frame = b.frame;
    if frame.coastal.shape[0] == SWITCH_ON {
        let short = fp.dist * frame.far.pixel_angle;
        let sigma = vec2(0.5 * short / max(fp.vy, 1e-4), 0.5 * short);
        let w = coastal_wave(input.pos, fp.h, sigma, vec2(0.0, 0.0), frame, b.floor_map);
        return vec3(w.y * input.weight, w.z * input.weight, 0.0);
    }
    if frame.gerstner.count > 0.0 {
        return gerstner_filtered_slopes(input.pos, fp, input.weight, frame);
    }
    let rel = input.rel;
    let wd = input.weight * frame.passes.waves;
    let plane = input.pos + vec2(frame.tiling.mesh_offset[0], frame.tiling.mesh_offset[1]);
    let wb = frame.passes.waves
        * shore_weight(plane.x, plane.y, frame.terrain.top[3], frame, b.floor_map);
    let h = fp.h;
    let mut dt = sample_footprint(
        b.displacement_slopes,
        input.uv_d,
        fp.step * frame.tiling.inv_displacement_size,
        fp.lods.x,
        fp.taps_log2,
        h,
    );
    if frame.scales.count > 0.0 {
        dt = multi_scale_taps(input.pos, fp, h, b);
    }
    let bt = sample_footprint(
        b.bump,
        input.uv_b,
        fp.step * frame.tiling.inv_bump_size,
        fp.lods.y,
        fp.taps_log2,
        h,
    );
    let (d, bm) = (dt.mean, bt.mean);
    let sd = d.xy() * wd;
    let sb = bm.xy() * wb;
    let mut s = vec2(sd.x + sb.x, sd.y + sb.y);
    let mut variance = 0.0;
    if frame.far.mode == FAR_VARIANCE {
        let vd = (max(d.z - d.x * d.x, 0.0) + max(d.w - d.y * d.y, 0.0)) * subtexel(fp.lods.x);
        let vb =
            (max(bm.z - bm.x * bm.x, 0.0) + max(bm.w - bm.y * bm.y, 0.0)) * subtexel(fp.lods.y);
        variance = 0.5 * (vd * (wd * wd) + vb * (wb * wb));
        if rel.y < 0.0 {
            let mu_raw = d.x * h.x + d.y * h.y;
            let mu = mu_raw * wd;
            let var_geo =
                max(dt.along_sq - mu_raw * mu_raw, 0.0) * (wd * wd) * mesh_share(fp, frame);
            let vis = visible_slopes(mu, var_geo, fp.vy, fp.vh);
            s = s + h * (vis.x - mu);
            variance = max(variance + 0.5 * (vis.y - var_geo), 0.0);
        }
    }
    vec3(s.x, s.y, variance)
}

/// `bumped_normal(in)`: the bumped unit normal (§5).
pub fn bumped_normal(input: &VertexOut, b: &Bindings<'_>) -> Vec3 {
    let s = filtered_slopes(input, b);
    unit(vec3(-s.x, 1.0, -s.y))
}

/// `fresnel_filtered(u_bumped, variance)`.
pub fn fresnel_filtered(u_bumped: Vec2, variance: f32, b: &Bindings<'_>) -> f32 {
    let far = &b.frame.far;
    let r = sqrt(u_bumped.x * u_bumped.x + u_bumped.y * u_bumped.y);
    let t = sqrt(sqrt(variance) * far.inv_sigma_max);
    let uv = vec2(
        r * far.filter_r_scale + far.filter_r_offset,
        t * far.filter_t_scale + far.filter_t_offset,
    );
    clamp(texture_sample_level(b.fresnel_filter, &CLAMP_LINEAR, uv, 0.0).x, 0.0, 1.0)
}

/// `lobe_side(ur, c, v, a)`: one half Gaussian of the sun's lobe averaged over N(ur, v):
/// (peak scale, mean, deviation) of the product.
pub fn lobe_side(ur: f32, c: f32, v: f32, a: f32) -> Vec3 {
    let d = ur - c;
    let m = (ur * a + c * v) / (a + v);
    let w = max(sqrt(v * a / (v + a)), 1e-30);
    vec3(sqrt(a / (a + v)) * exp_arith(-0.5 * d * d / (a + v)), m, w)
}

/// `sun_lobe_filtered(u, variance)`: the sun's lobe averaged over slopes of per-axis
/// variance `variance` > 0 about the bumped view vector's horizontal part `u`
/// (ocean-core `far_field::SunLobe`; the block carries its constants).
pub fn sun_lobe_filtered(u: Vec2, variance: f32, frame: &FrameUniforms) -> f32 {
    let far = &frame.far;
    let l = frame.sun.direction;
    let rh = vec2(-l[0], -l[2]);
    let len = sqrt(rh.x * rh.x + rh.y * rh.y);
    let mut rho = vec2(1.0, 0.0);
    if len > 1e-6 {
        rho = rh * (1.0 / len);
    }
    let ur = u.x * rho.x + u.y * rho.y;
    let ut = u.y * rho.x - u.x * rho.y;
    let v = variance;
    let at = far.sun_tangential;
    let across = sqrt(at / (at + v)) * exp_arith(-0.5 * ut * ut / (at + v));
    let beyond = far.sun_rim * normal_cdf((ur - 1.0) / sqrt(v));
    let c = far.sun_centre;
    let above = lobe_side(ur, c, v, far.sun_above);
    let below = lobe_side(ur, c, v, far.sun_below);
    let p_above = above.x * normal_cdf((c - above.y) / above.z);
    let p_below =
        below.x * (normal_cdf((1.0 - below.y) / below.z) - normal_cdf((c - below.y) / below.z));
    across * (beyond + p_above + p_below)
}

/// `SQRT2`.
pub const SQRT2: f32 = std::f32::consts::SQRT_2;

/// `grazing_square_axis(a, b)`.
pub fn grazing_square_axis(a: f32, b: f32) -> f32 {
    real::helpers::grazing_square_axis(a, b)
}

/// `bumped_view(view, n)`: the view vector's horizontal part bumped by the normal's
/// (§5.1, Fig. 4).
pub fn bumped_view(view: Vec3, n: Vec3) -> Vec2 {
    vec2(view.x - n.x, view.z - n.z)
}

/// `fresnel_st(u_bumped)`: the Fresnel texture's coordinates of the bumped view vector
/// (§5.1, Fig. 4) under the grazing mapping; `fresnel_scale` is the frame's
/// `hu.fresnel_scale`.
pub fn fresnel_st(u_bumped: Vec2, fresnel_scale: f32) -> Vec2 {
    let x = u_bumped.x;
    let y = u_bumped.y;
    let r2 = x * x + y * y;
    let z = sqrt(max(1.0 - r2, 0.0));
    let d = vec2(x, y) / max(sqrt(1.0 + z), sqrt(r2));
    let u = vec2(grazing_square_axis(d.x, d.y), grazing_square_axis(d.y, d.x));
    u * fresnel_scale + 0.5
}

/// `sky_filtered(view, slopes, variance)`.
pub fn sky_filtered(view: Vec3, slopes: Vec3, variance: f32, b: &Bindings<'_>) -> Vec3 {
    let sigma = sqrt(variance);
    let mut sum_fl = vec3(0.0, 0.0, 0.0);
    let mut sum_f = 0.0;
    for i in 0..4u32 {
        let mut o = vec2(0.0, 0.0);
        match i {
            0 => o.x = sigma,
            1 => o.x = -sigma,
            2 => o.y = sigma,
            _ => o.y = -sigma,
        }
        let ni = unit(vec3(-(slopes.x + o.x), 1.0, -(slopes.y + o.y)));
        let st = fresnel_st(bumped_view(view, ni), b.frame.hu.fresnel_scale);
        let fi = texture_sample_level(b.fresnel_above, &CLAMP_LINEAR, st, 0.0).w;
        let mut ri = ni * (2.0 * dot3(view, ni)) - view;
        ri.y = max(ri.y, 0.0);
        sum_fl = sum_fl + sky_radiance(b, unit(ri + vec3(0.0, 1e-6, 0.0))) * fi;
        sum_f += fi;
    }
    sum_fl / max(sum_f, 1e-30)
}

/// `surface_jacobian(in)`: J at the fragment, faded towards 1 with the mesh's weight.
pub fn surface_jacobian(input: &VertexOut, b: &Bindings<'_>) -> f32 {
    let frame = b.frame;
    if frame.coastal.shape[0] == SWITCH_ON {
        return 1.0;
    }
    if frame.gerstner.count > 0.0 {
        return 1.0 + (gerstner_jacobian(input.pos, frame) - 1.0) * input.weight;
    }
    let j = texture_sample_level(b.displacement, &WRAP_LINEAR, input.uv_d, 0.0).w;
    1.0 + (j - 1.0) * (input.weight * frame.passes.waves)
}

/// `SurfacePoint`: what the shading technique's `shade_above` needs of the surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// The filtered slopes (s_x, s_z, unresolved variance per axis).
    pub slopes: Vec3,
    /// The bumped unit normal.
    pub n: Vec3,
    /// The unit vector to the eye.
    pub view: Vec3,
    /// The bumped view vector's horizontal part.
    pub u_bumped: Vec2,
    /// The fragment's normalised screen position.
    pub screen: Vec2,
    /// Waves `coastal`: (φ in turns, the shore foam's turbulence, the share of the phase the
    /// pixel resolves); (0, 0, 1) otherwise.
    pub coastal: Vec3,
}

/// `fs_main(in)`; `input.clip` is the fragment's position.
pub fn fs_main(input: &VertexOut, b: &Bindings<'_>) -> [f32; 4] {
    let frame = b.frame;
    let slopes = filtered_slopes(input, b);
    let n = unit(vec3(-slopes.x, 1.0, -slopes.y));
    let view = unit(-input.rel);
    let u_bumped = bumped_view(view, n);
    let screen = input.clip.xy() * Vec2::from(frame.view.inv_viewport_size);
    if view.y >= 0.0 {
        let coastal = if frame.coastal.shape[0] == SWITCH_ON {
            let fp = footprint(input.rel, frame);
            let short = fp.dist * frame.far.pixel_angle;
            coastal_shore(
                input.pos,
                fp.h,
                vec2(short / max(fp.vy, 1e-4), short),
                frame,
                b.floor_map,
            )
        } else {
            vec3(0.0, 0.0, 1.0)
        };
        let p = SurfacePoint { slopes, n, view, u_bumped, screen, coastal };
        let c = (b.shade_above)(input, &p, b);
        let mut cover = (b.foam_coverage)(input, &p, b);
        if frame.coastal.shape[0] == SWITCH_ON && frame.foam.mode != FOAM_NONE {
            cover = max(cover, foam_mix(coastal.y, foam_texture_at(input.pos, frame), frame));
        }
        return foam_over(c, cover, n, input.rel, frame, b.shadow_map).extend(1.0).into();
    }
    let st = fresnel_st(u_bumped, frame.hu.fresnel_scale);
    let f = texture_sample_level(b.fresnel_below, &CLAMP_LINEAR, st, 0.0).w;
    let eta = frame.water.eta;
    let i = -view;
    let cos_i = dot3(i, n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    let mut sky_t = vec3(0.0, 0.0, 0.0);
    if k > 0.0 {
        let t = i * eta + n * (sqrt(k) - eta * cos_i);
        sky_t = sky_radiance(b, unit(vec3(t.x, max(t.y, 0.0) + 1e-6, t.z)));
    }
    let c = Vec3::from(frame.water.color) * f + sky_t * (1.0 - f);
    c.extend(1.0).into()
}

// Stage `water`: the sea surface. The vertex shaders displace the surface's mesh by the
// displacement map (vs_main: the near/far patch mesh of surface `hu_patches`, seed 000 §3,
// §5.4, the weight w forcing the near patch's boundary and the far patch flat;
// vs_projected_grid: surface `projected_grid`'s grid, seed 001 §3.1; vs_clipmap: surface
// `clipmap`'s nested levels, seed 002, the waves filtered to each vertex's spacing); under
// waves `gerstner`
// by the sum of the waves instead (shared/gerstner.wgsl, seed 002), whose slopes the fragment
// shader then takes unfiltered. The fragment shader
// bumps the normal with the bump map (§5), filtered by the far-field technique, and shades
// the water seen from above by the shading technique, imported as `technique/shading`
// (shade_above: `hu` seed 000's eq. 3, `chiu` seed 001's eqs. 2–8); the environment is the
// sky technique's radiance, imported as `technique/sky`.
// Seen from below (camera under the water) the surface reflects the water volume and
// transmits the sky through Snell's window, with F for η⁻¹ (total internal reflection).
// CPU mirror: crates/ocean-cpu/src/shaders/water.rs.

// #import shared/frame.wgsl
// #import shared/optics.wgsl
// #import shared/floor.wgsl
// #import shared/gerstner.wgsl
// #import shared/coastal.wgsl
// #import shared/detail.wgsl
// #import shared/sky_lut.wgsl
// #import shared/foam.wgsl
// #import technique/sky
// #import technique/shading
// #import technique/foam

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
// (disp_x, height, disp_z, jacobian) of the displacement map.
@group(0) @binding(1) var displacement: texture_2d<f32>;
// (slope_x, slope_z, 0, 0) of the displacement map.
@group(0) @binding(2) var displacement_slopes: texture_2d<f32>;
// (slope_x, slope_z, height, jacobian) of the bump map.
@group(0) @binding(3) var bump: texture_2d<f32>;
// The 2D Fresnel textures for η (seen from above) and η⁻¹ (from below): RGB = local view
// vector, A = F.
@group(0) @binding(4) var fresnel_above: texture_2d<f32>;
@group(0) @binding(5) var fresnel_below: texture_2d<f32>;
@group(0) @binding(6) var reflection_map: texture_2d<f32>;
@group(0) @binding(7) var refraction_map: texture_2d<f32>;
@group(0) @binding(8) var shadow_map: texture_2d<f32>;
// Repeat, bilinear, and linear between mip levels (the slope maps' chains of far fields `mip`
// and `variance`; a one-level map samples as plain bilinear).
@group(0) @binding(9) var wrap_linear: sampler;
@group(0) @binding(10) var clamp_linear: sampler;
// The filtered Fresnel table F̄(r, σ) of far field `variance` (ocean-core far_field).
@group(0) @binding(11) var fresnel_filter: texture_2d<f32>;
// The sea floor's relief (height in red, m), for eq. 8's depth (shared/floor.wgsl).
@group(0) @binding(12) var floor_map: texture_2d<f32>;
// Foam `accumulated`'s field (foam in x), written by stage `foam`; one zero texel otherwise.
@group(0) @binding(13) var foam_field: texture_2d<f32>;
// The environment the water reflects: the frame's sky technique (its interface: SkyUniforms,
// sky_radiance), a resource of the plan that the water reads.
@group(1) @binding(0) var<uniform> sky: SkyUniforms;
// Sky `atmosphere`'s sky-view table (zeros under the other sky techniques, which ignore it).
@group(1) @binding(1) var<uniform> sky_lut: SkyLut;

struct WaterVertex {
    // Position on the sea plane relative to the mesh's reference point c, (x, z), m
    // (ocean-core's geometry::WaterVertex).
    @location(0) pos: vec2<f32>,
    // Displacement weight: 1 inside the near patch, 0 on its boundary and the far patch.
    @location(1) weight: f32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    // Camera-relative position of the displaced surface point.
    @location(0) rel: vec3<f32>,
    @location(1) uv_d: vec2<f32>,
    @location(2) uv_b: vec2<f32>,
    @location(3) weight: f32,
    // The undisplaced point relative to the mesh's reference point (eq. 1's scales).
    @location(4) pos: vec2<f32>,
}

// x^n for a whole n by binary exponentiation: multiplications only, so every implementation
// rounds alike. (pow() is exp2(n·log2(x)) with the implementation's approximations: on
// lavapipe x^400 came out up to 4e-5 relative off the correctly rounded value, enough to
// move the sun's glitter beyond the CPU/GPU float tolerance.)
fn pow_int(x: f32, n: u32) -> f32 {
    var result = 1.0;
    var base = x;
    var e = n;
    loop {
        if ((e & 1u) == 1u) {
            result = result * base;
        }
        e = e >> 1u;
        if (e == 0u) {
            break;
        }
        base = base * base;
    }
    return result;
}

@vertex
fn vs_main(v: WaterVertex) -> VertexOut {
    return water_vertex(v.pos, v.weight);
}

// Surface `projected_grid`: vertex k of the grid's triangle list (six per quad, quads row by
// row; triangles (0,0) (1,0) (1,1) and (0,0) (1,1) (0,1) of each), on the sea plane at the
// bilinear blend of the corners in homogeneous coordinates, which is the projector ray's
// point exactly (ocean-core geometry::ProjectedGrid). No vertex buffer.
@vertex
fn vs_projected_grid(@builtin(vertex_index) k: u32) -> VertexOut {
    let g = frame.grid;
    let cols = u32(g.cols);
    let quad = k / 6u;
    let corner = k % 6u;
    var di = array<u32, 6>(0u, 1u, 1u, 0u, 1u, 0u);
    var dj = array<u32, 6>(0u, 0u, 1u, 0u, 1u, 1u);
    // Surface `shore_grid` (seed 004): row i at d = D/(n − 1)·(1/(1 − i/n) − 1) − back ahead
    // of the eye along its horizontal forward f, spanning ±w(d) along its right r
    // (ocean-core geometry::shore_grid).
    if (g.shore > 0.0) {
        let a = g.corners[0];
        let s = g.corners[1];
        let w = g.corners[2];
        let d = s.x * (1.0 / (1.0 - f32(quad / cols + dj[corner]) / s.y) - 1.0) - s.z;
        let x = (f32(quad % cols + di[corner]) / g.cols * 2.0 - 1.0) * (w.x + w.y * (d + s.z));
        let rel = vec2<f32>(a.x * d + a.z * x, a.y * d + a.w * x);
        return water_vertex(rel - frame.tiling.mesh_offset, 1.0);
    }
    let iu = quad % cols + di[corner];
    let iv = quad / cols + dj[corner];
    // Each weight and its complement from the integers, so that all four are ≥ 0 on any GPU
    // and the far edge's complement is 0: 1 − v at v = rows/rows is −2 ULP where the division
    // rounds up (WGSL allows 2.5 ULP), and that puts the horizon row's w = 6e-7 (of 3 at the
    // near row) below 0, behind the eye.
    let u = f32(iu) / g.cols;
    let v = f32(iv) / g.rows;
    let u1 = f32(cols - iu) / g.cols;
    let v1 = f32(u32(g.rows) - iv) / g.rows;
    let h = (g.corners[0] * u1 + g.corners[1] * u) * v1 + (g.corners[2] * u1 + g.corners[3] * u) * v;
    let inv_w = 1.0 / h.w;
    return water_vertex(vec2<f32>(h.x * inv_w, h.z * inv_w) - frame.tiling.mesh_offset, 1.0);
}

// Surface `clipmap` (ocean-core geometry::Clipmap): vertex k of level k / (6n²)'s n × n quads
// (six vertices a quad as vs_projected_grid's), at the integer lattice point
// g = C_l + (i − n/2)·2^l (units of level 0's quad s₀) morphed towards the even one below by
// α·2^l, α the ramp of the band [morph_start, morph_start + band] in Chebyshev quads from the
// eye. α reaches 1 exactly on the level's boundary, whose vertices are then the next level's
// hole's, bit for bit. The quads of a level's hole collapse to their first corner (zero area).
// The waves are filtered to the vertex spacing at the point (gerstner_displacement_filtered;
// the map's displacement faded out between 8 and 4 vertices per peak wavelength).
@vertex
fn vs_clipmap(@builtin(vertex_index) k: u32) -> VertexOut {
    let c = frame.clip;
    let n = u32(c.cells);
    let per_level = 6u * n * n;
    let level = k / per_level;
    let quad = (k % per_level) / 6u;
    let corner = k % 6u;
    var di = array<u32, 6>(0u, 1u, 1u, 0u, 1u, 0u);
    var dj = array<u32, 6>(0u, 0u, 1u, 0u, 1u, 1u);
    let lv = c.level[level];
    let qi = i32(quad % n);
    let qj = i32(quad / n);
    let half = i32(n / 2u);
    let in_hole = qi >= lv.z && qi < lv.z + half && qj >= lv.w && qj < lv.w + half;
    var i = qi + i32(di[corner]);
    var j = qj + i32(dj[corner]);
    if (in_hole) {
        i = qi;
        j = qj;
    }
    let e = c.eye[level];
    let step = i32(e.z);
    let dist = max(abs(f32(i - half) - e.x), abs(f32(j - half) - e.y));
    let alpha = clamp((dist - c.morph_start) * c.inv_band, 0.0, 1.0);
    let gx = lv.x + (i - half) * step;
    let gz = lv.y + (j - half) * step;
    // g_even − g: 0 or −2^l, exact, so the product with α is too and a fused sum rounds alike.
    let ox = -(i & 1) * step;
    let oz = -(j & 1) * step;
    var x = f32(gx) + f32(ox) * alpha;
    var z = f32(gz) + f32(oz) * alpha;
    if (alpha >= 1.0) {
        x = f32(gx + ox);
        z = f32(gz + oz);
    }
    let pos = vec2<f32>(x, z) * c.cell_m;
    // The vertex spacing at the morphed point, m: s_l (1 + α) with α evaluated there, so that a
    // vertex morphed onto another and the same point drawn by the next level (α = 1 and 0) are
    // displaced alike; constant inside the band's start.
    let mi = f32(i) + f32(-(i & 1)) * alpha;
    let mj = f32(j) + f32(-(j & 1)) * alpha;
    let mdist = max(abs(mi - f32(half) - e.x), abs(mj - f32(half) - e.y));
    let malpha = clamp((mdist - c.morph_start) * c.inv_band, 0.0, 1.0);
    let spacing = e.z * (1.0 + malpha) * c.cell_m;
    let uv = map_uvs(pos);
    // Waves `coastal` raise the point by their own height, faded to the vertex spacing as the
    // Gerstner waves' below: no map to fetch.
    if (frame.coastal.shape.x == SWITCH_ON) {
        let ch = coastal_wave(pos, vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 0.0), vec2<f32>(spacing, spacing)).x;
        return displaced_vertex(pos, vec4<f32>(0.0, ch, 0.0, 0.0), uv, 1.0);
    }
    // `[terrain] wave_damping`: the waves kept over the floor's depth here.
    let plane = pos + frame.tiling.mesh_offset;
    let sw = shore_weight(plane.x, plane.y, frame.terrain.top.z);
    // Waves `gerstner` sum their own displacement: no map to fetch.
    if (frame.gerstner.count > 0.0) {
        return displaced_vertex(pos, gerstner_displacement_filtered(pos, spacing) * sw, uv, sw);
    }
    var d = textureSampleLevel(displacement, wrap_linear, uv.xy, 0.0);
    if (frame.scales.count > 0.0) {
        d = multi_scale_displacement(pos);
    }
    d = d * (frame.passes.waves * clamp((c.fade_end - spacing) * c.fade_inv_span, 0.0, 1.0));
    return displaced_vertex(pos, d * sw, uv, sw);
}

// The displacement and bump maps' (u, v) at `pos` (m, relative to the mesh's reference point):
// texel (i, j) of an N×N map holds the sample at (i, j)·L/N, so u = x/L + ½/N.
fn map_uvs(pos: vec2<f32>) -> vec4<f32> {
    let uv_d = (pos + frame.tiling.displacement_origin) * frame.tiling.inv_displacement_size + frame.tiling.displacement_half_texel;
    let uv_b = (pos + frame.tiling.bump_origin) * frame.tiling.inv_bump_size + frame.tiling.bump_half_texel;
    return vec4<f32>(uv_d, uv_b);
}

// The screen grids' vertex spacing at `pos` (m, relative to the mesh's reference point):
// (h, along, across), h the unit horizontal direction to the eye, across the grid's cell angle
// times the distance, along that over the cosine of the view's angle from the vertical (as the
// fragments' footprint, with the grid's cell for the pixel). Zero spacing under the other
// surfaces (cell_angle 0).
fn grid_spacing(pos: vec2<f32>) -> vec4<f32> {
    let plane = pos + frame.tiling.mesh_offset;
    let horizontal = sqrt(plane.x * plane.x + plane.y * plane.y);
    let e = frame.view.eye_height;
    let dist = sqrt(horizontal * horizontal + e * e);
    let across = frame.grid.cell_angle * dist;
    let along = across / max(abs(e) / max(dist, 1e-30), 1e-4);
    let h = plane * (-1.0 / max(horizontal, 1e-30));
    return vec4<f32>(h.x, h.y, along, across);
}

// A water vertex at `pos` (m, relative to the mesh's reference point c) displaced by the
// displacement map times `weight`.
fn water_vertex(pos: vec2<f32>, mesh_weight: f32) -> VertexOut {
    let uv = map_uvs(pos);
    // `[terrain] wave_damping` (waves `fft` and `gerstner`): the mesh's weight times the waves
    // kept over the floor's depth here, for the displacement and, through `weight`, the
    // fragments' slopes of it.
    let plane = pos + frame.tiling.mesh_offset;
    let weight = mesh_weight * shore_weight(plane.x, plane.y, frame.terrain.top.z);
    // Waves technique `coastal`: the waves' height at the vertex, faded to the screen grids'
    // vertex spacing; no maps to fetch.
    if (frame.coastal.shape.x == SWITCH_ON) {
        let sp = grid_spacing(pos);
        let h = coastal_wave(pos, sp.xy, vec2<f32>(0.0, 0.0), sp.zw).x * weight;
        return displaced_vertex(pos, vec4<f32>(0.0, h, 0.0, 0.0), uv, weight);
    }
    // Waves technique `gerstner`: the sum of the waves at the vertex, no maps to fetch.
    if (frame.gerstner.count > 0.0) {
        return displaced_vertex(pos, gerstner_displacement(pos) * weight, uv, weight);
    }
    var d = textureSampleLevel(displacement, wrap_linear, uv.xy, 0.0) * (weight * frame.passes.waves);
    if (frame.scales.count > 0.0) {
        d = multi_scale_displacement(pos) * (weight * frame.passes.waves);
    }
    return displaced_vertex(pos, d, uv, weight);
}

// The vertex at `pos` moved by `d`, with the maps' coordinates `uv` and the fragment's slope
// weight `weight`.
fn displaced_vertex(pos: vec2<f32>, d: vec4<f32>, uv: vec4<f32>, weight: f32) -> VertexOut {
    // Camera-relative: c − eye (formed in f64 on the CPU) plus the vertex's offset from c.
    let plane = pos + frame.tiling.mesh_offset;
    let rel = vec3<f32>(plane.x + d.x, d.y - frame.view.eye_height, plane.y + d.z);
    var out: VertexOut;
    out.clip = transform_point(frame.view.view_proj, rel);
    out.rel = rel;
    out.uv_d = uv.xy;
    out.uv_b = uv.zw;
    out.weight = weight;
    out.pos = pos;
    return out;
}

// Eq. 1 of seed 001: Σ_i a_i·D((pos + origin_i)/(L·s_i)), the displacement map sampled at the
// point's object-space position at every scale (so the surface does not swim as the grid
// moves), in the scales' order.
fn multi_scale_displacement(pos: vec2<f32>) -> vec4<f32> {
    let m = frame.scales;
    var sum = vec4<f32>(0.0, 0.0, 0.0, 0.0);
    for (var i = 0u; i < u32(m.count); i = i + 1u) {
        let uv = (pos + vec2<f32>(m.origin_x[i], m.origin_z[i])) * m.inv_size[i] + frame.tiling.displacement_half_texel;
        sum = sum + textureSampleLevel(displacement, wrap_linear, uv, 0.0) * m.weight[i];
    }
    return sum;
}

// The slope chain's taps summed over eq. 1's scales: scale i's slopes are a_i/s_i times the
// map's at the stretched point (the chain rule), its squared slopes (a_i/s_i)² times the map's
// (the scales' cross terms left out), each at the footprint's LOD less log2 s_i.
fn multi_scale_taps(pos: vec2<f32>, fp: Footprint, h: vec2<f32>) -> Taps {
    let m = frame.scales;
    var mean = vec4<f32>(0.0, 0.0, 0.0, 0.0);
    var along_sq = 0.0;
    for (var i = 0u; i < u32(m.count); i = i + 1u) {
        let uv = (pos + vec2<f32>(m.origin_x[i], m.origin_z[i])) * m.inv_size[i] + frame.tiling.displacement_half_texel;
        let t = sample_footprint(displacement_slopes, uv, fp.step * m.inv_size[i], fp.lods.x + m.lod_offset[i], fp.taps_log2, h);
        let c = m.weight[i] * (m.inv_size[i] / frame.tiling.inv_displacement_size);
        mean = mean + vec4<f32>(t.mean.x * c, t.mean.y * c, t.mean.z * (c * c), t.mean.w * (c * c));
        along_sq = along_sq + t.along_sq * (c * c);
    }
    return Taps(mean, along_sq);
}

// log2(x) for x in [1e-30, 1e30] by frexp (exact) and a cubic in the mantissa m ∈ [0, 1),
// m (a + m (b + m c)) with a + b + c = 1 so that octaves meet continuously (within 2e-3 of
// log2): arithmetic only, so both back ends pick the same mip levels and weights bit for bit
// (lavapipe's log2 differs from the CPU's by ulps, which Snell's window near total internal
// reflection magnified past the float tolerance).
fn lod_log2(x: f32) -> f32 {
    let f = frexp(x);
    let m = f.fract * 2.0 - 1.0;
    return f32(f.exp - 1) + m * (1.4425449 + m * (-0.7181452 + m * 0.2756003));
}

// Where the pixel's taps on the slope maps lie (ocean-core far_field's module doc): the
// footprint on the sea is dist·δ across and dist·δ/cos θ_v along the view's horizontal
// direction. 2^k taps, k = ceil(log2(long/short)) ≤ max_aniso_log2, spaced long/2^k along
// that direction, each a trilinear sample at the LOD of max(short, long/2^k) in the map's
// texels. Explicit, from the fragment's own position: no derivatives. Far field `none`: one
// tap at LOD 0.
struct Footprint {
    lods: vec2<f32>,
    taps_log2: f32,
    step: vec2<f32>,
    // Unit horizontal direction from the point towards the eye (x, z); 0 for `none`.
    h: vec2<f32>,
    // The view vector's vertical and horizontal parts, |rel.y|/dist and horizontal/dist.
    vy: f32,
    vh: f32,
    // The distance to the eye and log2 of the footprint's length (for mesh_share).
    dist: f32,
    l_long: f32,
}

fn footprint(rel: vec3<f32>) -> Footprint {
    var fp: Footprint;
    if (frame.far.mode == FAR_NONE) {
        fp.lods = vec2<f32>(0.0, 0.0);
        fp.taps_log2 = 0.0;
        fp.step = vec2<f32>(0.0, 0.0);
        fp.h = vec2<f32>(0.0, 0.0);
        fp.vy = 0.0;
        fp.vh = 0.0;
        fp.dist = 0.0;
        fp.l_long = 0.0;
        return fp;
    }
    let dist = sqrt(rel.x * rel.x + rel.y * rel.y + rel.z * rel.z);
    let cos_view = abs(rel.y) / max(dist, 1e-30);
    let short = clamp(dist * frame.far.pixel_angle, 1e-30, 1e30);
    let long = clamp(short / max(cos_view, 1e-4), 1e-30, 1e30);
    let l_short = lod_log2(short);
    let l_long = lod_log2(long);
    let k = clamp(ceil(l_long - l_short), 0.0, frame.far.max_aniso_log2);
    let l = max(l_short, l_long - k) + frame.far.lod_bias;
    let horizontal = sqrt(rel.x * rel.x + rel.z * rel.z);
    let spacing = long * ldexp(1.0, -i32(k));
    fp.lods = vec2<f32>(l + frame.far.lod_offset_d, l + frame.far.lod_offset_b);
    fp.taps_log2 = k;
    fp.step = vec2<f32>(rel.x, rel.z) * (spacing / max(horizontal, 1e-30));
    fp.h = vec2<f32>(-rel.x, -rel.z) * (1.0 / max(horizontal, 1e-30));
    fp.vy = abs(rel.y) / max(dist, 1e-30);
    fp.vh = horizontal / max(dist, 1e-30);
    fp.dist = dist;
    fp.l_long = l_long;
    return fp;
}

// The share of the taps' lengthwise slope spread that the water mesh resolves, whose wave
// backs the eye cannot see: the octaves between the mesh's triangle leg and the footprint's
// length over the k octaves the taps span (the sea's slope variance is spread evenly over
// octaves, k⁻⁴ spectra); 0 with one tap.
fn mesh_share(fp: Footprint) -> f32 {
    let k = fp.taps_log2;
    if (k <= 0.0) {
        return 0.0;
    }
    let leg = max(frame.far.mesh_leg_scale * fp.dist, frame.far.mesh_leg_min);
    return clamp((fp.l_long - max(lod_log2(leg), fp.l_long - k)) / k, 0.0, 1.0);
}

// A slope chain averaged over the footprint's taps: the mean of the samples, and the mean of
// the squared slope along h (the horizontal direction towards the eye) over the taps.
struct Taps {
    mean: vec4<f32>,
    along_sq: f32,
}

// The chain's trilinear samples at the 2^k taps uv + step_uv·(i − (2^k − 1)/2), summed
// pairwise: tap i goes into the partial sums by the binary counter of i (partial[j] holds 2^j
// taps), so the CPU mirror's order is kept and equal taps sum exactly (a footprint with no
// unresolved slope then has variance 0 exactly and shades as `mip`); the scale by 2^−k is
// exact.
fn sample_footprint(chain: texture_2d<f32>, uv: vec2<f32>, step_uv: vec2<f32>, lod: f32, taps_log2: f32, h: vec2<f32>) -> Taps {
    let n = ldexp(1.0, i32(taps_log2));
    let centre = 0.5 * (n - 1.0);
    var partial: array<vec4<f32>, 5>;
    var sq_partial: array<f32, 5>;
    for (var i = 0.0; i < n; i = i + 1.0) {
        var t = textureSampleLevel(chain, wrap_linear, uv + step_uv * (i - centre), lod);
        let a = t.x * h.x + t.y * h.y;
        var q = a * a;
        var carry = u32(i);
        var j = 0u;
        while ((carry & 1u) == 1u) {
            t = partial[j] + t;
            q = q + sq_partial[j];
            carry = carry >> 1u;
            j = j + 1u;
        }
        partial[j] = t;
        sq_partial[j] = q;
    }
    let k = u32(taps_log2);
    let inv = ldexp(1.0, -i32(taps_log2));
    return Taps(partial[k] * inv, sq_partial[k] * inv);
}

// Φ(a), the standard normal distribution function, by Abramowitz & Stegun 7.1.26
// (|error| < 1.5e-7).
fn normal_cdf(a: f32) -> f32 {
    let x = abs(a) * 0.70710677;
    let t = 1.0 / (1.0 + 0.3275911 * x);
    let poly = ((((1.0614054 * t - 1.453152) * t + 1.4214138) * t - 0.28449674) * t + 0.2548296) * t;
    let erf = 1.0 - poly * exp_arith(-(x * x));
    if (a < 0.0) {
        return 0.5 - 0.5 * erf;
    }
    return 0.5 + 0.5 * erf;
}

// Below this standardised mean the facets' weights are clamped (the truncated moments lose
// every digit in f32 below it; the eye then sees the front-facing tail of a wave field whose
// mean faces away).
const VISIBLE_A_MIN: f32 = -2.0;
// Above it the reweighting is below f32's resolution and skipped.
const VISIBLE_A_MAX: f32 = 1e4;

// The geometric slopes the eye sees (ocean-core far_field's module doc): along h the facets'
// slope s is Gaussian (mean mu, variance var_geo), and a facet shows in proportion to its
// area projected towards the eye, ∝ max(0, v·n)/n_y = max(0, t), t = v_y − v_h·s. Returns the
// (mean, variance) of s over the facets weighted so. With t = st·(a + u), u ~ N(0, 1), the
// weight (a + u) on u > −a gives W₀ = aΦ + φ, W₁ = Φ, W₂ = aΦ + 2φ (Φ, φ at a): the mean of
// u is W₁/W₀ and its variance W₂/W₀ − (W₁/W₀)², both O(1) for every a (the raw moments of t
// cancel catastrophically in f32 once a is large).
fn visible_slopes(mu: f32, var_geo: f32, vy: f32, vh: f32) -> vec2<f32> {
    let mt = vy - vh * mu;
    let st = vh * sqrt(var_geo);
    if (st <= 0.0 || mt >= VISIBLE_A_MAX * st) {
        return vec2<f32>(mu, var_geo);
    }
    let a = max(mt / st, VISIBLE_A_MIN);
    let pdf = 0.3989423 * exp_arith(-0.5 * a * a);
    let cdf = normal_cdf(a);
    let w0 = a * cdf + pdf;
    let mean_u = cdf / w0;
    let var_u = max((a * cdf + 2.0 * pdf) / w0 - mean_u * mean_u, 0.0);
    return vec2<f32>((vy - st * (a + mean_u)) / vh, var_u * (st * st) / (vh * vh));
}

// The share of level 0's E[s²] − E[s]² that a footprint smaller than a texel (LOD < 0) holds:
// 4^lod. Level 0's "variance" between texel centres is the bilinear blend's, w(1 − w)·Δs², a
// property of the texel grid and not of the pixel; a slope field smooth at the texel's scale
// varies over a footprint f by ∝ f², which at f = one texel (LOD 0) is level 0's. (Measured
// against the 64-sample frames' own per-pixel spread, the unscaled one was 2.4× it in the near
// band.) exp by arithmetic only.
fn subtexel(lod: f32) -> f32 {
    if (lod >= 0.0) {
        return 1.0;
    }
    return exp_arith(lod * (2.0 * 0.6931472));
}

// The slopes the pixel sees (§5): the displacement map's (faded with w like the displacement
// itself) plus the bump map's, each averaged over its footprint's taps, and (far field
// `variance`) the variance per axis of the slopes the footprint averaged away,
// E[s²] − E[s]² of the chains' moments, summed over both maps (independent bands). The
// displacement map's slopes are geometry, so the eye above the sea sees its facets weighted
// by their projected area: the variance of its taps' slopes along h (the waves the footprint
// spans lengthwise) is replaced by that of the visible facets and the mean slope shifted by
// theirs. The bump map's slopes only bend the normal: no facet of theirs hides another.
fn filtered_slopes(in: VertexOut) -> vec3<f32> {
    // One footprint per fragment, for the waves and the detail map alike.
    let fp = footprint(in.rel);
    let s = wave_slopes(in, fp);
    // Shading `ggx`'s detail normal map, filtered over the same footprint as the Gerstner
    // waves' slopes (shared/detail.wgsl).
    if (frame.detail.count > 0.0) {
        let short = fp.dist * frame.far.pixel_angle;
        return s + detail_slopes(in.pos, fp.h, 0.5 * short / max(fp.vy, 1e-4), 0.5 * short);
    }
    return s;
}

// The waves' own slopes (filtered_slopes without the detail map), over the footprint `fp` of
// the fragment's `in.rel`.
fn wave_slopes(in: VertexOut, fp: Footprint) -> vec3<f32> {
    // Waves technique `coastal`: the waves' own slopes, filtered over the footprint as the
    // Gerstner waves' are (the far field `variance` gets no variance from them).
    if (frame.coastal.shape.x == SWITCH_ON) {
        let short = fp.dist * frame.far.pixel_angle;
        let sigma = vec2<f32>(0.5 * short / max(fp.vy, 1e-4), 0.5 * short);
        let w = coastal_wave(in.pos, fp.h, sigma, vec2<f32>(0.0, 0.0));
        return vec3<f32>(w.y * in.weight, w.z * in.weight, 0.0);
    }
    // Waves technique `gerstner`: the waves' own slopes, filtered analytically; no bump map.
    if (frame.gerstner.count > 0.0) {
        return gerstner_filtered_slopes(in.pos, fp, in.weight);
    }
    let rel = in.rel;
    let wd = in.weight * frame.passes.waves;
    // `[terrain] wave_damping`: the bump map's waves kept over the floor here.
    let plane = in.pos + frame.tiling.mesh_offset;
    let wb = frame.passes.waves * shore_weight(plane.x, plane.y, frame.terrain.top.w);
    let h = fp.h;
    var dt = sample_footprint(displacement_slopes, in.uv_d, fp.step * frame.tiling.inv_displacement_size, fp.lods.x, fp.taps_log2, h);
    if (frame.scales.count > 0.0) {
        dt = multi_scale_taps(in.pos, fp, h);
    }
    let bt = sample_footprint(bump, in.uv_b, fp.step * frame.tiling.inv_bump_size, fp.lods.y, fp.taps_log2, h);
    let d = dt.mean;
    let b = bt.mean;
    let sd = d.xy * wd;
    let sb = b.xy * wb;
    var s = vec2<f32>(sd.x + sb.x, sd.y + sb.y);
    var variance = 0.0;
    if (frame.far.mode == FAR_VARIANCE) {
        let vd = (max(d.z - d.x * d.x, 0.0) + max(d.w - d.y * d.y, 0.0)) * subtexel(fp.lods.x);
        let vb = (max(b.z - b.x * b.x, 0.0) + max(b.w - b.y * b.y, 0.0)) * subtexel(fp.lods.y);
        variance = 0.5 * (vd * (wd * wd) + vb * (wb * wb));
        if (rel.y < 0.0) {
            let mu_raw = d.x * h.x + d.y * h.y;
            let mu = mu_raw * wd;
            let var_geo = max(dt.along_sq - mu_raw * mu_raw, 0.0) * (wd * wd) * mesh_share(fp);
            let vis = visible_slopes(mu, var_geo, fp.vy, fp.vh);
            s = s + h * (vis.x - mu);
            variance = max(variance + 0.5 * (vis.y - var_geo), 0.0);
        }
    }
    return vec3<f32>(s.x, s.y, variance);
}

// Waves `gerstner`'s slopes at the fragment's undisplaced point `pos`, filtered over the pixel's
// footprint on the sea (far fields `mip` and `variance`; `none` takes them as they are): each
// wave's slope A k D cos θ averaged over a Gaussian of standard deviations half the footprint's
// short and long sides is damped by g = e^{−½((k·h) σ_long)² − ½((k·h⊥) σ_short)²} (h the
// horizontal direction to the eye); under `variance` what the average removes,
// ½(A k)²·[½(1 − g⁴) + cos²θ (g⁴ − g²)] per wave (the variance of A k cos(θ + k·δ) for a
// Gaussian δ, averaged over the two axes), goes to the BRDF as the maps' unresolved variance
// does. Returns (slope_x, slope_z, variance), times the mesh's weight; `fp` is the fragment's
// footprint.
fn gerstner_filtered_slopes(pos: vec2<f32>, fp: Footprint, weight: f32) -> vec3<f32> {
    let short = fp.dist * frame.far.pixel_angle;
    let sigma_long = 0.5 * short / max(fp.vy, 1e-4);
    let sigma_short = 0.5 * short;
    var s = vec2<f32>(0.0, 0.0);
    var variance = 0.0;
    for (var i = 0u; i < u32(frame.gerstner.count); i = i + 1u) {
        let a = frame.gerstner.waves[2u * i];
        let b = frame.gerstner.waves[2u * i + 1u];
        let c = gerstner_cis(i, pos).x;
        let kx = TAU * a.x;
        let kz = TAU * a.y;
        let k_long = (kx * fp.h.x + kz * fp.h.y) * sigma_long;
        let k_short = (kz * fp.h.x - kx * fp.h.y) * sigma_short;
        let g = exp_arith(-0.5 * (k_long * k_long + k_short * k_short));
        s = s + vec2<f32>(b.z, b.w) * (c * g);
        if (frame.far.mode == FAR_VARIANCE) {
            let g2 = g * g;
            let v = 0.5 * (1.0 - g2 * g2) + c * c * (g2 * g2 - g2);
            variance = variance + 0.5 * (b.z * b.z + b.w * b.w) * v;
        }
    }
    return vec3<f32>(s.x * weight, s.y * weight, variance * (weight * weight));
}

// The horizontal displacement's Jacobian J at the fragment (the foam techniques): waves
// `gerstner`'s analytic one at the undisplaced point, else the displacement map's (texels
// carry J in w; eq. 1's scales are not summed), both faded towards 1 with the mesh's weight
// as the displacement is.
fn surface_jacobian(in: VertexOut) -> f32 {
    // Waves `coastal` move the surface vertically only.
    if (frame.coastal.shape.x == SWITCH_ON) {
        return 1.0;
    }
    if (frame.gerstner.count > 0.0) {
        return 1.0 + (gerstner_jacobian(in.pos) - 1.0) * in.weight;
    }
    let j = textureSampleLevel(displacement, wrap_linear, in.uv_d, 0.0).w;
    return 1.0 + (j - 1.0) * (in.weight * frame.passes.waves);
}

// Bumped normal (§5) of the filtered slopes.
fn bumped_normal(in: VertexOut) -> vec3<f32> {
    let s = filtered_slopes(in);
    return unit(vec3<f32>(-s.x, 1.0, -s.y));
}

// √2 of the elliptical grid mapping's inverse.
const SQRT2: f32 = 1.4142135623730951;

// One axis of the disc-to-square map of the grazing mapping (ocean-core
// tables::grazing_square), u = ½ sqrt(2 + a² − b² + 2√2 a) − ½ sqrt(2 + a² − b² − 2√2 a),
// with each root's argument factorised, (√2 ± a)² − b² = (√2 ± a − b)(√2 ± a + b): where it
// vanishes (the corners' images on the rim) the factors are accurate and the expanded sum is
// not. max(0) guards round-off.
fn grazing_square_axis(a: f32, b: f32) -> f32 {
    let plus = (SQRT2 + a - b) * (SQRT2 + a + b);
    let minus = (SQRT2 - a - b) * (SQRT2 - a + b);
    return 0.5 * (sqrt(max(plus, 0.0)) - sqrt(max(minus, 0.0)));
}

// Fresnel bump mapping (§5.1, Fig. 4): the view vector's horizontal part bumped by (−du, −dv),
// (du, dv) the horizontal components of the bumped unit normal: the Fresnel texture's axes,
// which the slopes move one for one.
fn bumped_view(view: vec3<f32>, n: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(view.x - n.x, view.z - n.z);
}

// The bumped view vector `u_bumped` looked up in the grazing-mapped texture
// (the plan's `fresnel_mapping`): z = sqrt(1 − r²), the disc point d = (x, y)/sqrt(1 + z)
// (|d|² = 1 − z), a bumped vector beyond the rim (r > 1) put on the rim at its azimuth by
// max(…, r), then d to the square u ∈ [−1, 1]² and s = a·u + ½.
fn fresnel_st(u_bumped: vec2<f32>) -> vec2<f32> {
    let x = u_bumped.x;
    let y = u_bumped.y;
    let r2 = x * x + y * y;
    let z = sqrt(max(1.0 - r2, 0.0));
    let d = vec2<f32>(x, y) / max(sqrt(1.0 + z), sqrt(r2));
    let u = vec2<f32>(grazing_square_axis(d.x, d.y), grazing_square_axis(d.y, d.x));
    return u * frame.hu.fresnel_scale + 0.5;
}

// F averaged over the unresolved slopes (far field `variance`): the table's F̄ at the bumped
// view vector's radius r and t = sqrt(σ/Σ). F̄ itself, not F̄ − F added to the 2D texture's
// F: F rises from 0.68 to 1 within one texel of the rim, so F̄ − F falls as fast, and its
// bilinear lookup there was off by up to 0.16 (the horizon bands 5–11 % too bright); F̄ is smooth for σ > 0.
fn fresnel_filtered(u_bumped: vec2<f32>, variance: f32) -> f32 {
    let r = sqrt(u_bumped.x * u_bumped.x + u_bumped.y * u_bumped.y);
    let t = sqrt(sqrt(variance) * frame.far.inv_sigma_max);
    let uv = vec2<f32>(r * frame.far.filter_r_scale + frame.far.filter_r_offset, t * frame.far.filter_t_scale + frame.far.filter_t_offset);
    return clamp(textureSampleLevel(fresnel_filter, clamp_linear, uv, 0.0).x, 0.0, 1.0);
}

// One side of the sun's lobe along u_r: a half Gaussian of variance a about c (the lobe's
// peak), averaged over u_r ~ N(ur, v). The product of the two Gaussians is (x) the peak's
// scale times a Gaussian in u_r of mean (y) and deviation (z); the caller cuts it to the
// side's interval with Φ.
fn lobe_side(ur: f32, c: f32, v: f32, a: f32) -> vec3<f32> {
    let d = ur - c;
    let m = (ur * a + c * v) / (a + v);
    let w = max(sqrt(v * a / (v + a)), 1e-30);
    return vec3<f32>(sqrt(a / (a + v)) * exp_arith(-0.5 * d * d / (a + v)), m, w);
}

// The sun's lobe averaged over unresolved slopes of per-axis variance σ² > 0, at u, the
// bumped view vector's horizontal part (the Fresnel table's axes, which move one for one
// with the slope). In u the lobe is a Gaussian across the sun's azimuth (variance 1/s) times,
// along it, two half Gaussians meeting at cos α (the side towards the rim cut there) plus the
// rim's clamped value beyond (ocean-core far_field::SunLobe, whose constants the block
// carries); each piece has a closed-form expectation over a Gaussian: a wider, dimmer
// Gaussian, cut by Φ. A low sun's lobe is squeezed against the rim in u, which an isotropic
// blur of cos^s in angle (Toksvig) misses: it kept the glitter at the horizon, 17 % too bright.
fn sun_lobe_filtered(u: vec2<f32>, variance: f32) -> f32 {
    let far = frame.far;
    let rh = vec2<f32>(-frame.sun.direction.x, -frame.sun.direction.z);
    let len = sqrt(rh.x * rh.x + rh.y * rh.y);
    var rho = vec2<f32>(1.0, 0.0);
    if (len > 1e-6) {
        rho = rh * (1.0 / len);
    }
    let ur = u.x * rho.x + u.y * rho.y;
    let ut = u.y * rho.x - u.x * rho.y;
    let v = variance;
    let at = far.sun_tangential;
    let across = sqrt(at / (at + v)) * exp_arith(-0.5 * ut * ut / (at + v));
    let beyond = far.sun_rim * normal_cdf((ur - 1.0) / sqrt(v));
    let c = far.sun_centre;
    // The side towards the zenith, u_r < c, and the side towards the rim, c < u_r < 1.
    let above = lobe_side(ur, c, v, far.sun_above);
    let below = lobe_side(ur, c, v, far.sun_below);
    let p_above = above.x * normal_cdf((c - above.y) / above.z);
    let p_below = below.x * (normal_cdf((1.0 - below.y) / below.z) - normal_cdf((c - below.y) / below.z));
    return across * (beyond + p_above + p_below);
}

// The sky seen in the unresolved facets (far field `variance`): the reflected sky at the four
// sigma points of the slope distribution, s̄ ± σ along each axis (exact for the quadratic
// part of the radiance), each weighted by its facet's F so that the facets that reflect more
// count more; the caller's F̄ carries the magnitude.
fn sky_filtered(view: vec3<f32>, slopes: vec3<f32>, variance: f32) -> vec3<f32> {
    let sigma = sqrt(variance);
    var sum_fl = vec3<f32>(0.0, 0.0, 0.0);
    var sum_f = 0.0;
    for (var i = 0u; i < 4u; i = i + 1u) {
        var o = vec2<f32>(0.0, 0.0);
        if (i == 0u) {
            o.x = sigma;
        } else if (i == 1u) {
            o.x = -sigma;
        } else if (i == 2u) {
            o.y = sigma;
        } else {
            o.y = -sigma;
        }
        let ni = unit(vec3<f32>(-(slopes.x + o.x), 1.0, -(slopes.y + o.y)));
        let fi = textureSampleLevel(fresnel_above, clamp_linear, fresnel_st(bumped_view(view, ni)), 0.0).w;
        var ri = ni * (2.0 * dot3(view, ni)) - view;
        ri.y = max(ri.y, 0.0);
        sum_fl = sum_fl + sky_radiance(sky, unit(ri + vec3<f32>(0.0, 1e-6, 0.0))) * fi;
        sum_f = sum_f + fi;
    }
    return sum_fl / max(sum_f, 1e-30);
}

// What the shading technique's shade_above needs of the surface point: the filtered slopes
// (s_x, s_z, unresolved variance per axis), the bumped unit normal, the unit vector to the
// eye, the bumped view vector's horizontal part (the Fresnel texture's axes) and the
// fragment's normalised screen position; and under waves `coastal` their phase in turns, the
// shore foam's turbulence and the share of the phase the pixel resolves (coastal_shore;
// (0, 0, 1) under the other waves techniques).
struct SurfacePoint {
    slopes: vec3<f32>,
    n: vec3<f32>,
    view: vec3<f32>,
    u_bumped: vec2<f32>,
    screen: vec2<f32>,
    coastal: vec3<f32>,
}

// The water's colour at a fragment, from its interpolated inputs alone (`in.clip.xy` is the
// pixel centre): what fs_main returns and cs_shade stores.
fn shade(in: VertexOut) -> vec4<f32> {
    let slopes = filtered_slopes(in);
    let n = unit(vec3<f32>(-slopes.x, 1.0, -slopes.y));
    let view = unit(-in.rel);
    let u_bumped = bumped_view(view, n);
    // In the fragment stage `clip` is the fragment's position: (x + 0.5, y + 0.5, depth, 1/w).
    let screen = in.clip.xy * frame.view.inv_viewport_size;
    if (view.y >= 0.0) {
        var coastal = vec3<f32>(0.0, 0.0, 1.0);
        if (frame.coastal.shape.x == SWITCH_ON) {
            // The pixel's footprint on the sea (zero under far field `none`).
            let fp = footprint(in.rel);
            let short = fp.dist * frame.far.pixel_angle;
            coastal = coastal_shore(in.pos, fp.h, vec2<f32>(short / max(fp.vy, 1e-4), short));
        }
        let p = SurfacePoint(slopes, n, view, u_bumped, screen, coastal);
        let c = shade_above(in, p);
        var cover = foam_coverage(in, p);
        // The shore's foam (waves `coastal`) through the foam stage's texture, wherever a
        // foam technique is chosen.
        if (frame.coastal.shape.x == SWITCH_ON && frame.foam.mode != FOAM_NONE) {
            cover = max(cover, foam_mix(coastal.y, foam_texture_at(in.pos)));
        }
        return vec4<f32>(foam_over(c, cover, n, in.rel), 1.0);
    }
    // From below: the normal facing the eye is (n.x, −n.y, n.z), its horizontal part again
    // (du, dv); F for η⁻¹ (1 beyond the critical angle: total internal reflection).
    let st = fresnel_st(u_bumped);
    let f = textureSampleLevel(fresnel_below, clamp_linear, st, 0.0).w;
    // Snell's window: the ray i from the eye meets the surface from below (the normal facing
    // it is −n) and leaves into the air, η_i/η_t = η (water to air):
    // t = η i + (η cos θ_i − cos θ_t)(−n), cos θ_i = i·n, cos² θ_t = 1 − η² sin² θ_i.
    let eta = frame.water.eta;
    let i = -view;
    let cos_i = dot3(i, n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    var sky_t = vec3<f32>(0.0, 0.0, 0.0);
    if (k > 0.0) {
        let t = i * eta + n * (sqrt(k) - eta * cos_i);
        sky_t = sky_radiance(sky, unit(vec3<f32>(t.x, max(t.y, 0.0) + 1e-6, t.z)));
    }
    let c = frame.water.color * f + sky_t * (1.0 - f);
    return vec4<f32>(c, 1.0);
}

// The fragment path (a device whose colour attachments cannot hold the visibility buffer):
// each fragment shaded where it is rasterised.
@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return shade(in);
}

// The visibility buffer, the raster pass's output on the compute path: the interpolated
// inputs of the last fragment that passes the depth test at each pixel, exactly as the
// fragment stage received them (rgba32float holds every f32), and a coverage flag (pos_cover.z:
// 1, 0 where no water was drawn). Interpolated inputs rather than a triangle id and
// barycentrics: the shading then reads the very values a fragment would have, so the two
// paths store the same bits, and no vertex is transformed twice.
struct VisibilityOut {
    @location(0) rel_weight: vec4<f32>,
    @location(1) uvs: vec4<f32>,
    @location(2) pos_cover: vec4<f32>,
}

@fragment
fn fs_visibility(in: VertexOut) -> VisibilityOut {
    return VisibilityOut(
        vec4<f32>(in.rel, in.weight),
        vec4<f32>(in.uv_d, in.uv_b),
        vec4<f32>(in.pos, 1.0, 0.0),
    );
}

@group(2) @binding(0) var vis_rel_weight: texture_2d<f32>;
@group(2) @binding(1) var vis_uvs: texture_2d<f32>;
@group(2) @binding(2) var vis_pos_cover: texture_2d<f32>;
// The HDR frame. ocean-gpu makes the rgba16float variant by replacing this one declaration.
@group(2) @binding(3) var hdr_frame: texture_storage_2d<rgba32float, write>;

// The shading in compute (docs/design.md, "One frame, two back ends": on GPUs whose
// fragment work runs on a few units a compute pass uses the whole chip): one invocation per
// pixel the visibility buffer covers, shading what its fragment would have, at the pixel
// centre (`id + 0.5`, exact in f32, as a fragment's position is).
@compute @workgroup_size(8, 8, 1)
fn cs_shade(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(hdr_frame);
    if (id.x >= size.x || id.y >= size.y) {
        return;
    }
    let p = vec2<i32>(id.xy);
    let c = textureLoad(vis_pos_cover, p, 0);
    if (c.z == 0.0) {
        return;
    }
    let a = textureLoad(vis_rel_weight, p, 0);
    let b = textureLoad(vis_uvs, p, 0);
    var in: VertexOut;
    in.clip = vec4<f32>(vec2<f32>(id.xy) + vec2<f32>(0.5), 0.0, 1.0);
    in.rel = a.xyz;
    in.weight = a.w;
    in.uv_d = b.xy;
    in.uv_b = b.zw;
    in.pos = c.xy;
    textureStore(hdr_frame, p, shade(in));
}

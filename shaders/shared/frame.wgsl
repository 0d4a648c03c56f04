// The uniforms of the `objects`, `shadow` and `water` stages: ocean-core's
// `frame::FrameUniforms`, one named block per concern (same names, same layout; the stage
// registry's layout check in tests/wgsl.rs compares every member's name, offset and type).
struct ViewBlock {
    view_proj: mat4x4<f32>,
    viewport_size: vec2<f32>,
    inv_viewport_size: vec2<f32>,
    eye_height: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
}

struct SunBlock {
    shadow_view_proj: mat4x4<f32>,
    direction: vec3<f32>,
    lit: f32,
    radiance: vec3<f32>,
    pad: f32,
}

struct WaveTilingBlock {
    displacement_origin: vec2<f32>,
    bump_origin: vec2<f32>,
    mesh_offset: vec2<f32>,
    pad0: f32,
    pad1: f32,
    inv_displacement_size: f32,
    inv_bump_size: f32,
    displacement_half_texel: f32,
    bump_half_texel: f32,
}

struct WaterBlock {
    color: vec3<f32>,
    extinction_per_m: f32,
    eta: f32,
    inv_eta: f32,
    volume_model: f32,
    kd_per_m: f32,
}

struct HuShadingBlock {
    phong_exponent: f32,
    reflection_distortion: f32,
    refraction_distortion: f32,
    fresnel_scale: f32,
}

struct PassFlags {
    waves: f32,
    reflection_map: f32,
    refraction_map: f32,
    shadow_map: f32,
}

struct AmbientBlock {
    sky: vec3<f32>,
    pad: f32,
}

// A switch in the uniforms (an f32: uniform blocks hold no bool) is exactly SWITCH_ON or
// SWITCH_OFF (ocean-core switch::SWITCH_ON, …), tested with ==.
const SWITCH_OFF: f32 = 0.0;
const SWITCH_ON: f32 = 1.0;

// `FarFieldBlock::mode`: the far-field technique (ocean-core far_field::FAR_NONE, …).
const FAR_NONE: f32 = 0.0;
const FAR_MIP: f32 = 1.0;
const FAR_VARIANCE: f32 = 2.0;

struct FarFieldBlock {
    mode: f32,
    lod_bias: f32,
    pixel_angle: f32,
    inv_sigma_max: f32,
    lod_offset_d: f32,
    lod_offset_b: f32,
    filter_r_scale: f32,
    filter_r_offset: f32,
    filter_t_scale: f32,
    filter_t_offset: f32,
    max_aniso_log2: f32,
    sun_centre: f32,
    sun_above: f32,
    sun_below: f32,
    sun_tangential: f32,
    sun_rim: f32,
    mesh_leg_scale: f32,
    mesh_leg_min: f32,
    pad0: f32,
    pad1: f32,
}

// shore 1: surface `shore_grid` (ocean-core geometry::shore_grid), whose parameters the
// corners then hold.
struct ProjectedGridBlock {
    // Columns: the corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1).
    corners: mat4x4<f32>,
    cols: f32,
    rows: f32,
    shore: f32,
    // The angle between grid lines, rad.
    cell_angle: f32,
}

struct ChiuShadingBlock {
    zeta_m: f32,
    shininess_per_m: f32,
    clip_waves: f32,
    pad1: f32,
}

struct GgxShadingBlock {
    alpha: f32,
    schlick_fresnel: f32,
    schlick_geometry: f32,
    f0: f32,
}

struct TerrainBlock {
    // (∂y/∂x, ∂y/∂z, y under the eye, 1 with a relief map): the floor's plane in
    // camera-relative (x, z).
    floor: vec4<f32>,
    // (du/dx, dv/dz, u under the eye, v under the eye) of the relief map.
    relief: vec4<f32>,
    // The unit vector towards the sun under the water, and the relief march's horizontal step
    // (m; 0: no march).
    sun_under: vec4<f32>,
    // (highest floor height over the drawn square, world y; steps of the march; 0; 0).
    top: vec4<f32>,
}

// Eq. 1 (seed 001): per scale i, 1/(L·s_i), a_i, the mesh's reference point modulo L·s_i,
// −log2 s_i; count 0 = the single map.
struct MultiScaleBlock {
    inv_size: vec4<f32>,
    weight: vec4<f32>,
    origin_x: vec4<f32>,
    origin_z: vec4<f32>,
    lod_offset: vec4<f32>,
    count: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
}

// Waves technique `gerstner` (ocean-core waves::gerstner): per wave i, waves[2i] = (fx, fz,
// p0, A), (fx, fz) = k D/2π in turns per metre and p0 the phase at the mesh's reference point
// in turns; waves[2i + 1] = (qx, qz, A·kx, A·kz), (qx, qz) = (s/k) D. count 0: technique fft.
struct GerstnerBlock {
    count: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
    waves: array<vec4<f32>, 128>,
}

// Waves technique `coastal` (ocean-core waves::coastal): center = (c_x, c_z relative to the
// mesh's reference point, 1/Δ, Δ), shape = (1 on / 0 off, A, p, back factor), time = (ω t in
// turns, γ, correction waves, 0); per correction wave waves[j] = (fx, fz, p0, a) as
// gerstner's and damping[j] = 2/λ_j; per radial segment i, table[2i] = (Φ₀ mod 1, Φ₁, Φ₂, 0)
// and table[2i + 1] = (K_s·A's three coefficients, 0).
struct CoastalBlock {
    center: vec4<f32>,
    shape: vec4<f32>,
    time: vec4<f32>,
    // Column j is wave j (Rust's [[f32; 4]; 4] is WGSL's mat4x4 in the shared layout).
    waves: mat4x4<f32>,
    damping: vec4<f32>,
    // (the swash's level L, the run-up R (m), the radial profile's mean over its amplitude,
    // its RMS wavenumber over k).
    swash: vec4<f32>,
    table: array<vec4<f32>, 128>,
}

// Shading technique `coastal` (ocean-core waves::coastal::CoastalShadingBlock): schlick 1 for
// Schlick's Fresnel with f0, 0 for the exact one from the Fresnel texture.
struct CoastalShadingBlock {
    dull_color: vec3<f32>,
    dull_factor: f32,
    shininess: f32,
    distortion: f32,
    schlick: f32,
    f0: f32,
}

// Surface `clipmap` (ocean-core geometry::Clipmap): levels 0 under the other surfaces. Per
// level l, level[l] = (C_x, C_z, h_x, h_z): its centre in units of level 0's quad from the
// mesh's reference point and the first quad of its hole; eye[l] = (e_x, e_z, 2^l, 0): the eye
// relative to its centre in its quads.
struct ClipmapBlock {
    levels: f32,
    cells: f32,
    cell_m: f32,
    morph_start: f32,
    inv_band: f32,
    fade_end: f32,
    fade_inv_span: f32,
    pad0: f32,
    level: array<vec4<i32>, 24>,
    eye: array<vec4<f32>, 24>,
}

// Shading `ggx`'s detail normal map (ocean-core detail): per sinusoid (fx, fz, p0, a), turns
// per metre, its phase at the mesh's reference point in turns, and a = slope/|f|; count 0:
// none.
struct DetailBlock {
    count: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
    waves: array<vec4<f32>, 32>,
}

// `FoamBlock::mode`: the foam technique (ocean-core foam::FOAM_NONE, …).
const FOAM_NONE: f32 = 0.0;
const FOAM_HEURISTIC: f32 = 1.0;
const FOAM_JACOBIAN: f32 = 2.0;
const FOAM_ACCUMULATED: f32 = 3.0;

// Stage `foam` (ocean-core foam::FoamBlock).
struct FoamBlock {
    mode: f32,
    intensity: f32,
    threshold: f32,
    inv_softness: f32,
    color: vec3<f32>,
    inv_crest_height: f32,
    noise_origin: vec2<f32>,
    inv_noise_cell: f32,
    inv_crest_slope: f32,
    field_origin: vec2<f32>,
    inv_field_size: f32,
    field_half_texel: f32,
    window_outer: f32,
    inv_window_band: f32,
    seed: u32,
    inv_noise_cell_along: f32,
    wind: vec2<f32>,
    pad0: f32,
    pad1: f32,
}

struct FrameUniforms {
    view: ViewBlock,
    sun: SunBlock,
    tiling: WaveTilingBlock,
    water: WaterBlock,
    hu: HuShadingBlock,
    passes: PassFlags,
    ambient: AmbientBlock,
    far: FarFieldBlock,
    grid: ProjectedGridBlock,
    chiu: ChiuShadingBlock,
    terrain: TerrainBlock,
    scales: MultiScaleBlock,
    gerstner: GerstnerBlock,
    ggx: GgxShadingBlock,
    clip: ClipmapBlock,
    detail: DetailBlock,
    foam: FoamBlock,
    coastal: CoastalBlock,
    coastal_shading: CoastalShadingBlock,
}

// m · (p, 1), written out so that the order of operations is fixed (the CPU mirror,
// ocean-cpu/src/shaders/shared/frame.rs, sums the columns in the same order).
fn transform_point(m: mat4x4<f32>, p: vec3<f32>) -> vec4<f32> {
    return m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3];
}

// v / |v|, with the dot product written out (WGSL's normalize() may use an inverse square
// root whose rounding is the implementation's).
fn unit(v: vec3<f32>) -> vec3<f32> {
    return v / sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

fn dot3(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

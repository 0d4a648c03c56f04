// Stage `foam`'s shared pieces (ocean-core foam, whose f32 functions these write out): the
// foam texture (two octaves of hashed value noise on a world-fixed lattice whose cells are
// `[foam] texture_scale_m` across the wind and FOAM_STREAK times that along it), the coverage
// from a turbulence and the texture, and the foam's light (Lambertian, albedo `[foam] color`,
// lit as the objects are). The foam techniques (shaders/foam/<technique>.wgsl,
// `technique/foam`) give the turbulence; water.wgsl draws the foam over the shaded water.
// Reads the importing stage's `frame`.
// CPU mirror: ocean-cpu/src/shaders/shared/foam.rs.

// #import shared/shadow.wgsl

const FOAM_NOISE_PERIOD: u32 = 256u;
const FOAM_INV_PI: f32 = 0.318309886;
const FOAM_MIN_JACOBIAN: f32 = 0.1;

// A lattice value in [0, 1) for cell (i, j) of an octave: multiply–xorshift, top 24 bits.
fn foam_hash(i: i32, j: i32, octave: u32, seed: u32) -> f32 {
    let wrap = FOAM_NOISE_PERIOD - 1u;
    let iu = bitcast<u32>(i) & wrap;
    let ju = bitcast<u32>(j) & wrap;
    var h = (iu * 0x8da6b343u) ^ (ju * 0xd8163841u) ^ (octave * 0x9e3779b9u) ^ (seed * 0x85ebca6bu);
    h = (h ^ (h >> 15u)) * 0x2c1b3c6du;
    h = (h ^ (h >> 12u)) * 0x297a2d39u;
    h = h ^ (h >> 15u);
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Value noise: the four corners blended with smoothstep weights.
fn foam_value_noise(x: f32, z: f32, octave: u32, seed: u32) -> f32 {
    let fx = floor(x);
    let fz = floor(z);
    let i = i32(fx);
    let j = i32(fz);
    let tx = x - fx;
    let tz = z - fz;
    let ux = tx * tx * (3.0 - 2.0 * tx);
    let uz = tz * tz * (3.0 - 2.0 * tz);
    let a = foam_hash(i, j, octave, seed);
    let b = foam_hash(i + 1, j, octave, seed);
    let c = foam_hash(i, j + 1, octave, seed);
    let d = foam_hash(i + 1, j + 1, octave, seed);
    let ab = a * (1.0 - ux) + b * ux;
    let cd = c * (1.0 - ux) + d * ux;
    return ab * (1.0 - uz) + cd * uz;
}

fn foam_texture(x: f32, z: f32, seed: u32) -> f32 {
    let n0 = foam_value_noise(x, z, 0u, seed);
    let n1 = foam_value_noise(x * 2.0, z * 2.0, 1u, seed);
    return (n0 * 2.0 + n1) * (1.0 / 3.0);
}

// The foam texture at the undisplaced point `pos` (m, relative to the mesh's reference point),
// on axes along and across the wind, its cells FOAM_STREAK times longer along it (streaks).
fn foam_texture_at(pos: vec2<f32>) -> f32 {
    let f = frame.foam;
    // The origin added to the first product: the order lavapipe's compiler reassociates a
    // sum of two products and a constant into (shared/gerstner.wgsl), so both back ends round
    // alike.
    let along = (pos.x * f.wind.x + f.noise_origin.x) + pos.y * f.wind.y;
    let across = (pos.y * f.wind.x + f.noise_origin.y) - pos.x * f.wind.y;
    let q = vec2<f32>(along, across) * vec2<f32>(f.inv_noise_cell_along, f.inv_noise_cell);
    return foam_texture(q.x, q.y, f.seed);
}

// The share of the pixel the foam covers for turbulence t and texture value n.
fn foam_mix(t: f32, n: f32) -> f32 {
    return clamp((t - 0.6 * n) * 2.5, 0.0, 1.0) * frame.foam.intensity;
}

// `heuristic`'s turbulence: height h (m), slope magnitude s of the undisplaced
// parameterisation, Jacobian j.
fn heuristic_turbulence(h: f32, s: f32, j: f32) -> f32 {
    let slope = s / max(j, FOAM_MIN_JACOBIAN);
    let high = clamp(h * frame.foam.inv_crest_height, 0.0, 1.0);
    let steep = clamp(slope * frame.foam.inv_crest_slope, 0.0, 1.0);
    let compressed = clamp((1.0 - j) * frame.foam.inv_softness, 0.0, 1.0);
    return high * steep * compressed;
}

// `jacobian`'s turbulence.
fn jacobian_turbulence(j: f32) -> f32 {
    return clamp((frame.foam.threshold - j) * frame.foam.inv_softness, 0.0, 1.0);
}

// The foam's radiance with unit normal n at camera-relative `rel`: albedo/π · (E_sun cos θ
// shadowed + π·ambient), the objects' lighting.
fn foam_radiance(n: vec3<f32>, rel: vec3<f32>) -> vec3<f32> {
    let cos_sun = max(dot3(n, frame.sun.direction), 0.0) * (frame.sun.lit * sun_visibility(rel));
    let direct = frame.sun.radiance * (cos_sun * FOAM_INV_PI);
    return frame.foam.color * (direct + frame.ambient.sky);
}

// The water's colour c with the foam over it by coverage `cover`.
fn foam_over(c: vec3<f32>, cover: f32, n: vec3<f32>, rel: vec3<f32>) -> vec3<f32> {
    if (cover <= 0.0) {
        return c;
    }
    return c * (1.0 - cover) + foam_radiance(n, rel) * cover;
}

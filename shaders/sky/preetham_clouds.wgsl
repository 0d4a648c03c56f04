// Sky technique `preetham_clouds` (seed 001 eq. 4): the Preetham sky (shared/preetham.wgsl)
// under a procedural cloud layer,
//   C_skylight = C_skycolor·(1 − α) + C_cloud·α,
// α the layer's opacity in the direction: fractal value noise on a lattice over a plane at
// the clouds' altitude, fading to the layer's mean opacity towards the horizon; the sun disc is
// hidden behind it by (1 − α). The model, its constants and the f32 arithmetic written out
// here: ocean-core's `clouds` module, which the CPU mirror
// (ocean-cpu/src/shaders/sky/preetham_clouds.rs) runs. It implements the sky interface
// (sky_radiance, sun_disc; SkyUniforms) imported as `technique/sky`.

// #import shared/preetham.wgsl

const CLOUD_PERIOD: u32 = 256u;
const CLOUD_OCTAVES: u32 = 5u;
const CLOUD_HORIZON_GAIN: f32 = 10.0;

// A lattice value in [0, 1) for cell (i, j) of an octave: multiply–xorshift, top 24 bits.
fn cloud_hash(i: i32, j: i32, octave: u32) -> f32 {
    let wrap = CLOUD_PERIOD - 1u;
    let iu = bitcast<u32>(i) & wrap;
    let ju = bitcast<u32>(j) & wrap;
    var h = (iu * 0x8da6b343u) ^ (ju * 0xd8163841u) ^ (octave * 0x9e3779b9u);
    h = (h ^ (h >> 15u)) * 0x2c1b3c6du;
    h = (h ^ (h >> 12u)) * 0x297a2d39u;
    h = h ^ (h >> 15u);
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Value noise: the four corners blended with smoothstep weights.
fn cloud_value_noise(x: f32, z: f32, octave: u32) -> f32 {
    let fx = floor(x);
    let fz = floor(z);
    let i = i32(fx);
    let j = i32(fz);
    let tx = x - fx;
    let tz = z - fz;
    let ux = tx * tx * (3.0 - 2.0 * tx);
    let uz = tz * tz * (3.0 - 2.0 * tz);
    let a = cloud_hash(i, j, octave);
    let b = cloud_hash(i + 1, j, octave);
    let c = cloud_hash(i, j + 1, octave);
    let d = cloud_hash(i + 1, j + 1, octave);
    let ab = a + (b - a) * ux;
    let cd = c + (d - c) * ux;
    return ab + (cd - ab) * uz;
}

fn cloud_fbm(x: f32, z: f32) -> f32 {
    var sum = 0.0;
    var amp = 0.5;
    var freq = 1.0;
    for (var o = 0u; o < CLOUD_OCTAVES; o = o + 1u) {
        sum = sum + amp * cloud_value_noise(x * freq, z * freq, o);
        amp = amp * 0.5;
        freq = freq * 2.0;
    }
    return sum / 0.96875;
}

fn cloud_opacity(fbm: f32, threshold: f32) -> f32 {
    return clamp((fbm - threshold) * 4.0, 0.0, 1.0);
}

// The layer's opacity in unit direction dir from the eye.
fn cloud_alpha(sky: SkyUniforms, dir: vec3<f32>) -> f32 {
    let origin = sky.cloud_origin;
    let mean = sky.cloud_color.w;
    if (dir.y <= 0.0 || origin.z <= 0.0) {
        return 0.0;
    }
    let w = clamp(dir.y * CLOUD_HORIZON_GAIN, 0.0, 1.0);
    if (w == 0.0) {
        return mean;
    }
    let t = origin.z / dir.y;
    let a = cloud_opacity(cloud_fbm(origin.x + dir.x * t, origin.y + dir.z * t), origin.w);
    return a * w + mean * (1.0 - w);
}

// Eq. 4: the sky behind the cloud's opacity, the cloud's light over it.
fn sky_radiance(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    let alpha = cloud_alpha(sky, dir);
    return preetham_radiance(sky, dir) * (1.0 - alpha) + sky.cloud_color.xyz * alpha;
}

// The sun disc, hidden behind the cloud.
fn sun_disc(sky: SkyUniforms, dir: vec3<f32>) -> vec3<f32> {
    return preetham_sun_disc(sky, dir) * (1.0 - cloud_alpha(sky, dir));
}

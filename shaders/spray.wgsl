// Stage `spray` (spray technique `particles`, seed 001 §3.4): a state-preserving particle
// system. `step` (compute) advances every slot of the pool one fixed time step in place: an
// active particle falls under gravity and is freed when old or back under the water; a free
// slot whose emitter lies under the water is launched along the emitter's direction with a
// seeded random chance, speed and jitter. `vs_main` / `fs_main` draw the active particles as
// camera-facing quads (six vertices each from the vertex index), added to the HDR frame
// (blend One + One) behind the depth of what is drawn, with no depth write. The model, its
// random numbers and the emitters: ocean-core's `spray` module.
// CPU mirror: crates/ocean-cpu/src/shaders/spray.rs.

// #import shared/frame.wgsl

struct Particle {
    // Position relative to the spray's origin; w = 1 active, 0 free.
    pos: vec4<f32>,
    // Velocity; w = age, s.
    vel: vec4<f32>,
}

struct Emitter {
    pos: vec4<f32>,
    dir: vec4<f32>,
}

struct SprayUniforms {
    step: u32,
    count: u32,
    emitters: u32,
    seed: u32,
    dt: f32,
    gravity: f32,
    speed: f32,
    lifetime: f32,
    emit_chance: f32,
    inv_patch: f32,
    half_texel: f32,
    waves: f32,
    // The spray's origin minus the eye.
    origin_rel: vec4<f32>,
    // (half the sprite's side, the centre's radiance, 0, 0).
    sprite: vec4<f32>,
    color: vec4<f32>,
    // The camera's unit right and up vectors (the sprites face the eye).
    right: vec4<f32>,
    up: vec4<f32>,
}

// `step`'s bindings.
@group(0) @binding(0) var<uniform> params: SprayUniforms;
@group(0) @binding(1) var<storage, read_write> particles: array<Particle>;
@group(0) @binding(2) var<storage, read> emitters: array<Emitter>;
@group(0) @binding(3) var displacement: texture_2d<f32>;
@group(0) @binding(4) var wrap_linear: sampler;
// The draw's bindings (another layout of group 0).
@group(0) @binding(5) var<uniform> frame: FrameUniforms;
@group(0) @binding(6) var<storage, read> sprites: array<Particle>;
@group(0) @binding(7) var<uniform> draw: SprayUniforms;

// The random number of stream k for slot i at step `step`, in [0, 1): two lowbias32 rounds
// over the key, the top 24 bits (ocean-core spray::spray_random).
fn spray_random(i: u32, step: u32, k: u32) -> f32 {
    var h = params.seed ^ (i * 0x9e3779b9u) ^ (step * 0x85ebca6bu) ^ (k * 0xc2b2ae35u);
    for (var r = 0u; r < 2u; r = r + 1u) {
        h = h ^ (h >> 16u);
        h = h * 0x7feb352du;
        h = h ^ (h >> 15u);
        h = h * 0x846ca68bu;
        h = h ^ (h >> 16u);
    }
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

// The sea's height at (x, z) relative to the spray's origin: the displacement map's height
// channel, bilinear (its horizontal displacement is ignored).
fn water_height(x: f32, z: f32) -> f32 {
    let uv = vec2<f32>(x, z) * params.inv_patch + params.half_texel;
    return textureSampleLevel(displacement, wrap_linear, uv, 0.0).y * params.waves;
}

@compute @workgroup_size(64)
fn step(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= params.count) {
        return;
    }
    var p = particles[i];
    if (p.pos.w > 0.0) {
        var v = p.vel.xyz;
        v.y = v.y - params.gravity * params.dt;
        let x = p.pos.xyz + v * params.dt;
        let age = p.vel.w + params.dt;
        var alive = 1.0;
        if (age > params.lifetime || (v.y < 0.0 && x.y < water_height(x.x, x.z))) {
            alive = 0.0;
        }
        p.pos = vec4<f32>(x, alive);
        p.vel = vec4<f32>(v, age);
    } else if (params.emitters > 0u) {
        let e = emitters[i % params.emitters];
        if (e.pos.y < water_height(e.pos.x, e.pos.z) && spray_random(i, params.step, 0u) < params.emit_chance) {
            let s = params.speed * (0.6 + 0.8 * spray_random(i, params.step, 1u));
            let jitter = vec3<f32>(
                spray_random(i, params.step, 2u) - 0.5,
                spray_random(i, params.step, 3u) - 0.5,
                spray_random(i, params.step, 4u) - 0.5,
            ) * (0.3 * params.speed);
            p.pos = vec4<f32>(e.pos.xyz, 1.0);
            p.vel = vec4<f32>(e.dir.xyz * s + jitter, 0.0);
        }
    }
    particles[i] = p;
}

struct SpriteOut {
    @builtin(position) clip: vec4<f32>,
    // The quad's corner, (±1, ±1).
    @location(0) corner: vec2<f32>,
}

// Vertex k: corner k mod 6 of particle k / 6's quad (triangles (−,−) (+,−) (+,+) and
// (−,−) (+,+) (−,+)); a free particle's quad lies outside the clip volume.
@vertex
fn vs_main(@builtin(vertex_index) k: u32) -> SpriteOut {
    let p = sprites[k / 6u];
    var cx = array<f32, 6>(-1.0, 1.0, 1.0, -1.0, 1.0, -1.0);
    var cy = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let c = vec2<f32>(cx[k % 6u], cy[k % 6u]);
    var out: SpriteOut;
    out.corner = c;
    if (p.pos.w == 0.0) {
        out.clip = vec4<f32>(2.0, 2.0, 0.5, 1.0);
        return out;
    }
    let half = draw.sprite.x;
    let rel = p.pos.xyz + draw.origin_rel.xyz + (draw.right.xyz * c.x + draw.up.xyz * c.y) * half;
    out.clip = transform_point(frame.view.view_proj, rel);
    return out;
}

// A soft disc: the centre's radiance times (1 − r²), added to the frame.
@fragment
fn fs_main(in: SpriteOut) -> @location(0) vec4<f32> {
    let r2 = in.corner.x * in.corner.x + in.corner.y * in.corner.y;
    let a = max(1.0 - r2, 0.0) * draw.sprite.y;
    return vec4<f32>(draw.color.xyz * a, 0.0);
}

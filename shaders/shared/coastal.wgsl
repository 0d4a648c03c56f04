// Waves technique `coastal` (seed 004; ocean-core waves::coastal): the radial waves running to
// the shore centre, h = clamp(s^p·a·m − a·(m − 1), 0, a) with s = sin φ, φ = −Φ(r) − ω t and
// m the back factor where s·cos φ < 0, a = min(K_s·A, γ·h_floor), plus the correction waves
// faded by clamp(2h/λ, 0, 1). Φ and K_s·A come from the block's radial segments (quadratics
// in u = r − iΔ), so that every operation is + − × and both back ends round alike.
// Reads the importing stage's `frame` and, through floor.wgsl, `floor_map`.
// CPU mirror: ocean-cpu/src/shaders/shared/coastal.rs.

// #import shared/trig.wgsl
// #import shared/floor.wgsl
// #import shared/optics.wgsl

// Radial segments of the block's table.
const COASTAL_SEGMENTS: u32 = 64u;

// The damping of a slope of wave vector (kx, kz) (rad/m) averaged over a Gaussian footprint of
// standard deviations sigma = (along h, across h), h the unit horizontal direction to the eye:
// e^{−½((k·h) σ_long)² − ½((k·h⊥) σ_short)²}, as waves `gerstner`'s (water.wgsl). 1 for
// sigma = 0.
fn coastal_filter(kx: f32, kz: f32, h: vec2<f32>, sigma: vec2<f32>) -> f32 {
    let k_long = (kx * h.x + kz * h.y) * sigma.x;
    let k_short = (kz * h.x - kx * h.y) * sigma.y;
    return exp_arith(-0.5 * (k_long * k_long + k_short * k_short));
}

// (height, ∂h/∂x, ∂h/∂z, φ in turns ∈ [−½, ½]) of the coastal waves at `pos` (m, relative to
// the mesh's reference point), the slopes averaged over the footprint (h, sigma) of
// coastal_filter (sigma 0: the point's own). The amplitude's and the caps' own gradients
// are left out of the slopes (ocean-core waves::coastal says why).
fn coastal_wave(pos: vec2<f32>, h_dir: vec2<f32>, sigma: vec2<f32>) -> vec4<f32> {
    // The block is read through `frame.coastal.…`, never copied into a `let`: a copy of its
    // 2 KB table indexed at run time becomes a local array that lavapipe's LLVM compiles and
    // runs slowly (the water pipeline's compile went from seconds to minutes).
    let plane = pos + frame.tiling.mesh_offset;
    let depth = max(-floor_height(plane.x, plane.y), 0.0);
    let d = pos - frame.coastal.center.xy;
    let r = sqrt(d.x * d.x + d.y * d.y);
    let i = min(u32(r * frame.coastal.center.z), COASTAL_SEGMENTS - 1u);
    let u = r - f32(i) * frame.coastal.center.w;
    let p = frame.coastal.table[2u * i];
    let q = frame.coastal.table[2u * i + 1u];
    let phi = p.x + u * (p.y + u * p.z);
    let dphi = p.y + (u + u) * p.z;
    let cap = frame.coastal.time.y * depth;
    // The quadratic of a segment across the waterline dips below its ends' zero: max 0.
    var amp = max(q.x + u * (q.y + u * q.z), 0.0);
    if (cap < amp) {
        amp = cap;
    }
    let t = -(phi + frame.coastal.time.x);
    let turns = t - floor(t + 0.5);
    let cs = cis_turns(turns);
    var m = 1.0;
    if (cs.x * cs.y < 0.0) {
        m = frame.coastal.shape.w;
    }
    // s^(p − 1), then s^p.
    var sp1 = 1.0;
    for (var k = 1u; k < u32(frame.coastal.shape.z); k = k + 1u) {
        sp1 = sp1 * cs.y;
    }
    let sp = sp1 * cs.y;
    let b = sp * amp * m - amp * (m - 1.0);
    var h = clamp(b, 0.0, amp);
    var dh = 0.0;
    if (b > 0.0 && b < amp) {
        dh = m * (frame.coastal.shape.z * sp1 * cs.x * (-TAU * dphi) * amp);
    }
    var g = vec2<f32>(0.0, 0.0);
    if (r > 0.0) {
        let kr = TAU * dphi / r;
        g = d * (dh / r * coastal_filter(kr * d.x, kr * d.y, h_dir, sigma));
    }
    for (var j = 0u; j < u32(frame.coastal.time.z); j = j + 1u) {
        let w = frame.coastal.waves[j];
        let pj = (w.x * pos.x + w.z) + w.y * pos.y;
        let cj = cis_turns(pj - floor(pj + 0.5));
        let a = w.w * clamp(depth * frame.coastal.damping[j], 0.0, 1.0);
        h = h + a * cj.y;
        let f = coastal_filter(TAU * w.x, TAU * w.y, h_dir, sigma);
        g = g + vec2<f32>(w.x, w.y) * ((a * TAU) * cj.x * f);
    }
    return vec4<f32>(h, g.x, g.y, turns);
}

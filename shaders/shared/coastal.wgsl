// Waves technique `coastal` (seed 004; ocean-core waves::coastal): the radial waves running to
// the shore centre, h = clamp(s^p·a·m − a·(m − 1), 0, a) with s = sin φ, φ = −Φ(r) − ω t and
// m the back factor where s·cos φ < 0, a = min(K_s·A, γ·h_floor), plus the correction waves
// faded by clamp(2h/λ, 0, 1); the swash's film over the run-out zone; the shore foam's
// turbulence (ocean-core waves::coastal, "The shore zones"). Φ and K_s·A come from the block's radial segments (quadratics
// in u = r − iΔ), so that every operation is + − × and both back ends round alike.
// Reads the importing stage's `frame` and, through floor.wgsl, `floor_map`.
// CPU mirror: ocean-cpu/src/shaders/shared/coastal.rs.

// #import shared/trig.wgsl
// #import shared/floor.wgsl
// #import shared/optics.wgsl

// Radial segments of the block's table.
const COASTAL_SEGMENTS: u32 = 64u;
// The swash's water film over the sand, m.
const COASTAL_FILM_M: f32 = 0.03;
// The height band behind the swash's front that carries its foam line, m.
const COASTAL_EDGE_M: f32 = 0.08;

// The damping of a slope of wave vector (kx, kz) (rad/m) averaged over a Gaussian footprint of
// standard deviations sigma = (along h, across h), h the unit horizontal direction to the eye:
// e^{−½((k·h) σ_long)² − ½((k·h⊥) σ_short)²}, as waves `gerstner`'s (water.wgsl). 1 for
// sigma = 0.
fn coastal_filter(kx: f32, kz: f32, h: vec2<f32>, sigma: vec2<f32>) -> f32 {
    let k_long = (kx * h.x + kz * h.y) * sigma.x;
    let k_short = (kz * h.x - kx * h.y) * sigma.y;
    return exp_arith(-0.5 * (k_long * k_long + k_short * k_short));
}

// The radial wave at a point: its place, the floor, the amplitude before and after the breaker
// cap, and its phase.
struct CoastalRadial {
    // pos − centre, m, and its length r.
    d: vec2<f32>,
    r: f32,
    // dΦ/dr, turns per m.
    dphi: f32,
    // The floor's height under the point, m above the sea plane.
    floor_y: f32,
    // K_s·A, and a = min(K_s·A, γ·h).
    shoaled: f32,
    amp: f32,
    // φ in turns ∈ [−½, ½], and (cos φ, sin φ).
    turns: f32,
    cs: vec2<f32>,
}

// The radial wave's state at `pos` (m, relative to the mesh's reference point).
fn coastal_radial(pos: vec2<f32>) -> CoastalRadial {
    // The block is read through `frame.coastal.…`, never copied into a `let`: a copy of its
    // 2 KB table indexed at run time becomes a local array that lavapipe's LLVM compiles and
    // runs slowly (the water pipeline's compile went from seconds to minutes).
    let plane = pos + frame.tiling.mesh_offset;
    let floor_y = floor_height(plane.x, plane.y);
    let depth = max(-floor_y, 0.0);
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
    let shoaled = max(q.x + u * (q.y + u * q.z), 0.0);
    var amp = shoaled;
    if (cap < amp) {
        amp = cap;
    }
    let t = -(phi + frame.coastal.time.x);
    let turns = t - floor(t + 0.5);
    return CoastalRadial(d, r, dphi, floor_y, shoaled, amp, turns, cis_turns(turns));
}

// (b, s^(p − 1), m) of the radial wave: its unclamped height b = s^p·a·m − a·(m − 1).
fn coastal_shape(w: CoastalRadial) -> vec3<f32> {
    var m = 1.0;
    if (w.cs.x * w.cs.y < 0.0) {
        m = frame.coastal.shape.w;
    }
    var sp1 = 1.0;
    for (var k = 1u; k < u32(frame.coastal.shape.z); k = k + 1u) {
        sp1 = sp1 * w.cs.y;
    }
    let sp = sp1 * w.cs.y;
    return vec3<f32>(sp * w.amp * m - w.amp * (m - 1.0), sp1, m);
}

// The share of a wave of (fx, fz) cycles per m that vertices `spacing` m apart (along and
// across the horizontal direction h to the eye) hold: 1 down to 8 vertices per wavelength, 0
// at 4 (waves `gerstner`'s clipmap rule). 1 for spacing 0.
fn coastal_fade(fx: f32, fz: f32, h: vec2<f32>, spacing: vec2<f32>) -> f32 {
    let along = abs(fx * h.x + fz * h.y) * spacing.x;
    let across = abs(fz * h.x - fx * h.y) * spacing.y;
    return clamp(2.0 - 8.0 * (along + across), 0.0, 1.0);
}

// (height, ∂h/∂x, ∂h/∂z, φ in turns ∈ [−½, ½]) of the coastal waves at `pos` (m, relative to
// the mesh's reference point), the slopes averaged over the footprint (h, sigma) of
// coastal_filter (sigma 0: the point's own), the height faded for vertices `spacing` m apart
// (coastal_fade; 0: unfaded). The amplitude's and the caps' own gradients are left out of the
// slopes (ocean-core waves::coastal says why), and so is the swash film's.
fn coastal_wave(pos: vec2<f32>, h_dir: vec2<f32>, sigma: vec2<f32>, spacing: vec2<f32>) -> vec4<f32> {
    let w = coastal_radial(pos);
    let depth = max(-w.floor_y, 0.0);
    let shape = coastal_shape(w);
    let b = shape.x;
    var h = clamp(b, 0.0, w.amp);
    var dh = 0.0;
    if (b > 0.0 && b < w.amp) {
        dh = shape.z * (frame.coastal.shape.z * shape.y * w.cs.x * (-TAU * w.dphi) * w.amp);
    }
    var g = vec2<f32>(0.0, 0.0);
    if (w.r > 0.0) {
        let kr = TAU * frame.coastal.swash.w * w.dphi / w.r;
        g = w.d * (dh / w.r * coastal_filter(kr * w.d.x, kr * w.d.y, h_dir, sigma));
        let f = frame.coastal.swash.w * w.dphi / w.r;
        let fade = coastal_fade(f * w.d.x, f * w.d.y, h_dir, spacing);
        if (fade < 1.0) {
            let mean = frame.coastal.swash.z * w.amp;
            h = mean + (h - mean) * fade;
        }
    }
    for (var j = 0u; j < u32(frame.coastal.time.z); j = j + 1u) {
        let c = frame.coastal.waves[j];
        let pj = (c.x * pos.x + c.z) + c.y * pos.y;
        let cj = cis_turns(pj - floor(pj + 0.5));
        let a = c.w * clamp(depth * frame.coastal.damping[j], 0.0, 1.0) * coastal_fade(c.x, c.y, h_dir, spacing);
        h = h + a * cj.y;
        let f = coastal_filter(TAU * c.x, TAU * c.y, h_dir, sigma);
        g = g + vec2<f32>(c.x, c.y) * ((a * TAU) * cj.x * f);
    }
    let film = min(frame.coastal.swash.x, w.floor_y + COASTAL_FILM_M);
    return vec4<f32>(max(h, film), g.x, g.y, w.turns);
}

// (φ in turns, the shore foam's turbulence ∈ [0, 1], the share of the phase a footprint of
// `spacing` (along and across h) resolves) at `pos`: the surf zone's breaking,
// 1 − γh/(K_s·A), times 0.2 + 0.8·h/a (the crests carry it), and the swash's front; the
// share is coastal_fade of the radial wave's own wavenumber.
fn coastal_shore(pos: vec2<f32>, h: vec2<f32>, spacing: vec2<f32>) -> vec3<f32> {
    let w = coastal_radial(pos);
    var resolved = 1.0;
    if (w.r > 0.0) {
        let f = w.dphi / w.r;
        resolved = coastal_fade(f * w.d.x, f * w.d.y, h, spacing);
    }
    var breaking = 0.0;
    if (w.shoaled > 0.0) {
        breaking = clamp(1.0 - frame.coastal.time.y * max(-w.floor_y, 0.0) / w.shoaled, 0.0, 1.0);
    }
    var crest = 0.0;
    if (w.amp > 0.0) {
        crest = clamp(coastal_shape(w).x, 0.0, w.amp) / w.amp;
    }
    let above = frame.coastal.swash.x - w.floor_y;
    var edge = 0.0;
    if (w.floor_y > -COASTAL_FILM_M && above > 0.0) {
        edge = clamp(1.0 - above / COASTAL_EDGE_M, 0.0, 1.0);
    }
    return vec3<f32>(w.turns, max(breaking * (0.2 + 0.8 * crest), edge), resolved);
}

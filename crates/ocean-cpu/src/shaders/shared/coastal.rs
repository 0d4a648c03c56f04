//! Mirror of `shaders/shared/coastal.wgsl`: waves technique `coastal` at a point of the mesh.

use ocean_core::frame::FrameUniforms;

use super::floor::floor_height;
use super::optics::exp_arith;
use super::trig::{TAU, cis_turns};
use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec2, Vec3, Vec4, clamp, vec2, vec3, vec4};

/// `COASTAL_SEGMENTS`.
pub const COASTAL_SEGMENTS: u32 = 64;
/// `COASTAL_FILM_M`: ocean-core's swash film.
pub const COASTAL_FILM_M: f32 = ocean_core::waves::coastal::SWASH_FILM_M as f32;
/// `COASTAL_EDGE_M`: ocean-core's swash foam band.
pub const COASTAL_EDGE_M: f32 = ocean_core::waves::coastal::SWASH_EDGE_M as f32;

/// `coastal_filter(kx, kz, h, sigma)`: a slope's damping over a Gaussian footprint.
pub fn coastal_filter(kx: f32, kz: f32, h: Vec2, sigma: Vec2) -> f32 {
    let k_long = (kx * h.x + kz * h.y) * sigma.x;
    let k_short = (kz * h.x - kx * h.y) * sigma.y;
    exp_arith(-0.5 * (k_long * k_long + k_short * k_short))
}

/// `CoastalRadial`: the radial wave's state at a point.
#[derive(Clone, Copy, Debug)]
pub struct CoastalRadial {
    /// pos − centre, m.
    pub d: Vec2,
    /// |d|.
    pub r: f32,
    /// dΦ/dr, turns per m.
    pub dphi: f32,
    /// The floor's height under the point, m above the sea plane.
    pub floor_y: f32,
    /// K_s·A.
    pub shoaled: f32,
    /// min(K_s·A, γ·h).
    pub amp: f32,
    /// φ in turns ∈ [−½, ½].
    pub turns: f32,
    /// (cos φ, sin φ).
    pub cs: [f32; 2],
}

/// `coastal_radial(pos)`.
pub fn coastal_radial(pos: Vec2, frame: &FrameUniforms, floor_map: &Texture2D) -> CoastalRadial {
    let c = &frame.coastal;
    let plane = pos + vec2(frame.tiling.mesh_offset[0], frame.tiling.mesh_offset[1]);
    let floor_y = floor_height(plane.x, plane.y, frame, floor_map);
    let depth = (-floor_y).max(0.0);
    let d = pos - vec2(c.center[0], c.center[1]);
    let r = (d.x * d.x + d.y * d.y).sqrt();
    // WGSL's u32(f32) saturates, as Rust's `as` does.
    let i = ((r * c.center[2]) as u32).min(COASTAL_SEGMENTS - 1) as usize;
    let u = r - i as f32 * c.center[3];
    let p = c.table[2 * i];
    let q = c.table[2 * i + 1];
    let phi = p[0] + u * (p[1] + u * p[2]);
    let dphi = p[1] + (u + u) * p[2];
    let cap = c.time[1] * depth;
    let shoaled = (q[0] + u * (q[1] + u * q[2])).max(0.0);
    let amp = if cap < shoaled { cap } else { shoaled };
    let t = -(phi + c.time[0]);
    let turns = t - (t + 0.5).floor();
    CoastalRadial { d, r, dphi, floor_y, shoaled, amp, turns, cs: cis_turns(turns) }
}

/// `coastal_shape(w)`: (b, s^(p − 1), m).
pub fn coastal_shape(w: &CoastalRadial, frame: &FrameUniforms) -> [f32; 3] {
    let c = &frame.coastal;
    let [cos, sin] = w.cs;
    let m = if cos * sin < 0.0 { c.shape[3] } else { 1.0 };
    let mut sp1 = 1.0_f32;
    for _ in 1..c.shape[2] as u32 {
        sp1 *= sin;
    }
    let sp = sp1 * sin;
    [sp * w.amp * m - w.amp * (m - 1.0), sp1, m]
}

/// `coastal_fade(fx, fz, h, spacing)`: the share of a wave vertices `spacing` apart hold.
pub fn coastal_fade(fx: f32, fz: f32, h: Vec2, spacing: Vec2) -> f32 {
    let along = (fx * h.x + fz * h.y).abs() * spacing.x;
    let across = (fz * h.x - fx * h.y).abs() * spacing.y;
    clamp(2.0 - 8.0 * (along + across), 0.0, 1.0)
}

/// `coastal_wave(pos, h_dir, sigma, spacing)`: (height, ∂h/∂x, ∂h/∂z, φ in turns), the slopes
/// filtered over the footprint (`sigma` 0: unfiltered), the height faded for vertices
/// `spacing` apart (0: unfaded).
pub fn coastal_wave(
    pos: Vec2,
    h_dir: Vec2,
    sigma: Vec2,
    spacing: Vec2,
    frame: &FrameUniforms,
    floor_map: &Texture2D,
) -> Vec4 {
    let c = &frame.coastal;
    let w = coastal_radial(pos, frame, floor_map);
    let depth = (-w.floor_y).max(0.0);
    let [b, sp1, m] = coastal_shape(&w, frame);
    let mut h = clamp(b, 0.0, w.amp);
    let dh = if b > 0.0 && b < w.amp {
        m * (c.shape[2] * sp1 * w.cs[0] * (-TAU * w.dphi) * w.amp)
    } else {
        0.0
    };
    let mut g = vec2(0.0, 0.0);
    if w.r > 0.0 {
        let kr = TAU * c.swash[3] * w.dphi / w.r;
        g = w.d * (dh / w.r * coastal_filter(kr * w.d.x, kr * w.d.y, h_dir, sigma));
        let f = c.swash[3] * w.dphi / w.r;
        let fade = coastal_fade(f * w.d.x, f * w.d.y, h_dir, spacing);
        if fade < 1.0 {
            let mean = c.swash[2] * w.amp;
            h = mean + (h - mean) * fade;
        }
    }
    for j in 0..c.time[2] as usize {
        let cw = c.waves[j];
        let pj = (cw[0] * pos.x + cw[2]) + cw[1] * pos.y;
        let [cj, sj] = cis_turns(pj - (pj + 0.5).floor());
        let a = cw[3]
            * clamp(depth * c.damping[j], 0.0, 1.0)
            * coastal_fade(cw[0], cw[1], h_dir, spacing);
        h += a * sj;
        let f = coastal_filter(TAU * cw[0], TAU * cw[1], h_dir, sigma);
        g = g + vec2(cw[0], cw[1]) * ((a * TAU) * cj * f);
    }
    let film = c.swash[0].min(w.floor_y + COASTAL_FILM_M);
    vec4(h.max(film), g.x, g.y, w.turns)
}

/// `coastal_shore(pos, h, spacing)`: (φ in turns, the shore foam's turbulence, the share of
/// the phase the footprint resolves).
pub fn coastal_shore(
    pos: Vec2,
    h: Vec2,
    spacing: Vec2,
    frame: &FrameUniforms,
    floor_map: &Texture2D,
) -> Vec3 {
    let w = coastal_radial(pos, frame, floor_map);
    let resolved = if w.r > 0.0 {
        let f = w.dphi / w.r;
        coastal_fade(f * w.d.x, f * w.d.y, h, spacing)
    } else {
        1.0
    };
    let breaking = if w.shoaled > 0.0 {
        clamp(1.0 - frame.coastal.time[1] * (-w.floor_y).max(0.0) / w.shoaled, 0.0, 1.0)
    } else {
        0.0
    };
    let crest =
        if w.amp > 0.0 { clamp(coastal_shape(&w, frame)[0], 0.0, w.amp) / w.amp } else { 0.0 };
    let above = frame.coastal.swash[0] - w.floor_y;
    let edge = if w.floor_y > -COASTAL_FILM_M && above > 0.0 {
        clamp(1.0 - above / COASTAL_EDGE_M, 0.0, 1.0)
    } else {
        0.0
    };
    vec3(w.turns, (breaking * (0.2 + 0.8 * crest)).max(edge), resolved)
}

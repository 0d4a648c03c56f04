//! Mirror of `shaders/shared/gerstner.wgsl`: waves technique `gerstner` at a point of the mesh.

use ocean_core::frame::FrameUniforms;

use super::trig::{TAU, cis_turns};
use crate::shaders::wgsl::{Vec2, Vec4, clamp, vec2, vec4};

/// `gerstner_cis(i, pos)`: wave i's (cos θ, sin θ).
pub fn gerstner_cis(i: usize, pos: Vec2, frame: &FrameUniforms) -> [f32; 2] {
    let a = frame.gerstner.waves[2 * i];
    let p = (a[0] * pos.x + a[2]) + a[1] * pos.y;
    cis_turns(p - (p + 0.5).floor())
}

/// `gerstner_displacement(pos)`.
pub fn gerstner_displacement(pos: Vec2, frame: &FrameUniforms) -> Vec4 {
    let mut d = vec4(0.0, 0.0, 0.0, 0.0);
    for i in 0..frame.gerstner.count as usize {
        let cs = gerstner_cis(i, pos, frame);
        let (a, b) = (frame.gerstner.waves[2 * i], frame.gerstner.waves[2 * i + 1]);
        d = d + vec4(b[0] * cs[0], a[3] * cs[1], b[1] * cs[0], 0.0);
    }
    d
}

/// `gerstner_displacement_filtered(pos, spacing)`: each wave times
/// g = clamp(2 − 8·spacing/λ, 0, 1).
pub fn gerstner_displacement_filtered(pos: Vec2, spacing: f32, frame: &FrameUniforms) -> Vec4 {
    let mut d = vec4(0.0, 0.0, 0.0, 0.0);
    for i in 0..frame.gerstner.count as usize {
        let a = frame.gerstner.waves[2 * i];
        let g = clamp(2.0 - 8.0 * (spacing * (a[0] * a[0] + a[1] * a[1]).sqrt()), 0.0, 1.0);
        if g > 0.0 {
            let [c, s] = gerstner_cis(i, pos, frame);
            let cs = [c * g, s * g];
            let b = frame.gerstner.waves[2 * i + 1];
            d = d + vec4(b[0] * cs[0], a[3] * cs[1], b[1] * cs[0], 0.0);
        }
    }
    d
}

/// `gerstner_slopes(pos)`.
pub fn gerstner_slopes(pos: Vec2, frame: &FrameUniforms) -> Vec2 {
    let mut s = vec2(0.0, 0.0);
    for i in 0..frame.gerstner.count as usize {
        let cs = gerstner_cis(i, pos, frame);
        let b = frame.gerstner.waves[2 * i + 1];
        s = s + vec2(b[2] * cs[0], b[3] * cs[0]);
    }
    s
}

/// `gerstner_jacobian(pos)`: J = (1 + ∂Dx/∂x)(1 + ∂Dz/∂z) − (∂Dx/∂z)².
pub fn gerstner_jacobian(pos: Vec2, frame: &FrameUniforms) -> f32 {
    let mut dxx = 0.0;
    let mut dzz = 0.0;
    let mut dxz = 0.0;
    for i in 0..frame.gerstner.count as usize {
        let sn = gerstner_cis(i, pos, frame)[1];
        let (a, b) = (frame.gerstner.waves[2 * i], frame.gerstner.waves[2 * i + 1]);
        let kx = TAU * a[0];
        let kz = TAU * a[1];
        dxx -= (b[0] * kx) * sn;
        dzz -= (b[1] * kz) * sn;
        dxz -= (b[0] * kz) * sn;
    }
    (1.0 + dxx) * (1.0 + dzz) - dxz * dxz
}

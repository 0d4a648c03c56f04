//! Mirror of `shaders/shared/detail.wgsl`: shading `ggx`'s detail normal map.

use ocean_core::far_field::FAR_VARIANCE;
use ocean_core::frame::FrameUniforms;

use super::optics::exp_arith;
use super::trig::{TAU, cis_turns};
use crate::shaders::wgsl::{Vec2, Vec3, vec2, vec3};

/// `detail_slopes(pos, h, sigma_long, sigma_short)`.
pub fn detail_slopes(
    pos: Vec2,
    h: Vec2,
    sigma_long: f32,
    sigma_short: f32,
    frame: &FrameUniforms,
) -> Vec3 {
    let mut s = vec2(0.0, 0.0);
    let mut variance = 0.0;
    for w in &frame.detail.waves[..frame.detail.count as usize] {
        let p = (w[0] * pos.x + w[2]) + w[1] * pos.y;
        let c = cis_turns(p - (p + 0.5).floor())[0];
        let kx = TAU * w[0];
        let kz = TAU * w[1];
        let k_long = (kx * h.x + kz * h.y) * sigma_long;
        let k_short = (kz * h.x - kx * h.y) * sigma_short;
        let g = exp_arith(-0.5 * (k_long * k_long + k_short * k_short));
        s = s + vec2(w[0], w[1]) * (w[3] * (c * g));
        if frame.far.mode == FAR_VARIANCE {
            let g2 = g * g;
            let v = 0.5 * (1.0 - g2 * g2) + c * c * (g2 * g2 - g2);
            variance += 0.5 * (w[3] * w[3]) * (w[0] * w[0] + w[1] * w[1]) * v;
        }
    }
    vec3(s.x, s.y, variance)
}

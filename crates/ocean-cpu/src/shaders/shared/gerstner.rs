//! Mirror of `shaders/shared/gerstner.wgsl`: waves technique `gerstner` at a point of the mesh.

use ocean_core::frame::FrameUniforms;

use super::trig::{TAU, cis_reduced_r};
use crate::envelope::{Real, choose_n};
use crate::shaders::wgsl::{Vec2, Vec4, vec2, vec4};

/// `gerstner_cis(i, pos)`: wave i's (cos θ, sin θ).
pub fn gerstner_cis(i: usize, pos: Vec2, frame: &FrameUniforms) -> [f32; 2] {
    gerstner_cis_r(i, [pos.x, pos.y], frame)
}

/// [`gerstner_cis`] over any [`Real`]: the phase `(a.x·x + a.z) + a.y·z` is a sum a GPU may
/// reassociate.
pub fn gerstner_cis_r<R: Real>(i: usize, pos: [R; 2], frame: &FrameUniforms) -> [R; 2] {
    let a = frame.gerstner.waves[2 * i].map(R::lit);
    let terms = [a[0] * pos[0], a[2], a[1] * pos[1]];
    cis_reduced_r(R::sum_as_written(&terms, |t| (t[0] + t[1]) + t[2]))
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
    let [x, y, z, w] = gerstner_displacement_filtered_r([pos.x, pos.y], spacing, frame);
    vec4(x, y, z, w)
}

/// [`gerstner_displacement_filtered`] over any [`Real`] (a wave whose g may or may not be
/// positive: both, united).
pub fn gerstner_displacement_filtered_r<R: Real>(
    pos: [R; 2],
    spacing: R,
    frame: &FrameUniforms,
) -> [R; 4] {
    let l = R::lit;
    let mut d = [l(0.0); 4];
    for i in 0..frame.gerstner.count as usize {
        let a = frame.gerstner.waves[2 * i];
        let k = (l(a[0]) * l(a[0]) + l(a[1]) * l(a[1])).sqrt();
        let g = (l(2.0) - l(8.0) * (spacing * k)).clamp(l(0.0), l(1.0));
        d = choose_n(
            l(0.0).lt(g),
            || {
                let [c, s] = gerstner_cis_r(i, pos, frame);
                let cs = [c * g, s * g];
                let b = frame.gerstner.waves[2 * i + 1];
                let w = [l(b[0]) * cs[0], l(a[3]) * cs[1], l(b[1]) * cs[0], l(0.0)];
                std::array::from_fn(|c| d[c] + w[c])
            },
            || d,
        );
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
    gerstner_jacobian_r([pos.x, pos.y], frame)
}

/// [`gerstner_jacobian`] over any [`Real`] (the loop's sums in the WGSL's order: a loop over
/// a uniform count is not a sum a compiler may reorder).
pub fn gerstner_jacobian_r<R: Real>(pos: [R; 2], frame: &FrameUniforms) -> R {
    let l = R::lit;
    let (mut dxx, mut dzz, mut dxz) = (l(0.0), l(0.0), l(0.0));
    for i in 0..frame.gerstner.count as usize {
        let sn = gerstner_cis_r(i, pos, frame)[1];
        let (a, b) = (frame.gerstner.waves[2 * i], frame.gerstner.waves[2 * i + 1]);
        let kx = l(TAU) * l(a[0]);
        let kz = l(TAU) * l(a[1]);
        dxx = dxx - (l(b[0]) * kx) * sn;
        dzz = dzz - (l(b[1]) * kz) * sn;
        dxz = dxz - (l(b[0]) * kz) * sn;
    }
    (l(1.0) + dxx) * (l(1.0) + dzz) - dxz * dxz
}

//! Mirror of `shaders/composite.wgsl`: the sea's frame copied into an embedding program's
//! colour target, with the depth each pixel's surface point has under the caller's
//! projection (`ocean_core::composite` states the formulas). The embedding test holds the
//! GPU's written depth against [`caller_depth`] of the frame's own depth, pixel by pixel.

use ocean_core::composite::CompositeUniforms;

use crate::shaders::shared::fullscreen::fullscreen_position;
use crate::shaders::wgsl::Vec4;

/// `VertexOut` of `composite.wgsl`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub position: Vec4,
}

/// `vs_main`: the full-screen triangle.
pub fn vs_main(vertex_index: u32) -> VertexOut {
    VertexOut { position: fullscreen_position(vertex_index) }
}

/// `srgb_to_linear`: the sRGB curve inverted (IEC 61966-2-1).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        return c / 12.92;
    }
    ((c + 0.055) / 1.055).powf(2.4)
}

/// `caller_depth`: the caller's depth of the surface point the frame's depth `d` (near /
/// distance, 0 for sky) stands for.
pub fn caller_depth(u: &CompositeUniforms, d: f32) -> f32 {
    if d <= 0.0 {
        return u.params[1];
    }
    let z_view = -(u.params[0] / d);
    let z = u.depth[0] * z_view + u.depth[1];
    let w = u.depth[2] * z_view + u.depth[3];
    (z / w).clamp(0.0, 1.0)
}

/// `fs_main` for the frame's texel `rgba` (floats as `textureLoad` returns them) and depth
/// `d`: the colour written (before the target's own encoding) and the fragment depth.
pub fn fs_main(u: &CompositeUniforms, rgba: [f32; 4], d: f32) -> ([f32; 4], f32) {
    let mut rgb = [rgba[0], rgba[1], rgba[2]];
    if u.params[2] > 0.5 {
        rgb = rgb.map(srgb_to_linear);
    }
    ([rgb[0], rgb[1], rgb[2], 1.0], caller_depth(u, d))
}

#[cfg(test)]
mod tests {
    use glam::{DMat4, DVec4};

    use super::*;

    /// The depth a point at `distance` m ahead has under `p`, computed directly in f64.
    fn projected(p: DMat4, distance: f64) -> f64 {
        let c = p * DVec4::new(0.0, 0.0, -distance, 1.0);
        c.z / c.w
    }

    #[test]
    fn depth_matches_the_callers_projection_in_both_conventions() {
        let near = ocean_core::camera::NEAR_PLANE_M;
        for (p, far) in [
            (glam::dcamera::rh::proj::directx::perspective(1.0, 1.5, 0.1, 1000.0), 1.0),
            (glam::dcamera::rh::proj::directx::perspective_infinite_reverse(1.0, 1.5, 0.1), 0.0),
        ] {
            let u = CompositeUniforms::new(p, far, false);
            for distance in [0.2, 1.0, 37.5, 400.0, 999.0] {
                let d = (near / distance) as f32;
                let got = f64::from(caller_depth(&u, d));
                let want = projected(p, distance);
                assert!(
                    (got - want).abs() < 1e-5 * want.abs().max(1e-3),
                    "{distance}: {got} {want}"
                );
            }
            // The sky keeps the caller's far depth; beyond the far plane, the depth clamps.
            assert_eq!(caller_depth(&u, 0.0), far);
        }
        let u = CompositeUniforms::new(
            glam::dcamera::rh::proj::directx::perspective(1.0, 1.5, 0.1, 100.0),
            1.0,
            false,
        );
        assert_eq!(caller_depth(&u, (near / 5000.0) as f32), 1.0);
    }

    #[test]
    fn the_srgb_curve_inverts_the_encoding() {
        for k in 0..=255u32 {
            let c = k as f32 / 255.0;
            let linear = srgb_to_linear(c);
            let back = if linear <= 0.003_130_8 {
                12.92 * linear
            } else {
                1.055 * linear.powf(1.0 / 2.4) - 0.055
            };
            assert_eq!((back * 255.0).round() as u32, k);
        }
        let u = CompositeUniforms::new(DMat4::IDENTITY, 1.0, true);
        assert_eq!(fs_main(&u, [1.0, 0.0, 0.5, 0.3], 0.0).0[3], 1.0);
        let plain = CompositeUniforms::new(DMat4::IDENTITY, 1.0, false);
        assert_eq!(fs_main(&plain, [1.0, 0.0, 0.5, 0.3], 0.0).0, [1.0, 0.0, 0.5, 1.0]);
        assert_eq!(vs_main(2).position, Vec4::from([-1.0, 3.0, 0.0, 1.0]));
    }
}

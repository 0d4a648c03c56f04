//! The camera of a frame: camera-relative matrices built in f64 and handed to both back ends
//! as f32.
//!
//! Camera-relative rendering: every world position p reaches a shader as p − eye (formed in
//! f64, then rounded to f32), and the view matrix holds only the rotation. A camera 10⁶ m from
//! the origin then has the same f32 precision near the eye as one at the origin.
//!
//! Projection: reversed-Z with an infinite far plane (clip z = near, w = −z_view, so NDC
//! depth is near/distance: 1 at the near plane, → 0 at infinity). f32 depth keeps ~constant
//! relative precision over distance that way, which a sea reaching the horizon needs; the
//! depth test is `Greater`, the clear value 0, and the sky is drawn at depth 0. wgpu's clip
//! conventions: NDC x right, y up, depth in [0, 1].

use glam::{DMat4, DVec3, DVec4};

use crate::scene;
use crate::{Error, Result};

/// Near-plane distance, m. Small enough for a camera 0.5 m above the crests; with reversed-Z
/// it costs no far-field precision.
pub const NEAR_PLANE_M: f64 = 0.05;

/// A frame's camera, f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position in the world, m.
    pub eye: DVec3,
    /// Unit forward direction.
    pub forward: DVec3,
    /// Unit right direction (forward × world up, or a fallback when looking straight up or
    /// down).
    pub right: DVec3,
    /// Unit up direction of the image.
    pub up: DVec3,
    /// Vertical field of view, radians.
    pub fov_y: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
}

impl Camera {
    /// The camera of a scene (validated: eye ≠ look_at, fov in (0°, 180°)).
    pub fn from_scene(c: &scene::Camera) -> Result<Self> {
        Self::look_at(
            DVec3::from_array(c.position),
            DVec3::from_array(c.look_at),
            c.fov_y_deg.to_radians(),
            c.width,
            c.height,
        )
    }

    /// A camera at `eye` looking at `target`.
    pub fn look_at(eye: DVec3, target: DVec3, fov_y: f64, width: u32, height: u32) -> Result<Self> {
        let d = target - eye;
        if !(d.is_finite() && eye.is_finite()) || d.length_squared() == 0.0 {
            return Err(Error::InvalidParameter {
                name: "camera.look_at",
                value: d.length(),
                reason: "the camera must look at a finite point other than its own position".into(),
            });
        }
        if !(fov_y > 0.0 && fov_y < std::f64::consts::PI) || width == 0 || height == 0 {
            return Err(Error::InvalidParameter {
                name: "camera.fov_y_deg",
                value: fov_y.to_degrees(),
                reason: "the field of view must be in (0, 180) degrees and the image non-empty"
                    .into(),
            });
        }
        let forward = d.normalize();
        // Looking straight up or down, forward × up vanishes: take the image's up from −z
        // instead (a camera looking down then has +x to its right, as if it had pitched down
        // from looking along −z).
        let mut right = forward.cross(DVec3::Y);
        if right.length_squared() < 1e-20 {
            right = forward.cross(DVec3::NEG_Z);
        }
        let right = right.normalize();
        let up = right.cross(forward);
        Ok(Self { eye, forward, right, up, fov_y, width, height })
    }

    /// The angle a pixel spans at the image's centre, rad: 2 tan(fov_y/2) / height.
    pub fn pixel_angle(&self) -> f64 {
        2.0 * (0.5 * self.fov_y).tan() / f64::from(self.height.max(1))
    }

    /// Width / height.
    pub fn aspect(&self) -> f64 {
        self.width as f64 / self.height as f64
    }

    /// The rotation-only view matrix (world directions → view space, −z forward).
    pub fn view_rotation(&self) -> DMat4 {
        let (r, u, f) = (self.right, self.up, self.forward);
        DMat4::from_cols(
            DVec4::new(r.x, u.x, -f.x, 0.0),
            DVec4::new(r.y, u.y, -f.y, 0.0),
            DVec4::new(r.z, u.z, -f.z, 0.0),
            DVec4::W,
        )
    }

    /// The reversed-Z infinite perspective projection.
    pub fn projection(&self) -> DMat4 {
        let f = 1.0 / (0.5 * self.fov_y).tan();
        let a = self.aspect();
        // x_c = f/a·x, y_c = f·y, z_c = near, w_c = −z: NDC depth = near / (−z).
        DMat4::from_cols(
            DVec4::new(f / a, 0.0, 0.0, 0.0),
            DVec4::new(0.0, f, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 0.0, -1.0),
            DVec4::new(0.0, 0.0, NEAR_PLANE_M, 0.0),
        )
    }

    /// Camera-relative view-projection: clip = M · (p − eye, 1).
    pub fn view_proj(&self) -> DMat4 {
        self.projection() * self.view_rotation()
    }

    /// The world direction of the ray through NDC (x, y), x right, y up, both in [−1, 1].
    pub fn ray_direction(&self, ndc_x: f64, ndc_y: f64) -> DVec3 {
        let t = (0.5 * self.fov_y).tan();
        (self.forward + self.right * (ndc_x * t * self.aspect()) + self.up * (ndc_y * t))
            .normalize()
    }
}

/// NDC (x right, y up) of the centre of pixel (px, py) of a `w × h` image whose row 0 is at
/// the top.
pub fn pixel_centre_ndc(px: u32, py: u32, w: u32, h: u32) -> (f64, f64) {
    (
        (f64::from(px) + 0.5) / f64::from(w) * 2.0 - 1.0,
        1.0 - (f64::from(py) + 0.5) / f64::from(h) * 2.0,
    )
}

/// An f64 matrix as the column arrays of an f32 `mat4x4<f32>` uniform.
pub fn to_cols_f32(m: DMat4) -> [[f32; 4]; 4] {
    let c = m.to_cols_array_2d();
    c.map(|col| col.map(|v| v as f32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(eye: [f64; 3], target: [f64; 3]) -> Camera {
        Camera::look_at(DVec3::from(eye), DVec3::from(target), 60f64.to_radians(), 320, 180)
            .unwrap()
    }

    #[test]
    fn projection_is_reversed_z_infinite() {
        let c = cam([0.0, 5.0, 0.0], [0.0, 5.0, -10.0]);
        let vp = c.view_proj();
        let near = vp * DVec4::new(0.0, 0.0, -NEAR_PLANE_M, 1.0);
        assert!((near.z / near.w - 1.0).abs() < 1e-12);
        let far = vp * DVec4::new(0.0, 0.0, -1e9, 1.0);
        assert!(far.z / far.w > 0.0 && far.z / far.w < 1e-9);
        // The forward direction projects to the image centre.
        assert!((far.x / far.w).abs() < 1e-12 && (far.y / far.w).abs() < 1e-12);
    }

    #[test]
    fn ray_direction_inverts_the_projection() {
        let c = cam([3.0, 7.0, 2.0], [10.0, 0.0, -40.0]);
        let vp = c.view_proj();
        for (x, y) in [(0.0, 0.0), (0.7, -0.3), (-1.0, 1.0)] {
            let d = c.ray_direction(x, y);
            let p = vp * (d * 100.0).extend(1.0);
            assert!((p.x / p.w - x).abs() < 1e-12 && (p.y / p.w - y).abs() < 1e-12, "{x},{y}");
        }
    }

    #[test]
    fn straight_down_and_far_away_cameras_are_valid() {
        let c = cam([0.0, 100.0, 0.0], [0.0, 0.0, 0.0]);
        assert!(c.right.is_finite() && c.up.is_finite());
        assert!((c.right.length() - 1.0).abs() < 1e-12);
        let c = cam([1e6, 2.0, -1e6], [1e6 + 10.0, 0.0, -1e6]);
        assert!(c.view_proj().is_finite());
        assert!(Camera::look_at(DVec3::ONE, DVec3::ONE, 1.0, 10, 10).is_err());
        assert!(Camera::look_at(DVec3::ZERO, DVec3::X, 0.0, 10, 10).is_err());
        assert!(Camera::look_at(DVec3::ZERO, DVec3::NAN, 1.0, 10, 10).is_err());
    }
}

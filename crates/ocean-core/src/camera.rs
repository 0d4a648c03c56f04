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

    /// The camera of someone else's renderer, from its world → view matrix (a rigid motion:
    /// right-handed, −z forward, y up) and its perspective projection (any near and far
    /// plane, either depth convention; symmetric: no off-axis or oblique terms), for an image
    /// of `width × height` pixels. The sea is then drawn with this crate's own reversed-Z
    /// infinite projection of the same eye, directions and field of view (the caller's near
    /// and far planes only decide the depth it writes into the caller's buffer,
    /// [`crate::composite`]); a camera that rolls keeps its roll.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for non-finite matrices, a view that is not a rotation
    /// and a translation (scale, shear, mirror: tolerance 1e-4), a projection that is not
    /// a symmetric perspective (`w = −z_view`), or an aspect ratio other than the image's
    /// (relative tolerance 1e-3: the sea's pixels must be square where the caller's are).
    pub fn from_view_projection(
        view: DMat4,
        projection: DMat4,
        width: u32,
        height: u32,
    ) -> Result<Self> {
        let invalid = |name: &'static str, value: f64, reason: &str| Error::InvalidParameter {
            name,
            value,
            reason: reason.into(),
        };
        if !view.is_finite() || !projection.is_finite() {
            return Err(invalid("camera.view", f64::NAN, "the matrices must be finite"));
        }
        let r = glam::DMat3::from_mat4(view);
        let off = (r.transpose() * r - glam::DMat3::IDENTITY).to_cols_array();
        let worst = off.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if worst > 1e-4 || r.determinant() <= 0.0 || view.row(3) != DVec4::W {
            return Err(invalid(
                "camera.view",
                worst,
                "the view matrix must be a rotation and a translation (no scale, shear, mirror or projective row)",
            ));
        }
        let p = projection;
        let symmetric = p.x_axis.y == 0.0
            && p.x_axis.z == 0.0
            && p.x_axis.w == 0.0
            && p.y_axis.x == 0.0
            && p.y_axis.z == 0.0
            && p.y_axis.w == 0.0
            && p.z_axis.x == 0.0
            && p.z_axis.y == 0.0
            && p.z_axis.w == -1.0
            && p.w_axis.x == 0.0
            && p.w_axis.y == 0.0
            && p.w_axis.w == 0.0;
        if !(symmetric && p.x_axis.x > 0.0 && p.y_axis.y > 0.0) {
            return Err(invalid(
                "camera.projection",
                p.z_axis.w,
                "the projection must be a symmetric perspective with w = −z_view (as glam's \
                 camera::rh::proj::directx::perspective and perspective_infinite_reverse)",
            ));
        }
        if width == 0 || height == 0 {
            return Err(invalid("camera.width", 0.0, "the image must not be empty"));
        }
        let aspect = p.y_axis.y / p.x_axis.x;
        let image = f64::from(width) / f64::from(height);
        if ((aspect - image) / image).abs() > 1e-3 {
            return Err(invalid(
                "camera.projection",
                aspect,
                &format!("the projection's aspect ratio differs from the image's {image}"),
            ));
        }
        let fov_y = 2.0 * (1.0 / p.y_axis.y).atan();
        // Rows of the rotation: the camera's axes in the world.
        let right = r.row(0).normalize();
        let up = r.row(1).normalize();
        let forward = -r.row(2).normalize();
        let eye = -(r.transpose() * view.w_axis.truncate());
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
    fn a_callers_matrices_give_back_the_camera() {
        use glam::dcamera::rh::{proj::directx, view::look_at_mat4};
        for (eye, target) in [
            ([0.0, 8.0, 0.0], [0.0, 2.0, -100.0]),
            ([3.0, 7.0, 2.0], [10.0, 0.0, -40.0]),
            ([1e5, 2.0, -3e4], [1e5 + 5.0, 1.0, -3e4 + 1.0]),
        ] {
            let want = cam(eye, target);
            let view = look_at_mat4(DVec3::from(eye), DVec3::from(target), DVec3::Y);
            let aspect = 320.0 / 180.0;
            for projection in [
                directx::perspective(want.fov_y, aspect, 0.1, 1000.0),
                directx::perspective_infinite_reverse(want.fov_y, aspect, 0.3),
            ] {
                let got = Camera::from_view_projection(view, projection, 320, 180).unwrap();
                let scale = 1.0 + want.eye.length();
                assert!((got.eye - want.eye).length() < 1e-12 * scale, "{got:?}");
                for (a, b) in
                    [(got.forward, want.forward), (got.right, want.right), (got.up, want.up)]
                {
                    assert!((a - b).length() < 1e-12, "{a} vs {b}");
                }
                assert!((got.fov_y - want.fov_y).abs() < 1e-12);
                // Its scene camera is the same camera again.
                let base = crate::scene::Camera::default();
                let again = Camera::from_scene(&got.to_scene(&base)).unwrap();
                assert!((again.forward - want.forward).length() < 1e-12);
                assert_eq!((again.width, again.height), (320, 180));
            }
        }
        // A rolled camera keeps its roll: up is not in the vertical plane of forward.
        let roll = DMat4::from_rotation_z(0.3)
            * look_at_mat4(DVec3::new(0.0, 5.0, 0.0), DVec3::new(0.0, 5.0, -1.0), DVec3::Y);
        let p = glam::dcamera::rh::proj::directx::perspective(1.0, 2.0, 0.1, 10.0);
        let c = Camera::from_view_projection(roll, p, 200, 100).unwrap();
        assert!((c.up.x.abs() - 0.3f64.sin()).abs() < 1e-12, "{:?}", c.up);
        // Refusals: an aspect ratio other than the image's, a scale, an off-axis projection.
        assert!(Camera::from_view_projection(roll, p, 100, 100).is_err());
        assert!(
            Camera::from_view_projection(roll * DMat4::from_scale(DVec3::splat(2.0)), p, 200, 100)
                .is_err()
        );
        let mut off_axis = p;
        off_axis.z_axis.x = 0.1;
        assert!(Camera::from_view_projection(roll, off_axis, 200, 100).is_err());
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

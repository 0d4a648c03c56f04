//! The scene's `[camera]` section and the camera it makes ([`crate::camera::Camera`]): here,
//! above both, so the camera's geometry does not depend on the scene file.

use glam::DVec3;

use super::Camera;
use crate::Result;
use crate::camera::Camera as CameraView;

impl CameraView {
    /// The camera of a scene (validated: eye ≠ look_at, fov in (0°, 180°)).
    pub fn from_scene(c: &Camera) -> Result<Self> {
        CameraView::look_at(
            DVec3::from_array(c.position),
            DVec3::from_array(c.look_at),
            c.fov_y_deg.to_radians(),
            c.width,
            c.height,
        )
    }

    /// `base` (exposure and the rest) with this camera's eye, a point 1 m ahead, field of
    /// view and image size: the scene camera a plan is made for. Its roll, if any, is not in
    /// a scene camera; frames drawn with this camera itself keep it
    /// ([`crate::graph::FrameInputs::with_camera`]).
    pub fn to_scene(&self, base: &Camera) -> Camera {
        Camera {
            position: self.eye.to_array(),
            look_at: (self.eye + self.forward).to_array(),
            fov_y_deg: self.fov_y.to_degrees(),
            width: self.width,
            height: self.height,
            ..base.clone()
        }
    }
}

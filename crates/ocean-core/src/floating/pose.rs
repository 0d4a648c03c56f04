//! Where a floating body is and how it is turned: what the renderer needs to draw it.
//!
//! Body frame (the frame a hull mesh is modelled in): x forward (towards the bow), y up (keel to
//! deck), z to starboard (the right hand of someone facing the bow), so that forward × up =
//! starboard and the frame is right-handed like the world's. Its origin is the centre of the
//! keel rectangle, the four corner points' centroid.
//!
//! Angles are right-handed about the body's own axes: pitch about starboard (positive: bow up),
//! roll about forward (positive: starboard side down), yaw about world up (positive: the bow
//! turns to port, anticlockwise seen from above).

use glam::{DMat3, DMat4, DVec3};

/// The pose of a floating body: position and an orthonormal, right-handed frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoatPose {
    /// The body frame's origin in the world (the keel rectangle's centre), m.
    pub position: DVec3,
    /// Unit vector towards the bow (body +x).
    pub forward: DVec3,
    /// Unit vector from keel to deck (body +y).
    pub up: DVec3,
    /// Unit vector to starboard (body +z), forward × up.
    pub starboard: DVec3,
}

impl BoatPose {
    /// The pose at `position` turned by `yaw_rad`, then pitched by `pitch_rad` and rolled by
    /// `roll_rad` about the turned body's own axes (the conventions of the module doc).
    pub fn from_angles(position: DVec3, yaw_rad: f64, pitch_rad: f64, roll_rad: f64) -> Self {
        // Intrinsic yaw (about y), pitch (about the body's z), roll (about the body's x):
        // R = R_y(yaw)·R_z(pitch)·R_x(roll), whose columns are the body axes in the world.
        let r = DMat3::from_rotation_y(yaw_rad)
            * DMat3::from_rotation_z(pitch_rad)
            * DMat3::from_rotation_x(roll_rad);
        Self { position, forward: r.x_axis, up: r.y_axis, starboard: r.z_axis }
    }

    /// The pose of a body whose forward axis points along `forward_raw` and whose starboard
    /// side lies along `starboard_raw` (neither needs unit length nor exact orthogonality):
    /// Gram–Schmidt with forward kept exactly, so pitch is the bow's true elevation. A zero
    /// or non-finite input falls back to the world axes (forward +x, starboard +z), which only
    /// a degenerate body could produce.
    pub fn from_axes(position: DVec3, forward_raw: DVec3, starboard_raw: DVec3) -> Self {
        let forward = forward_raw.try_normalize().unwrap_or(DVec3::X);
        // up = starboard × forward, then starboard = forward × up: orthonormal and
        // right-handed whatever the inputs' skew.
        let up = starboard_raw.cross(forward).try_normalize().unwrap_or_else(|| {
            // Starboard parallel to forward (or zero): any up perpendicular to forward will
            // do; world up projected off forward, else world z.
            (DVec3::Y - forward * forward.y).try_normalize().unwrap_or(DVec3::Z)
        });
        let starboard = forward.cross(up);
        Self { position, forward, up, starboard }
    }

    /// The body-to-world transform: columns forward, up, starboard and the position, so a
    /// mesh modelled in the body frame (module doc) is drawn in place by
    /// `model_matrix() · (x, y, z, 1)`.
    pub fn model_matrix(&self) -> DMat4 {
        DMat4::from_cols(
            self.forward.extend(0.0),
            self.up.extend(0.0),
            self.starboard.extend(0.0),
            self.position.extend(1.0),
        )
    }

    /// The bow's elevation above the horizontal plane, rad (positive: bow up).
    pub fn pitch_rad(&self) -> f64 {
        // asin of a unit vector's component; the clamp only absorbs round-off past ±1.
        self.forward.y.clamp(-1.0, 1.0).asin()
    }

    /// The heel, rad: the rotation about the forward axis, positive starboard side down — the
    /// roll of [`Self::from_angles`], which it inverts: with the bow pitched by p, starboard.y =
    /// −sin(roll)·cos(p) and up.y = cos(roll)·cos(p), so the atan2 of the two is the roll at any
    /// pitch short of vertical.
    pub fn roll_rad(&self) -> f64 {
        (-self.starboard.y).atan2(self.up.y)
    }

    /// The heading, rad: the angle of the bow's horizontal direction from world +x,
    /// anticlockwise seen from above (towards −z), in (−π, π].
    pub fn yaw_rad(&self) -> f64 {
        (-self.forward.z).atan2(self.forward.x)
    }

    /// A body-frame point in the world.
    pub fn to_world(&self, body: DVec3) -> DVec3 {
        self.position + self.forward * body.x + self.up * body.y + self.starboard * body.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_round_trip_and_matrix_maps_the_body_axes() {
        let p = BoatPose::from_angles(DVec3::new(1.0, -2.0, 3.0), 0.7, 0.2, -0.1);
        // 1e-12: a few products of sines and cosines and one asin/atan2, each ≲ 1e-15.
        assert!((p.yaw_rad() - 0.7).abs() < 1e-12, "{}", p.yaw_rad());
        assert!((p.pitch_rad() - 0.2).abs() < 1e-12, "{}", p.pitch_rad());
        assert!((p.roll_rad() + 0.1).abs() < 1e-12, "{}", p.roll_rad());
        let m = p.model_matrix();
        let bow = m.transform_point3(DVec3::X);
        assert!((bow - (p.position + p.forward)).length() < 1e-12);
        assert!((p.forward.cross(p.up) - p.starboard).length() < 1e-12);
        assert!(
            (p.to_world(DVec3::new(0.0, 0.0, 1.0)) - m.transform_point3(DVec3::Z)).length() < 1e-12
        );
    }

    #[test]
    fn positive_yaw_turns_the_bow_to_port() {
        // Port is −z when facing +x; a quarter turn anticlockwise from above faces −z.
        let p = BoatPose::from_angles(DVec3::ZERO, std::f64::consts::FRAC_PI_2, 0.0, 0.0);
        assert!((p.forward - DVec3::NEG_Z).length() < 1e-12, "{:?}", p.forward);
    }

    #[test]
    fn degenerate_axes_give_an_orthonormal_frame() {
        for (f, s) in [
            (DVec3::ZERO, DVec3::ZERO),
            (DVec3::X, DVec3::X),
            (DVec3::Y, DVec3::ZERO),
            (DVec3::NAN, DVec3::Z),
        ] {
            let p = BoatPose::from_axes(DVec3::ZERO, f, s);
            for (a, b) in [(p.forward, p.up), (p.up, p.starboard), (p.forward, p.starboard)] {
                assert!(a.dot(b).abs() < 1e-12 && (a.length() - 1.0).abs() < 1e-12, "{f} {s}");
            }
        }
    }
}

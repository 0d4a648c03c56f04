//! The camera as the render stages see it (`CameraUniforms` in `shaders/shared/camera.wgsl`).
//!
//! Camera-relative rendering: the renderer translates the world by −eye in f64 before it casts
//! anything to f32, so the eye is at the origin of every matrix here and a camera 10⁶ m from
//! the world origin loses no precision. Matrices are column-major as WGSL's `mat4x4<f32>`:
//! `m[c]` is column `c`, and `m · v = Σ_c m[c] v[c]`.
//!
//! Clip space is wgpu's: x right, y up, z in [0, 1]; with reversed Z the far plane (or
//! infinity) is z = 0.

use crate::{Error, Result};

/// The camera uniforms shared by the render stages.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CameraUniforms {
    /// Projection × view of the camera-relative world (the eye at the origin), column-major.
    pub view_proj: [[f32; 4]; 4],
    /// The inverse of `view_proj`, inverted in f64 before the cast.
    pub inv_view_proj: [[f32; 4]; 4],
    /// World position of the eye (x, y, z, 1) in f32, for effects that need an absolute
    /// position (height above the sea); imprecise far from the origin. The sky ignores it.
    pub eye: [f32; 4],
    /// Viewport (width, height, 1/width, 1/height) in pixels.
    pub viewport: [f32; 4],
}

impl CameraUniforms {
    /// The uniforms of a camera at world position `eye` whose camera-relative projection ×
    /// view matrix (column-major, f64) is `view_proj`, for a `width × height` viewport.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for an empty viewport or a singular or non-finite
    /// `view_proj`.
    pub fn new(view_proj: [[f64; 4]; 4], eye: [f64; 3], width: u32, height: u32) -> Result<Self> {
        if width == 0 || height == 0 {
            return Err(Error::InvalidParameter {
                name: "viewport",
                value: f64::from(width.min(height)),
                reason: "the viewport needs at least one pixel on each side".into(),
            });
        }
        let inv = invert(&view_proj).ok_or_else(|| Error::InvalidParameter {
            name: "view_proj",
            value: f64::NAN,
            reason: "the projection × view matrix is singular or not finite".into(),
        })?;
        let cast = |m: [[f64; 4]; 4]| m.map(|col| col.map(|v| v as f32));
        let (w, h) = (f64::from(width), f64::from(height));
        Ok(Self {
            view_proj: cast(view_proj),
            inv_view_proj: cast(inv),
            eye: [eye[0] as f32, eye[1] as f32, eye[2] as f32, 1.0],
            viewport: [w as f32, h as f32, (1.0 / w) as f32, (1.0 / h) as f32],
        })
    }
}

/// The inverse of a 4×4 matrix by Gauss–Jordan elimination with partial pivoting, in f64, or
/// `None` if it is singular (a pivot below 1e-300 in magnitude) or not finite. Rows and
/// columns may be swapped freely: the inverse of the transpose is the transpose of the
/// inverse, so the column-major layout needs no special care.
pub fn invert(m: &[[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let mut a = *m;
    let mut inv = [[0.0; 4]; 4];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for col in 0..4 {
        let pivot = (col..4).max_by(|&r, &s| a[r][col].abs().total_cmp(&a[s][col].abs()))?;
        if !(a[pivot][col].abs() > 1e-300 && a[pivot][col].is_finite()) {
            return None;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        for k in 0..4 {
            a[col][k] /= p;
            inv[col][k] /= p;
        }
        for r in 0..4 {
            if r != col {
                let f = a[r][col];
                for k in 0..4 {
                    a[r][k] -= f * a[col][k];
                    inv[r][k] -= f * inv[col][k];
                }
            }
        }
    }
    inv.iter().flatten().all(|v| v.is_finite()).then_some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
        std::array::from_fn(|c| std::array::from_fn(|r| (0..4).map(|k| a[k][r] * b[c][k]).sum()))
    }

    #[test]
    fn inverse_times_matrix_is_identity() {
        let m = [
            [2.0, 0.5, 0.0, 1.0],
            [0.0, 3.0, 1.0, 0.0],
            [1.0, 0.0, -1.0, 0.25],
            [0.0, 2.0, 0.0, 4.0],
        ];
        let p = mul(&invert(&m).unwrap(), &m);
        for (c, col) in p.iter().enumerate() {
            for (r, v) in col.iter().enumerate() {
                let want = if r == c { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-14, "({r}, {c}) = {v}");
            }
        }
    }

    #[test]
    fn singular_and_non_finite_matrices_are_rejected() {
        let mut m = [[1.0, 2.0, 3.0, 4.0]; 4];
        assert!(invert(&m).is_none());
        m = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        assert!(invert(&m).is_some());
        m[2][1] = f64::NAN;
        assert!(invert(&m).is_none());
        assert!(CameraUniforms::new(m, [0.0; 3], 4, 4).is_err());
    }

    #[test]
    fn viewport_holds_size_and_reciprocal() {
        let id = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let c = CameraUniforms::new(id, [1e6, 2.0, 3.0], 640, 480).unwrap();
        assert_eq!(c.viewport, [640.0, 480.0, 1.0 / 640.0, 1.0 / 480.0]);
        assert_eq!(c.eye, [1e6, 2.0, 3.0, 1.0]);
        assert!(CameraUniforms::new(id, [0.0; 3], 0, 480).is_err());
    }
}

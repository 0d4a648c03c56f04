//! Surface `shore_grid` (seed 004, "Surface vertices"): a grid laid on the sea plane in front of
//! the camera, turned with the camera's yaw only ("I simply don't allow to change the angle
//! between the camera and the grid"), whose rows are spaced so that each covers about the same
//! height on the screen:
//!
//! ```text
//! d_i = D/(n − 1) · (1/(1 − i/n) − 1),   i = 0 … n − 1      (d₀ = 0, d_{n−1} = D)
//! ```
//!
//! the seed's formula: 1/(d_i + D/(n − 1)) falls linearly with i, as the screen height of a
//! point on the plane falls with 1/distance for a camera looking at the horizon. Here the rows
//! start `back` metres behind the eye (so a camera looking down still sees grid under it) and
//! reach 2·(eye height)/(pixel angle) ahead of it, where the plane is within half a pixel of
//! the horizon (D is that plus `back`); each row spans the view's half-width at its distance, w(d) = w₀ + t·(d + back),
//! with t = 1.25·tan(½ horizontal fov) (the margin covers the waves' bound and the camera's
//! pitch). Its density is `[quality] projected_grid_cell_px`'s: ⌈width/cell⌉ columns and
//! ⌈height/cell⌉ rows, as the projected grid's.
//!
//! It is drawn by the projected grid's vertex-index draw (`vs_projected_grid`, whose block
//! [`ProjectedGridBlock`] then has `shore` 1 and these parameters in its corners): both are
//! screen-space grids of ⌈w/cell⌉ × ⌈h/cell⌉ quads, and the back ends draw either the same way.
//! Like the seed's, the grid moves with the camera, so the waves slide through its vertices.

use super::ProjectedGridBlock;
use crate::camera::Camera;

/// The farthest row, m, for a camera of pixel angle `pixel_angle` at `height` above the plane:
/// where the plane is half a pixel below the horizon, within [100 m, 10⁵ m].
pub fn far_distance(height: f64, pixel_angle: f64) -> f64 {
    (2.0 * height.abs().max(0.5) / pixel_angle.max(1e-9)).clamp(100.0, 1.0e5)
}

/// The block of surface `shore_grid` for `camera`, `cell_px` pixels between grid lines.
///
/// Corners: `[0]` = (f_x, f_z, r_x, r_z), the camera's horizontal forward and right;
/// `[1]` = (D/(n − 1), n, back, 0) with D = back + the far distance; `[2]` = (w₀, t, 0, 0);
/// `[3]` = 0.
pub fn block(camera: &Camera, cell_px: f64) -> ProjectedGridBlock {
    let (cols, rows) = ProjectedGridBlock::quads(camera.width, camera.height, cell_px);
    let f = camera.forward;
    // Looking straight down the forward axis has no horizontal part: the camera's up has it.
    let horizontal = if f.x.hypot(f.z) > 1e-6 { (f.x, f.z) } else { (camera.up.x, camera.up.z) };
    let len = horizontal.0.hypot(horizontal.1).max(1e-12);
    let (fx, fz) = (horizontal.0 / len, horizontal.1 / len);
    let (rx, rz) = (-fz, fx);
    let height = camera.eye.y.abs();
    let pixel = 2.0 * (0.5 * camera.fov_y).tan() / f64::from(camera.height.max(1));
    let far = far_distance(height, pixel);
    let n = f64::from(rows) + 1.0;
    let t = 1.25 * (0.5 * camera.fov_y).tan() * camera.aspect();
    let back = 2.0 * height.max(1.0);
    let w0 = 2.0 * height.max(1.0);
    let mut b = ProjectedGridBlock {
        corners: [[0.0; 4]; 4],
        cols: cols as f32,
        rows: rows as f32,
        shore: 1.0,
        cell_angle: (cell_px * pixel) as f32,
    };
    b.corners[0] = [fx as f32, fz as f32, rx as f32, rz as f32];
    // The seed's D spans back + far, so that the last row is `far` ahead of the eye.
    b.corners[1] = [((far + back) / (n - 1.0)) as f32, n as f32, back as f32, 0.0];
    b.corners[2] = [w0 as f32, t as f32, 0.0, 0.0];
    b
}

/// Row i's distance ahead of the eye, m (f64; the shader's is the same formula in f32).
pub fn row_distance(block: &ProjectedGridBlock, i: u32) -> f64 {
    let [step, n, back, _] = block.corners[1].map(f64::from);
    step * (1.0 / (1.0 - f64::from(i) / n) - 1.0) - back
}

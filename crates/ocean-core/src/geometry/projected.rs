//! The projected grid (seed 001 §3.1, Fig. 1; Johanson 2004): a regular grid in the screen
//! space of a *projector* camera, projected onto the sea plane y = 0, so the mesh's vertices
//! are spread evenly over the image instead of over the sea.
//!
//! **Projector.** It stands where the eye is, but at least [`PROJECTOR_CLEARANCE_M`] beyond
//! the wave bound A from the plane (on the eye's side), so that every projector ray meets the
//! plane in front of it, even when the eye is in the waves or on the plane. It keeps the eye's
//! heading and pitch, but looks at least [`PROJECTOR_MIN_PITCH_DEG`] towards the plane, and
//! steeply enough that every point of the range lies in front of it with room to spare (the
//! rearmost at less than half the angle the pitch leaves): an eye in the waves looking up sees
//! sea all around itself. Under the water
//! everything is mirrored in the plane (the projector looks up at the surface from below).
//!
//! **Range.** The sea the eye can see, displaced by up to ±A, lies in the slab |y| ≤ A and in
//! the eye's frustum; a vertex at plane point g is displaced vertically to g + (0, h, 0). So the
//! grid must hold the vertical projections onto the plane of that region. The region is
//! convex; a vertical projection and then a central projection from the projector map it to a
//! convex set of the projector's image plane, whose bounding box is attained at the images of
//! the region's vertices: where the frustum's edges meet the slab's two planes, the eye itself if
//! it is inside the slab, and (the frustum is infinite) where rays within the slab reach
//! [`HORIZON_DISTANCE_H`] times the eye's clearance: the sea beyond is drawn as the horizon
//! band's last row. The frustum's four edges are sampled at [`EDGE_SAMPLES`] rays each (the
//! corners exactly) and the box is widened by [`RANGE_MARGIN`] of its size.
//!
//! **Corners in homogeneous coordinates.** A projector ray through image point (x, y) is
//! D = f + x·r + y·u, and it meets the plane at P + s·D with s = −P_y/D_y. Scaled by −D_y·σ
//! (σ the side of the plane the projector is on), the point is H = (P·(−D_y) + D·P_y)·σ with
//! weight w = −D_y·σ > 0: H is affine in (x, y), so the four corners of the range in
//! homogeneous form interpolate bilinearly to every vertex exactly, and the horizon (w → 0)
//! stays finite because the range ends below it.

use bytemuck::{Pod, Zeroable};
use glam::{DVec3, DVec4};

use crate::camera::Camera;

/// The projector's least distance beyond the wave bound from the plane, m.
pub const PROJECTOR_CLEARANCE_M: f64 = 1.0;

/// The projector's least angle towards the plane, degrees.
pub const PROJECTOR_MIN_PITCH_DEG: f64 = 10.0;

/// How far the grid reaches, in multiples of the projector's height above the plane (the far
/// patch of `hu_patches` reaches ~10⁶ H too).
pub const HORIZON_DISTANCE_H: f64 = 1e6;

/// Rays sampled along each edge of the eye's frustum for the range.
pub const EDGE_SAMPLES: usize = 64;

/// The range's widening on each side, as a share of its size.
pub const RANGE_MARGIN: f64 = 0.01;

/// A projected grid for one view: where its corners lie on the sea plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedGrid {
    /// The corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1) on the plane y = 0, homogeneous and
    /// relative to the eye: (p − eye)·w and w > 0, so vertex (u, v) is the bilinear blend
    /// divided by its w.
    pub corners: [DVec4; 4],
}

impl ProjectedGrid {
    /// The grid of `camera`'s view over a sea whose surface stays within ±`wave_bound_m` of
    /// the plane and within `horizontal_m` of its undisplaced point horizontally (the choppy
    /// displacement); `None` when the eye sees no part of that slab.
    pub fn new(camera: &Camera, wave_bound_m: f64, horizontal_m: f64) -> Option<Self> {
        let a = wave_bound_m.max(0.0);
        let reach_h = horizontal_m.max(0.0);
        let eye = camera.eye;
        // Work above the water: mirror an eye below it (and its directions) in the plane.
        let side = if eye.y < 0.0 { -1.0 } else { 1.0 };
        let m = |v: DVec3| DVec3::new(v.x, v.y * side, v.z);
        let (e, forward, right) = (m(eye), m(camera.forward), m(camera.right));
        let up = m(camera.up);

        let p = DVec3::new(e.x, e.y.max(a + PROJECTOR_CLEARANCE_M), e.z);
        let heading = DVec3::Y.cross(right).normalize();
        let reach = HORIZON_DISTANCE_H * p.y;

        // The vertices of (frustum ∩ slab), projected vertically onto the plane.
        let t = (0.5 * camera.fov_y).tan();
        let (tx, ty) = (t * camera.aspect(), t);
        let mut ground = Vec::with_capacity(5 * (8 * EDGE_SAMPLES + 1));
        // Each point, and (with a choppy sea) the points the horizontal displacement could
        // bring it from, so the grid's displaced edge still reaches the view's edge.
        let mut add = |q: DVec3| {
            ground.push(DVec3::new(q.x, 0.0, q.z));
            if reach_h > 0.0 {
                for (dx, dz) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
                    ground.push(DVec3::new(q.x + dx * reach_h, 0.0, q.z + dz * reach_h));
                }
            }
        };
        if e.y <= a {
            add(e);
        }
        let n = EDGE_SAMPLES;
        for k in 0..4 * n {
            let s = (k % n) as f64 / n as f64 * 2.0 - 1.0;
            let (x, y) = match k / n {
                0 => (s, -1.0),
                1 => (1.0, s),
                2 => (-s, 1.0),
                _ => (-1.0, -s),
            };
            let d = forward + right * (x * tx) + up * (y * ty);
            // The ray's stretch inside the slab: t in [t0, t1] ∩ (0, reach along the sea].
            let horizontal = (d.x * d.x + d.z * d.z).sqrt();
            let t_max = if horizontal > 0.0 { reach / horizontal } else { f64::INFINITY };
            let (t0, t1) = if d.y == 0.0 {
                if e.y.abs() <= a { (0.0, t_max) } else { continue }
            } else {
                let (ta, tb) = ((a - e.y) / d.y, (-a - e.y) / d.y);
                (ta.min(tb).max(0.0), ta.max(tb).min(t_max))
            };
            if t0 > t1 {
                continue;
            }
            add(e + d * t0);
            add(e + d * t1);
        }
        if ground.is_empty() {
            return None;
        }
        // The projector's pitch: the eye's, at least PROJECTOR_MIN_PITCH_DEG down, and steep
        // enough that the rearmost ground point lies well in front of it (an eye looking up
        // from inside the waves sees sea all around itself).
        let behind = ground.iter().map(|g| -(*g - p).dot(heading)).fold(0.0f64, f64::max);
        let pitch = forward
            .y
            .clamp(-1.0, 1.0)
            .asin()
            .min(-PROJECTOR_MIN_PITCH_DEG.to_radians())
            .min(-(2.0 * behind / p.y).atan());
        let f_p = heading * pitch.cos() + DVec3::Y * pitch.sin();
        let u_p = right.cross(f_p);
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for g in &ground {
            let dd = *g - p;
            let z = dd.dot(f_p);
            let xy = [dd.dot(right) / z, dd.dot(u_p) / z];
            for k in 0..2 {
                lo[k] = lo[k].min(xy[k]);
                hi[k] = hi[k].max(xy[k]);
            }
        }
        if !(lo[0] < hi[0] && lo[1] < hi[1]) {
            return None;
        }
        let margin = [RANGE_MARGIN * (hi[0] - lo[0]), RANGE_MARGIN * (hi[1] - lo[1])];
        let (x0, x1) = (lo[0] - margin[0], hi[0] + margin[0]);
        // Not past the projector's horizon (where w reaches 0): the range's top stays below
        // where its rays reach twice `reach`.
        let y_horizon_cap = {
            let d_far = heading * (2.0 * reach) - DVec3::Y * p.y;
            d_far.dot(u_p) / d_far.dot(f_p)
        };
        let (y0, y1) = (lo[1] - margin[1], (hi[1] + margin[1]).min(y_horizon_cap));
        let corner = |x: f64, y: f64| {
            let d = f_p + right * x + u_p * y;
            let w = -d.y;
            let h = (p * w + d * p.y) - e * w;
            // Back to the eye's side of the plane (x, z unchanged; y is 0 on the plane).
            DVec4::new(h.x, h.y * side, h.z, w)
        };
        Some(Self { corners: [corner(x0, y0), corner(x1, y0), corner(x0, y1), corner(x1, y1)] })
    }

    /// Vertex (u, v) ∈ [0, 1]² on the plane, relative to the eye.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        let [c00, c10, c01, c11] = self.corners;
        let h = (c00 * (1.0 - u) + c10 * u) * (1.0 - v) + (c01 * (1.0 - u) + c11 * u) * v;
        h.truncate() / h.w
    }
}

/// Surface `projected_grid` ([`ProjectedGrid`]): the grid's corners and size.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ProjectedGridBlock {
    /// The corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1) on the sea plane, homogeneous and
    /// relative to the eye ((p − eye)·w, w).
    pub corners: [[f32; 4]; 4],
    /// Quads across (u); 0 when the view holds no sea or the surface is another technique.
    pub cols: f32,
    /// Quads along v.
    pub rows: f32,
    /// 1: surface `shore_grid`, whose parameters the corners hold
    /// ([`crate::geometry::shore_grid::block`]); 0: the projected grid.
    pub shore: f32,
    /// The angle between grid lines, rad (`cell_px` pixels): a vertex's spacing across the
    /// view is this times its distance (waves `coastal` fade what it cannot hold).
    pub cell_angle: f32,
}

impl ProjectedGridBlock {
    /// The margin of the wave bound over the sea's significant wave height: the crests and
    /// the horizontal (choppy) displacement stay within 3·H_s of the plane but for a chance of
    /// about e^(−18) per wave (Rayleigh crests, P(a > x) = e^(−2x²/H_s²)).
    pub const BOUND_OVER_HS: f64 = 3.0;

    /// The block of a `width` × `height` view through `camera` over a sea whose waves stay
    /// within `wave_bound` = (vertical, horizontal) m of their undisplaced point (the plan's
    /// `wave_bound_m`, [`Self::BOUND_OVER_HS`] times H_s, and that times the choppiness),
    /// `cell_px` pixels between grid lines (at most 4096 quads a side).
    pub fn new(camera: &crate::camera::Camera, wave_bound: [f64; 2], cell_px: f64) -> Self {
        // The corners' search (5 × 513 candidate points in a 60 KiB list) was two thirds of a
        // steady `chiu` frame's `prepare`, asked again every frame for the same view.
        static KEPT: crate::kept::Kept<[u64; 18], ProjectedGridBlock> = crate::kept::Kept::new();
        let c = camera;
        // The view's bits: 4 vectors of 3, the field of view, the bound, the cell, the size.
        let mut key = [0u64; 18];
        let vectors = [c.eye, c.forward, c.right, c.up];
        let bits = vectors
            .iter()
            .flat_map(|v| v.to_array())
            .chain([c.fov_y, wave_bound[0], wave_bound[1], cell_px])
            .map(f64::to_bits)
            .chain([u64::from(c.width), u64::from(c.height)]);
        for (k, b) in key.iter_mut().zip(bits) {
            *k = b;
        }
        KEPT.get(key, || Self::make(camera, wave_bound, cell_px))
    }

    /// [`Self::new`], made anew.
    fn make(camera: &crate::camera::Camera, wave_bound: [f64; 2], cell_px: f64) -> Self {
        let Some(grid) = ProjectedGrid::new(camera, wave_bound[0], wave_bound[1]) else {
            return Self::zeroed();
        };
        let (cols, rows) = Self::quads(camera.width, camera.height, cell_px);
        Self {
            corners: grid.corners.map(|c| c.as_vec4().to_array()),
            cols: cols as f32,
            rows: rows as f32,
            shore: 0.0,
            cell_angle: (cell_px * camera.pixel_angle()) as f32,
        }
    }

    /// The grid's quads across and along for a `width` × `height` image, `cell_px` pixels
    /// between lines: ⌈width/cell⌉ × ⌈height/cell⌉, each from 1 to 4096.
    pub fn quads(width: u32, height: u32, cell_px: f64) -> (u32, u32) {
        let q = |px: u32| (f64::from(px) / cell_px).ceil().clamp(1.0, 4096.0) as u32;
        (q(width), q(height))
    }

    /// Vertices the water pass draws (a triangle list, six per quad).
    pub fn vertex_count(&self) -> u32 {
        6 * self.cols as u32 * self.rows as u32
    }
}

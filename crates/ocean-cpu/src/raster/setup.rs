//! Triangle setup: from three clipped vertices to edge functions, a pixel bounding box and the
//! per-vertex data the interpolation needs.

use super::Vertex;
use super::edge::Edge;
use super::fixed_point::{FIXED_HALF, FIXED_ONE, to_framebuffer};
use super::state::{CullMode, FrontFace, RasterState};

/// A triangle ready to rasterize. Vertex order is the submitted one (the orientation is folded
/// into the edge functions), so interpolation sums in submission order whatever the winding.
#[derive(Clone, Copy, Debug)]
pub struct TriangleSetup<const V: usize> {
    /// `edges[i]` is the edge opposite vertex i: its value is vertex i's barycentric weight
    /// times twice the area. `edges[0]`: v1→v2, `edges[1]`: v2→v0, `edges[2]`: v0→v1.
    pub edges: [Edge; 3],
    /// Inclusive pixel bounding box of the covered pixel centres, clamped to the target:
    /// `[x0, y0, x1, y1]`.
    pub bbox: [u32; 4],
    /// `1 / (twice the area in snapped units²)`, in f32.
    pub inv_area: f32,
    /// Framebuffer depth (z_ndc) of each vertex.
    pub z: [f32; 3],
    /// 1 / w_clip of each vertex.
    pub inv_w: [f32; 3],
    /// Varyings of each vertex.
    pub varyings: [[f32; V]; 3],
    /// Whether the triangle is front-facing under the state's [`FrontFace`].
    pub front_facing: bool,
}

/// Sets up one clipped triangle. `None` when it has zero area after snapping, is culled, or
/// covers no pixel centre of the target.
pub fn setup_triangle<const V: usize>(
    tri: &[Vertex<V>; 3],
    state: &RasterState,
    width: u32,
    height: u32,
) -> Option<TriangleSetup<V>> {
    let s = tri.map(|v| to_framebuffer(v.clip, width, height));
    let p = s.map(|v| (v.x, v.y));

    // Twice the signed area, framebuffer y down: > 0 is clockwise on screen.
    let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
    if area == 0 {
        return None;
    }
    let ccw_on_screen = area < 0;
    let front_facing = match state.front_face {
        FrontFace::Ccw => ccw_on_screen,
        FrontFace::Cw => !ccw_on_screen,
    };
    let culled = match state.cull_mode {
        CullMode::None => false,
        CullMode::Front => front_facing,
        CullMode::Back => !front_facing,
    };
    if culled {
        return None;
    }

    let sign = area.signum();
    let edges =
        [Edge::new(p[1], p[2], sign), Edge::new(p[2], p[0], sign), Edge::new(p[0], p[1], sign)];
    debug_assert_eq!(
        edges[0].at(0, 0) + edges[1].at(0, 0) + edges[2].at(0, 0),
        area.abs(),
        "edge functions sum to twice the area everywhere"
    );

    // Pixel x is sampled at x·FIXED_ONE + FIXED_HALF: the first centre ≥ min and the last ≤ max.
    let min_x = p.iter().map(|q| q.0).min()?;
    let max_x = p.iter().map(|q| q.0).max()?;
    let min_y = p.iter().map(|q| q.1).min()?;
    let max_y = p.iter().map(|q| q.1).max()?;
    let first = |lo: i64| -((FIXED_HALF - lo).div_euclid(FIXED_ONE)); // ceil((lo − ½)/1)
    let last = |hi: i64| (hi - FIXED_HALF).div_euclid(FIXED_ONE);
    let x0 = first(min_x).max(0);
    let y0 = first(min_y).max(0);
    let x1 = last(max_x).min(i64::from(width) - 1);
    let y1 = last(max_y).min(i64::from(height) - 1);
    if x0 > x1 || y0 > y1 {
        return None;
    }

    Some(TriangleSetup {
        edges,
        bbox: [x0, y0, x1, y1].map(|c| c as u32),
        inv_area: 1.0 / area.abs() as f32,
        z: s.map(|v| v.z),
        inv_w: s.map(|v| v.inv_w),
        varyings: tri.map(|v| v.varyings),
        front_facing,
    })
}

//! Rasterization of one band of rows: coverage, interpolation, depth test, shading, blending.
//!
//! Bands are disjoint slices of the target; each walks its triangles in submission order, so
//! every pixel sees exactly the sequence of fragments the serial algorithm would give it,
//! whatever thread runs the band.

use super::FragmentInput;
use super::setup::TriangleSetup;
use super::state::RasterState;

/// Rows per band: small enough to balance a few threads on a 1080p frame, large enough that
/// binning stays cheap.
pub const BAND_ROWS: u32 = 16;

/// Where a band lies in the target.
#[derive(Clone, Copy, Debug)]
pub struct Band {
    /// First row of the band.
    pub y0: u32,
    /// Rows in the band (the last band may be shorter).
    pub rows: u32,
    /// Target width.
    pub width: u32,
}

/// Rasterizes the triangles `bin` (indices into `tris`, increasing) into one band's colour and
/// depth rows.
pub fn raster_band<const V: usize, F>(
    band: Band,
    color: &mut [[f32; 4]],
    depth: &mut [f32],
    tris: &[TriangleSetup<V>],
    bin: &[usize],
    state: &RasterState,
    shader: &F,
) where
    F: Fn(&FragmentInput<V>) -> Option<[f32; 4]> + Sync,
{
    debug_assert_eq!(color.len(), (band.rows * band.width) as usize);
    debug_assert!(bin.windows(2).all(|w| w[0] < w[1]), "submission order");
    let band_y1 = band.y0 + band.rows - 1;
    for tri in bin.iter().map(|&i| &tris[i]) {
        let [bx0, by0, bx1, by1] = tri.bbox;
        for y in by0.max(band.y0)..=by1.min(band_y1) {
            let row = ((y - band.y0) * band.width) as usize;
            let yi = i64::from(y);
            let mut span = (i64::from(bx0), i64::from(bx1));
            for edge in &tri.edges {
                span = edge.clip_span(yi, span.0, span.1);
            }
            for x in span.0..=span.1 {
                let i = row + x as usize;
                shade_pixel(x, yi, tri, &mut color[i], &mut depth[i], state, shader);
            }
        }
    }
}

/// One covered pixel centre. The order of operations here is part of the contract (the GPU
/// cross-check depends on it):
///
/// ```text
/// e_i  = edge_i(pixel centre)                    exact i64, e0 + e1 + e2 = 2·area
/// b_i  = (e_i as f32) · inv_area                 inv_area = 1 / (2·area as f32)
/// z    = (b0·z0 + b1·z1) + b2·z2, clamped to [0, 1]   (screen-space linear, like Vulkan)
/// f_i  = b_i · inv_w_i
/// s    = (f0 + f1) + f2                          (= frag_coord.w, the interpolated 1/w)
/// p_i  = f_i · (1 / s)
/// v[k] = (p0·v0[k] + p1·v1[k]) + p2·v2[k]        (perspective-correct)
/// ```
///
/// The depth test runs before the shader (the shader cannot write depth and its result does
/// not depend on whether it ran, so this equals the late test); a discarded fragment writes
/// nothing.
#[inline]
fn shade_pixel<const V: usize, F>(
    x: i64,
    y: i64,
    tri: &TriangleSetup<V>,
    color: &mut [f32; 4],
    depth: &mut f32,
    state: &RasterState,
    shader: &F,
) where
    F: Fn(&FragmentInput<V>) -> Option<[f32; 4]>,
{
    let e = tri.edges.map(|edge| edge.at(x, y));
    debug_assert!(
        e.iter().zip(&tri.edges).all(|(v, edge)| v - edge.bias >= 0),
        "pixel ({x}, {y}) is not covered"
    );
    let b = e.map(|v| v as f32 * tri.inv_area);
    let z = (b[0] * tri.z[0] + b[1] * tri.z[1]) + b[2] * tri.z[2];
    let frag_depth = z.clamp(0.0, 1.0);
    if !state.depth_compare.passes(frag_depth, *depth) {
        return;
    }

    let f = [0, 1, 2].map(|i| b[i] * tri.inv_w[i]);
    let s = (f[0] + f[1]) + f[2];
    let inv_s = 1.0 / s;
    let p = f.map(|fi| fi * inv_s);
    let [v0, v1, v2] = &tri.varyings;
    let input = FragmentInput {
        frag_coord: [x as f32 + 0.5, y as f32 + 0.5, frag_depth, s],
        varyings: std::array::from_fn(|k| (p[0] * v0[k] + p[1] * v1[k]) + p[2] * v2[k]),
        front_facing: tri.front_facing,
    };
    let Some(src) = shader(&input) else {
        return;
    };
    if state.depth_write {
        *depth = frag_depth;
    }
    *color = state.blend.apply(src, *color);
}

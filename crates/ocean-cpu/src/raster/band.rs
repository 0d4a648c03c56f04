//! Rasterization of one band of rows: coverage, interpolation, depth test, shading, blending.
//!
//! Bands are disjoint slices of the target; each walks its triangles in submission order, so
//! every pixel sees exactly the sequence of fragments the serial algorithm would give it,
//! whatever thread runs the band.

use ocean_core::frame_format::FrameFormat;

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
    /// The target's colour format: what a blended colour is stored as.
    pub format: FrameFormat,
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
    for tri in bin.iter().map(|&i| &tris[i]) {
        for_each_covered(band, tri, |i, x, y| {
            if let Some(c) = shade_pixel(x, y, tri, color[i], &mut depth[i], state, shader) {
                // Blending read the stored value and worked in f32; the result is stored in
                // the target's format (truncated to binary16 for `rgba16float`), as the GPU's
                // blend unit writes it.
                color[i] = band.format.store4(c);
            }
        });
    }
}

/// Calls `f(i, x, y)` for every pixel centre of `band` that `tri` covers, row by row and left
/// to right: `i` the pixel's index in the band's rows, (x, y) its integer coordinates.
#[inline]
fn for_each_covered<const V: usize>(
    band: Band,
    tri: &TriangleSetup<V>,
    mut f: impl FnMut(usize, i64, i64),
) {
    let [bx0, by0, bx1, by1] = tri.bbox;
    for y in by0.max(band.y0)..=by1.min(band.y0 + band.rows - 1) {
        let row = ((y - band.y0) * band.width) as usize;
        let yi = i64::from(y);
        let mut span = (i64::from(bx0), i64::from(bx1));
        for edge in &tri.edges {
            span = edge.clip_span(yi, span.0, span.1);
        }
        for x in span.0..=span.1 {
            f(row + x as usize, x, yi);
        }
    }
}

/// One covered pixel centre. The order of operations here is part of the contract (the GPU
/// cross-check depends on it; [`super::setup::Plane`] has lavapipe's plane setup):
///
/// ```text
/// z    = fma(dz/dy, y, fma(dz/dx, x, z0)), clamped to [0, 1]   (linear in screen space)
/// s    = the same for 1/w                   (= frag_coord.w)
/// v[k] = plane_k(x, y) · (1 / s)           plane_k of v[k]/w: perspective-correct
/// ```
///
/// with x, y the integer pixel coordinates. The depth test runs before the shader (the shader
/// cannot write depth and its result does not depend on whether it ran, so this equals the
/// late test); a discarded fragment writes nothing (`None`); otherwise the blended colour.
#[inline]
fn shade_pixel<const V: usize, F>(
    x: i64,
    y: i64,
    tri: &TriangleSetup<V>,
    color: [f32; 4],
    depth: &mut f32,
    state: &RasterState,
    shader: &F,
) -> Option<[f32; 4]>
where
    F: Fn(&FragmentInput<V>) -> Option<[f32; 4]>,
{
    debug_assert!(
        tri.edges.iter().all(|edge| edge.at(x, y) - edge.bias >= 0),
        "pixel ({x}, {y}) is not covered"
    );
    let (xf, yf) = (x as f32, y as f32);
    let z = tri.z.at(xf, yf);
    let frag_depth = z.clamp(0.0, 1.0);
    if !state.depth_compare.passes(frag_depth, *depth) {
        return None;
    }

    let src = shader(&fragment_input(xf, yf, frag_depth, tri))?;
    if state.depth_write {
        *depth = frag_depth;
    }
    Some(state.blend.apply(src, color))
}

/// The shader's input at pixel (x, y) of `tri` with the tested depth `frag_depth`.
#[inline]
fn fragment_input<const V: usize>(
    xf: f32,
    yf: f32,
    frag_depth: f32,
    tri: &TriangleSetup<V>,
) -> FragmentInput<V> {
    let s = tri.inv_w.at(xf, yf);
    let inv_s = 1.0 / s;
    FragmentInput {
        frag_coord: [xf + 0.5, yf + 0.5, frag_depth, s],
        varyings: std::array::from_fn(|k| tri.varyings[k].at(xf, yf) * inv_s),
        front_facing: tri.front_facing,
    }
}

/// [`raster_band`] for a shader that never discards under [`super::BlendMode::Replace`]: a
/// pixel's colour is then the last fragment that passed its depth test, whatever the ones
/// before it were, so the band runs every depth test first (in submission order, writing
/// depth as the serial algorithm does) and shades only each pixel's last passing fragment,
/// once, with the same input. Bit-identical to [`raster_band`] for a pure shader; the
/// overdrawn fragments cost a depth test instead of a shading.
pub fn raster_band_visible<const V: usize, F>(
    band: Band,
    color: &mut [[f32; 4]],
    depth: &mut [f32],
    tris: &[TriangleSetup<V>],
    bin: &[usize],
    state: &RasterState,
    shader: &F,
) where
    F: Fn(&FragmentInput<V>) -> [f32; 4] + Sync,
{
    debug_assert_eq!(color.len(), (band.rows * band.width) as usize);
    debug_assert!(matches!(state.blend, super::BlendMode::Replace));
    const NONE: u32 = u32::MAX;
    thread_local! {
        /// Each pixel's last passing triangle, kept per thread across bands and draws (taken
        /// out while in use, so a re-entrant band on this thread allocates its own).
        static LAST: std::cell::Cell<Vec<u32>> = const { std::cell::Cell::new(Vec::new()) };
    }
    let mut last = LAST.take();
    last.clear();
    last.resize(color.len(), NONE);
    for &t in bin {
        let tri = &tris[t];
        for_each_covered(band, tri, |i, x, y| {
            let frag_depth = tri.z.at(x as f32, y as f32).clamp(0.0, 1.0);
            if state.depth_compare.passes(frag_depth, depth[i]) {
                if state.depth_write {
                    depth[i] = frag_depth;
                }
                last[i] = t as u32;
            }
        });
    }
    for (i, &t) in last.iter().enumerate() {
        if t == NONE {
            continue;
        }
        let tri = &tris[t as usize];
        let (x, y) = (i as u32 % band.width, band.y0 + i as u32 / band.width);
        let (xf, yf) = (x as f32, y as f32);
        let frag_depth = tri.z.at(xf, yf).clamp(0.0, 1.0);
        let src = shader(&fragment_input(xf, yf, frag_depth, tri));
        color[i] = band.format.store4(state.blend.apply(src, color[i]));
    }
    LAST.set(last);
}

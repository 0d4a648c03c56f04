//! A triangle rasterizer with Vulkan's rules, as Mesa's lavapipe (llvmpipe) implements them.
//!
//! Pipeline, per triangle, in submission order:
//!
//! 1. **Clip** in clip space to `−w ≤ x, y ≤ w`, `0 ≤ z ≤ w` the way Mesa's draw module does
//!    (`clip.rs`); varyings of new vertices are interpolated linearly in clip space. A triangle
//!    with a NaN, infinite or enormous (beyond ±[`MAX_CLIP_COORD`] ≈ 4e37) clip coordinate is
//!    dropped. The clipped convex polygon is fanned from its first vertex.
//! 2. **Viewport transform** of wgpu on Vulkan: NDC x right, y up, z in [0, 1];
//!    `x_fb = (x/w + 1)·W/2`, `y_fb = (1 − y/w)·H/2` (framebuffer y down), `z_fb = z/w`
//!    (`fixed_point.rs` has lavapipe's exact order of operations).
//! 3. **Snap** x_fb, y_fb to 1/256 pixel, round half to even (`fixed_point.rs`).
//! 4. **Cull** on the sign of the snapped area ([`FrontFace`] documents the winding); zero-area
//!    triangles are dropped.
//! 5. **Coverage**: pixel (x, y) is sampled at its centre (x + ½, y + ½); exact i64 edge
//!    functions with the top-left rule (`edge.rs`).
//! 6. **Interpolation**: lavapipe's plane equations from the unsnapped positions, anchored at
//!    pixel (0, 0) (`setup.rs`), depth linear in screen space, varyings perspective-correct
//!    (the formulas are on `shade_pixel` in `band.rs`); bit for bit what lavapipe computes.
//! 7. **Depth test** on the f32 depth buffer, **shading** by a closure (which may discard),
//!    **blending** into the RGBA target, stored in its format (f32, or rounded to binary16).
//!
//! Parallelism: the target is split into bands of [`BAND_ROWS`] rows; each band draws the
//! triangles that overlap it, in submission order, on whatever rayon thread runs it. Bands are
//! disjoint and floats are never reduced across them, so the image is bit-identical for any
//! number of threads. Triangle setup runs in parallel too and is collected in order. The draw
//! runs on the current rayon pool (use `ThreadPool::install` to choose one).

mod band;
mod clip;
mod edge;
mod fixed_point;
mod setup;
mod state;
mod target;

use rayon::prelude::*;

pub use band::BAND_ROWS;
pub use clip::{MAX_CLIP_COORD, W_MIN};
pub use fixed_point::SUBPIXEL_BITS;
pub use state::{BlendMode, CompareFunction, CullMode, FrontFace, RasterState};
pub use target::RenderTarget;

use band::{Band, raster_band, raster_band_visible};
use setup::{TriangleSetup, setup_triangle};

/// A vertex as a vertex shader outputs it: the clip-space position (`@builtin(position)`) and
/// `V` f32 varyings (the `@location` outputs, flattened).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex<const V: usize> {
    /// Clip-space position (x, y, z, w), wgpu conventions.
    pub clip: [f32; 4],
    /// Varyings, interpolated perspective-correctly.
    pub varyings: [f32; V],
}

impl<const V: usize> Vertex<V> {
    /// The vertex at the clip-space origin with zero varyings.
    pub const ZERO: Self = Self { clip: [0.0; 4], varyings: [0.0; V] };

    /// A vertex from its clip position and varyings.
    pub const fn new(clip: [f32; 4], varyings: [f32; V]) -> Self {
        Self { clip, varyings }
    }
}

/// What a fragment shader receives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FragmentInput<const V: usize> {
    /// `@builtin(position)`: (x + 0.5, y + 0.5, depth, interpolated 1/w_clip).
    pub frag_coord: [f32; 4],
    /// The interpolated varyings.
    pub varyings: [f32; V],
    /// `@builtin(front_facing)`.
    pub front_facing: bool,
}

/// Draws a triangle list.
///
/// `shader` returns the fragment's RGBA colour, or `None` to discard it. It runs on rayon
/// threads, in no particular order across bands: it must be a pure function of its input for
/// the result to be deterministic.
pub fn draw<const V: usize, F>(
    target: &mut RenderTarget,
    state: &RasterState,
    triangles: &[[Vertex<V>; 3]],
    shader: F,
) where
    F: Fn(&FragmentInput<V>) -> Option<[f32; 4]> + Sync,
{
    draw_with(target, state, triangles.len(), |i| triangles[i], shader);
}

/// Draws an indexed triangle list: triangle `i` is `vertices[indices[i][0..3]]`.
///
/// # Panics
/// If an index is out of range of `vertices`.
pub fn draw_indexed<const V: usize, F>(
    target: &mut RenderTarget,
    state: &RasterState,
    vertices: &[Vertex<V>],
    indices: &[[u32; 3]],
    shader: F,
) where
    F: Fn(&FragmentInput<V>) -> Option<[f32; 4]> + Sync,
{
    draw_with(target, state, indices.len(), |i| indices[i].map(|k| vertices[k as usize]), shader);
}

/// [`draw_indexed`] of a shader that never discards, under [`BlendMode::Replace`]: each
/// pixel is shaded once, for the last fragment that passes its depth test (every depth test
/// runs first, in submission order). The same target, bit for bit, as [`draw_indexed`] with
/// `Some(shader(..))` for a pure shader, with the overdraw's shading left out.
///
/// # Panics
/// If an index is out of range of `vertices`, or the state blends (only `Replace` makes the
/// last passing fragment the whole story).
pub fn draw_indexed_visible<const V: usize, F>(
    target: &mut RenderTarget,
    state: &RasterState,
    vertices: &[Vertex<V>],
    indices: &[[u32; 3]],
    shader: F,
) where
    F: Fn(&FragmentInput<V>) -> [f32; 4] + Sync,
{
    assert!(matches!(state.blend, BlendMode::Replace), "draw_indexed_visible blends nothing");
    let fetch = |i: usize| indices[i].map(|k| vertices[k as usize]);
    let Some((tris, bins)) = bin_triangles(target, state, indices.len(), fetch) else { return };
    for_each_band(target, &bins, |band, color, depth, bin| {
        raster_band_visible(band, color, depth, &tris, bin, state, &shader);
    });
}

/// Runs `draw` on every band of the target in parallel, with the band's rows of colour and
/// depth and its bin of triangles.
fn for_each_band(
    target: &mut RenderTarget,
    bins: &[Vec<usize>],
    draw: impl Fn(Band, &mut [[f32; 4]], &mut [f32], &[usize]) + Sync,
) {
    let (width, height, format) = (target.width, target.height, target.format);
    let band_len = (BAND_ROWS * width) as usize;
    target
        .color
        .par_chunks_mut(band_len)
        .zip(target.depth.par_chunks_mut(band_len))
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(k, ((color, depth), bin))| {
            let y0 = k as u32 * BAND_ROWS;
            draw(Band { y0, rows: BAND_ROWS.min(height - y0), width, format }, color, depth, bin);
        });
}

/// The triangles set up (in parallel, collected in order) and binned into bands; `None` for
/// an empty target.
///
/// # Panics
/// If the target is beyond [`RenderTarget::MAX_SIZE`] or its buffers do not match its size.
#[allow(clippy::type_complexity, reason = "the triangles and their bins, used together")]
fn bin_triangles<const V: usize>(
    target: &RenderTarget,
    state: &RasterState,
    count: usize,
    fetch: impl Fn(usize) -> [Vertex<V>; 3] + Sync,
) -> Option<(Vec<TriangleSetup<V>>, Vec<Vec<usize>>)> {
    let (width, height) = (target.width, target.height);
    let pixels = width as usize * height as usize;
    assert!(
        width <= RenderTarget::MAX_SIZE && height <= RenderTarget::MAX_SIZE,
        "render target {width}x{height} exceeds {} pixels per side",
        RenderTarget::MAX_SIZE
    );
    assert!(
        target.color.len() == pixels && target.depth.len() == pixels,
        "render target buffers do not match {width}x{height}"
    );
    if pixels == 0 {
        return None;
    }

    let tris: Vec<TriangleSetup<V>> = (0..count)
        .into_par_iter()
        .flat_map_iter(|i| {
            clip::clip_triangle(fetch(i))
                .fan()
                .filter_map(|t| setup_triangle(&t, state, width, height))
        })
        .collect();

    let bands = height.div_ceil(BAND_ROWS) as usize;
    let mut bins: Vec<Vec<usize>> = vec![Vec::new(); bands];
    for (i, tri) in tris.iter().enumerate() {
        let [_, y0, _, y1] = tri.bbox;
        for bin in &mut bins[(y0 / BAND_ROWS) as usize..=(y1 / BAND_ROWS) as usize] {
            bin.push(i);
        }
    }
    Some((tris, bins))
}

/// The draw: parallel setup (collected in order), binning into bands, parallel bands.
fn draw_with<const V: usize, F>(
    target: &mut RenderTarget,
    state: &RasterState,
    count: usize,
    fetch: impl Fn(usize) -> [Vertex<V>; 3] + Sync,
    shader: F,
) where
    F: Fn(&FragmentInput<V>) -> Option<[f32; 4]> + Sync,
{
    let Some((tris, bins)) = bin_triangles(target, state, count, fetch) else { return };
    for_each_band(target, &bins, |band, color, depth, bin| {
        raster_band(band, color, depth, &tris, bin, state, &shader);
    });
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;

    /// Random overlapping triangles at random depths (some poking out of the view, so that
    /// clipping runs too) and their indices.
    fn scene(count: usize) -> (Vec<Vertex<3>>, Vec<[u32; 3]>) {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut unit = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 40) as f32 / (1u64 << 24) as f32
        };
        let vertices: Vec<Vertex<3>> = (0..3 * count)
            .map(|_| {
                let w = 0.5 + 2.0 * unit();
                let clip = [(2.4 * unit() - 1.2) * w, (2.4 * unit() - 1.2) * w, unit() * w, w];
                Vertex::new(clip, [unit(), unit(), 8.0 * unit()])
            })
            .collect();
        let indices = (0..count as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        (vertices, indices)
    }

    fn shade(f: &FragmentInput<3>) -> [f32; 4] {
        let [x, y, z, s] = f.frag_coord;
        let [a, b, c] = f.varyings;
        [a * z + x * 1e-3, b.mul_add(s, y * 1e-3), c.sin(), if f.front_facing { 1.0 } else { 0.5 }]
    }

    /// A target cleared as the eye's views are (reversed Z: depth 0).
    fn target() -> RenderTarget {
        let mut t = RenderTarget::new(67, 45);
        t.clear_depth(0.0);
        t
    }

    fn bits(t: &RenderTarget) -> Vec<u32> {
        t.color.iter().flatten().chain(&t.depth).map(|v| v.to_bits()).collect()
    }

    #[test]
    fn shading_only_the_last_passing_fragment_gives_the_same_target() {
        let state = RasterState {
            depth_compare: CompareFunction::Greater,
            cull_mode: CullMode::None,
            ..RasterState::default()
        };
        let (vertices, indices) = scene(60);
        let (serial_calls, visible_calls) = (AtomicUsize::new(0), AtomicUsize::new(0));
        let mut serial = target();
        draw_indexed(&mut serial, &state, &vertices, &indices, |f| {
            serial_calls.fetch_add(1, Ordering::Relaxed);
            Some(shade(f))
        });
        let mut visible = target();
        draw_indexed_visible(&mut visible, &state, &vertices, &indices, |f| {
            visible_calls.fetch_add(1, Ordering::Relaxed);
            shade(f)
        });
        assert!(bits(&serial) == bits(&visible), "the targets differ");
        let (serial_calls, visible_calls) = (serial_calls.into_inner(), visible_calls.into_inner());
        // The scene overdraws, so the check saw hidden fragments left out.
        assert!(visible_calls <= 67 * 45 && serial_calls > visible_calls + 500, "{serial_calls}");

        // Control: the comparison sees one triangle fewer.
        let mut fewer = target();
        draw_indexed_visible(&mut fewer, &state, &vertices, &indices[1..], shade);
        assert!(bits(&fewer) != bits(&visible), "a missing triangle went unseen");
    }
}

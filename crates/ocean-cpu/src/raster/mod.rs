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

use band::{Band, raster_band};
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
        return;
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

    let band_len = (BAND_ROWS * width) as usize;
    let format = target.format;
    target
        .color
        .par_chunks_mut(band_len)
        .zip(target.depth.par_chunks_mut(band_len))
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(k, ((color, depth), bin))| {
            let y0 = k as u32 * BAND_ROWS;
            let band = Band { y0, rows: BAND_ROWS.min(height - y0), width, format };
            raster_band(band, color, depth, &tris, bin, state, &shader);
        });
}

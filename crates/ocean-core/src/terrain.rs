//! The sea floor (`[terrain]`, docs/design.md): its height anywhere, its drawn mesh and what the
//! shaders need of it (the uniforms of [`TerrainBlock`] and the relief map).
//!
//! The floor is a plane — `depth_m` below the sea plane at `center`, rising by `slope` towards
//! `slope_direction_deg` — plus, for `kind = "heightmap"`, a relief read from a 16-bit
//! grayscale PNG or an EXR: a sample v maps linearly onto `height_range_m` (v = 0 → the
//! first value, v = 1 → the second) and is added to the plane. The map covers the square of
//! side `extent_m` about `center` with its outermost texel centres on the square's edges:
//! column i lies at x = x₀ + i·extent/(W − 1), row j (the image's top row first) at
//! z = z₀ + j·extent/(H − 1). Between texel centres the height is bilinear; beyond the
//! square it is the edge's (clamp to edge), which is how both back ends sample the map.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::geometry::ObjectVertex;

use serde::{Deserialize, Serialize};

/// The largest relief map side, texels (a 16384² f32 RGBA texture is 4 GiB).
pub const MAX_RELIEF_SIDE: u32 = 8192;
/// Quads per side of a plane floor's drawn square (a plane: more would only cost).
pub const TERRAIN_QUADS: u32 = 8;
/// The most quads per side of a relief's mesh; a larger map is drawn through every k-th texel
/// (its shading and eq. 8's depth still read every texel).
pub const MAX_RELIEF_QUADS: u32 = 256;
/// Steps of the relief's self-shadow march (shared/floor.wgsl `relief_sun`), half a texel
/// each: 48 texels of shadow at most, which a sun 41° up under the water (the lowest there is)
/// casts from a ridge 42 texels tall.
pub const RELIEF_SHADOW_STEPS: u32 = 96;

/// A relief map: heights in metres (the v of the file already mapped onto `height_range_m`),
/// as f32 because that is what both back ends sample.
#[derive(Clone, PartialEq)]
pub struct Relief {
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Row-major heights, m; row 0 at the square's lowest z.
    pub heights: Vec<f32>,
    /// The lowest and highest texel, m.
    pub range: (f32, f32),
}

impl fmt::Debug for Relief {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Relief {}×{} in [{}, {}] m", self.width, self.height, self.range.0, self.range.1)
    }
}

impl Relief {
    /// A relief from normalised samples v (row-major, `width × height`), v ↦ lo + v·(hi − lo).
    ///
    /// # Errors
    /// A message when the size is zero or too large, the count is wrong, or a sample or the
    /// height it maps to is not finite (an EXR sample of 3e38 is finite, but its height in
    /// f32 is not: the floor would be infinite, and vanish).
    pub fn from_normalised(
        width: u32,
        height: u32,
        v: impl ExactSizeIterator<Item = f64>,
        range: [f64; 2],
    ) -> Result<Self, String> {
        if width == 0 || height == 0 || width > MAX_RELIEF_SIDE || height > MAX_RELIEF_SIDE {
            return Err(format!(
                "a heightmap must be 1 to {MAX_RELIEF_SIDE} texels per side, got {width}×{height}"
            ));
        }
        if v.len() != width as usize * height as usize {
            return Err(format!("{width}×{height} texels need {} samples", width * height));
        }
        let mut heights = Vec::with_capacity(v.len());
        for (i, s) in v.enumerate() {
            let h = (range[0] + s * (range[1] - range[0])) as f32;
            if !h.is_finite() {
                let (x, y) = (i % width as usize, i / width as usize);
                return Err(if s.is_finite() {
                    format!(
                        "the heightmap's texel ({x}, {y}) = {s:e} maps to a height beyond f32's \
                         range ({:e} m, with height_range_m {range:?})",
                        range[0] + s * (range[1] - range[0])
                    )
                } else {
                    format!("the heightmap's texel ({x}, {y}) is not finite")
                });
            }
            heights.push(h);
        }
        Ok(Self::from_heights(width, height, heights))
    }

    /// A relief of `width × height` heights in metres (row-major, checked by the caller),
    /// its range found here.
    fn from_heights(width: u32, height: u32, heights: Vec<f32>) -> Self {
        let lo = heights.iter().copied().fold(f32::INFINITY, f32::min);
        let hi = heights.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        Self { width, height, heights, range: (lo, hi) }
    }

    /// Reads a 16-bit grayscale PNG (v = value/65535) or an EXR (v = the first layer's `Y`,
    /// `R` or only channel, as stored) and maps it onto `range`.
    ///
    /// # Errors
    /// A message naming the file: unreadable, not a 16-bit grayscale PNG nor an EXR, or as
    /// [`Self::from_normalised`].
    pub fn load(path: &Path, range: [f64; 2]) -> Result<Self, String> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => read_png16(path, range),
            Some("exr") => read_exr(path, range),
            _ => Err(format!(
                "{}: a heightmap is a 16-bit grayscale .png or an .exr",
                path.display()
            )),
        }
    }

    /// Texel (i, j), clamped to the map.
    pub fn texel(&self, i: i64, j: i64) -> f32 {
        let i = i.clamp(0, i64::from(self.width) - 1) as usize;
        let j = j.clamp(0, i64::from(self.height) - 1) as usize;
        self.heights[j * self.width as usize + i]
    }

    /// The bilinear height at texture coordinates (u, v) (texel centres at (i + ½)/W),
    /// clamped to the edge, in f64.
    pub fn sample(&self, u: f64, v: f64) -> f64 {
        let x = u * f64::from(self.width) - 0.5;
        let y = v * f64::from(self.height) - 0.5;
        let (i, j) = (x.floor(), y.floor());
        let (fx, fy) = (x - i, y - j);
        let (i, j) = (i as i64, j as i64);
        let t = |a: i64, b: i64| f64::from(self.texel(a, b));
        let top = t(i, j) * (1.0 - fx) + t(i + 1, j) * fx;
        let bottom = t(i, j + 1) * (1.0 - fx) + t(i + 1, j + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

/// Reads a 16-bit grayscale PNG heightmap: its header first (size and the memory decoding
/// takes, 2 bytes a texel decoded + 4 for the relief's f32), then its pixels.
fn read_png16(path: &Path, range: [f64; 2]) -> Result<Relief, String> {
    let size = crate::input::png_size(path)?;
    crate::input::check_image_size(path, size, u64::from(MAX_RELIEF_SIDE), 2 + 4)?;
    match crate::input::decode_png(path)? {
        image::DynamicImage::ImageLuma16(g) => {
            let (w, h) = g.dimensions();
            let v = g.as_raw().iter().map(|&s| f64::from(s) / 65535.0);
            Relief::from_normalised(w, h, v, range).map_err(|e| format!("{}: {e}", path.display()))
        }
        other => Err(format!(
            "{}: a heightmap PNG must be 16-bit grayscale, this one is {:?} (8 bits would \
             quantise the relief to 1/255 of its range)",
            path.display(),
            other.color()
        )),
    }
}

/// Reads an EXR heightmap: its header first (size, and the memory decoding takes: every
/// channel's samples + 4 bytes a texel for the relief), then its pixels.
fn read_exr(path: &Path, range: [f64; 2]) -> Result<Relief, String> {
    use exr::prelude::*;
    let (size, bytes_per_texel) = crate::input::exr_header(path)?;
    crate::input::check_image_size(path, size, u64::from(MAX_RELIEF_SIDE), bytes_per_texel + 4)?;
    let image =
        read_all_flat_layers_from_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let layer = image
        .layer_data
        .first()
        .ok_or_else(|| format!("{}: the EXR has no layer", path.display()))?;
    let channels = &layer.channel_data.list;
    let channel = ["Y", "R"]
        .iter()
        .find_map(|n| channels.iter().find(|c| c.name.to_string() == *n))
        .or(if channels.len() == 1 { channels.first() } else { None })
        .ok_or_else(|| {
            format!(
                "{}: the EXR needs a `Y` or `R` channel, or exactly one channel",
                path.display()
            )
        })?;
    let (w, h) = (layer.size.0 as u32, layer.size.1 as u32);
    let relief = match &channel.sample_data {
        FlatSamples::F16(s) => {
            Relief::from_normalised(w, h, s.iter().map(|x| f64::from(x.to_f32())), range)
        }
        FlatSamples::F32(s) => {
            Relief::from_normalised(w, h, s.iter().map(|&x| f64::from(x)), range)
        }
        FlatSamples::U32(s) => {
            Relief::from_normalised(w, h, s.iter().map(|&x| f64::from(x)), range)
        }
    };
    relief.map_err(|e| format!("{}: {e}", path.display()))
}

impl Terrain {
    /// ∂y/∂x and ∂y/∂z of the plane.
    pub fn gradient(&self) -> (f64, f64) {
        let a = self.slope_direction_deg.to_radians();
        (self.slope * a.cos(), self.slope * a.sin())
    }

    /// The plane's height (y, m) at world (x, z), without the relief.
    pub fn plane_height(&self, x: f64, z: f64) -> f64 {
        let (gx, gz) = self.gradient();
        -self.depth_m + gx * (x - self.center[0]) + gz * (z - self.center[1])
    }

    /// The loaded relief of a `heightmap` floor (`None` for a plane, or before
    /// [`crate::scene::Scene::load`] read the file).
    pub fn relief(&self) -> Option<&Relief> {
        match self.kind {
            TerrainKind::Heightmap | TerrainKind::Island => self.relief.as_deref(),
            TerrainKind::Plane => None,
        }
    }

    /// Makes what the floor's kind computes rather than reads: an island's relief, from its
    /// profile ([`island_relief`]), again when its keys changed. Loading a scene calls it; a
    /// caller that builds or edits a floor calls it before drawing.
    pub fn prepare(&mut self) {
        if self.kind == TerrainKind::Island {
            self.relief = Some(Arc::new(island_relief(self)));
        }
    }

    /// The map's texture coordinates (u, v) at world (x, z): see the module doc.
    pub fn relief_uv(&self, r: &Relief, x: f64, z: f64) -> (f64, f64) {
        let (a_u, a_v) = self.relief_scale(r);
        let (x0, z0) = self.corner();
        (0.5 / f64::from(r.width) + (x - x0) * a_u, 0.5 / f64::from(r.height) + (z - z0) * a_v)
    }

    /// d(u, v)/d(x, z) of the map: (W − 1)/(W·extent), 0 for a single texel.
    fn relief_scale(&self, r: &Relief) -> (f64, f64) {
        let s = |n: u32| f64::from(n - 1) / (f64::from(n) * self.extent_m);
        (s(r.width), s(r.height))
    }

    /// The drawn square's corner of least (x, z).
    fn corner(&self) -> (f64, f64) {
        (self.center[0] - 0.5 * self.extent_m, self.center[1] - 0.5 * self.extent_m)
    }

    /// The floor's height (y, m) at world (x, z): the plane plus the relief (bilinear,
    /// clamped to the edge beyond the square).
    pub fn height(&self, x: f64, z: f64) -> f64 {
        let relief = self.relief().map_or(0.0, |r| {
            let (u, v) = self.relief_uv(r, x, z);
            r.sample(u, v)
        });
        self.plane_height(x, z) + relief
    }

    /// The lowest and highest floor height over the drawn square, m.
    pub fn y_range(&self) -> (f64, f64) {
        let (gx, gz) = self.gradient();
        let spread = 0.5 * self.extent_m * (gx.abs() + gz.abs());
        let (lo, hi) =
            self.relief().map_or((0.0, 0.0), |r| (f64::from(r.range.0), f64::from(r.range.1)));
        (-self.depth_m - spread + lo, -self.depth_m + spread + hi)
    }

    /// Quads per side of the drawn mesh (x, z): [`TERRAIN_QUADS`] for a plane; a relief's
    /// texel spacing, every k-th texel beyond [`MAX_RELIEF_QUADS`].
    pub fn mesh_quads(&self) -> (u32, u32) {
        match self.relief() {
            None => (TERRAIN_QUADS, TERRAIN_QUADS),
            Some(r) => {
                let q = |n: u32| (n.saturating_sub(1)).clamp(1, MAX_RELIEF_QUADS);
                (q(r.width), q(r.height))
            }
        }
    }

    /// Triangles of the drawn mesh.
    pub fn mesh_triangles(&self) -> u64 {
        let (qx, qz) = self.mesh_quads();
        2 * u64::from(qx) * u64::from(qz)
    }
}

/// Finest texel of an island's relief, m: fine enough for the waterline's wet band.
pub const ISLAND_TEXEL_M: f64 = 0.25;
/// Most texels per side of an island's relief (1025² f32 RGBA: 16.8 MB per back end).
pub const MAX_ISLAND_SIDE: u32 = 1025;

/// How far from its centre an island's shore meets the floor, m: R + d/s (with d ≤ 0, R).
pub fn island_reach(t: &Terrain) -> f64 {
    t.island_radius_m + t.depth_m.max(0.0) / t.shore_slope
}

/// The island's profile: the height (y, m) of the floor at distance `r` from its centre, on
/// a flat floor `d` = `depth_m` deep, with H = `island_height_m`, R = `island_radius_m`,
/// s = `shore_slope`:
///
/// ```text
/// r ≤ R:  y = s·(R − r) + (H − s·R)·(1 − u²)²,  u = r/R   (the top H at r = 0, 0 at R)
/// r > R:  y = −min(s · (r − R), d)                        (a straight shore to the floor)
/// ```
///
/// The hill's term has zero slope at the waterline, so the slope there is s on both sides:
/// the beach is one slope through the water's edge, which is where waves run up. With
/// H ≥ s·R the land rises monotonically to a top whose cone has slope s (4.6° at s = 0.08);
/// a lower H makes a dip behind the beach (a lagoon when it falls below 0). H = 0 and R = 0:
/// no land, the shore starts at the centre.
pub fn island_height(t: &Terrain, r: f64) -> f64 {
    let (h, big_r, s, d) = (t.island_height_m, t.island_radius_m, t.shore_slope, t.depth_m);
    if r <= big_r && big_r > 0.0 {
        let u = r / big_r;
        let hill = (1.0 - u * u) * (1.0 - u * u);
        s * (big_r - r) + (h - s * big_r) * hill
    } else {
        -(s * (r - big_r).max(0.0)).min(d)
    }
}

/// The relief of `kind = "island"`: [`island_height`] + `depth_m` (the relief is added to
/// the plane, which lies `depth_m` down) at texel centres over the drawn square,
/// [`ISLAND_TEXEL_M`] apart, or further where that would pass [`MAX_ISLAND_SIDE`] per side.
pub fn island_relief(t: &Terrain) -> Relief {
    let n = ((t.extent_m / ISLAND_TEXEL_M).ceil() as u32 + 1).clamp(2, MAX_ISLAND_SIDE);
    let step = t.extent_m / f64::from(n - 1);
    let (x0, z0) = (-0.5 * t.extent_m, -0.5 * t.extent_m);
    let heights: Vec<f32> = (0..n * n)
        .map(|i| {
            let (x, z) = (x0 + f64::from(i % n) * step, z0 + f64::from(i / n) * step);
            (island_height(t, x.hypot(z)) + t.depth_m) as f32
        })
        .collect();
    Relief::from_heights(n, n, heights)
}

/// A floor mesh's vertices in world space, row-major ((qx + 1) × (qz + 1)): the point (f64),
/// its normal and its albedo — everything of a vertex but the camera-relative shift, which is
/// all that changes from pass to pass and frame to frame.
struct FloorGrid {
    /// Quads per side.
    quads: (u32, u32),
    /// The vertices.
    vertices: Vec<(DVec3, [f32; 3], [f32; 3])>,
}

/// A relief compared by identity: a relief is made once, at load or `prepare`, and comparing
/// its texels would cost what keeping the grid saves.
pub(crate) struct SameRelief(pub(crate) Option<Arc<Relief>>);

impl PartialEq for SameRelief {
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

/// The world-space grid of floor `t` under a wet band up to `wet_top_m`, made once and kept
/// (`crate::kept`): a relief floor's 257² vertices take five height lookups each, and the
/// coastal frame drew its island four times a frame, every frame (the bulk of its CPU encode).
fn floor_grid(t: &Terrain, wet_top_m: f64) -> Arc<FloorGrid> {
    type Key = (Terrain, SameRelief, u64);
    static KEPT: crate::kept::Kept<Key, Arc<FloorGrid>> = crate::kept::Kept::new();
    let mut bare = t.clone();
    bare.relief = None;
    let key = (bare, SameRelief(t.relief().and(t.relief.clone())), wet_top_m.to_bits());
    KEPT.get(key, || Arc::new(make_floor_grid(t, wet_top_m)))
}

/// [`floor_grid`]'s grid, made.
fn make_floor_grid(t: &Terrain, wet_top_m: f64) -> FloorGrid {
    let (qx, qz) = t.mesh_quads();
    let (x0, z0) = t.corner();
    let (sx, sz) = (t.extent_m / f64::from(qx), t.extent_m / f64::from(qz));
    // Half a vertex spacing: the differences span the mesh's own resolution.
    let (hx, hz) = (0.5 * sx, 0.5 * sz);
    let mut vertices = Vec::with_capacity(((qx + 1) * (qz + 1)) as usize);
    for j in 0..=qz {
        for i in 0..=qx {
            let x = x0 + f64::from(i) * sx;
            let z = z0 + f64::from(j) * sz;
            let dx = (t.height(x + hx, z) - t.height(x - hx, z)) / (2.0 * hx);
            let dz = (t.height(x, z + hz) - t.height(x, z - hz)) / (2.0 * hz);
            let normal = DVec3::new(-dx, 1.0, -dz).normalize().as_vec3().to_array();
            let y = t.height(x, z);
            let color = wet_sand_color(t.color, y, wet_top_m).map(|v| v as f32);
            vertices.push((DVec3::new(x, y, z), normal, color));
        }
    }
    FloorGrid { quads: (qx, qz), vertices }
}

/// Triangles of the sea floor's drawn square, camera-relative, counter-clockwise seen from
/// above; normals from the floor's central differences (the plane's own for a plane). Sand
/// below `wet_top_m` (> 0) is wet: [`wet_sand_color`]. The world-space grid is made once per
/// floor (`floor_grid`), and the camera-relative triangles once per floor and eye and kept:
/// the passes of a frame that draw the floor (up to four) share one list, and so do the
/// frames of a still camera; a caller may tell the same list by its pointer
/// ([`Arc::ptr_eq`]).
pub fn terrain_triangles(t: &Terrain, eye: DVec3, wet_top_m: f64) -> Arc<Vec<[ObjectVertex; 3]>> {
    type Key = (usize, [u64; 3]);
    /// The grid (held, so that its address stays its own) and its triangles from one eye.
    type Value = (Arc<FloorGrid>, Arc<Vec<[ObjectVertex; 3]>>);
    static KEPT: crate::kept::Kept<Key, Value> = crate::kept::Kept::new();
    let grid = floor_grid(t, wet_top_m);
    // The grid's address names it while the kept entry holds it (so it cannot be reused).
    let key = (Arc::as_ptr(&grid) as usize, eye.to_array().map(f64::to_bits));
    KEPT.get(key, || {
        let tris = Arc::new(make_terrain_triangles(&grid, t, eye));
        (grid.clone(), tris)
    })
    .1
}

/// [`terrain_triangles`]' list, made.
fn make_terrain_triangles(grid: &FloorGrid, t: &Terrain, eye: DVec3) -> Vec<[ObjectVertex; 3]> {
    let (qx, qz) = grid.quads;
    let vertex = |i: u32, j: u32| {
        let (p, normal, color) = grid.vertices[(j * (qx + 1) + i) as usize];
        ObjectVertex { position: (p - eye).as_vec3().to_array(), normal, color }
    };
    let row = |j: u32| (0..=qx).map(|i| vertex(i, j)).collect::<Vec<_>>();
    let mut tris = Vec::with_capacity(t.mesh_triangles() as usize);
    let mut below = row(0);
    for j in 0..qz {
        let above = row(j + 1);
        for i in 0..qx as usize {
            tris.push([below[i], above[i], below[i + 1]]);
            tris.push([below[i + 1], above[i], above[i + 1]]);
        }
        below = above;
    }
    tris
}

/// The albedo of sand `color` at height `y` (m above the sea plane) under a wet band up to
/// `wet_top_m`: × [`crate::sand::WET_SAND_DARKENING`] up to ¾ of the band, rising
/// linearly to dry at its top; `color` itself without a band (`wet_top_m` ≤ 0).
pub fn wet_sand_color(color: [f64; 3], y: f64, wet_top_m: f64) -> [f64; 3] {
    if wet_top_m.is_nan() || wet_top_m <= 0.0 {
        return color;
    }
    let wet = ((wet_top_m - y) / (0.25 * wet_top_m)).clamp(0.0, 1.0);
    let k = 1.0 - wet * (1.0 - crate::sand::WET_SAND_DARKENING);
    color.map(|c| c * k)
}

/// The sea floor under the water (`[terrain]`), for eq. 8's depth and the floor's shadows: its
/// height is the plane y = floor.z + floor.x·rel.x + floor.y·rel.z in camera-relative (x, z)
/// (formed in f64 about the eye) plus the relief map sampled at
/// uv = (rel.x·relief.x + relief.z, rel.z·relief.y + relief.w). A bottomless sea is the flat
/// plane at `[chiu] open_sea_depth_m`, a plane floor has a one-texel zero map.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct TerrainBlock {
    /// (∂y/∂x, ∂y/∂z, y under the eye, 1 with a relief map else 0).
    pub floor: [f32; 4],
    /// (du/dx, dv/dz, u under the eye, v under the eye) of the relief map.
    pub relief: [f32; 4],
    /// The unit vector towards the sun under the water (refracted at a flat surface), and the
    /// horizontal length of a step of the relief's self-shadow march, m (0: no march).
    pub sun_under: [f32; 4],
    /// (highest floor height over the drawn square (world y, m), steps of the march,
    /// 1/(r·λ) of the displacement's waves, 1/(r·λ) of the bump map's; 0: undamped), r
    /// `wave_damping` (waves `fft` and `gerstner` near the shore, shared/floor.wgsl).
    pub top: [f32; 4],
}

impl TerrainBlock {
    /// The block of `terrain` (or of the open sea at `open_sea_depth_m` without a floor) seen
    /// from `eye`, with the sun at `sun_dir` (unit, towards the sun; `None`: no sun), the
    /// water's index `eta`, and the representative wavelengths (m) of the displacement's and
    /// the bump map's waves that `wave_damping` scales (`None`: waves `coastal`, undamped).
    pub fn new(
        terrain: Option<&Terrain>,
        open_sea_depth_m: f64,
        eye: DVec3,
        sun_dir: Option<DVec3>,
        eta: f64,
        damped_wavelengths_m: Option<[f64; 2]>,
    ) -> Self {
        // Snell at a flat surface, towards the sun: the horizontal part shrinks by 1/η.
        let sun_under = match sun_dir {
            Some(d) if d.y > 0.0 => {
                let (tx, tz) = (d.x / eta, d.z / eta);
                let ty = (1.0 - tx * tx - tz * tz).max(0.0).sqrt();
                [tx as f32, ty as f32, tz as f32, 0.0]
            }
            _ => [0.0; 4],
        };
        let flat_map = [0.0, 0.0, 0.5, 0.5];
        let Some(t) = terrain else {
            return Self {
                floor: [0.0, 0.0, -open_sea_depth_m as f32, 0.0],
                relief: flat_map,
                sun_under,
                top: [0.0; 4],
            };
        };
        let (gx, gz) = t.gradient();
        let plane = [gx as f32, gz as f32, t.plane_height(eye.x, eye.z) as f32];
        let inv = |l: f64| {
            let v = 1.0 / (t.wave_damping * l);
            if v.is_finite() && v > 0.0 { v as f32 } else { 0.0 }
        };
        let damping = match damped_wavelengths_m {
            Some([d, b]) if t.wave_damping > 0.0 => [inv(d), inv(b)],
            _ => [0.0, 0.0],
        };
        let Some(r) = t.relief() else {
            return Self {
                floor: [plane[0], plane[1], plane[2], 0.0],
                relief: flat_map,
                sun_under,
                top: [0.0, 0.0, damping[0], damping[1]],
            };
        };
        let (a_u, a_v) = t.relief_scale(r);
        let (u, v) = t.relief_uv(r, eye.x, eye.z);
        // Half a texel: a step of one misses ridges a texel wide that a ray grazes (the bilinear
        // peak between two samples; tests/terrain.rs measures what half a texel still misses).
        let step = 0.5 * t.extent_m / f64::from(r.width.max(r.height).max(2) - 1);
        Self {
            floor: [plane[0], plane[1], plane[2], 1.0],
            relief: [a_u as f32, a_v as f32, u as f32, v as f32],
            sun_under: [sun_under[0], sun_under[1], sun_under[2], step as f32],
            top: [t.y_range().1 as f32, RELIEF_SHADOW_STEPS as f32, damping[0], damping[1]],
        }
    }
}

/// The relief map as RGBA texels (height in red), or one zero texel without one: what both
/// back ends bind as `floor_map`.
pub fn relief_texels(terrain: Option<&Terrain>) -> (u32, u32, Vec<[f32; 4]>) {
    match terrain.and_then(Terrain::relief) {
        Some(r) => (r.width, r.height, r.heights.iter().map(|&h| [h, 0.0, 0.0, 0.0]).collect()),
        None => (1, 1, vec![[0.0; 4]]),
    }
}

/// The relief of a `heightmap` floor loaded from `path` (relative paths against `base`),
/// shared so that clones of a scene do not copy it.
///
/// # Errors
/// As [`Relief::load`].
pub fn load_relief(path: &Path, base: &Path, range: [f64; 2]) -> Result<Arc<Relief>, String> {
    let full = if path.is_absolute() { path.to_owned() } else { base.join(path) };
    Relief::load(&full, range).map(Arc::new)
}

/// What a sea floor is (`kind = "plane"`, `"island"` or `"heightmap"`). A sloping beach is a
/// `plane` with a `slope`: the waterline runs where it reaches the sea plane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TerrainKind {
    /// A flat or sloping plane: `depth_m` below the sea plane at `center`, rising by `slope`
    /// metres per metre towards `slope_direction_deg`.
    #[default]
    Plane,
    /// The plane plus a relief read from `heightmap` (a 16-bit grayscale PNG or an EXR) over
    /// the square of side `extent_m`, its samples mapped onto `height_range_m`.
    Heightmap,
    /// A round island about `center` rising from the plane (`crate::terrain::island_height`
    /// has the profile): `island_height_m` above the sea at its top, the waterline at
    /// `island_radius_m` (on a flat floor), sloping into the water by `shore_slope` down to
    /// the floor `depth_m` deep. Drawn through a relief made from the profile at load.
    Island,
}

/// The `[terrain]` table: the sea floor (docs/design.md; [`crate::terrain`] has its geometry).
/// Drawn as a square of side `extent_m` about `center` in the main view, the refraction map
/// and the reflection map; its depth under each point of the sea is eq. 8's y (shading
/// `chiu`), the plane's (and the relief's edge) also beyond the drawn square.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Terrain {
    /// What the floor is.
    pub kind: TerrainKind,
    /// Depth of the floor's plane below the sea plane at `center`, m (negative: above).
    pub depth_m: f64,
    /// (x, z) of the floor's reference point and the centre of the drawn square, m.
    pub center: [f64; 2],
    /// Rise of the plane per metre along `slope_direction_deg` (0: flat).
    pub slope: f64,
    /// The direction in which the plane rises, degrees from +x towards +z.
    pub slope_direction_deg: f64,
    /// Side of the drawn square (and of the heightmap), m.
    pub extent_m: f64,
    /// Linear RGB albedo; by default dry beach sand from a measured spectrum
    /// ([`crate::sand::DRY_SAND_ALBEDO`]).
    pub color: [f64; 3],
    /// `kind = "heightmap"`: the file, relative to the scene file's folder (to the working
    /// folder for scene text).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heightmap: Option<PathBuf>,
    /// The relief's height at sample 0 and at sample 1 (65535 in a PNG), m, added to the plane.
    pub height_range_m: [f64; 2],
    /// `kind = "island"`: the waterline's radius on a flat floor, m.
    pub island_radius_m: f64,
    /// `kind = "island"`: the island's top above the sea plane, m.
    pub island_height_m: f64,
    /// `kind = "island"`: the fall of the shore per metre at the waterline and below it,
    /// down to the floor.
    pub shore_slope: f64,
    /// Waves `fft` and `gerstner` near the shore: r in w = clamp(h/(r·λ), 0, 1), the share of
    /// the waves kept over h m of water, λ the sea's representative wavelength (the spectral
    /// peak's or the Gerstner median's for the displacement, the bump patch for the bump map).
    /// 0.5 is Crest's "a wave feels the floor below half its wavelength"; 0 (the default)
    /// leaves them undamped. Waves `coastal` shoal and break by their own rules.
    pub wave_damping: f64,
    /// The relief read from `heightmap`, or made from the island's profile, when the scene
    /// was loaded (or by [`Terrain::prepare`]).
    #[serde(skip)]
    pub relief: Option<std::sync::Arc<crate::terrain::Relief>>,
}

impl Default for Terrain {
    fn default() -> Self {
        Self {
            kind: TerrainKind::Plane,
            depth_m: 10.0,
            center: [0.0, 0.0],
            slope: 0.0,
            slope_direction_deg: 0.0,
            extent_m: 400.0,
            color: crate::sand::DRY_SAND_ALBEDO,
            heightmap: None,
            height_range_m: [0.0, 1.0],
            island_radius_m: 60.0,
            island_height_m: 12.0,
            shore_slope: 0.08,
            wave_damping: 0.0,
            relief: None,
        }
    }
}

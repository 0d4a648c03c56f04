//! The memory a frame will need, estimated from its plan before anything is allocated, so
//! that a render that cannot fit is refused at once with the figure and the scene key that
//! drives it, instead of aborting in an allocation minutes in.
//!
//! The estimate is an upper bound by construction: it adds every item as if all were alive
//! at once (the back ends free the wave scratch before the water pass, so the true peak is
//! lower). `tests/memory_estimate.rs` measures the CPU back end's peak heap with a counting
//! allocator and holds the estimate between that peak and a small multiple of it.
//!
//! Per-item costs, measured with that allocator on this project's back ends:
//! - wave synthesis: [`WAVE_BYTES_PER_SAMPLE`] per sample of each N × N map (the modes, the
//!   complex f64 spectra and FFT scratch, the f32 maps);
//! - water mesh: [`MESH_BYTES_PER_TRIANGLE`] per triangle of the near patch's bintree (nodes,
//!   vertices, indices) and of the far patch;
//! - surface `projected_grid`: [`GRID_BYTES_PER_TRIANGLE`] per triangle of its list (counted);
//! - surface `clipmap`: as many per triangle of its levels' list, holes included (counted);
//! - objects: [`OBJECT_BYTES_PER_TRIANGLE`] per triangle, once per pass that draws them;
//! - each texture of the plan at its size and format, and a 4-byte depth buffer per render
//!   target; the encoded output once more.

use std::f64::consts::PI;

use super::{Format, FramePlan, Pass, ResourceId};
use crate::objects::{SPHERE_BANDS, SPHERE_SEGMENTS};
use crate::scene::{Scene, Shape};

/// Bytes per sample of a wave map's synthesis (calibrated: 1024² displacement maps peak at
/// 163 MiB above the base frame, 155 B per sample).
pub const WAVE_BYTES_PER_SAMPLE: u64 = 176;

/// Bytes per triangle of the water mesh (calibrated: a full-depth 2048-cell near patch,
/// 8.4 M triangles, peaks at 864 MiB, 103 B per triangle).
pub const MESH_BYTES_PER_TRIANGLE: u64 = 128;

/// Bytes per triangle of surface `projected_grid` on the CPU (counted, not calibrated: its
/// triangle list shares no vertex, three transformed vertices of 16 + 4·8 bytes and a 12-byte
/// index triple).
pub const GRID_BYTES_PER_TRIANGLE: u64 = 3 * 48 + 12;

/// Bytes per object triangle per pass: three 36-byte vertices and the rasteriser's
/// transformed copy of them (calibrated: 2000 spheres, 4.4 M triangles drawn in three passes,
/// peak at 1.6 GiB, 130 B per triangle per pass).
pub const OBJECT_BYTES_PER_TRIANGLE: u64 = 2 * 3 * 36;

/// The back end whose memory is estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemoryBackend {
    /// The CPU oracle: everything in host memory.
    Cpu,
    /// The wgpu path: the same items, held by the driver (host memory on lavapipe, device
    /// memory on a discrete GPU), plus the CPU-side modes and readback copies.
    Gpu,
}

/// One line of the estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryItem {
    /// What it is.
    pub what: String,
    /// Bytes.
    pub bytes: u64,
    /// The scene key that sets its size.
    pub key: &'static str,
}

/// What a frame will allocate, item by item.
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryEstimate {
    /// Every item, in plan order.
    pub items: Vec<MemoryItem>,
}

/// A render refused by the memory limit.
#[derive(Debug, thiserror::Error)]
#[error(
    "the frame needs an estimated {} (limit {}); the largest part is {} ({}, set by `{}`); \
     lower that key or raise the limit with --memory-limit",
    bytes(*total),
    bytes(*limit),
    largest.what,
    bytes(largest.bytes),
    largest.key
)]
pub struct OverLimit {
    /// The estimate.
    pub total: u64,
    /// The limit.
    pub limit: u64,
    /// Its largest item.
    pub largest: MemoryItem,
}

impl MemoryEstimate {
    /// The estimate of `plan` (made for `scene`) on `backend`.
    pub fn of(scene: &Scene, plan: &FramePlan, backend: MemoryBackend) -> Self {
        let mut items = Vec::new();
        let mut add = |what: String, bytes: u64, key: &'static str| {
            items.push(MemoryItem { what, bytes, key });
        };
        let o = &scene.ocean;
        if plan.runs(Pass::Waves) {
            for (n, what, key) in [
                (o.resolution, "displacement map synthesis", "ocean.resolution"),
                (o.bump_resolution, "bump map synthesis", "ocean.bump_resolution"),
            ] {
                add(format!("{what} ({n}²)"), u64::from(n).pow(2) * WAVE_BYTES_PER_SAMPLE, key);
            }
        }
        for r in plan.resources.iter().filter(|r| r.written) {
            let [w, h] = r.size.map(u64::from);
            let texel = match r.format {
                Format::Rgba32Float => 16,
                Format::Rgba16Float => 8,
                Format::R32Float | Format::Rgba8Unorm => 4,
                Format::Uniform => 1,
            };
            let depth = matches!(
                r.id,
                ResourceId::Hdr
                    | ResourceId::ReflectionMap
                    | ResourceId::RefractionMap
                    | ResourceId::ShadowMap
            );
            let copies = match backend {
                // The GPU reads the output back into host memory.
                MemoryBackend::Gpu if matches!(r.id, ResourceId::Hdr | ResourceId::Ldr) => 2,
                // Foam `accumulated`'s field: the state, the frame's copy and the step's new
                // field on the CPU; two textures and the read-back on the GPU.
                _ if r.id == ResourceId::FoamField => 3,
                _ => 1,
            };
            let key = match r.id {
                ResourceId::Displacement | ResourceId::DisplacementSlopes => "ocean.resolution",
                ResourceId::Bump => "ocean.bump_resolution",
                ResourceId::FresnelAbove | ResourceId::FresnelBelow => "quality.fresnel_table_size",
                ResourceId::ReflectionMap => "quality.reflection_map_scale",
                ResourceId::ShadowMap => "sun",
                ResourceId::FoamField
                    if crate::foam::FieldGrid::of(scene, plan.techniques.waves()).windowed =>
                {
                    "foam.grid"
                }
                ResourceId::FoamField => "ocean.resolution",
                _ => "camera.width",
            };
            let bytes = w * h * (texel * copies + if depth { 4 } else { 0 });
            add(format!("{} ({w}×{h})", r.id.name()), bytes, key);
        }
        let (w, h) = (u64::from(scene.camera.width), u64::from(scene.camera.height));
        if plan.runs(Pass::Tonemap) {
            add("encoded PNG".into(), w * h * 4, "camera.width");
        } else {
            add("encoded EXR".into(), w * h * 16 * 2, "camera.width");
        }
        if plan.runs(Pass::Spray) {
            // The pool (two vec4 a slot) and, on the CPU, its sprites' triangle list (two
            // triangles a slot, each vertex a position and a corner: as the grid's triangles).
            let n = u64::from(scene.spray.particles);
            add(
                format!("spray ({n} particles and their sprites)"),
                n * 32 + 2 * n * GRID_BYTES_PER_TRIANGLE,
                "spray.particles",
            );
        }
        if plan.runs(Pass::Water) {
            let surface = plan.techniques.surface();
            if surface.clipmap_levels() {
                let q = &scene.quality;
                let levels = crate::geometry::Clipmap::levels_for(
                    scene.camera.position[1],
                    q.clipmap_cell_m,
                    q.clipmap_cells,
                );
                let vertices = crate::geometry::Clipmap::vertex_count(levels, q.clipmap_cells);
                add(
                    format!("clipmap ({levels} levels)"),
                    vertices / 3 * GRID_BYTES_PER_TRIANGLE,
                    "quality.clipmap_cells",
                );
            } else if surface.camera_grid() {
                let (cols, rows) = crate::geometry::ProjectedGridBlock::quads(
                    scene.camera.width,
                    scene.camera.height,
                    scene.quality.projected_grid_cell_px,
                );
                add(
                    surface.name().replace('_', " "),
                    2 * u64::from(cols) * u64::from(rows) * GRID_BYTES_PER_TRIANGLE,
                    "quality.projected_grid_cell_px",
                );
            } else {
                add(
                    "water mesh".into(),
                    water_triangles(scene) * MESH_BYTES_PER_TRIANGLE,
                    "quality.lod_split_threshold",
                );
            }
        }
        let object_passes: Vec<Pass> =
            [Pass::ShadowMap, Pass::ReflectionMap, Pass::RefractionMap, Pass::Objects]
                .into_iter()
                .filter(|p| plan.runs(*p))
                .collect();
        let objects = plan.objects();
        let triangles: u64 = object_passes
            .iter()
            .map(|p| {
                let floor = match &scene.terrain {
                    Some(t) if plan.passes.iter().any(|q| q.name == *p && q.terrain) => {
                        t.mesh_triangles()
                    }
                    _ => 0,
                };
                objects.of(*p).iter().map(|&i| object_triangles(scene, i)).sum::<u64>() + floor
            })
            .sum();
        if triangles > 0 {
            add(
                format!(
                    "object geometry ({} objects, {} passes)",
                    scene.objects.len(),
                    object_passes.len()
                ),
                triangles * OBJECT_BYTES_PER_TRIANGLE,
                "objects",
            );
        }
        if let Some(r) = scene.terrain.as_ref().and_then(crate::scene::Terrain::relief) {
            // The file's heights as f32, and the RGBA f32 texture both back ends bind.
            add(
                format!("sea floor relief ({}×{})", r.width, r.height),
                u64::from(r.width) * u64::from(r.height) * (4 + 16),
                "terrain.heightmap",
            );
        }
        Self { items }
    }

    /// The sum of every item, bytes.
    pub fn total(&self) -> u64 {
        self.items.iter().map(|i| i.bytes).sum()
    }

    /// The largest item (`None` for an empty estimate).
    pub fn largest(&self) -> Option<&MemoryItem> {
        self.items.iter().max_by_key(|i| i.bytes)
    }

    /// `Ok` when the estimate is within `limit` bytes.
    ///
    /// # Errors
    /// [`OverLimit`] with the estimate and its largest item.
    pub fn check(&self, limit: u64) -> Result<(), OverLimit> {
        let total = self.total();
        match self.largest() {
            Some(largest) if total > limit => {
                Err(OverLimit { total, limit, largest: largest.clone() })
            }
            _ => Ok(()),
        }
    }
}

/// Triangles of one object's mesh.
fn object_triangles(scene: &Scene, index: usize) -> u64 {
    match scene.objects.get(index).and_then(|o| o.shape()) {
        Some(Shape::Sphere { .. }) => {
            u64::from(2 * SPHERE_BANDS * SPHERE_SEGMENTS - 2 * SPHERE_SEGMENTS)
        }
        Some(Shape::Box { .. }) => 12,
        Some(Shape::Boat { .. }) => u64::from(crate::objects::HULL_TRIANGLES),
        None => 0,
    }
}

/// An upper bound of the water mesh's triangles: the near patch refined where a triangle's
/// hypotenuse exceeds `split_threshold ×` its distance (at most the full bintree), and the
/// far patch's polar grid.
///
/// Near the eye, within d₀ = √2·g / θ, every triangle is at the finest level (area g²/2);
/// beyond, a triangle at distance r has hypotenuse ≈ θ·r and area θ²r²/4, so the annulus out
/// to the patch's half diagonal R holds ∫ 2πr dr / (θ²r²/4) = (8π/θ²) ln(R/d₀). The bintree's
/// forced splits at most double the count.
pub fn water_triangles(scene: &Scene) -> u64 {
    // The near patch as the scene's camera sizes it (a camera that cannot be built has no
    // frame: the scene's grid alone).
    let p = crate::camera::Camera::from_scene(&scene.camera)
        .map_or_else(|_| scene.patch_params(), |c| scene.patch_params_for(&c));
    let g = p.grid_spacing_m;
    let levels = (p.near_size_m / g).log2().round().clamp(0.0, 31.0);
    let full = 2.0 * 4f64.powf(levels);
    let theta = p.split_threshold;
    let d0 = std::f64::consts::SQRT_2 * g / theta;
    let r = p.near_size_m / std::f64::consts::SQRT_2;
    let refined = if r <= d0 {
        full
    } else {
        2.0 * (2.0 * PI * d0 * d0 / (g * g) + 8.0 * PI / (theta * theta) * (r / d0).ln())
    };
    let rings = ((p.far_max_radius / p.far_min_radius).ln() / p.far_ring_ratio.ln()).ceil() + 1.0;
    let far = 2.0 * rings * f64::from(p.far_segments);
    (refined.min(full) + far) as u64
}

pub use crate::sizes::{bytes, default_limit, parse_bytes, physical_memory};

//! View-dependent wave geometry (seed 000 §3, Fig. 2): the mesh the water is drawn with.
//!
//! The mesh lies on the sea plane y = 0; the vertex shader displaces each vertex by the
//! (tiled) displacement map at its world (x, z), times the vertex's weight w ∈ [0, 1]. It has
//! three parts:
//! - the **near patch** ([`NearPatch`], `near.rs`): a square of side S centred under the eye
//!   (snapped to the displacement grid), triangulated by a ROAM binary triangle tree whose
//!   refinement follows the eye's height and distance; w = 1 inside, ramping to 0 on the
//!   boundary ("boundary heights forced to 0"), whose subdivision is fixed;
//! - the **far patch** ([`FarPatch`], `far.rs`): a planar polar mesh out to ~10⁶·H,
//!   precomputed for H = 1 over the region that any pitch can see with the given fov (bounded
//!   by the paper's two conics), scaled by H and turned with the camera's yaw each frame;
//!   w = 0 (the waves there are the bump map's);
//! - the **stitch** (`mesh.rs`): the far rings inside a clearance around the near patch are
//!   dropped and the gap is triangulated between the near patch's boundary vertices and the
//!   first kept ring, so that the union ([`WaterMesh`]) is one conforming triangulation: no
//!   T-junctions, no overlap.
//!
//! Conventions: positions are world (x, z) in metres relative to a reference point near the
//! camera ([`WaterMesh::origin`], the near patch's centre); triangles are counter-clockwise
//! seen from above (+y), so a renderer that culls back faces must not cull under water, where
//! the surface is seen from below. Viewpoint height H = max(|eye.y|, `min_height_m`): under
//! water the mesh is the one of the mirrored eye above the surface.

mod clipmap;
mod far;
mod mesh;
mod near;
mod params;
mod projected;
pub mod shore_grid;

pub use clipmap::{CLIPMAP_CELLS_RANGE, Clipmap, ClipmapBlock, MAX_CLIPMAP_LEVELS};
pub use far::{FarPatch, PlacedFarPatch, visible_half_angle};
pub use mesh::{MeshSummary, ObjectVertex, WaterMesh};
pub use near::NearPatch;
pub use params::{
    DEFAULT_NEAR_SIZE_M, MAX_HEIGHT_M, MAX_NEAR_LEVELS, PatchParams, STITCH_CLEARANCE,
    stitch_radius, wave_reach_m,
};
pub use projected::{HORIZON_DISTANCE_H, ProjectedGrid, ProjectedGridBlock};

use crate::Result;
use params::invalid;

/// One vertex of the water mesh, as the vertex buffer holds it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WaterVertex {
    /// World (x, z) on the sea plane, metres, relative to the mesh's reference point.
    pub pos: [f32; 2],
    /// Displacement weight: the vertex moves by `weight ×` the displacement map.
    pub weight: f32,
}

/// The viewpoint height the meshes are built for: max(|eye_y|, `min_height_m`), metres.
/// Errors on a NaN or infinite `eye_y` or one beyond [`MAX_HEIGHT_M`].
pub fn effective_height(params: &PatchParams, eye_y: f64) -> Result<f64> {
    if !eye_y.is_finite() || eye_y.abs() > MAX_HEIGHT_M {
        return Err(invalid(
            "eye.y",
            eye_y,
            format!("must be finite, at most {MAX_HEIGHT_M} m from the sea plane"),
        ));
    }
    Ok(eye_y.abs().max(params.min_height_m))
}

/// The grid point nearest to the eye's (x, z): (index in grid cells, position in metres).
fn snap_to_grid(params: &PatchParams, eye_xz: [f64; 2]) -> Result<([i64; 2], [f64; 2])> {
    let g = params.grid_spacing_m;
    let mut cell = [0i64; 2];
    for (c, (&v, name)) in cell.iter_mut().zip(eye_xz.iter().zip(["eye.x", "eye.z"])) {
        let k = (v / g).round();
        // Beyond 2^52 cells f64 no longer holds every grid point (and i64 casts saturate).
        if !(k.is_finite() && k.abs() < 4.5e15) {
            return Err(invalid(name, v, "must be finite, within 2^52 grid cells of 0".into()));
        }
        *c = k as i64;
    }
    Ok((cell, cell.map(|k| k as f64 * g)))
}

/// The near patch's square for an eye at (x, z) = `eye_xz`: its centre (the eye snapped to
/// the displacement grid, world x, z) and half side, metres. The far patch and the stitch lie
/// outside it.
pub fn near_patch_square(params: &PatchParams, eye_xz: [f64; 2]) -> Result<([f64; 2], f64)> {
    let layout = params.validate()?;
    let (_, origin) = snap_to_grid(params, eye_xz)?;
    Ok((origin, layout.grid * f64::from(layout.half_cells)))
}

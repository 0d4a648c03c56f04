//! The water mesh of one frame: the near patch, the far patch's kept rings, and the strip
//! that stitches them.
//!
//! **Stitching.** Seed 000 culls the far triangles inside the near patch and moves the inner
//! vertices of the straddling ones onto its boundary; unless those land exactly on the near
//! patch's boundary vertices that leaves T-junctions. Here instead:
//! - every far ring inside [`STITCH_CLEARANCE`] times the radius [`stitch_radius`] (about
//!   the eye) is dropped: the first kept ring k₀ is the smallest k ≥ 1 with ρ_k·H at least
//!   that (about 1.9 × the near patch's half-size for the defaults);
//! - ring k₀ is kept whole (all M vertices), and the annulus between the near patch's
//!   boundary polygon (its fixed `4·boundary_segments` vertices, the very same vertex
//!   indices) and ring k₀'s polygon is triangulated by zipping the two vertex loops in order
//!   of azimuth about the eye: each step adds the triangle whose new vertex comes first. Both
//!   loops are convex and surround the eye, and [`stitch_radius`] makes every triangle
//!   counter-clockwise (checked with `debug_assert!`; the tests check it exactly), so the
//!   strip covers the annulus exactly once;
//! - rows k₀ … R−1 follow, each with its precomputed cells.
//!
//! The union is then one conforming triangulation: the near and strip triangles share the
//! boundary vertices by index, the strip and the rows share ring k₀ by index, and every far
//! cell edge is shared by index. All far and strip vertices have weight 0.

#[cfg(test)]
use std::f64::consts::PI;
use std::f64::consts::TAU;

use super::far::{FarPatch, PlacedFarPatch};
use super::near::NearPatch;
use super::params::{PatchParams, STITCH_CLEARANCE, invalid, stitch_radius};
use super::{WaterVertex, effective_height};
use bytemuck::{Pod, Zeroable};

use crate::Result;

/// The water mesh of one frame.
///
/// Vertex positions are world (x, z) relative to `origin` (camera-relative rendering adds
/// `origin − camera` in f64, then draws in f32). For the displacement-map lookup use the grid
/// index rather than the world position: the vertex is at map sample coordinates
/// s = (origin_cell mod N) + pos / g (g = L/N), small numbers with no loss for an eye far
/// from the world origin. Near vertices have integer s: sample (i, j) of the map (at
/// x = i·g) is texel (i, j), whose centre is at texture coordinate (i + ½)/N, so fetch with
/// `textureLoad(s mod N)`, or sample at (s + ½)/N with repeat addressing.
#[derive(Clone, Debug, PartialEq)]
pub struct WaterMesh {
    /// The reference point c (world x, z), metres: the near patch's centre.
    pub origin: [f64; 2],
    /// c in displacement-grid cells: origin = origin_cell · grid_spacing_m.
    pub origin_cell: [i64; 2],
    /// The vertices: near patch first, then the far rings.
    pub vertices: Vec<WaterVertex>,
    /// Triangles, counter-clockwise seen from above (+y): the y component of
    /// (p1 − p0) × (p2 − p0) is positive. Near patch first, then the strip, then the rows.
    pub indices: Vec<[u32; 3]>,
    /// How many leading vertices belong to the near patch.
    pub near_vertices: usize,
    /// How many leading triangles belong to the near patch.
    pub near_triangles: usize,
    /// How many triangles stitch the near patch to the first far ring (they follow the near
    /// ones).
    pub stitch_triangles: usize,
    /// Index k₀ of the first far ring kept (into [`FarPatch::ring_radii`]).
    pub far_first_ring: usize,
    /// Radius of the first kept far ring about the eye, metres.
    pub far_inner_radius_m: f64,
    /// Radius of the outermost far ring about the eye, metres.
    pub far_outer_radius_m: f64,
}

/// Vertex and triangle counts of a mesh, for plans and reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshSummary {
    /// All vertices.
    pub vertices: usize,
    /// Near-patch vertices.
    pub near_vertices: usize,
    /// Near-patch triangles.
    pub near_triangles: usize,
    /// Stitch-strip triangles.
    pub stitch_triangles: usize,
    /// Far-row triangles.
    pub far_triangles: usize,
    /// Radius of the first kept far ring, metres.
    pub far_inner_radius_m: f64,
    /// Radius of the outermost far ring, metres.
    pub far_outer_radius_m: f64,
}

impl std::fmt::Display for MeshSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} vertices ({} near), {} triangles: {} near, {} stitch, {} far (rings {:.4e} m … {:.4e} m)",
            self.vertices,
            self.near_vertices,
            self.near_triangles + self.stitch_triangles + self.far_triangles,
            self.near_triangles,
            self.stitch_triangles,
            self.far_triangles,
            self.far_inner_radius_m,
            self.far_outer_radius_m
        )
    }
}

impl WaterMesh {
    /// The mesh for a camera at `eye` (world, metres) looking along `forward` (any length,
    /// not zero) with a vertical field of view `fov_y_rad` and aspect ratio `aspect`
    /// (width / height). The camera is a look-at camera with world up +y (no roll).
    ///
    /// Precomputes the far patch for this fov on every call (cheap: a few hundred rings);
    /// a renderer keeps one [`FarPatch`] and calls [`Self::for_view_with`].
    pub fn for_view(
        params: &PatchParams,
        eye: [f64; 3],
        forward: [f64; 3],
        fov_y_rad: f64,
        aspect: f64,
    ) -> Result<Self> {
        let far = FarPatch::precompute(params, fov_y_rad, aspect)?;
        Self::for_view_with(params, &far, eye, forward)
    }

    /// [`Self::for_view`] with a far patch precomputed by [`FarPatch::precompute`] (with the
    /// same `params`).
    ///
    /// Only the eye and the forward azimuth matter: the near patch depends on the eye alone
    /// and the far patch covers every pitch. Looking straight up or down the azimuth is
    /// undefined; yaw 0 is used, and the far patch's disc about the eye covers the footprint
    /// whatever the camera's roll.
    pub fn for_view_with(
        params: &PatchParams,
        far: &FarPatch,
        eye: [f64; 3],
        forward: [f64; 3],
    ) -> Result<Self> {
        if let Some(bad) = forward.iter().copied().find(|v| !v.is_finite()) {
            return Err(invalid("forward", bad, "must be finite".into()));
        }
        let length = forward[0].hypot(forward[1]).hypot(forward[2]);
        if length == 0.0 {
            return Err(invalid("forward", length, "must not be the zero vector".into()));
        }
        let horizontal = forward[0].hypot(forward[2]);
        let yaw = if horizontal > 1e-12 * length { forward[0].atan2(forward[2]) } else { 0.0 };
        let near = NearPatch::kept(params, eye)?;
        let height = effective_height(params, eye[1])?;
        Self::stitch(&near, &far.place(yaw, height)?, eye)
    }

    /// Joins a near patch and a placed far patch around the eye at `eye` (the same eye both
    /// were built for): see the module doc.
    pub fn stitch(near: &NearPatch, far: &PlacedFarPatch<'_>, eye: [f64; 3]) -> Result<Self> {
        if let Some(bad) = eye.iter().copied().find(|v| !v.is_finite()) {
            return Err(invalid("eye", bad, "must be finite".into()));
        }
        let patch = far.patch();
        let m = patch.segments();
        let rings = patch.ring_radii();
        let h = far.height_m();
        // The eye relative to the reference point, and where the first far ring must be.
        let eye_rel = [eye[0] - near.origin[0], eye[2] - near.origin[1]];
        let needed = stitch_radius(0.5 * near.size_m, eye_rel, m).ok_or_else(|| {
            invalid("far_segments", f64::from(m), "too coarse to stitch to the near patch".into())
        })?;
        let first = (1..rings.len())
            .find(|&k| rings[k] * h >= STITCH_CLEARANCE * needed)
            .filter(|&k| k + 1 < rings.len())
            .ok_or_else(|| {
                invalid(
                    "far_max_radius",
                    rings[rings.len() - 1],
                    format!(
                        "the far patch (× H = {h} m) does not reach past the near patch of \
                         {} m",
                        near.size_m
                    ),
                )
            })?;

        let mut vertices = near.vertices.clone();
        let mut indices = near.indices.clone();
        let near_vertices = vertices.len();
        let near_triangles = indices.len();
        let far_vertex = |ring: usize, j: i64| {
            let o = far.offset(ring, j);
            WaterVertex {
                pos: [(eye_rel[0] + o[0]) as f32, (eye_rel[1] + o[1]) as f32],
                weight: 0.0,
            }
        };

        // Ring k₀, whole: vertex j (0 … M−1) at index ring0 + j.
        let ring0 = vertices.len() as u32;
        vertices.extend((0..i64::from(m)).map(|j| far_vertex(first, j)));

        // The strip: zip the boundary loop and ring k₀ by azimuth about the eye.
        let azimuth = |p: [f32; 2]| {
            let a = (f64::from(p[0]) - eye_rel[0]).atan2(f64::from(p[1]) - eye_rel[1]);
            if a < 0.0 { a + TAU } else { a }
        };
        let loop_by_azimuth = |ids: &mut dyn Iterator<Item = u32>, vertices: &[WaterVertex]| {
            let mut l: Vec<(f64, u32)> =
                ids.map(|i| (azimuth(vertices[i as usize].pos), i)).collect();
            // Both loops are already in counter-clockwise order: start at the smallest
            // azimuth.
            let start = (0..l.len()).min_by(|&a, &b| l[a].0.total_cmp(&l[b].0)).unwrap_or(0);
            l.rotate_left(start);
            l
        };
        let inner = loop_by_azimuth(&mut near.boundary.iter().copied(), &vertices);
        let outer = loop_by_azimuth(&mut (ring0..ring0 + m), &vertices);
        zip(&inner, &outer, &mut indices);
        let stitch_triangles = indices.len() - near_triangles;

        // Rows k₀ … R−1. Ring k (> k₀) holds vertices j ∈ [−n, n] where n is row k−1's
        // half-width (rows shrink outwards), or the whole circle.
        let mut ring_start = vec![0u32; rings.len()];
        let mut ring_full = vec![false; rings.len()];
        let mut ring_half = vec![0i64; rings.len()];
        ring_start[first] = ring0;
        ring_full[first] = true;
        for k in first + 1..rings.len() {
            let n = patch.row_half_cells(k - 1);
            ring_start[k] = vertices.len() as u32;
            if n == m / 2 {
                ring_full[k] = true;
                vertices.extend((0..i64::from(m)).map(|j| far_vertex(k, j)));
            } else {
                let n = i64::from(n);
                ring_half[k] = n;
                vertices.extend((-n..=n).map(|j| far_vertex(k, j)));
            }
        }
        let id = |k: usize, j: i64| {
            let local = if ring_full[k] { j.rem_euclid(i64::from(m)) } else { j + ring_half[k] };
            ring_start[k] + local as u32
        };
        for r in first..rings.len() - 1 {
            let n = i64::from(patch.row_half_cells(r));
            for j in -n..n {
                let (a, b) = (id(r, j), id(r, j + 1));
                let (c, d) = (id(r + 1, j), id(r + 1, j + 1));
                indices.push([a, c, b]);
                indices.push([b, c, d]);
            }
        }

        debug_assert!(
            indices[near_triangles..].iter().all(|t| {
                let [a, b, c] = t.map(|i| vertices[i as usize].pos.map(f64::from));
                (b[1] - a[1]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[1] - a[1]) > 0.0
            }),
            "a stitch or far triangle is not counter-clockwise"
        );
        Ok(Self {
            origin: near.origin,
            origin_cell: near.origin_cell,
            vertices,
            indices,
            near_vertices,
            near_triangles,
            stitch_triangles,
            far_first_ring: first,
            far_inner_radius_m: rings[first] * h,
            far_outer_radius_m: rings[rings.len() - 1] * h,
        })
    }

    /// The near patch alone, for a view whose footprint on the sea lies inside it (the plan's
    /// `far_patch` rule): the far patch and the stitch would be clipped whole, so they are not
    /// built. The far-ring fields are 0.
    pub fn near_only(params: &PatchParams, eye: [f64; 3]) -> Result<Self> {
        let near = NearPatch::kept(params, eye)?;
        Ok(Self {
            origin: near.origin,
            origin_cell: near.origin_cell,
            near_vertices: near.vertices.len(),
            near_triangles: near.indices.len(),
            vertices: near.vertices,
            indices: near.indices,
            stitch_triangles: 0,
            far_first_ring: 0,
            far_inner_radius_m: 0.0,
            far_outer_radius_m: 0.0,
        })
    }

    /// Vertex and triangle counts.
    pub fn summary(&self) -> MeshSummary {
        MeshSummary {
            vertices: self.vertices.len(),
            near_vertices: self.near_vertices,
            near_triangles: self.near_triangles,
            stitch_triangles: self.stitch_triangles,
            far_triangles: self.indices.len() - self.near_triangles - self.stitch_triangles,
            far_inner_radius_m: self.far_inner_radius_m,
            far_outer_radius_m: self.far_outer_radius_m,
        }
    }
}

/// Triangulates the annulus between two loops around the eye, each given as (azimuth in
/// [0, 2π), vertex) in counter-clockwise order from its smallest azimuth: at each step the
/// loop whose next vertex has the smaller azimuth advances (the inner one on ties).
fn zip(inner: &[(f64, u32)], outer: &[(f64, u32)], out: &mut Vec<[u32; 3]>) {
    let (na, nb) = (inner.len(), outer.len());
    let at = |l: &[(f64, u32)], k: usize| {
        let (a, i) = l[k % l.len()];
        (if k >= l.len() { a + TAU } else { a }, i)
    };
    let (mut i, mut k) = (0, 0);
    while i < na || k < nb {
        let advance_inner = k == nb || (i < na && at(inner, i + 1).0 <= at(outer, k + 1).0);
        if advance_inner {
            out.push([at(inner, i).1, at(outer, k).1, at(inner, i + 1).1]);
            i += 1;
        } else {
            out.push([at(outer, k).1, at(outer, k + 1).1, at(inner, i).1]);
            k += 1;
        }
    }
}

/// Vertex of the objects' meshes (WGSL `ObjectVertex`): camera-relative position, unit normal,
/// linear albedo.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ObjectVertex {
    /// Position − eye, m.
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Linear RGB albedo.
    pub color: [f32; 3],
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Zips a square's boundary (`per_side` edges per side) to a ring of `m` vertices at
    /// radius `r` about `eye`; returns the smallest orientation (y of (b − a) × (c − a)).
    fn worst_orientation(
        half: f64,
        per_side: i32,
        eye: [f64; 2],
        m: u32,
        r: f64,
        phase: f64,
    ) -> f64 {
        let mut pts: Vec<[f64; 2]> = Vec::new();
        for side in 0..4 {
            for k in 0..per_side {
                let s = -half + 2.0 * half * f64::from(k) / f64::from(per_side);
                pts.push(match side {
                    0 => [-half, s],
                    1 => [s, half],
                    2 => [half, -s],
                    _ => [-s, -half],
                });
            }
        }
        let inner_n = pts.len() as u32;
        for j in 0..m {
            let phi = TAU * f64::from(j) / f64::from(m) + phase;
            pts.push([eye[0] + r * phi.sin(), eye[1] + r * phi.cos()]);
        }
        let by_azimuth = |ids: std::ops::Range<u32>| {
            let mut l: Vec<(f64, u32)> = ids
                .map(|i| {
                    let p = pts[i as usize];
                    let a = (p[0] - eye[0]).atan2(p[1] - eye[1]);
                    (if a < 0.0 { a + TAU } else { a }, i)
                })
                .collect();
            l.sort_by(|a, b| a.0.total_cmp(&b.0));
            l
        };
        let mut out = Vec::new();
        zip(&by_azimuth(0..inner_n), &by_azimuth(inner_n..inner_n + m), &mut out);
        assert_eq!(out.len(), (inner_n + m) as usize);
        out.iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| pts[i as usize]);
                (b[1] - a[1]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[1] - a[1])
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn stitch_radius_keeps_the_zip_counter_clockwise() {
        for (half, per_side, eye, m) in [
            (2.0, 4, [0.5, 0.5], 16),
            (2.0, 1, [-0.5, 0.3], 16),
            (256.0, 64, [0.5, -0.5], 128),
            (256.0, 64, [0.0, 0.0], 16),
        ] {
            let needed = stitch_radius(half, eye, m).expect("stitchable");
            for scale in [1.0, 1.25, 3.0, 1e3] {
                for phase in 0..20 {
                    let phase = f64::from(phase) * 0.05;
                    let worst = worst_orientation(half, per_side, eye, m, needed * scale, phase);
                    assert!(worst > 0.0, "half {half} eye {eye:?} M {m} ×{scale}: {worst}");
                }
            }
        }
        // Negative control: the plain clearance of the corners is not enough.
        let (half, eye, m) = (2.0, [0.5, 0.5], 16);
        let corner = 2.5f64.hypot(2.5) / (PI / 16.0).cos();
        let worst = (0..40)
            .map(|p| worst_orientation(half, 4, eye, m, 1.001 * corner, f64::from(p) * 0.01))
            .fold(f64::INFINITY, f64::min);
        assert!(worst <= 0.0, "{worst}");
        assert!(stitch_radius(half, eye, m).unwrap() > corner);
        // And no radius works when a ring step plus the corner angle reach 90°.
        assert!(stitch_radius(256.0, [0.0, 0.0], 4).is_none());
    }
}

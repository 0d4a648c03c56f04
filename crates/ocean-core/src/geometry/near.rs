//! The near patch (seed 000 §3, Fig. 2a): a square of side S under the eye, triangulated by a
//! right-isosceles binary triangle tree (Duchaineau et al. 1997, ROAM) refined by distance
//! to the eye.
//!
//! **Grid.** Everything is computed on integer grid coordinates (i, j), one unit = the
//! displacement grid spacing g = L/N, relative to the patch centre c = origin_cell · g. The
//! centre is the eye's (x, z) rounded to the nearest grid point, so every vertex is a sample
//! point of the displacement map (sample (i, j) of the map is at (i·g, j·g)) whatever the eye
//! does: as the camera moves the vertices jump by whole samples and never slide across the
//! map ("swimming").
//!
//! **Tree.** Level 0 is the square cut along its diagonal from (−h, −h) to (h, h), h = S/2g.
//! Splitting a triangle (apex a, hypotenuse l–r) at the hypotenuse midpoint m gives the
//! children (m, a, l) and (m, r, a). Each leaf keeps links to its neighbours across its
//! hypotenuse (base), and across its legs; a triangle may only be split together with its
//! base neighbour (a "diamond"), and when that neighbour is coarser it is split first,
//! recursively (ROAM's forced split). So the mesh is always conforming: no T-junctions.
//!
//! **Which triangles split.** A leaf below `max_depth` is split when it wants to and can:
//! - it wants to when its hypotenuse (length ℓ, circumscribed disc of radius ℓ/2 about the
//!   hypotenuse midpoint) subtends more than `split_threshold` at the eye: ℓ > τ·d with
//!   d = √(H² + max(0, |e − m| − ℓ/2)²), e the eye's (x, z); or when one of its edges lies on
//!   the patch boundary and is longer than the boundary edge S/boundary_segments;
//! - it can unless the split (with the forced splits it implies) would cut a boundary edge of
//!   length S/boundary_segments: the boundary is subdivided exactly that finely, always.
//!
//! Both tests are fixed properties of a triangle (for given eye and parameters), so the result
//! is the smallest conforming tree containing every wanted, feasible split: independent of
//! the order of the work list, and monotone in H (d grows with H, so a higher eye wants a
//! subset of the splits).

use std::collections::HashMap;

use super::params::{Layout, PatchParams};
use super::{WaterVertex, effective_height, snap_to_grid};
use crate::Result;

/// "No triangle": a missing neighbour (the patch boundary) or child.
const NONE: u32 = u32::MAX;

/// One bintree triangle, in grid coordinates. Counter-clockwise seen from above (+y).
#[derive(Clone, Copy, Debug)]
struct Node {
    apex: [i32; 2],
    left: [i32; 2],
    right: [i32; 2],
    depth: u32,
    /// Index of the left child (the one holding `left`); the right child follows it.
    children: u32,
    /// Neighbour across the hypotenuse left–right.
    base: u32,
    /// Neighbour across the leg apex–left.
    left_n: u32,
    /// Neighbour across the leg apex–right.
    right_n: u32,
}

impl Node {
    fn hypotenuse_len2(&self) -> i64 {
        let dx = i64::from(self.right[0] - self.left[0]);
        let dz = i64::from(self.right[1] - self.left[1]);
        dx * dx + dz * dz
    }
}

/// The refinement rule, with everything it needs.
struct Refiner {
    nodes: Vec<Node>,
    layout: Layout,
    max_depth: u32,
    /// Leaves at this depth whose hypotenuse is on the boundary are never split.
    frozen_depth: u32,
    /// Eye (x, z) relative to the centre, in grid units, and its height in grid units.
    eye: [f64; 2],
    height: f64,
    threshold: f64,
}

impl Refiner {
    fn wants(&self, t: u32) -> bool {
        let n = &self.nodes[t as usize];
        if n.depth >= self.max_depth {
            return false;
        }
        let h = self.layout.half_cells;
        let step = i64::from(self.layout.boundary_step());
        // An edge on the boundary longer than a boundary edge.
        let coarse_boundary = |p: [i32; 2], q: [i32; 2]| {
            let on_side = (p[0] == q[0] && p[0].abs() == h) || (p[1] == q[1] && p[1].abs() == h);
            on_side && i64::from((p[0] - q[0]).abs() + (p[1] - q[1]).abs()) > step
        };
        if coarse_boundary(n.left, n.right)
            || coarse_boundary(n.apex, n.left)
            || coarse_boundary(n.apex, n.right)
        {
            return true;
        }
        let len = (n.hypotenuse_len2() as f64).sqrt();
        let mid =
            [0.5 * f64::from(n.left[0] + n.right[0]), 0.5 * f64::from(n.left[1] + n.right[1])];
        let planar = ((self.eye[0] - mid[0]).hypot(self.eye[1] - mid[1]) - 0.5 * len).max(0.0);
        len > self.threshold * self.height.hypot(planar)
    }

    /// Whether `t` can be split without cutting a boundary edge of the final size.
    fn can_split(&self, t: u32) -> bool {
        let n = &self.nodes[t as usize];
        if n.children != NONE {
            return true;
        }
        if n.base == NONE {
            return n.depth < self.frozen_depth;
        }
        // A diamond partner shares the (interior) hypotenuse: it is never frozen.
        self.nodes[n.base as usize].base == t || self.can_split(n.base)
    }

    /// ROAM's split: the coarser base neighbour first, then the diamond.
    fn split(&mut self, t: u32) {
        if self.nodes[t as usize].children != NONE {
            return;
        }
        let b = self.nodes[t as usize].base;
        if b != NONE && self.nodes[b as usize].base != t {
            self.split(b);
        }
        // After the forced split the base link names the partner across the same hypotenuse.
        let b = self.nodes[t as usize].base;
        self.make_children(t);
        if b != NONE {
            debug_assert_eq!(self.nodes[b as usize].base, t, "base neighbour is no diamond");
            debug_assert_eq!(self.nodes[b as usize].children, NONE);
            self.make_children(b);
            let (tl, tr) = (self.nodes[t as usize].children, self.nodes[t as usize].children + 1);
            let (bl, br) = (self.nodes[b as usize].children, self.nodes[b as usize].children + 1);
            self.nodes[tl as usize].right_n = br;
            self.nodes[tr as usize].left_n = bl;
            self.nodes[bl as usize].right_n = tr;
            self.nodes[br as usize].left_n = tl;
        }
    }

    /// Splits `t` alone at its hypotenuse midpoint and relinks its leg neighbours; the links
    /// across the hypotenuse are left to [`Self::split`].
    fn make_children(&mut self, t: u32) {
        let n = self.nodes[t as usize];
        debug_assert!((n.left[0] + n.right[0]) % 2 == 0 && (n.left[1] + n.right[1]) % 2 == 0);
        let m = [(n.left[0] + n.right[0]) / 2, (n.left[1] + n.right[1]) / 2];
        let lc = self.nodes.len() as u32;
        let rc = lc + 1;
        self.nodes.push(Node {
            apex: m,
            left: n.apex,
            right: n.left,
            depth: n.depth + 1,
            children: NONE,
            base: n.left_n,
            left_n: rc,
            right_n: NONE,
        });
        self.nodes.push(Node {
            apex: m,
            left: n.right,
            right: n.apex,
            depth: n.depth + 1,
            children: NONE,
            base: n.right_n,
            left_n: NONE,
            right_n: lc,
        });
        self.relink(n.left_n, t, lc);
        self.relink(n.right_n, t, rc);
        self.nodes[t as usize].children = lc;
    }

    /// In neighbour `x`, replaces the link to `old` by `new`.
    fn relink(&mut self, x: u32, old: u32, new: u32) {
        if x == NONE {
            return;
        }
        let n = &mut self.nodes[x as usize];
        if n.base == old {
            n.base = new;
        } else if n.left_n == old {
            n.left_n = new;
        } else if n.right_n == old {
            n.right_n = new;
        } else {
            debug_assert!(false, "neighbour {x} has no link to {old}");
        }
    }
}

/// The near patch of one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct NearPatch {
    /// The patch centre in grid cells: c = origin_cell · grid_spacing_m. Vertex positions are
    /// relative to c.
    pub origin_cell: [i64; 2],
    /// The patch centre c, metres (world x, z).
    pub origin: [f64; 2],
    /// The patch's side S, metres.
    pub size_m: f64,
    /// Vertices: positions relative to `origin`, all on the grid; weight 0 on the boundary.
    pub vertices: Vec<WaterVertex>,
    /// Triangles, counter-clockwise seen from above (+y).
    pub indices: Vec<[u32; 3]>,
    /// The boundary vertices (indices into `vertices`), `4 · boundary_segments` of them,
    /// counter-clockwise seen from above starting at the corner (−S/2, −S/2).
    pub boundary: Vec<u32>,
    /// The deepest level among the leaves.
    pub deepest_level: u32,
}

impl NearPatch {
    /// [`Self::build`], made once per (params, eye) and copied from then on: a steady camera
    /// asks the same patch every frame (its quadtree refinement was a share of `hu`'s CPU
    /// encode every frame).
    ///
    /// # Errors
    /// As [`Self::build`] (an error is not kept).
    pub fn kept(params: &PatchParams, eye: [f64; 3]) -> Result<Self> {
        static KEPT: crate::kept::Kept<(PatchParams, [u64; 3]), NearPatch> =
            crate::kept::Kept::new();
        KEPT.get_or_make((params.clone(), eye.map(f64::to_bits)), || Self::build(params, eye))
    }

    /// Builds the near patch for an eye at `eye` (world x, y, z, metres): centred on the
    /// eye's (x, z) snapped to the grid, refined for H = max(|eye.y|, min_height_m).
    pub fn build(params: &PatchParams, eye: [f64; 3]) -> Result<Self> {
        let layout = params.validate()?;
        let height = effective_height(params, eye[1])?;
        let (origin_cell, origin) = snap_to_grid(params, [eye[0], eye[2]])?;
        let g = layout.grid;
        let h = layout.half_cells;

        let root = |apex, left, right, base| Node {
            apex,
            left,
            right,
            depth: 0,
            children: NONE,
            base,
            left_n: NONE,
            right_n: NONE,
        };
        let mut refiner = Refiner {
            nodes: vec![root([h, -h], [-h, -h], [h, h], 1), root([-h, h], [h, h], [-h, -h], 0)],
            layout,
            max_depth: params.max_depth,
            frozen_depth: 2 * layout.boundary_level + 1,
            eye: [(eye[0] - origin[0]) / g, (eye[2] - origin[1]) / g],
            height: height / g,
            threshold: params.split_threshold,
        };
        let mut work = vec![0u32, 1];
        while let Some(t) = work.pop() {
            if refiner.nodes[t as usize].children == NONE
                && refiner.wants(t)
                && refiner.can_split(t)
            {
                let first_new = refiner.nodes.len() as u32;
                refiner.split(t);
                work.extend(first_new..refiner.nodes.len() as u32);
            }
        }

        // Leaves in depth-first order, left child first; vertices numbered on first use.
        let mut index_of = VertexIndex::new(h);
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        let mut deepest_level = 0;
        let taper_cells = params.weight_taper_m / g;
        let mut vertex = |p: [i32; 2], vertices: &mut Vec<WaterVertex>| {
            index_of.get_or_insert(p, || {
                vertices.push(WaterVertex {
                    pos: [(f64::from(p[0]) * g) as f32, (f64::from(p[1]) * g) as f32],
                    weight: near_weight(h - p[0].abs().max(p[1].abs()), taper_cells),
                });
                (vertices.len() - 1) as u32
            })
        };
        let mut stack = vec![1u32, 0];
        while let Some(t) = stack.pop() {
            let n = refiner.nodes[t as usize];
            if n.children != NONE {
                stack.push(n.children + 1);
                stack.push(n.children);
                continue;
            }
            deepest_level = deepest_level.max(n.depth);
            let tri = [n.apex, n.left, n.right].map(|p| vertex(p, &mut vertices));
            indices.push(tri);
        }

        // The boundary, counter-clockwise seen from above: x = −h upwards in z, then z = h,
        // x = h, z = −h.
        let step = layout.boundary_step();
        let per_side = 2 * h / step;
        let mut boundary = Vec::with_capacity(4 * per_side as usize);
        for side in 0..4 {
            for k in 0..per_side {
                let s = -h + k * step;
                let p = match side {
                    0 => [-h, s],
                    1 => [s, h],
                    2 => [h, -s],
                    _ => [-s, -h],
                };
                let i = index_of.get(p);
                boundary.push(i.expect("the bintree subdivides the boundary exactly"));
            }
        }
        debug_assert_eq!(
            vertices.iter().filter(|v| v.weight == 0.0).count(),
            boundary.len(),
            "a boundary vertex off the fixed boundary subdivision"
        );

        Ok(Self {
            origin_cell,
            origin,
            size_m: g * f64::from(2 * h),
            vertices,
            indices,
            boundary,
            deepest_level,
        })
    }
}

/// Vertex numbers by grid point: a dense table up to 2^22 grid points, a hash map beyond.
enum VertexIndex {
    Dense { half: i32, ids: Vec<u32> },
    Sparse(HashMap<[i32; 2], u32>),
}

impl VertexIndex {
    fn new(half: i32) -> Self {
        let side = 2 * i64::from(half) + 1;
        if side * side <= 1 << 22 {
            Self::Dense { half, ids: vec![NONE; (side * side) as usize] }
        } else {
            Self::Sparse(HashMap::new())
        }
    }

    fn slot(half: i32, p: [i32; 2]) -> usize {
        let side = 2 * half as usize + 1;
        (p[1] + half) as usize * side + (p[0] + half) as usize
    }

    fn get(&self, p: [i32; 2]) -> Option<u32> {
        match self {
            Self::Dense { half, ids } => Some(ids[Self::slot(*half, p)]).filter(|&i| i != NONE),
            Self::Sparse(map) => map.get(&p).copied(),
        }
    }

    fn get_or_insert(&mut self, p: [i32; 2], make: impl FnOnce() -> u32) -> u32 {
        match self {
            Self::Dense { half, ids } => {
                let slot = &mut ids[Self::slot(*half, p)];
                if *slot == NONE {
                    *slot = make();
                }
                *slot
            }
            Self::Sparse(map) => *map.entry(p).or_insert_with(make),
        }
    }
}

/// The displacement weight of a near vertex `cells` grid cells inside the boundary: 0 on it,
/// rising linearly to 1 at `taper_cells` (a hard 0/1 step for `taper_cells = 0`).
fn near_weight(cells: i32, taper_cells: f64) -> f32 {
    if cells <= 0 {
        0.0
    } else if f64::from(cells) >= taper_cells {
        1.0
    } else {
        (f64::from(cells) / taper_cells) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(levels: u32, boundary: u32) -> PatchParams {
        PatchParams {
            near_size_m: f64::from(1u32 << levels),
            max_depth: 2 * levels,
            boundary_segments: boundary,
            ..PatchParams::for_grid(1.0)
        }
    }

    #[test]
    fn coarsest_patch_is_the_forced_boundary() {
        // Eye very high: only the boundary rule splits. With one segment per side the patch
        // stays the two root triangles.
        let mut p = params(3, 1);
        p.min_height_m = 1e5;
        let near = NearPatch::build(&p, [0.0, 1e5, 0.0]).unwrap();
        assert_eq!(near.indices.len(), 2);
        assert_eq!(near.boundary.len(), 4);
        // Two segments per side: 4 boundary triangles at depth 2… and their conforming
        // closure.
        let mut p = params(3, 2);
        p.min_height_m = 1e5;
        let near = NearPatch::build(&p, [0.0, 1e5, 0.0]).unwrap();
        assert_eq!(near.boundary.len(), 8);
        assert_eq!(near.indices.len(), 8);
    }

    #[test]
    fn dense_and_sparse_vertex_indices_agree() {
        let mut dense = VertexIndex::new(4);
        let mut sparse = VertexIndex::Sparse(HashMap::new());
        assert!(matches!(dense, VertexIndex::Dense { .. }));
        assert!(matches!(VertexIndex::new(1 << 11), VertexIndex::Sparse(_)));
        let points = [[-4, -4], [4, 4], [0, 0], [-4, 4], [3, -2], [0, 0], [4, 4]];
        let (mut nd, mut ns) = (0, 0);
        for p in points {
            let a = dense.get_or_insert(p, || {
                nd += 1;
                nd - 1
            });
            let b = sparse.get_or_insert(p, || {
                ns += 1;
                ns - 1
            });
            assert_eq!(a, b);
        }
        assert_eq!(nd, 5);
        for p in [[-4, -4], [1, 1], [3, -2], [4, -4]] {
            assert_eq!(dense.get(p), sparse.get(p));
        }
        assert_eq!(dense.get([1, 1]), None);
        // A patch big enough for the sparse table builds too.
        let mut p = params(12, 64);
        p.min_height_m = 1e5;
        let near = NearPatch::build(&p, [0.0, 1e5, 0.0]).unwrap();
        assert_eq!(near.boundary.len(), 256);
    }

    #[test]
    fn triangles_are_counter_clockwise_from_above() {
        let near = NearPatch::build(&params(5, 8), [0.3, 1.0, -0.2]).unwrap();
        for t in &near.indices {
            let [a, b, c] = t.map(|i| near.vertices[i as usize].pos.map(f64::from));
            // y of (b − a) × (c − a), with (x, z) stored as [0], [1].
            let up = (b[1] - a[1]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[1] - a[1]);
            assert!(up > 0.0, "{t:?}");
        }
    }
}

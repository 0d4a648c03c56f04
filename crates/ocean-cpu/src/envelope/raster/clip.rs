//! The clipper's envelope: a triangle that may cross the near or far plane becomes the pieces
//! the clipper leaves, each vertex a box in clip space that knows its barycentrics in the
//! original triangle, how far off the original's span the clipper's roundings may put it, and
//! where along its cut edge it may lie (docs/tolerances.md, "Clipping").

use super::cut;
use crate::envelope::{Iv, Real};

/// The clipper's own arithmetic (the implementation's), relative to a new vertex's
/// magnitude: an assumption, generous against f32's few roundings.
pub const CLIP_SLACK: f64 = 1.0 / (1u64 << 20) as f64;

/// A vertex of a clipped triangle: its clip position, its barycentric coordinates in the
/// original triangle (its varyings are the combination they name), and how far each of those
/// may be off (the clipper's own crossing point).
#[derive(Clone, Copy, Debug)]
pub struct ClipVertex {
    /// Clip position.
    pub clip: [Iv; 4],
    /// Barycentric coordinates in the original triangle.
    pub bary: [f64; 3],
    /// The largest error of `bary`'s components.
    pub bary_err: f64,
    /// Per clip coordinate, how far the clipper's roundings may put the vertex off the span
    /// of the original triangle's clip positions (0 for one of them).
    pub off: [f64; 4],
    /// Where on its edge the vertex may lie ([`Slide`]); `None` for a vertex cut from an edge
    /// that was itself cut (its place is not one segment).
    pub slide: Option<Slide>,
}

/// The clip positions (midpoints) at the two ends of the range of the clipper's crossing
/// t ± dt along a cut edge, and the half-width of each coordinate about either end (the
/// edge's endpoints' boxes and the clipper's roundings): every position the vertex may take
/// lies in the convex hull of the two boxes (for a vertex of the original triangle, both
/// ends are its box's midpoint).
#[derive(Clone, Copy, Debug)]
pub struct Slide {
    /// The midpoints at t − dt and t + dt.
    pub ends: [[f64; 4]; 2],
    /// The half-width of each coordinate about either end.
    pub half: [f64; 4],
}

/// The distances to the planes a triangle is clipped against for the envelope: near
/// (z ≤ w) and far (z ≥ 0). The side planes need no clipping: a vertex beyond them still
/// projects, with w > 0, and the target's bounds cut its coverage.
pub(crate) fn plane_distances(v: &[f64; 4]) -> [f64; 2] {
    [v[3] - v[2], v[2]]
}

/// Whether a clip position (intervals) certainly lies inside the near and far planes
/// (0 ≤ z ≤ w, w > 0) for every value of its box: the clipper leaves such a vertex as it is.
/// The bounds' differences need no slack: the sign of an f64 subtraction is exact.
pub fn inside_near_far(v: &[Iv; 4]) -> bool {
    !v[2].full && !v[3].full && v[3].lo > 0.0 && v[3].lo - v[2].hi > 0.0 && v[2].lo >= 0.0
}

/// A triangle of clip positions (intervals) as the rasteriser draws it after the near and
/// far planes: itself where every vertex is inside both, else the fan of the polygon the
/// clipper leaves, each new vertex on an edge from the midpoints, widened by the endpoints'
/// half-widths, by how far their boxes may move the crossing, and by [`CLIP_SLACK`]. Also the
/// barycentric coordinates of each vertex in the original triangle (the varyings of a new
/// vertex are the convex combination they name). `None` where a vertex's side of a plane is
/// undecided by its box or a vertex kept may have w ≤ 0 (the caller then cannot bound it).
pub fn clip_near_far(tri: [[Iv; 4]; 3]) -> Option<Vec<[ClipVertex; 3]>> {
    clip_near_far_deciding(tri, None)
}

/// Whether every point of the triangle lies outside one side plane of the clip volume
/// (x > w, x < −w, y > w or y < −w at all three vertices, for every value of their boxes):
/// the convex combinations do too, so no rasteriser draws any of it, whatever the near
/// plane does to it.
pub fn outside_a_side(tri: [[Iv; 4]; 3]) -> bool {
    if tri.iter().flatten().any(|c| c.full) {
        return false;
    }
    let beyond = |f: &dyn Fn(&[Iv; 4]) -> f64| tri.iter().all(|v| f(v) > 0.0);
    beyond(&|v| v[0].lo - v[3].hi)
        || beyond(&|v| -v[0].hi - v[3].hi)
        || beyond(&|v| v[1].lo - v[3].hi)
        || beyond(&|v| -v[1].hi - v[3].hi)
}

/// [`clip_near_far`] where a vertex's side of a plane is undecided by its box: the pieces of
/// both decisions (the clipper keeps it, or cuts it off), each possible, none certain — the
/// GPU's polygon is one of the two. `None` only where a vertex kept may have w ≤ 0.
pub fn clip_near_far_either(tri: [[Iv; 4]; 3]) -> Option<(Vec<[ClipVertex; 3]>, bool)> {
    if let Some(p) = clip_near_far_deciding(tri, None) {
        return Some((p, true));
    }
    let mut both = clip_near_far_deciding(tri, Some(true))?;
    both.extend(clip_near_far_deciding(tri, Some(false))?);
    Some((both, false))
}

/// [`clip_near_far`], an undecided vertex kept (`Some(true)`), cut (`Some(false)`) or the
/// whole undecided (`None`).
fn clip_near_far_deciding(
    tri: [[Iv; 4]; 3],
    undecided: Option<bool>,
) -> Option<Vec<[ClipVertex; 3]>> {
    let mid = |v: &[Iv; 4]| v.map(|c| 0.5 * (c.lo + c.hi));
    let half = |v: &[Iv; 4]| v.map(|c| 0.5 * (c.hi - c.lo));
    let corner = |k: usize| {
        let mut b = [0.0; 3];
        b[k] = 1.0;
        let slide = Some(Slide { ends: [mid(&tri[k]); 2], half: half(&tri[k]) });
        ClipVertex { clip: tri[k], bary: b, bary_err: 0.0, off: [0.0; 4], slide }
    };
    if tri.iter().all(inside_near_far) {
        return Some(vec![[corner(0), corner(1), corner(2)]]);
    }
    let mut poly: Vec<ClipVertex> = (0..3).map(corner).collect();
    for p in 0..2 {
        let mut out = Vec::new();
        for i in 0..poly.len() {
            let (a, b) = (&poly[i], &poly[(i + 1) % poly.len()]);
            let (da, db) = (plane_distances(&mid(&a.clip))[p], plane_distances(&mid(&b.clip))[p]);
            // A vertex whose box straddles the plane: the clipper's decision is undecided.
            let spread = |v: &[Iv; 4]| half(v)[3] + half(v)[2];
            let side = |d: f64, v: &ClipVertex| {
                if d.abs() <= spread(&v.clip) { undecided } else { Some(d >= 0.0) }
            };
            let (Some(ka), Some(kb)) = (side(da, a), side(db, b)) else { return None };
            if ka {
                out.push(*a);
            }
            if ka != kb {
                let t = da / (da - db);
                let dt = 2.0 * (spread(&a.clip) + spread(&b.clip)) / (da - db).abs() + CLIP_SLACK;
                let (ma, mb, ha, hb) = (mid(&a.clip), mid(&b.clip), half(&a.clip), half(&b.clip));
                let clip: [Iv; 4] = std::array::from_fn(|c| {
                    let m = ma[c] + t * (mb[c] - ma[c]);
                    let h = ha[c].max(hb[c])
                        + (mb[c] - ma[c]).abs() * dt
                        + (m.abs() + ma[c].abs().max(mb[c].abs())) * CLIP_SLACK;
                    Iv::new(m - h, m + h)
                });
                let bary: [f64; 3] =
                    std::array::from_fn(|k| a.bary[k] + t * (b.bary[k] - a.bary[k]));
                // The clipper's own t may differ by dt: so may the weights. Its slide along
                // the edge keeps the vertex on the original's plane; its roundings do not.
                let bary_err = a.bary_err.max(b.bary_err) + dt;
                let off = std::array::from_fn(|c| {
                    let m = ma[c] + t * (mb[c] - ma[c]);
                    a.off[c].max(b.off[c]) + cut::clip_off(m, clip[c].hi - m, ma[c], mb[c])
                });
                let original = a.bary_err == 0.0 && b.bary_err == 0.0;
                let slide = original.then(|| Slide {
                    ends: [t - dt, t + dt]
                        .map(|t| std::array::from_fn(|c| ma[c] + t * (mb[c] - ma[c]))),
                    half: std::array::from_fn(|c| ha[c].max(hb[c]) + off[c]),
                });
                out.push(ClipVertex { clip, bary, bary_err, off, slide });
            }
        }
        poly = out;
        if poly.len() < 3 {
            return Some(Vec::new());
        }
    }
    if poly.iter().any(|v| v.clip[3].lo <= 0.0) {
        return None;
    }
    Some((1..poly.len() - 1).map(|i| [poly[0], poly[i], poly[i + 1]]).collect())
}

/// The value at a vertex of a clipper's piece whose varyings' values at the original
/// triangle's vertices are `vals`: the combination its barycentrics `bary` name (each within
/// `err`, so their sum of changes within 3·err), plus [`VARYING_ULPS`](super::VARYING_ULPS) for its arithmetic; a vertex of the original triangle
/// (`err` 0, one barycentric 1) is its own value.
pub fn part_value(vals: [Iv; 3], bary: [f64; 3], err: f64) -> Iv {
    if err == 0.0 && bary.iter().filter(|&&x| x != 0.0).count() == 1 {
        return vals[bary.iter().position(|&x| x != 0.0).unwrap_or(0)];
    }
    let x = Iv::sum(&[0, 1, 2].map(|j| vals[j] * Iv::new(bary[j], bary[j])));
    let spread = vals.iter().map(|v| v.magnitude()).fold(0.0, f64::max);
    // Each barycentric within err: Σ|Δbary| ≤ 3·err (a forced clipping's may lie outside the
    // triangle, where the tighter 2·err does not hold).
    let u = super::VARYING_ULPS * crate::envelope::f32_ulp(x.magnitude()) + 3.0 * err * spread;
    if x.full { x } else { Iv::new(x.lo - u, x.hi + u) }
}

//! The depth of a clipper's piece from the plane of the triangle it was cut from.
//!
//! A vertex the clipper makes lies on the cut edge at the clipper's own crossing t, which the
//! bounds know only within dt: over an edge whose w spans 4·10⁴ and crosses the near plane at
//! w ≈ 20, that slide is a box of ±115 px on screen. No plane through such boxes can be
//! bounded, so the piece's depth was (−∞, ∞) wherever it may cover. But every slide stays on
//! the edge, and the edge on the original triangle's projective plane: in clip space the
//! triangle spans the 3-space {v : n·v = 0} with n the generalised cross product of its three
//! clip positions, so every point of it on screen (X, Y) (NDC) has depth
//! Z_P = −(n_x·X + n_y·Y + n_w)/n_z, wherever the clipper put its vertices. What remains
//! is each vertex's distance off that plane:
//! - the clipper's roundings ε (`CLIP_SLACK` of the coordinates, per coordinate): a point
//!   v = s + ε with s on the span has z/w − Z_P(x/w, y/w) = n·ε/(w·n_z) exactly;
//! - the rounding of the projective divide and the viewport transform, and the snap (where a
//!   GPU interpolates from the snapped positions): the plane's gradient times the move;
//! - the depth's own rounding.
//!
//! The piece's depth at a sample p is Σλₖzₖ with Σλₖ(Xₖ, Yₖ) = p (the GPU's barycentrics,
//! from the snapped or the unsnapped positions, whichever it interpolates from), so it is
//! Z_P(p) + Σλₖδₖ, and |λₖ| is twice the area of (p, the opposite edge) over twice the
//! piece's: each bounded from the places the vertices may take, not their boxes. Each vertex
//! lies within r of a point of the segment between its slide's ends; twice an area is
//! multilinear in the points' positions on their segments, so it is extreme at the
//! segments' ends, and moving the vertices by r changes it by at most Σ rᵢ·(the opposite
//! edge) + Σ rᵢrⱼ. A new vertex far from the screen (the large δ) then weighs little at a
//! sample near the kept ones.

use super::{CLIP_SLACK, F64_SLACK, ScreenIv, Span, cross, dist};
use crate::envelope::{Iv, f32_ulp};

/// The projective plane a vertex of a clipper's piece lies on (that of the triangle it was
/// cut from, n·v = 0 with n within these spans for every position of the original's vertices
/// in their boxes), how far off it the clipper's roundings may put the vertex (per clip
/// coordinate), and the least w of the vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnPlane {
    normal: [(f64, f64); 4],
    off: [f64; 4],
    w_lo: f64,
    /// The screen positions (px) of the slide's ends, and how far from the segment between
    /// them the vertex may lie (px, per axis; the snap not included): the hull of the ends'
    /// boxes holds every exact projection between them, as the projection of a segment
    /// (w > 0 along it) is a segment.
    ends: [[f64; 2]; 2],
    rho: f64,
}

/// det of a 3×3 matrix of spans, widened for f64's roundings of its six triple products.
fn det3(m: [[Span; 3]; 3]) -> Span {
    let add = |a: Span, b: Span| Span(a.0 + b.0, a.1 + b.1);
    let mut sum = Span(0.0, 0.0);
    let mut terms = 0.0;
    for (p, sign) in [([0, 1, 2], 1.0), ([1, 2, 0], 1.0), ([2, 0, 1], 1.0)].into_iter().chain([
        ([0, 2, 1], -1.0),
        ([2, 1, 0], -1.0),
        ([1, 0, 2], -1.0),
    ]) {
        let t = m[0][p[0]].mul(m[1][p[1]]).mul(m[2][p[2]]);
        terms += t.magnitude();
        sum = add(sum, if sign > 0.0 { t } else { Span(-t.1, -t.0) });
    }
    sum.widen((terms + sum.magnitude()) * F64_SLACK)
}

/// n for the clip positions `tri` (intervals): nⱼ = (−1)ʲ times the minor without column j,
/// so n·v is the 4×4 determinant of (the three positions, v), 0 on their span. `None` where
/// a position may be anything, or the plane may be seen edge-on (n_z's span holds 0: no depth
/// as a function of the screen position).
pub(super) fn span_normal(tri: &[[Iv; 4]; 3]) -> Option<[(f64, f64); 4]> {
    if tri.iter().flatten().any(|c| c.full || !c.lo.is_finite() || !c.hi.is_finite()) {
        return None;
    }
    let n: [Span; 4] = std::array::from_fn(|j| {
        let cols: Vec<usize> = (0..4).filter(|&c| c != j).collect();
        let d = det3(std::array::from_fn(|r| {
            std::array::from_fn(|c| Span(tri[r][cols[c]].lo, tri[r][cols[c]].hi))
        }));
        if j % 2 == 0 { d } else { Span(-d.1, -d.0) }
    });
    let finite = n.iter().all(|s| s.0.is_finite() && s.1.is_finite());
    (finite && (n[2].0 > 0.0 || n[2].1 < 0.0)).then(|| n.map(|s| (s.0, s.1)))
}

/// How far one rounding of the clipper may put a new vertex off the cut edge, per coordinate:
/// [`CLIP_SLACK`] of the coordinate's magnitude and of the endpoints' (the clipper's
/// arithmetic is the implementation's; the same assumption as the vertex's box).
pub(super) fn clip_off(m: f64, half: f64, a: f64, b: f64) -> f64 {
    (m.abs() + half + a.abs().max(b.abs())) * CLIP_SLACK
}

/// The vertices of a clipper's piece after the viewport transform, each knowing the plane of
/// `original` (the triangle's clip positions) it lies on: `None` where a vertex may have
/// w ≤ 0. A piece that is the whole triangle, or one whose plane cannot be bounded, is
/// returned without it (its boxes are then all the rasteriser has).
pub fn piece_to_screen(
    part: &[super::ClipVertex; 3],
    original: &[[Iv; 4]; 3],
    width: u32,
    height: u32,
) -> Option<[ScreenIv; 3]> {
    let [a, b, c] = part.map(|p| super::to_screen(p.clip, width, height));
    let mut s = [a?, b?, c?];
    if part.iter().all(|p| p.bary_err == 0.0) {
        return Some(s);
    }
    let Some(normal) = span_normal(original) else { return Some(s) };
    let mut on = [None; 3];
    for (o, p) in on.iter_mut().zip(part) {
        let Some(slide) = p.slide else { return Some(s) };
        let end = |e: &[f64; 4]| {
            let clip = std::array::from_fn(|c| Iv::new(e[c] - slide.half[c], e[c] + slide.half[c]));
            super::to_screen(clip, width, height)
        };
        let (Some(e0), Some(e1)) = (end(&slide.ends[0]), end(&slide.ends[1])) else {
            return Some(s);
        };
        let mid = |i: Iv| 0.5 * (i.lo + i.hi);
        let half = |i: Iv| 0.5 * (i.hi - i.lo);
        // The ends' boxes hold the exact projections of the two ends (and their roundings);
        // a position between them is rounded on its own: a few ULP more.
        let big = [e0.x, e0.y, e1.x, e1.y].into_iter().map(Iv::magnitude).fold(0.0, f64::max);
        let rho = [e0.x, e0.y, e1.x, e1.y].into_iter().map(half).fold(0.0, f64::max)
            + 8.0 * f32_ulp(big + f64::from(width.max(height)));
        let ends = [[mid(e0.x), mid(e0.y)], [mid(e1.x), mid(e1.y)]];
        *o = Some(OnPlane { normal, off: p.off, w_lo: p.clip[3].lo, ends, rho });
    }
    for (v, o) in s.iter_mut().zip(on) {
        v.on = o;
    }
    Some(s)
}

/// Where a piece's vertices may lie on screen: each within `r` px (Euclidean) of a point of
/// the segment between its slide's `ends`.
#[derive(Clone, Copy, Debug)]
struct Places {
    ends: [[[f64; 2]; 2]; 3],
    r: [f64; 3],
}

impl Places {
    /// The least |twice the area| of any triangle in the places: at the corners of the
    /// slides (multilinear), less the moves' share (each vertex's r times the opposite edge's
    /// length, plus their products). `None` where the area's sign may change.
    fn least_area(&self) -> Option<f64> {
        let (mut lo, mut hi, mut moved) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
        for corner in 0..8usize {
            let p: [[f64; 2]; 3] = std::array::from_fn(|k| self.ends[k][corner >> k & 1]);
            let a2 = cross(p[0], p[1], p[2]);
            lo = lo.min(a2);
            hi = hi.max(a2);
            let share =
                (0..3).map(|k| self.r[k] * dist(p[(k + 1) % 3], p[(k + 2) % 3])).sum::<f64>();
            moved = moved.max(share);
        }
        let [r0, r1, r2] = self.r;
        let least = if lo > 0.0 {
            lo
        } else if hi < 0.0 {
            -hi
        } else {
            return None;
        };
        // f64's roundings of the corners: far below the 1e-9 kept.
        let least = least * (1.0 - 1e-9) - moved - (r0 * r1 + r1 * r2 + r2 * r0);
        (least.is_finite() && least > 0.0).then_some(least)
    }

    /// The largest |twice the area| of (vertex i, vertex j, p): the GPU's barycentric of the
    /// third vertex at p is that over twice the piece's area.
    fn most_area_with(&self, i: usize, j: usize, p: [f64; 2]) -> f64 {
        let (ri, rj) = (self.r[i], self.r[j]);
        let mut most = 0.0f64;
        for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            let (vi, vj) = (self.ends[i][a], self.ends[j][b]);
            let e = cross(vi, vj, p).abs() + ri * dist(vj, p) + rj * dist(p, vi) + ri * rj;
            most = most.max(e);
        }
        most * (1.0 + 1e-9)
    }

    /// The most the edge (i, j) may extend along x and along y: |∂λₖ/∂y| and |∂λₖ/∂x| of
    /// the third vertex k times twice the area.
    fn extent(&self, i: usize, j: usize) -> [f64; 2] {
        let mut most = [0.0f64; 2];
        for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            let (p, q) = (self.ends[i][a], self.ends[j][b]);
            most = [most[0].max((q[0] - p[0]).abs()), most[1].max((q[1] - p[1]).abs())];
        }
        most.map(|m| m + self.r[i] + self.r[j])
    }

    /// The longest the edge (i, j) may be.
    fn longest(&self, i: usize, j: usize) -> f64 {
        let mut most = 0.0f64;
        for (a, b) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            most = most.max(dist(self.ends[i][a], self.ends[j][b]));
        }
        most + self.r[i] + self.r[j]
    }
}

/// A piece's depth from its original plane, set up for one device's snap.
#[derive(Clone, Copy, Debug)]
pub(super) struct CutDepth {
    normal: [Span; 4],
    size: [f64; 2],
    places: Places,
    /// Per vertex, how far its depth may lie off the plane (δₖ).
    delta: [f64; 3],
    /// The least |twice the piece's area| (px²).
    area: f64,
    /// The largest term of the GPU's depth plane for the piece anchored anywhere in the
    /// target (what its f32 evaluation's allowance scales with).
    pub(super) magnitude: f64,
    /// Per vertex, how far (px, per axis) the GPU's position may lie from the exact
    /// projection of its point on the original's span: the snap, the divide's and the
    /// viewport's roundings, and the clipper's roundings seen on screen.
    shift: [[f64; 2]; 3],
    /// The largest relative error of a vertex's 1/w against its point on the span's (the
    /// clipper's rounding of w, the divide's).
    rho: f64,
    /// The farthest a plane of the GPU's interpolation may be anchored (px, along x and y).
    arm: [f64; 2],
}

impl CutDepth {
    /// The piece `v`'s depth bound at a snap of `snap` px: `None` where its vertices know no
    /// common plane, or their places bound no area.
    pub(super) fn new(v: &[ScreenIv; 3], size: [u32; 2], snap: f64) -> Option<CutDepth> {
        let on = v.map(|v| v.on);
        let first = on[0]?;
        if on.iter().any(|o| o.map(|o| o.normal) != Some(first.normal)) {
            return None;
        }
        let on = [first, on[1]?, on[2]?];
        let places = Places {
            ends: on.map(|o| o.ends),
            r: on.map(|o| std::f64::consts::SQRT_2 * (o.rho + snap)),
        };
        let area = places.least_area()?;
        let normal = first.normal.map(|(lo, hi)| Span(lo, hi));
        let nz_min = normal[2].0.abs().min(normal[2].1.abs());
        let (w, h) = (f64::from(size[0]), f64::from(size[1]));
        // |∂Z_P/∂px|, |∂Z_P/∂py|: X = 2px/W − 1, Y = 1 − 2py/H.
        let gx = normal[0].magnitude() / nz_min * 2.0 / w;
        let gy = normal[1].magnitude() / nz_min * 2.0 / h;
        let delta: [f64; 3] = std::array::from_fn(|k| {
            let (v, o) = (&v[k], on[k]);
            let off =
                (0..4).map(|c| normal[c].magnitude() * o.off[c]).sum::<f64>() / (o.w_lo * nz_min);
            // The divide and viewport transform's roundings (a few ULP of the result, and of
            // the viewport's offset), and the snap.
            let moved = |m: f64, extent: f64| snap + 8.0 * f32_ulp(m + extent);
            off + gx * moved(v.x.magnitude(), w)
                + gy * moved(v.y.magnitude(), h)
                + 8.0 * f32_ulp(v.z.magnitude())
        });
        // The GPU's plane: Z_P's gradient plus the offsets' plane's (Σδₖ∇λₖ, |∇λₖ| the
        // opposite edge's length over twice the area), anchored as far as the farthest
        // vertex or the target's edge.
        let g_off =
            (0..3).map(|k| delta[k] * places.longest((k + 1) % 3, (k + 2) % 3) / area).sum::<f64>();
        let (arm_x, arm_y) =
            v.iter().fold((w, h), |(ax, ay), v| (ax.max(v.x.magnitude()), ay.max(v.y.magnitude())));
        let z_max = v.iter().map(|v| v.z.magnitude()).fold(0.0, f64::max);
        let magnitude = z_max + (gx + g_off) * arm_x + (gy + g_off) * arm_y;
        let shift: [[f64; 2]; 3] = std::array::from_fn(|k| {
            let (v, o) = (&v[k], on[k]);
            // x/w moves by (|εx| + |x/w|·|εw|)/w for a rounding ε of (x, w); NDC to px × W/2.
            let axis = |m: f64, extent: f64, off: f64| {
                let ndc = 2.0 * m / extent + 1.0;
                snap + 8.0 * f32_ulp(m + extent) + (off + ndc * o.off[3]) / o.w_lo * 0.5 * extent
            };
            [axis(v.x.magnitude(), w, o.off[0]), axis(v.y.magnitude(), h, o.off[1])]
        });
        // 1/w of w + ε, then the divide's few ULP u: (1 + u)/(1 + ε/w) − 1 is within
        // (|ε/w| + u)/(1 − |ε/w|).
        let moved_w = on.iter().map(|o| o.off[3] / o.w_lo).fold(0.0, f64::max);
        // (Past a half, no bound: the varyings then keep the piece's own.)
        let rho = if moved_w < 0.5 {
            (moved_w + 4.0 * f32_ulp(1.0)) / (1.0 - moved_w)
        } else {
            f64::INFINITY
        };
        let finite = delta.iter().all(|d| d.is_finite())
            && magnitude.is_finite()
            && shift.as_flattened().iter().all(|s| s.is_finite());
        finite.then_some(CutDepth {
            normal,
            size: [w, h],
            places,
            delta,
            area,
            magnitude,
            shift,
            rho,
            arm: [arm_x, arm_y],
        })
    }

    /// Where the GPU's interpolation at sample (px, py) takes its varyings from in the
    /// original triangle ([`CutSample`]).
    pub(super) fn sample(&self, px: f64, py: f64) -> CutSample {
        let lam: [f64; 3] = std::array::from_fn(|k| {
            self.places.most_area_with((k + 1) % 3, (k + 2) % 3, [px, py]) / self.area
        });
        let reach = [0, 1].map(|a| (0..3).map(|k| lam[k] * self.shift[k][a]).sum::<f64>());
        // |∂λₖ/∂x| is the opposite edge's extent along y over twice the area, and the other
        // way round: a piece 10⁵ px long and 40 px across has steep λ planes across it, and
        // along x, where its far vertex lies, 14 times flatter.
        let anchor: [f64; 3] = std::array::from_fn(|k| {
            let [ex, ey] = self.places.extent((k + 1) % 3, (k + 2) % 3);
            (ey * self.arm[0] + ex * self.arm[1]) / self.area
        });
        CutSample { at: [px, py], reach, size: self.size, lam, anchor, rho: self.rho }
    }

    /// [lo, hi] of the piece's depth at sample (px, py), before the f32 evaluation's
    /// allowance: the plane's, and Σ|λₖ|δₖ off it.
    pub(super) fn at(&self, px: f64, py: f64) -> (f64, f64) {
        let x = 2.0 * px / self.size[0] - 1.0;
        let y = 1.0 - 2.0 * py / self.size[1];
        let [nx, ny, nz, nw] = self.normal;
        let num = Span(
            nx.mul(Span(x, x)).0 + ny.mul(Span(y, y)).0 + nw.0,
            nx.mul(Span(x, x)).1 + ny.mul(Span(y, y)).1 + nw.1,
        );
        let num = num.widen(
            (nx.magnitude() * x.abs() + ny.magnitude() * y.abs() + nw.magnitude()) * F64_SLACK,
        );
        // n_z's span excludes 0 (span_normal), so the quotient exists.
        let Some(z) = num.div(nz) else { return (f64::NEG_INFINITY, f64::INFINITY) };
        let off = (0..3)
            .map(|k| {
                let lam =
                    self.places.most_area_with((k + 1) % 3, (k + 2) % 3, [px, py]) / self.area;
                lam * self.delta[k]
            })
            .sum::<f64>();
        (-z.1 - off, -z.0 + off)
    }
}

/// Where a sample of a clipper's piece takes its varyings from in the original triangle. A
/// piece's vertex holds the position and the values of one point of the original's span
/// (the clipper interpolates both with its own t), so the GPU's perspective-correct
/// interpolation at the sample is the original triangle's own at a screen point p*: its
/// barycentrics at the sample, from its snapped and rounded positions, are the exact ones at
/// p* = Σλ′ⱼ·(the exact projections), within Σ|λ′ⱼ|·(the moves) of the sample
/// (docs/tolerances.md, "The device's precision").
#[derive(Clone, Copy, Debug)]
pub(super) struct CutSample {
    at: [f64; 2],
    /// How far p* may lie from the sample (px, per axis).
    reach: [f64; 2],
    size: [f64; 2],
    /// |λ′ⱼ| at the sample, at most.
    lam: [f64; 3],
    /// Per vertex, |∇λ′ⱼ| times the farthest anchor: its interpolation planes' terms per
    /// unit value.
    anchor: [f64; 3],
    /// As [`CutDepth`]'s.
    rho: f64,
}

#[cfg(test)]
impl CutSample {
    /// The same sample with no allowance for the interpolation planes' gradients (a
    /// negative control's).
    pub(super) fn without_planes(self) -> CutSample {
        CutSample { anchor: [0.0; 3], ..self }
    }
}

/// (a × b) over spans, widened for f64's roundings.
fn cross_span(a: [Span; 3], b: [Span; 3]) -> [Span; 3] {
    std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let (p, q) = (a[j].mul(b[k]), a[k].mul(b[j]));
        p.sub(q).widen((p.magnitude() + q.magnitude()) * F64_SLACK)
    })
}

/// The values a varying of a clipper's piece may take at a sample, from the triangle it was
/// cut from: its clip positions `clip` and its vertices' values `a` (both as the vertex stage
/// left them); `piece` the piece's vertices' values and `q` their 1/w. `None` where the
/// bound cannot be made (a value or position unbounded, the original's w may change sign
/// near the sample).
///
/// The reference is the GPU's piece with its vertices moved to their points Sⱼ on the
/// original's span (the clipper's own t) and the exact projection: its barycentrics at p*
/// are the GPU's at the sample, and its perspective interpolation is the original's value
/// at p*, Σeₖaₖ/Σeₖ with eₖ = (Hᵢ × Hⱼ)·(X, Y, 1) over the clip positions' (x, y, w):
/// linear-fractional in (X, Y), so extreme at the corners of p*'s box. The GPU's differs
/// from it by its 1/w (each weight scaled by 1 + ρⱼ: at most ρG(1 + G)/(1 − ρG) times half
/// the piece's values' spread, G ≥ Σ|weights|), the clipper's rounding of the new vertices'
/// values (G times it), and the interpolation's own arithmetic (as
/// [`super::Interp::varying`]'s, its planes' terms bounded from the places).
pub(super) fn original_value(
    s: &CutSample,
    clip: &[[Iv; 4]; 3],
    a: [Iv; 3],
    piece: [Iv; 3],
    q: [(f64, f64); 3],
) -> Option<Iv> {
    use super::VARYING_ULPS;
    let bad = |c: &Iv| c.full || !c.lo.is_finite() || !c.hi.is_finite();
    if clip.iter().flatten().any(bad) || a.iter().chain(&piece).any(bad) {
        return None;
    }
    let sum3 = |t: [Span; 3]| {
        let sum = Span(t[0].0 + t[1].0 + t[2].0, t[0].1 + t[1].1 + t[2].1);
        sum.widen(t.iter().map(|&t| t.magnitude()).sum::<f64>() * 4.0 * F64_SLACK)
    };
    let h = clip.map(|c| [c[0], c[1], c[3]].map(Span::of));
    let c = [cross_span(h[1], h[2]), cross_span(h[2], h[0]), cross_span(h[0], h[1])];
    // det(H) = H₀·(H₁ × H₂): Σeₖ(P)/det is the original's 1/w at P.
    let det = sum3(std::array::from_fn(|i| h[0][i].mul(c[0][i])));
    if !(det.0 > 0.0 || det.1 < 0.0) {
        return None;
    }
    let av = a.map(Span::of);
    let (mut lo, mut hi, mut inv_w_min) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    for corner in 0..4u32 {
        let d = |bit: u32| if corner >> bit & 1 == 0 { -1.0 } else { 1.0 };
        let px = s.at[0] + d(0) * s.reach[0];
        let py = s.at[1] + d(1) * s.reach[1];
        // x and y carry f64's roundings: relative 2⁻⁵², inside the slack (+1 per term).
        let (x, y) = (2.0 * px / s.size[0] - 1.0, 1.0 - 2.0 * py / s.size[1]);
        let e = c.map(|c| {
            let t = [c[0].mul(Span(x, x)), c[1].mul(Span(y, y)), c[2]];
            sum3(t).widen((t[0].magnitude() + t[1].magnitude()) * 4.0 * F64_SLACK)
        });
        let den = sum3(e);
        // The original's 1/w there must be positive (so Σeₖ keeps one sign over the box,
        // being linear in P): the piece lies in front of the eye.
        let inv_w = den.div(det)?;
        if inv_w.0 <= 0.0 {
            return None;
        }
        inv_w_min = inv_w_min.min(inv_w.0);
        let num = sum3([e[0].mul(av[0]), e[1].mul(av[1]), e[2].mul(av[2])]);
        let v = num.div(den)?;
        lo = lo.min(v.0);
        hi = hi.max(v.1);
    }
    // The GPU's Σλ′q′ is the reference's (1/w at p*) but for each q′ⱼ off by ρ; the sum of
    // the weights' magnitudes is then at most G.
    let lq: f64 = (0..3).map(|j| s.lam[j] * q[j].1).sum();
    let den_min = inv_w_min - s.rho * lq;
    // NaN compares false: not bounded either.
    if den_min.is_nan() || den_min <= 0.0 {
        return None;
    }
    let g = lq * (1.0 + s.rho) / den_min;
    let piece_max = piece.iter().map(|a| a.magnitude()).fold(0.0, f64::max);
    let spread = piece.iter().map(|a| a.hi).fold(f64::NEG_INFINITY, f64::max)
        - piece.iter().map(|a| a.lo).fold(f64::INFINITY, f64::min);
    if s.rho * g >= 0.5 {
        return None;
    }
    // With weights γ (Σγ = 1, Σ|γ| ≤ G) scaled by 1 + ρⱼ and renormalised, each moves by at
    // most |γⱼ|·ρ(1 + G)/(1 − ρG), and the value by Σ|Δγⱼ|·|aⱼ − m| for any m (ΣΔγ = 0): the
    // values' midpoint, half their spread away.
    let rounded_w = s.rho * g * (1.0 + g) / (1.0 - s.rho * g) * 0.5 * spread;
    // The clipper's rounding of a new vertex's values (as `part_value`'s).
    let clipped = g * VARYING_ULPS * f32_ulp(piece_max);
    // The interpolation's arithmetic: VARYING_ULPS of its terms, and of its planes' (anchored
    // anywhere in the target), as in `Interp::varying`, each vertex's gradient with its own
    // values (the far vertex's steep plane carries its own).
    let terms = g * piece_max;
    let aq: [(f64, f64); 3] = std::array::from_fn(|k| {
        let c = [
            piece[k].lo * q[k].0,
            piece[k].lo * q[k].1,
            piece[k].hi * q[k].0,
            piece[k].hi * q[k].1,
        ];
        (
            c.iter().copied().fold(f64::INFINITY, f64::min),
            c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    });
    let tn = super::interp::plane_terms(aq, s.anchor, s.lam);
    let td = super::interp::plane_terms(q, s.anchor, s.lam);
    let den_err = VARYING_ULPS * f32_ulp(td);
    if den_min - den_err <= 0.0 {
        return None;
    }
    // |v|, the GPU's exact quotient: the reference's value, moved by 1/w's and the
    // clipper's roundings.
    let vmag = lo.abs().max(hi.abs()) + rounded_w + clipped;
    let planes = VARYING_ULPS * (f32_ulp(tn) + vmag * f32_ulp(td)) / (den_min - den_err);
    let slack = rounded_w
        + clipped
        + VARYING_ULPS * f32_ulp(terms)
        + terms * F64_SLACK
        + planes
        + (lo.abs().max(hi.abs())) * F64_SLACK;
    (slack.is_finite() && lo.is_finite() && hi.is_finite()).then(|| Iv::new(lo - slack, hi + slack))
}

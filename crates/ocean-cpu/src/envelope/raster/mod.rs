//! The rasteriser's envelope: which pixels a conformant GPU may cover with a triangle, and
//! the depth it may give the sample there (docs/tolerances.md, "Rasterisation").
//!
//! What Vulkan leaves to the implementation, and how it is carried:
//! - **Snapping.** Framebuffer coordinates are snapped to a grid of at least
//!   [`MIN_SUBPIXEL_BITS`] sub-pixel bits, rounding either way: each vertex's x and y lie
//!   within [`SNAP_PX`] of the viewport transform's result (itself an [`Iv`]).
//! - **Coverage.** A sample is covered when it is inside all three edges; on an edge, the
//!   tie-break rule decides. A sample is *certainly* covered when every edge function is
//!   positive for every vertex position in the boxes, *possibly* when none is certainly
//!   negative. A triangle whose area may be 0 is never certain.
//! - **Depth.** z = Σ λₖ zₖ with the barycentrics λₖ = Eₖ / Σ E of the sample (from the
//!   snapped or the unsnapped positions: the boxes hold both), within the hull of the
//!   vertices' z; its evaluation in f32 (a plane equation anchored anywhere in the target) is
//!   allowed [`DEPTH_ULPS`] ULP of the plane's largest term. Vulkan leaves the interpolation's
//!   precision to the implementation: this is the one figure here that is an assumption, not
//!   a rule (lavapipe's plane equation is three roundings).
//! - **Clipping.** A fragment whose z may leave [0, 1] may be clipped: it is possible, never
//!   certain.
//!
//! A depth-only pass with the `Less` test then leaves at each pixel the smallest z of the
//! fragments that reached it, or the clear value: the pixel's value lies in
//! [min(clear, lo of every possible fragment), min(clear, hi of every certain fragment)].

mod blend;
mod color;
mod cut;
mod jitter;
mod mesh;

pub use blend::additive_quads;
pub use color::{Shaded, color_pass_greater};
pub use cut::{OnPlane, piece_to_screen};
pub use jitter::{jitter_blend_pass, jitter_depth_pass, jitter_pass, jitter_pass_at};
pub use mesh::{MeshEnvelope, MeshTri, color_pass_mesh};

use super::{Iv, Real};

/// Vulkan's minimum `subPixelPrecisionBits`.
pub const MIN_SUBPIXEL_BITS: u32 = 4;

/// How far a snapped coordinate may lie from the unsnapped one, px: one sub-pixel step at the
/// minimum precision (the rounding direction is the implementation's).
pub const SNAP_PX: f64 = 1.0 / (1u32 << MIN_SUBPIXEL_BITS) as f64;

/// The f32 evaluation of the depth plane: ULP of its largest term.
pub const DEPTH_ULPS: f64 = 4.0;

/// A vertex after the viewport transform, as intervals: framebuffer x, y (px, y down) and z.
#[derive(Clone, Copy, Debug)]
pub struct ScreenIv {
    /// Framebuffer x, px.
    pub x: Iv,
    /// Framebuffer y, px (down).
    pub y: Iv,
    /// Depth z/w.
    pub z: Iv,
    /// 1/w: the weight of the vertex's varyings in perspective-correct interpolation.
    pub inv_w: Iv,
    /// For a vertex of a clipper's piece, the plane of the triangle it was cut from
    /// ([`piece_to_screen`]): the piece's depth is bounded from it where the boxes cannot.
    pub on: Option<OnPlane>,
}

/// The perspective divide and wgpu's viewport transform (origin (0, H), extent (W, −H),
/// depth [0, 1]) of a clip position over [`Iv`]: `None` where w may be ≤ 0 (the clipper's
/// work, not carried here).
pub fn to_screen(clip: [Iv; 4], width: u32, height: u32) -> Option<ScreenIv> {
    if clip[3].lo <= 0.0 || clip[3].full {
        return None;
    }
    let [x, y, z] = to_screen_r(clip, width, height);
    Some(ScreenIv { x, y, z, inv_w: Iv::lit(1.0) / clip[3], on: None })
}

/// [`to_screen`] over any [`Real`]: (x, y, z) in the framebuffer, unsnapped.
pub fn to_screen_r<R: Real>(clip: [R; 4], width: u32, height: u32) -> [R; 3] {
    let l = R::lit;
    let (half_w, half_h) = (l(width as f32 * 0.5), l(height as f32 * 0.5));
    let inv_w = l(1.0) / clip[3];
    [(clip[0] * inv_w) * half_w + half_w, (clip[1] * inv_w) * -half_h + half_h, clip[2] * inv_w]
}

/// The clipper's own arithmetic (the implementation's), relative to a new vertex's
/// magnitude: an assumption, generous against f32's few roundings.
pub const CLIP_SLACK: f64 = 1.0 / (1u64 << 20) as f64;

/// The relative widening of a bound this module computes in f64 (a few operations on the
/// boxes, each rounded within 2⁻⁵³ ≈ 1.1e-16): far above f64's own error, far below an f32
/// ULP (6e-8), so it covers the bound's arithmetic without loosening what it bounds.
const F64_SLACK: f64 = 1e-12;

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
/// `err`, so their sum of changes within 3·err), plus [`VARYING_ULPS`] for its arithmetic; a vertex of the original triangle
/// (`err` 0, one barycentric 1) is its own value.
pub fn part_value(vals: [Iv; 3], bary: [f64; 3], err: f64) -> Iv {
    if err == 0.0 && bary.iter().filter(|&&x| x != 0.0).count() == 1 {
        return vals[bary.iter().position(|&x| x != 0.0).unwrap_or(0)];
    }
    let x = Iv::sum(&[0, 1, 2].map(|j| vals[j] * Iv::new(bary[j], bary[j])));
    let spread = vals.iter().map(|v| v.magnitude()).fold(0.0, f64::max);
    // Each barycentric within err: Σ|Δbary| ≤ 3·err (a forced clipping's may lie outside the
    // triangle, where the tighter 2·err does not hold).
    let u = VARYING_ULPS * super::f32_ulp(x.magnitude()) + 3.0 * err * spread;
    if x.full { x } else { Iv::new(x.lo - u, x.hi + u) }
}

/// [lo, hi] in exact f64 arithmetic (the rasteriser's fixed point has no rounding to carry).
#[derive(Clone, Copy, Debug)]
struct Span(f64, f64);

impl Span {
    fn sub(self, o: Span) -> Span {
        Span(self.0 - o.1, self.1 - o.0)
    }
    fn mul(self, o: Span) -> Span {
        let c = [self.0 * o.0, self.0 * o.1, self.1 * o.0, self.1 * o.1];
        Span(
            c.iter().copied().fold(f64::INFINITY, f64::min),
            c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    }
    fn widen(self, d: f64) -> Span {
        Span(self.0 - d, self.1 + d)
    }
    /// `self / o` for a divisor of one sign (`None` where it may be 0), widened for f64's
    /// roundings.
    fn div(self, o: Span) -> Option<Span> {
        if !(o.0 > 0.0 || o.1 < 0.0) {
            return None;
        }
        let c = [self.0 / o.0, self.0 / o.1, self.1 / o.0, self.1 / o.1];
        let lo = c.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = c.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let slack = (lo.abs().max(hi.abs())) * F64_SLACK;
        (lo.is_finite() && hi.is_finite()).then_some(Span(lo - slack, hi + slack))
    }
    fn of(v: Iv) -> Span {
        Span(v.lo, v.hi)
    }
}

/// A triangle set up for the envelope: its snapped vertex boxes and depth intervals.
#[derive(Clone, Debug)]
struct Setup {
    x: [Span; 3],
    y: [Span; 3],
    z: [Iv; 3],
    /// Twice the signed area: its sign decides the orientation where it is certain.
    area: Span,
    /// The pixel box the triangle may touch (inclusive).
    bbox: [u32; 4],
    /// The largest term of the depth plane anchored anywhere in the target:
    /// max |z| + |∂z/∂x|·W + |∂z/∂y|·H (from the vertices' midpoints).
    plane_magnitude: f64,
    /// The depth plane of the vertices' midpoints and how far any plane through points of
    /// the boxes may stray from it (`None`: too close to degenerate to bound; the hull).
    plane: Option<Plane>,
    /// The screen-space barycentrics as planes (1 at one vertex, 0 at the others).
    bary: [Option<Plane>; 3],
    /// The vertices' 1/w.
    inv_w: [Iv; 3],
    /// How far below 0 a covered sample's barycentrics may reach ([`extrapolation`]).
    extrapolation: f64,
    /// Per vertex, the largest gradient terms of its barycentric's plane anchored anywhere in
    /// the target (∞: no plane bounds it): what a varying's plane equation scales with.
    anchor: [f64; 3],
    /// For a clipper's piece, its depth from the plane of the triangle it was cut from.
    cut: Option<cut::CutDepth>,
}

/// z(p) = z0 + g·(p − v0) through the midpoints, and the bound |Δz| ≤ k1·|p − v0| + k0 on
/// any plane through points of the vertices' boxes (each coordinate within `h` of its
/// midpoint, each z within `wz`): with M the 2×2 matrix of edge vectors, ΔM's entries within
/// 2h (‖ΔM‖ ≤ 4h), r = ‖M⁻¹‖·‖ΔM‖ < ½, the perturbed gradient g' satisfies
/// ‖g' − g‖ ≤ r‖g‖/(1 − r), so z'(p) − z(p) = (g' − g)·(p − v0) − g'·Δv0 + (the z's share,
/// a convex combination of their errors: ≤ wz).
#[derive(Clone, Copy, Debug)]
struct Plane {
    v0: [f64; 2],
    z0: f64,
    g: [f64; 2],
    k1: f64,
    k0: f64,
}

impl Plane {
    /// [lo, hi] of any plane through the boxes at sample (px, py) (with a little slack for
    /// f64's own roundings).
    fn at(&self, px: f64, py: f64) -> (f64, f64) {
        let (dx, dy) = (px - self.v0[0], py - self.v0[1]);
        let v = self.z0 + self.g[0] * dx + self.g[1] * dy;
        let d = self.k1 * dx.hypot(dy) + self.k0;
        let d = d + (v.abs() + d) * F64_SLACK;
        (v - d, v + d)
    }
}

/// The gradient of the plane through values `p` at the points (`mx`, `my`), whose doubled
/// signed area is `a`.
fn plane_gradient(mx: [f64; 3], my: [f64; 3], a: f64, p: [f64; 3]) -> [f64; 2] {
    [
        ((p[1] - p[0]) * (my[2] - my[0]) - (p[2] - p[0]) * (my[1] - my[0])) / a,
        ((p[2] - p[0]) * (mx[1] - mx[0]) - (p[1] - p[0]) * (mx[2] - mx[0])) / a,
    ]
}

fn setup(v: &[ScreenIv; 3], width: u32, height: u32, snap: f64) -> Option<Setup> {
    if v.iter().any(|v| v.x.full || v.y.full || v.z.full) {
        return None;
    }
    let x = v.map(|v| Span::of(v.x).widen(snap));
    let y = v.map(|v| Span::of(v.y).widen(snap));
    let area = edge(x[0], y[0], x[1], y[1], x[2], y[2]);
    let lo_x = x.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
    let hi_x = x.iter().map(|s| s.1).fold(f64::NEG_INFINITY, f64::max);
    let lo_y = y.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
    let hi_y = y.iter().map(|s| s.1).fold(f64::NEG_INFINITY, f64::max);
    // Pixel i's sample is at i + ½: the pixels whose centre may fall in [lo, hi].
    let first = |lo: f64| (lo - 0.5).ceil().max(0.0);
    let last = |hi: f64, n: u32| (hi - 0.5).floor().min(f64::from(n) - 1.0);
    let (x0, x1, y0, y1) = (first(lo_x), last(hi_x, width), first(lo_y), last(hi_y, height));
    if x0 > x1 || y0 > y1 {
        return None;
    }
    let mid = |s: Span| 0.5 * (s.0 + s.1);
    let (mx, my, mz) = (x.map(mid), y.map(mid), v.map(|v| 0.5 * (v.z.lo + v.z.hi)));
    let a = (mx[1] - mx[0]) * (my[2] - my[0]) - (mx[2] - mx[0]) * (my[1] - my[0]);
    let [dzdx, dzdy] = plane_gradient(mx, my, a, mz);
    let wz = v.iter().map(|v| 0.5 * (v.z.hi - v.z.lo)).fold(0.0, f64::max);
    let z_max = v.iter().map(|v| v.z.magnitude()).fold(0.0, f64::max);
    let h = x.iter().chain(&y).map(|s| 0.5 * (s.1 - s.0)).fold(0.0, f64::max);
    let m_f = ((mx[1] - mx[0]).powi(2)
        + (my[1] - my[0]).powi(2)
        + (mx[2] - mx[0]).powi(2)
        + (my[2] - my[0]).powi(2))
    .sqrt();
    // ‖M⁻¹‖ ≤ ‖M⁻¹‖_F = ‖M‖_F / |det M| for a 2×2 matrix; a little slack for f64's roundings.
    let r = m_f / a.abs() * 4.0 * h * (1.0 + 1e-9);
    let g_norm = dzdx.hypot(dzdy);
    // Any plane through the boxes has |∂z/∂x| ≤ (|dzdx| + r‖g‖)/(1 − r) + (its z's share).
    let plane_magnitude = if r < 0.5 {
        z_max
            + (dzdx.abs() + r * g_norm) / (1.0 - r) * f64::from(width)
            + (dzdy.abs() + r * g_norm) / (1.0 - r) * f64::from(height)
            + wz * 4.0 * m_f / a.abs() * f64::from(width.max(height))
    } else {
        f64::INFINITY
    };
    let plane_of = |vals: [f64; 3], w: f64| -> Option<Plane> {
        let [gx, gy] = plane_gradient(mx, my, a, vals);
        let g_norm = gx.hypot(gy);
        (r < 0.5 && a.is_finite() && g_norm.is_finite()).then(|| Plane {
            v0: [mx[0], my[0]],
            z0: vals[0],
            g: [gx, gy],
            k1: r * g_norm / (1.0 - r),
            k0: g_norm / (1.0 - r) * h * std::f64::consts::SQRT_2 + w,
        })
    };
    // The z's share: their errors weighted by barycentrics that may dip to −e.
    let extrapolation = extrapolation_with(v, snap);
    let cut = cut::CutDepth::new(v, [width, height], snap);
    let plane_magnitude = cut.map_or(plane_magnitude, |c| plane_magnitude.min(c.magnitude));
    let z_share = if wz == 0.0 { 0.0 } else { wz * (1.0 + 4.0 * extrapolation) };
    let plane = plane_of(mz, z_share);
    let bary = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|b| plane_of(b, 0.0));
    // Any plane through the boxes has a gradient within k1 of the midpoints' (per component,
    // as ‖·‖ bounds each); the value's own term is the sample's (`barycentrics`).
    // The lever arm: the target, or a vertex beyond it (lavapipe's a0 = v0 − x0·∂/∂x − y0·∂/∂y
    // rounds at |x0·∂/∂x| for a vertex in the guard band).
    let reach = |m: [f64; 3], n: u32| m.iter().fold(f64::from(n), |r, v| r.max(v.abs() + h));
    let (arm_x, arm_y) = (reach(mx, width), reach(my, height));
    let anchor = bary.map(|b| match b {
        Some(b) => (b.g[0].abs() + b.k1) * arm_x + (b.g[1].abs() + b.k1) * arm_y,
        None => f64::INFINITY,
    });
    Some(Setup {
        x,
        y,
        z: v.map(|v| v.z),
        area,
        bbox: [x0 as u32, y0 as u32, x1 as u32, y1 as u32],
        plane_magnitude: if plane_magnitude.is_finite() { plane_magnitude } else { f64::MAX },
        plane,
        bary,
        inv_w: v.map(|v| v.inv_w),
        extrapolation,
        anchor,
        cut,
    })
}

/// (b − a) × (p − a): positive with p to the right of a → b in a y-down frame for a
/// clockwise-on-screen triangle; the sign convention only has to agree with `area`'s.
fn edge(ax: Span, ay: Span, bx: Span, by: Span, px: Span, py: Span) -> Span {
    // (b − a) × (p − a) = (b − a) × (p − b) exactly; over boxes each form is loosest far from
    // its base vertex, so the two are intersected.
    let from_a = bx.sub(ax).mul(py.sub(ay)).sub(by.sub(ay).mul(px.sub(ax)));
    let from_b = bx.sub(ax).mul(py.sub(by)).sub(by.sub(ay).mul(px.sub(bx)));
    let e = Span(from_a.0.max(from_b.0), from_a.1.min(from_b.1));
    // f64 rounds these to nearest: widened outward by far more than its error.
    let mag = |s: Span| s.0.abs().max(s.1.abs());
    let terms = mag(bx.sub(ax)) * mag(py.sub(ay)) + mag(by.sub(ay)) * mag(px.sub(ax));
    e.widen((terms + mag(e)) * F64_SLACK)
}

/// What a triangle may do at one sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cover {
    /// Not covered by any conformant rasteriser.
    No,
    /// Covered by some, with the depth interval.
    Possible(Iv),
    /// Covered by every one, with the depth interval.
    Certain(Iv),
}

fn cover(t: &Setup, px: f64, py: f64) -> Cover {
    let (p, q) = (Span(px, px), Span(py, py));
    let e = [
        edge(t.x[1], t.y[1], t.x[2], t.y[2], p, q),
        edge(t.x[2], t.y[2], t.x[0], t.y[0], p, q),
        edge(t.x[0], t.y[0], t.x[1], t.y[1], p, q),
    ];
    // Inside for one orientation: all edge functions of that sign (0 on an edge: the
    // tie-break's, so possible).
    let may = |s: f64| e.iter().all(|e| (s * e.0).max(s * e.1) >= 0.0);
    let sure = |s: f64| e.iter().all(|e| (s * e.0).min(s * e.1) > 0.0);
    let area_sure = |s: f64| (s * t.area.0).min(s * t.area.1) > 0.0;
    let possible = may(1.0) || may(-1.0);
    if !possible {
        return Cover::No;
    }
    let z = depth(t, px, py);
    let z_inside = z.lo >= 0.0 && z.hi <= 1.0;
    let z_may = z.hi >= 0.0 && z.lo <= 1.0;
    if !z_may {
        return Cover::No;
    }
    let certain = [1.0, -1.0].iter().any(|&s| area_sure(s) && sure(s)) && z_inside;
    if certain { Cover::Certain(z) } else { Cover::Possible(z) }
}

/// How far below 0 the barycentrics of a covered sample may go. Coverage is decided on the
/// snapped vertices, interpolation may use the unsnapped ones (lavapipe does): every point of
/// the snapped triangle is a convex combination of the GPU's unsnapped vertices plus one of
/// their snap offsets, so a covered sample lies within √2·[`SNAP_PX`] of the GPU's unsnapped
/// triangle. Its vertices lie in boxes of half-width h around the midpoints, each moved by at
/// most √2·h, which shrinks the smallest altitude a by at most 5√2·h; so the barycentrics
/// are at least −√2·SNAP/(a − 5√2·h). ∞ for a triangle too thin for that to mean anything
/// (a ≤ 8√2·h). From the snapped vertices they are ≥ 0.
pub fn extrapolation(v: &[ScreenIv; 3]) -> f64 {
    extrapolation_with(v, SNAP_PX)
}

/// [`extrapolation`] for a snap of `snap` px.
pub fn extrapolation_with(v: &[ScreenIv; 3], snap: f64) -> f64 {
    let (altitude, h) = altitude(v);
    let s2 = std::f64::consts::SQRT_2;
    if altitude.is_finite() && altitude > 8.0 * s2 * h {
        s2 * snap / (altitude - 5.0 * s2 * h) * (1.0 + 1e-9)
    } else {
        f64::INFINITY
    }
}

/// The smallest altitude (px) of the triangle through the midpoints of the vertices' boxes,
/// and the boxes' largest half-width.
fn altitude(v: &[ScreenIv; 3]) -> (f64, f64) {
    let mid = |i: Iv| 0.5 * (i.lo + i.hi);
    let h = v.iter().flat_map(|v| [v.x, v.y]).map(|i| 0.5 * (i.hi - i.lo)).fold(0.0, f64::max);
    let p = v.map(|v| [mid(v.x), mid(v.y)]);
    let area2 = ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
        - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))
        .abs();
    let longest = (0..3)
        .map(|i| (p[(i + 1) % 3][0] - p[i][0]).hypot(p[(i + 1) % 3][1] - p[i][1]))
        .fold(0.0, f64::max);
    (area2 / longest, h)
}

/// [lo, hi] of three values, widened for barycentrics down to −`e` (Σλ = 1): the convex
/// hull grows by at most 2e·(hi − lo) on each side; an unbounded `e` gives anything.
pub fn extrapolated_hull(lo: f64, hi: f64, e: f64) -> (f64, f64) {
    if e.is_infinite() {
        return (f64::NEG_INFINITY, f64::INFINITY);
    }
    let d = 2.0 * e * (hi - lo);
    (lo - d, hi + d)
}

/// How far a conformant GPU's interpolated varying may stray from the exact interpolation of
/// its vertices' values, in ULP of the largest: Vulkan leaves the interpolation's precision to
/// the implementation, so this is an assumption, like [`DEPTH_ULPS`].
pub const VARYING_ULPS: f64 = 4.0;

/// The perspective-correct interpolation a conformant GPU may apply at a covered sample:
/// the screen-space barycentrics λ₁, λ₂ within their planes' bounds and no lower than
/// −[`extrapolation`] (λ₀ = 1 − λ₁ − λ₂), weighted by the vertices' 1/w (intervals).
#[derive(Clone, Copy, Debug)]
pub struct Interp {
    l1: (f64, f64),
    l2: (f64, f64),
    q: [(f64, f64); 3],
    /// Σₖ of the gradient terms of λₖ's plane anchored anywhere in the target ([`Setup`]).
    grad: f64,
    /// Σₖ |λₖ| at the sample.
    lam_sum: f64,
    /// The vertices' screen boxes (the snap included): x, then y.
    boxes: [[(f64, f64); 3]; 2],
    /// The sample's position.
    at: [f64; 2],
}

impl Interp {
    /// The values a varying whose vertices hold `v` may take. The share of vertex k,
    /// λₖqₖ/Σλⱼqⱼ, is linear-fractional along each of λ₁, λ₂, q₀, q₁, q₂ with the others
    /// fixed, hence monotone along each while the denominator (multilinear, so extreme at
    /// the corners) stays positive; so the interpolation of fixed values is extreme at one
    /// of the 32 corners of their box, and the values' own errors add at most Σ|shares|
    /// times their half-width there. Plus [`VARYING_ULPS`] of the sum of the terms'
    /// magnitudes for the interpolation's arithmetic, and of the largest terms of the planes
    /// a GPU may interpolate by (anchored anywhere in the target).
    pub fn varying(&self, v: [Iv; 3]) -> Iv {
        if v.iter().any(|v| v.full) || !self.l1.0.is_finite() || !self.l2.0.is_finite() {
            return Iv::FULL;
        }
        let m = v.map(|v| 0.5 * (v.lo + v.hi));
        let hw = v.iter().map(|v| 0.5 * (v.hi - v.lo)).fold(0.0, f64::max);
        let (mut lo, mut hi, mut terms) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
        let mut den_min = f64::INFINITY;
        for corner in 0..32u32 {
            let pick = |bit: u32, r: (f64, f64)| if corner >> bit & 1 == 0 { r.0 } else { r.1 };
            let (a, b) = (pick(0, self.l1), pick(1, self.l2));
            let q = [pick(2, self.q[0]), pick(3, self.q[1]), pick(4, self.q[2])];
            let w = [(1.0 - a - b) * q[0], a * q[1], b * q[2]];
            let den = w[0] + w[1] + w[2];
            if den <= 0.0 || !den.is_finite() {
                return Iv::FULL;
            }
            den_min = den_min.min(den);
            let share = w.map(|w| w / den);
            let x = share[0] * m[0] + share[1] * m[1] + share[2] * m[2];
            let spread = share.iter().map(|s| s.abs()).sum::<f64>();
            lo = lo.min(x - spread * hw);
            hi = hi.max(x + spread * hw);
            terms = terms.max(spread * (m.iter().fold(0.0f64, |t, v| t.max(v.abs())) + hw));
        }
        // A GPU may interpolate by plane equations anchored anywhere in the target (lavapipe
        // evaluates a·q and q as a0 + x·∂/∂x + y·∂/∂y, then their quotient): each plane's f32
        // evaluation is allowed VARYING_ULPS of its largest term, which for a small triangle
        // far from the anchor is far larger than the value.
        // |v| at most Σ|shares|·(max|m| + hw) (a share is negative past an edge).
        let vmag = terms;
        // A plane through values pₖ at the vertices has the gradient Σ(pₖ − c)∇λₖ for any c
        // (Σ∇λₖ = 0): at most half their spread times the λ planes' gradient terms; its own
        // value at the sample at most Σ|λₖ| times the largest |pₖ|.
        let term = |p: [(f64, f64); 3]| {
            let lo = p.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
            let hi = p.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
            let spread = if hi > lo { 0.5 * (hi - lo) * self.grad } else { 0.0 };
            spread + self.lam_sum * lo.abs().max(hi.abs())
        };
        let aq: [(f64, f64); 3] = std::array::from_fn(|k| {
            let c = [m[k] - hw, m[k] + hw].map(|a| [a * self.q[k].0, a * self.q[k].1]);
            let c = c.as_flattened();
            (
                c.iter().copied().fold(f64::INFINITY, f64::min),
                c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            )
        });
        let (tn, td) = (term(aq), term(self.q));
        // (N + εN)/(D + εD) − N/D = (εN − v·εD)/(D + εD), with D ≥ den_min.
        let den_err = VARYING_ULPS * super::f32_ulp(td);
        if den_min - den_err <= 0.0 {
            return Iv::FULL;
        }
        let planes =
            VARYING_ULPS * (super::f32_ulp(tn) + vmag * super::f32_ulp(td)) / (den_min - den_err);
        let slack = VARYING_ULPS * super::f32_ulp(terms) + terms * F64_SLACK + planes;
        if !slack.is_finite() || !lo.is_finite() || !hi.is_finite() {
            return Iv::FULL;
        }
        let (lo, hi) = match self.moved_vertices(v) {
            Some((l, h)) if l.max(lo) <= h.min(hi) => (l.max(lo), h.min(hi)),
            _ => (lo, hi),
        };
        Iv::new(lo - slack, hi + slack)
    }

    /// The exact interpolation's range by the vertices' moves rather than the barycentrics'
    /// box, which forgets that λ₁ and λ₂ move with the same vertices (by centimetres on a
    /// thin, distant triangle where a vertex's snap moves the varying by millimetres).
    ///
    /// With the vertices at x′ᵢ = x̄ᵢ + δᵢ (x̄ the boxes' midpoints) and any values
    /// pᵢ = L(x̄ᵢ) + εᵢ on a plane L through the midpoints, Σλ′ᵢ = 1 and Σλ′ᵢx′ᵢ = p give
    /// exactly Σλ′ᵢpᵢ = L(p) − ∇L·w + Σλ′ᵢεᵢ, w = Σλ′ᵢδᵢ, |w| ≤ Σ|λ′ᵢ|·(the boxes'
    /// half-widths) per axis. The numerator (values qᵢmᵢ) and the denominator (qᵢ) of the
    /// perspective interpolation share w, so their quotient is linear-fractional over the box
    /// of (w, the numerator's ε share, the denominator's): extreme at one of its 16 corners
    /// while the denominator stays positive. `None` where the midpoints' triangle is too
    /// thin to give a plane, or a denominator may reach 0.
    fn moved_vertices(&self, v: [Iv; 3]) -> Option<(f64, f64)> {
        let [bx, by] = self.boxes;
        let mid = |r: (f64, f64)| 0.5 * (r.0 + r.1);
        let half = |r: (f64, f64)| 0.5 * (r.1 - r.0);
        let (mx, my) = (bx.map(mid), by.map(mid));
        let (e1, e2) = ((mx[1] - mx[0]) * (my[2] - my[0]), (mx[2] - mx[0]) * (my[1] - my[0]));
        let a = e1 - e2;
        // Used only where the doubled area is no cancellation of its two products (at least
        // 1e-6 of them): its relative error is then at most 2·2⁻⁵³/1e-6 ≈ 2.2e-10, and the
        // gradients, planes and corners below add a few roundings of 2⁻⁵³ each, which the
        // 1e-9 of their terms allowed at the end covers.
        if !a.is_finite() || a.abs() < 1e-6 * (e1.abs() + e2.abs()) || a == 0.0 {
            return None;
        }
        // |λ′ᵢ| at most: λ₁, λ₂ within their bounds, λ₀ = 1 − λ₁ − λ₂.
        let big = |r: (f64, f64)| r.0.abs().max(r.1.abs());
        let l0 = (1.0 - self.l1.1 - self.l2.1, 1.0 - self.l1.0 - self.l2.0);
        let lam = [big(l0), big(self.l1), big(self.l2)];
        let reach = |axis: usize| (0..3).map(|i| lam[i] * half(self.boxes[axis][i])).sum::<f64>();
        let w = [reach(0), reach(1)];
        // The plane through the midpoints with values `p` there, at the sample, and its
        // gradient.
        let (sx, sy) = (self.at[0] - mx[0], self.at[1] - my[0]);
        let plane = |p: [f64; 3]| {
            let [gx, gy] = plane_gradient(mx, my, a, p);
            let terms = p[0].abs() + gx.abs() * (sx.abs() + w[0]) + gy.abs() * (sy.abs() + w[1]);
            (p[0] + gx * sx + gy * sy, gx, gy, terms)
        };
        // Midpoint values, and how far each vertex's true value may lie from them.
        let (qm, qh) = (self.q.map(mid), self.q.map(half));
        let n_mid: [f64; 3] = std::array::from_fn(|i| qm[i] * 0.5 * (v[i].lo + v[i].hi));
        let n_err: [f64; 3] = std::array::from_fn(|i| {
            let (q, x) = (self.q[i], v[i]);
            [q.0 * x.lo, q.0 * x.hi, q.1 * x.lo, q.1 * x.hi]
                .iter()
                .map(|c| (c - n_mid[i]).abs())
                .fold(0.0, f64::max)
        });
        let share = |e: [f64; 3]| (0..3).map(|i| lam[i] * e[i]).sum::<f64>();
        let (en, ed) = (share(n_err), share(qh));
        let (n_at, ngx, ngy, n_terms) = plane(n_mid);
        let (d_at, dgx, dgy, d_terms) = plane(qm);
        let (mut lo, mut hi, mut den_min) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        for corner in 0..16u32 {
            let sign = |bit: u32| if corner >> bit & 1 == 0 { -1.0 } else { 1.0 };
            let (wx, wy) = (sign(0) * w[0], sign(1) * w[1]);
            let num = n_at - (ngx * wx + ngy * wy) + sign(2) * en;
            let den = d_at - (dgx * wx + dgy * wy) + sign(3) * ed;
            if den.is_nan() || den <= 0.0 || !num.is_finite() {
                return None;
            }
            den_min = den_min.min(den);
            lo = lo.min(num / den);
            hi = hi.max(num / den);
        }
        // f64's roundings: 1e-9 of the planes' terms (the area's bound above), in the
        // numerator and, times the quotient, in the denominator.
        let value = lo.abs().max(hi.abs());
        let margin = 1e-9 * (n_terms + en + value * (d_terms + ed)) / den_min;
        if !margin.is_finite() {
            return None;
        }
        Some((lo - margin, hi + margin))
    }
}

/// The interpolation a conformant GPU may apply at a covered sample of `t` ([`Interp`]).
fn barycentrics(t: &Setup, px: f64, py: f64) -> Interp {
    let e = t.extrapolation;
    // λₖ is also the ratio of the sample's edge function to the doubled area, each bounded
    // over the vertices' boxes: near a vertex other than the plane's anchor that is several
    // times tighter than the plane's bound (whose gradient error grows with the distance from
    // the anchor), so both are intersected.
    let (p, q) = (Span(px, px), Span(py, py));
    let quotient = |k: usize| {
        let edge_k = match k {
            1 => edge(t.x[2], t.y[2], t.x[0], t.y[0], p, q),
            _ => edge(t.x[0], t.y[0], t.x[1], t.y[1], p, q),
        };
        edge_k.div(t.area)
    };
    let lam = |k: usize| {
        let (mut lo, mut hi) = (-e, 1.0 + e);
        if let Some(p) = t.bary[k] {
            let (l, h) = p.at(px, py);
            lo = lo.max(l);
            hi = hi.min(h);
        }
        if let Some(Span(l, h)) = quotient(k) {
            lo = lo.max(l);
            hi = hi.min(h);
        }
        if lo <= hi { (lo, hi) } else { (-e, 1.0 + e) }
    };
    if t.inv_w.iter().any(|q| q.full || q.lo <= 0.0) {
        let any = (f64::NEG_INFINITY, f64::INFINITY);
        let (grad, lam_sum) = (f64::INFINITY, f64::INFINITY);
        let (boxes, at) = ([[any; 3]; 2], [px, py]);
        return Interp { l1: any, l2: any, q: [(1.0, 1.0); 3], grad, lam_sum, boxes, at };
    }
    let (l1, l2) = (lam(1), lam(2));
    // Σ|λₖ| at the sample, λ₀ = 1 − λ₁ − λ₂.
    let l0 = (1.0 - l1.1 - l2.1, 1.0 - l1.0 - l2.0);
    let big = |r: (f64, f64)| r.0.abs().max(r.1.abs());
    let lam_sum = big(l0) + big(l1) + big(l2);
    let boxes = [t.x.map(|s| (s.0, s.1)), t.y.map(|s| (s.0, s.1))];
    let q = t.inv_w.map(|q| (q.lo, q.hi));
    Interp { l1, l2, q, grad: t.anchor.iter().sum(), lam_sum, boxes, at: [px, py] }
}

/// The sample's depth: on the plane through the vertices' boxes (within [`Plane`]'s bound),
/// inside the hull of the vertices' z widened for the barycentrics' [`extrapolation`], plus
/// the plane's f32 evaluation allowance.
fn depth(t: &Setup, px: f64, py: f64) -> Iv {
    let (hull_lo, hull_hi) = extrapolated_hull(
        t.z.iter().map(|z| z.lo).fold(f64::INFINITY, f64::min),
        t.z.iter().map(|z| z.hi).fold(f64::NEG_INFINITY, f64::max),
        t.extrapolation,
    );
    let (mut lo, mut hi) = (hull_lo, hull_hi);
    if let Some(p) = t.plane {
        let (l, h) = p.at(px, py);
        lo = lo.max(l);
        hi = hi.min(h);
    }
    if let Some(c) = t.cut {
        let (l, h) = c.at(px, py);
        lo = lo.max(l);
        hi = hi.min(h);
    }
    // The plane's f32 evaluation: ULP of its largest term (a near-degenerate plane's terms
    // are large, and so is its allowance).
    let slack = DEPTH_ULPS * super::f32_ulp(t.plane_magnitude.min(1e30));
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hull_lo, hull_hi) };
    Iv::new(lo - slack, hi + slack)
}

/// Every sample a triangle may cover, triangle by triangle in submission order:
/// `visit(pixel index, triangle index, what it may do there)` (never with [`Cover::No`]).
/// False (and nothing visited) where a vertex may be anything: the pass is then unbounded.
pub fn fragments(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    visit: impl FnMut(usize, usize, Cover, &dyn Fn() -> Interp),
) -> bool {
    fragments_at(tris, width, height, SNAP_PX, visit)
}

/// [`fragments`] on a device whose snap is `snap` px.
pub fn fragments_at(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    snap: f64,
    mut visit: impl FnMut(usize, usize, Cover, &dyn Fn() -> Interp),
) -> bool {
    // A vertex that may be anything (an infinite or NaN input, an overflow): the triangle
    // may cover anything, which no per-sample bound can say.
    if tris.iter().flatten().any(|v| v.x.full || v.y.full || v.z.full) {
        return false;
    }
    for (k, t) in tris.iter().enumerate() {
        let Some(t) = setup(t, width, height, snap) else { continue };
        let [x0, y0, x1, y1] = t.bbox;
        for py in y0..=y1 {
            for px in x0..=x1 {
                let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                let c = cover(&t, sx, sy);
                if c != Cover::No {
                    let bary = || barycentrics(&t, sx, sy);
                    visit(py as usize * width as usize + px as usize, k, c, &bary);
                }
            }
        }
    }
    true
}

/// The envelope of a depth-only pass with the `Less` test (no culling) on a device whose snap
/// is `snap` px: per pixel, the interval its value lies in, and whether its coverage is
/// ambiguous (some triangle may or may not cover it).
pub fn depth_pass(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    clear: f32,
    snap: f64,
) -> (Vec<Iv>, Vec<bool>) {
    let n = (width as usize) * (height as usize);
    let clear = f64::from(clear);
    let mut lo = vec![clear; n];
    let mut hi = vec![clear; n];
    let mut ambiguous = vec![false; n];
    let bounded = fragments_at(tris, width, height, snap, |i, _, c, _| match c {
        Cover::No => {}
        Cover::Possible(z) => {
            lo[i] = lo[i].min(z.lo);
            ambiguous[i] = true;
        }
        Cover::Certain(z) => {
            lo[i] = lo[i].min(z.lo);
            hi[i] = hi[i].min(z.hi);
        }
    });
    if !bounded {
        return (vec![Iv::FULL; n], vec![true; n]);
    }
    let env = lo.iter().zip(&hi).map(|(&l, &h)| Iv::new(l.min(h), h)).collect();
    (env, ambiguous)
}

#[cfg(test)]
mod tests;

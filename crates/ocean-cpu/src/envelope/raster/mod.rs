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
mod clip;
mod color;
mod cut;
mod interp;
mod jitter;
mod mesh;

pub use blend::additive_quads;
pub(crate) use clip::plane_distances;
pub use clip::{
    CLIP_SLACK, ClipVertex, Slide, clip_near_far, clip_near_far_either, inside_near_far,
    outside_a_side, part_value,
};
pub use color::{Shaded, color_pass_greater};
pub use cut::{OnPlane, piece_to_screen};
use interp::barycentrics;
pub use interp::{Interp, VARYING_ULPS, narrowed};
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

/// The relative widening of a bound this module computes in f64 (a few operations on the
/// boxes, each rounded within 2⁻⁵³ ≈ 1.1e-16): far above f64's own error, far below an f32
/// ULP (6e-8), so it covers the bound's arithmetic without loosening what it bounds.
const F64_SLACK: f64 = 1e-12;

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
    /// The largest magnitude in the span.
    fn magnitude(self) -> f64 {
        self.0.abs().max(self.1.abs())
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
    let terms = bx.sub(ax).magnitude() * py.sub(ay).magnitude()
        + by.sub(ay).magnitude() * px.sub(ax).magnitude();
    e.widen((terms + e.magnitude()) * F64_SLACK)
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
    let longest = (0..3).map(|i| dist(p[i], p[(i + 1) % 3])).fold(0.0, f64::max);
    (cross(p[0], p[1], p[2]).abs() / longest, h)
}

/// The cross product (b − a) × (c − a): twice the signed area of (a, b, c).
fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
}

/// The distance from a to b.
fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
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

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

use super::{Iv, Jitter, JitterRules, Real};

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
}

/// The perspective divide and wgpu's viewport transform (origin (0, H), extent (W, −H),
/// depth [0, 1]) of a clip position over [`Iv`]: `None` where w may be ≤ 0 (the clipper's
/// work, not carried here).
pub fn to_screen(clip: [Iv; 4], width: u32, height: u32) -> Option<ScreenIv> {
    if clip[3].lo <= 0.0 || clip[3].full {
        return None;
    }
    let [x, y, z] = to_screen_r(clip, width, height);
    Some(ScreenIv { x, y, z })
}

/// [`to_screen`] over any [`Real`]: (x, y, z) in the framebuffer, unsnapped.
pub fn to_screen_r<R: Real>(clip: [R; 4], width: u32, height: u32) -> [R; 3] {
    let l = R::lit;
    let (half_w, half_h) = (l(width as f32 * 0.5), l(height as f32 * 0.5));
    let inv_w = l(1.0) / clip[3];
    [(clip[0] * inv_w) * half_w + half_w, (clip[1] * inv_w) * -half_h + half_h, clip[2] * inv_w]
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

fn setup(v: &[ScreenIv; 3], width: u32, height: u32) -> Option<Setup> {
    if v.iter().any(|v| v.x.full || v.y.full || v.z.full) {
        return None;
    }
    let x = v.map(|v| Span::of(v.x).widen(SNAP_PX));
    let y = v.map(|v| Span::of(v.y).widen(SNAP_PX));
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
    let dzdx = ((mz[1] - mz[0]) * (my[2] - my[0]) - (mz[2] - mz[0]) * (my[1] - my[0])) / a;
    let dzdy = ((mz[2] - mz[0]) * (mx[1] - mx[0]) - (mz[1] - mz[0]) * (mx[2] - mx[0])) / a;
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
    let plane = (r < 0.5 && a.is_finite() && g_norm.is_finite()).then(|| Plane {
        v0: [mx[0], my[0]],
        z0: mz[0],
        g: [dzdx, dzdy],
        k1: r * g_norm / (1.0 - r),
        k0: g_norm / (1.0 - r) * h * std::f64::consts::SQRT_2 + wz,
    });
    Some(Setup {
        x,
        y,
        z: v.map(|v| v.z),
        area,
        bbox: [x0 as u32, y0 as u32, x1 as u32, y1 as u32],
        plane_magnitude: if plane_magnitude.is_finite() { plane_magnitude } else { f64::MAX },
        plane,
    })
}

/// (b − a) × (p − a): positive with p to the right of a → b in a y-down frame for a
/// clockwise-on-screen triangle; the sign convention only has to agree with `area`'s.
fn edge(ax: Span, ay: Span, bx: Span, by: Span, px: Span, py: Span) -> Span {
    bx.sub(ax).mul(py.sub(ay)).sub(by.sub(ay).mul(px.sub(ax)))
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

/// The sample's depth: on the plane through the vertices' boxes (within [`Plane`]'s bound),
/// inside the hull of the vertices' z (a covered sample is inside its triangle, so its depth
/// is a convex combination of theirs), plus the plane's f32 evaluation allowance.
fn depth(t: &Setup, px: f64, py: f64) -> Iv {
    let hull_lo = t.z.iter().map(|z| z.lo).fold(f64::INFINITY, f64::min);
    let hull_hi = t.z.iter().map(|z| z.hi).fold(f64::NEG_INFINITY, f64::max);
    let (mut lo, mut hi) = (hull_lo, hull_hi);
    if let Some(p) = t.plane {
        let (dx, dy) = (px - p.v0[0], py - p.v0[1]);
        let z = p.z0 + p.g[0] * dx + p.g[1] * dy;
        let d = p.k1 * dx.hypot(dy) + p.k0;
        let d = d + (z.abs() + d) * 1e-12;
        lo = lo.max(z - d);
        hi = hi.min(z + d);
    }
    // The plane's f32 evaluation: ULP of its largest term (a near-degenerate plane's terms
    // are large, and so is its allowance).
    let slack = DEPTH_ULPS * super::f32_ulp(t.plane_magnitude.min(1e30));
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hull_lo, hull_hi) };
    Iv::new(lo - slack, hi + slack)
}

/// The envelope of a depth-only pass with the `Less` test (no culling): per pixel, the
/// interval its value lies in, and whether its coverage is ambiguous (some triangle may or
/// may not cover it).
pub fn depth_pass(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    clear: f32,
) -> (Vec<Iv>, Vec<bool>) {
    let n = (width as usize) * (height as usize);
    let clear = f64::from(clear);
    let mut lo = vec![clear; n];
    let mut hi = vec![clear; n];
    let mut ambiguous = vec![false; n];
    for t in tris.iter().filter_map(|t| setup(t, width, height)) {
        let [x0, y0, x1, y1] = t.bbox;
        for py in y0..=y1 {
            for px in x0..=x1 {
                let i = py as usize * width as usize + px as usize;
                match cover(&t, f64::from(px) + 0.5, f64::from(py) + 0.5) {
                    Cover::No => {}
                    Cover::Possible(z) => {
                        lo[i] = lo[i].min(z.lo);
                        ambiguous[i] = true;
                    }
                    Cover::Certain(z) => {
                        lo[i] = lo[i].min(z.lo);
                        hi[i] = hi[i].min(z.hi);
                    }
                }
            }
        }
    }
    let env = lo.iter().zip(&hi).map(|(&l, &h)| Iv::new(l.min(h), h)).collect();
    (env, ambiguous)
}

/// A depth-only `Less` pass (no culling) as one random conformant GPU draws it (the
/// envelope's soundness test): each vertex transformed with random roundings and snapped to a
/// 1/16-pixel grid, up or down at random; each edge's tie-break drawn; the depth plane through
/// the snapped or the unsnapped vertices, evaluated with an error drawn within
/// [`DEPTH_ULPS`]. At `rules.scale` 2 the snap may move a vertex twice as far and the depth
/// error is doubled: the negative control.
pub fn jitter_depth_pass(
    tris: &[[[f32; 4]; 3]],
    width: u32,
    height: u32,
    clear: f32,
    rules: JitterRules,
) -> Vec<f32> {
    use ocean_core::rng::SplitMix64;
    let mut g = SplitMix64::new(rules.seed ^ 0x005e_ed0f_da7a);
    let mut unit = move || (g.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let n = (width as usize) * (height as usize);
    let mut out = vec![clear; n];
    let mut depth = vec![f64::from(clear); n];
    for (k, t) in tris.iter().enumerate() {
        Jitter::reseed(rules, k as u64);
        if t.iter().any(|v| v[3] <= 0.0) {
            continue;
        }
        let raw: [[f64; 3]; 3] =
            t.map(|v| to_screen_r(v.map(Jitter), width, height).map(|c| f64::from(c.0)));
        let grid = f64::from(1u32 << MIN_SUBPIXEL_BITS);
        let mut snap = |c: f64| {
            let s = if unit() < 0.5 { (c * grid).floor() } else { (c * grid).ceil() };
            let extra =
                if rules.scale > 1.0 { (unit() * 2.0 - 1.0) * (rules.scale - 1.0) } else { 0.0 };
            (s + extra.round()) / grid
        };
        let snapped: [[f64; 3]; 3] = raw.map(|v| [snap(v[0]), snap(v[1]), v[2]]);
        let area = (snapped[1][0] - snapped[0][0]) * (snapped[2][1] - snapped[0][1])
            - (snapped[2][0] - snapped[0][0]) * (snapped[1][1] - snapped[0][1]);
        if area == 0.0 {
            continue;
        }
        let sign = area.signum();
        let ties = [unit() < 0.5, unit() < 0.5, unit() < 0.5];
        // The depth plane through the snapped or the unsnapped vertices.
        let plane_of = if unit() < 0.5 { &snapped } else { &raw };
        let [a, b, c] = *plane_of;
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let gx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / det;
        let gy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / det;
        let magnitude = [a[2], b[2], c[2]].iter().fold(0.0f64, |m, z| m.max(z.abs()))
            + gx.abs() * f64::from(width)
            + gy.abs() * f64::from(height);
        let err = DEPTH_ULPS * rules.scale * super::f32_ulp(magnitude);
        let xs = snapped.map(|v| v[0]);
        let ys = snapped.map(|v| v[1]);
        let (x0, x1) = (
            xs.iter().copied().fold(f64::INFINITY, f64::min),
            xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let (y0, y1) = (
            ys.iter().copied().fold(f64::INFINITY, f64::min),
            ys.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let first = |lo: f64| (lo - 0.5).ceil().max(0.0) as u32;
        let last = |hi: f64, n: u32| (hi - 0.5).floor().min(f64::from(n) - 1.0);
        let (lx, hx, ly, hy) = (first(x0), last(x1, width), first(y0), last(y1, height));
        if hx < 0.0 || hy < 0.0 {
            continue;
        }
        for py in ly..=hy as u32 {
            for px in lx..=hx as u32 {
                let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                let inside = (0..3).all(|e| {
                    let (p, q) = (snapped[(e + 1) % 3], snapped[(e + 2) % 3]);
                    let f = sign * ((q[0] - p[0]) * (sy - p[1]) - (q[1] - p[1]) * (sx - p[0]));
                    f > 0.0 || (f == 0.0 && ties[e])
                });
                if !inside {
                    continue;
                }
                let z = a[2] + gx * (sx - a[0]) + gy * (sy - a[1]) + (unit() * 2.0 - 1.0) * err;
                if !(0.0..=1.0).contains(&z) {
                    continue;
                }
                let i = py as usize * width as usize + px as usize;
                let stored = z as f32;
                if f64::from(stored) < depth[i] {
                    depth[i] = f64::from(stored);
                    out[i] = stored;
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> ScreenIv {
        let p = |a: f64| Iv::point(a as f32);
        ScreenIv { x: p(x), y: p(y), z: p(z) }
    }

    /// A large triangle: its interior certain, its outside not covered, a band along its
    /// edges possible, and the depth at an interior sample close to the plane's.
    #[test]
    fn a_triangle_is_certain_inside_possible_at_its_edges() {
        let t = setup(&[v(1.0, 1.0, 0.2), v(30.0, 2.0, 0.4), v(5.0, 28.0, 0.6)], 32, 32).unwrap();
        assert!(matches!(cover(&t, 8.5, 8.5), Cover::Certain(_)));
        assert_eq!(cover(&t, 30.5, 30.5), Cover::No);
        // On the edge from (1, 1) to (30, 2), well inside in x.
        let y_edge = 1.0 + (15.5 - 1.0) / 29.0;
        assert!(matches!(cover(&t, 15.5, y_edge + 0.01), Cover::Possible(_)));
        let Cover::Certain(z) = cover(&t, 10.5, 10.5) else { panic!() };
        assert!(z.lo > 0.2 && z.hi < 0.6 && z.hi - z.lo < 0.02, "{z:?}");
    }

    /// A depth-only pass of two overlapping triangles keeps the nearer where both certainly
    /// cover, and the clear value outside.
    #[test]
    fn the_nearer_triangle_wins() {
        let far = [v(0.0, 0.0, 0.8), v(16.0, 0.0, 0.8), v(0.0, 16.0, 0.8)];
        let near = [v(0.0, 0.0, 0.3), v(16.0, 0.0, 0.3), v(0.0, 16.0, 0.3)];
        let (env, amb) = depth_pass(&[far, near], 16, 16, 1.0);
        let at = |x: usize, y: usize| env[y * 16 + x];
        assert!(at(3, 3).contains(0.3) && !at(3, 3).contains(0.8));
        assert!(at(15, 15).contains(1.0) && !at(15, 15).contains(0.3));
        assert!(!amb[3 * 16 + 3] && amb.iter().any(|&a| a));
    }
}

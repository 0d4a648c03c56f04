//! The interpolation of a varying at a covered sample: the screen-space barycentrics a
//! conformant GPU may use (within their planes' bounds, the edge functions' quotient and the
//! snap's extrapolation), weighted by the vertices' 1/w (docs/tolerances.md, "Varyings").

use super::{F64_SLACK, Setup, Span, edge, plane_gradient};
use crate::envelope::{Iv, f32_ulp};

/// How far a conformant GPU's interpolated varying may stray from the exact interpolation of
/// its vertices' values, in ULP of the largest: Vulkan leaves the interpolation's precision to
/// the implementation, so this is an assumption, like [`DEPTH_ULPS`](super::DEPTH_ULPS).
pub const VARYING_ULPS: f64 = 4.0;

/// The perspective-correct interpolation a conformant GPU may apply at a covered sample:
/// the screen-space barycentrics λ₁, λ₂ within their planes' bounds and no lower than
/// −[`extrapolation`](super::extrapolation) (λ₀ = 1 − λ₁ − λ₂), weighted by the vertices' 1/w (intervals).
#[derive(Clone, Copy, Debug)]
pub struct Interp {
    /// λ₁'s and λ₂'s bounds (λ₀ = 1 − λ₁ − λ₂).
    pub(super) l1: (f64, f64),
    /// See `l1`.
    pub(super) l2: (f64, f64),
    /// The vertices' 1/w.
    pub(super) q: [(f64, f64); 3],
    /// Per vertex, the gradient terms of λₖ's plane anchored anywhere in the target ([`Setup`]).
    pub(super) anchor: [f64; 3],
    /// Per vertex, |λₖ| at the sample, at most.
    pub(super) lam: [f64; 3],
    /// The vertices' screen boxes (the snap included): x, then y.
    pub(super) boxes: [[(f64, f64); 3]; 2],
    /// The sample's position.
    pub(super) at: [f64; 2],
    /// For a clipper's piece, where the sample takes its varyings from in the original.
    pub(super) cut: Option<super::cut::CutSample>,
}

impl Interp {
    /// A varying of a clipper's piece bounded from the triangle it was cut from: `clip` that
    /// triangle's clip positions, `a` its vertices' values (both as its vertex stage left
    /// them), `piece` the piece's own vertices' values. `None` for a whole triangle, or where the bound cannot be made; where it is
    /// made, it holds as [`Self::varying`] of the piece's own values does, and the two may be
    /// intersected ([`narrowed`]).
    pub fn from_original(&self, clip: &[[Iv; 4]; 3], a: [Iv; 3], piece: [Iv; 3]) -> Option<Iv> {
        super::cut::original_value(self.cut.as_ref()?, clip, a, piece, self.q)
    }

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
        // The exact quotient v = N/D at the GPU's barycentrics and 1/w lies within the
        // corners' range (Σ|shares|·(max|m| + hw) bounds it too, but a horizon triangle's far
        // vertex, 10⁷ m away, makes that 10³ times larger than the value at the sample).
        let vmag = lo.abs().max(hi.abs());
        let aq: [(f64, f64); 3] = std::array::from_fn(|k| {
            let c = [m[k] - hw, m[k] + hw].map(|a| [a * self.q[k].0, a * self.q[k].1]);
            let c = c.as_flattened();
            (
                c.iter().copied().fold(f64::INFINITY, f64::min),
                c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            )
        });
        let (tn, td) =
            (plane_terms(aq, self.anchor, self.lam), plane_terms(self.q, self.anchor, self.lam));
        // (N + εN)/(D + εD) − N/D = (εN − v·εD)/(D + εD), with D ≥ den_min.
        let den_err = VARYING_ULPS * f32_ulp(td);
        if den_min - den_err <= 0.0 {
            return Iv::FULL;
        }
        let planes = VARYING_ULPS * (f32_ulp(tn) + vmag * f32_ulp(td)) / (den_min - den_err);
        let slack = VARYING_ULPS * f32_ulp(terms) + terms * F64_SLACK + planes;
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
    pub(super) fn moved_vertices(&self, v: [Iv; 3]) -> Option<(f64, f64)> {
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
pub(super) fn barycentrics(t: &Setup, px: f64, py: f64) -> Interp {
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
        let (anchor, lam) = ([f64::INFINITY; 3], [f64::INFINITY; 3]);
        let (boxes, at) = ([[any; 3]; 2], [px, py]);
        let cut = None;
        return Interp { l1: any, l2: any, q: [(1.0, 1.0); 3], anchor, lam, boxes, at, cut };
    }
    let (l1, l2) = (lam(1), lam(2));
    // |λₖ| at the sample, λ₀ = 1 − λ₁ − λ₂.
    let l0 = (1.0 - l1.1 - l2.1, 1.0 - l1.0 - l2.0);
    let big = |r: (f64, f64)| r.0.abs().max(r.1.abs());
    let lam = [big(l0), big(l1), big(l2)];
    let boxes = [t.x.map(|s| (s.0, s.1)), t.y.map(|s| (s.0, s.1))];
    let q = t.inv_w.map(|q| (q.lo, q.hi));
    let cut = t.cut.map(|c| c.sample(px, py));
    Interp { l1, l2, q, anchor: t.anchor, lam, boxes, at: [px, py], cut }
}

/// The largest term of a GPU's f32 plane through values `p` at a triangle's vertices,
/// anchored anywhere within the arm its gradients' terms `anchor` were made for, at a sample
/// where |λₖ| ≤ `lam`ₖ: what its evaluation's rounding scales with.
///
/// A GPU sets the plane up from one base vertex b (lavapipe's and NVIDIA's plane equations,
/// AMD's v₀ + i·(v₁ − v₀) + j·(v₂ − v₀)): its gradient Σₖ(pₖ − p_b)∇λₖ comes from the
/// differences pₖ − p_b and the edges, so its rounding scales with Σₖ|pₖ − p_b|·|∇λₖ|, and
/// then with the arm. Any vertex may be the base (a clipper's pieces are ordered as it
/// pleases), so the largest over b. Each vertex's gradient counts with its own differences:
/// on a clipper's piece whose new vertex lies 10⁵ px off screen at 1/w = 20 while the others
/// are at 0.04, the two on-screen vertices' steep λ planes carry 1/w's small differences
/// unless the far vertex is the base. The plane's value at the sample is at most
/// Σₖ|λₖ|·max|pₖ|, and at an anchor on a vertex that vertex's.
pub(super) fn plane_terms(p: [(f64, f64); 3], anchor: [f64; 3], lam: [f64; 3]) -> f64 {
    let ok = |x: f64| x.is_finite();
    if !p.iter().all(|p| ok(p.0) && ok(p.1)) || !anchor.iter().chain(&lam).copied().all(ok) {
        return f64::INFINITY;
    }
    let apart = |k: usize, b: usize| (p[k].1 - p[b].0).abs().max((p[k].0 - p[b].1).abs());
    let gradient =
        (0..3).map(|b| (0..3).map(|k| anchor[k] * apart(k, b)).sum::<f64>()).fold(0.0, f64::max);
    let big = p.map(|p| p.0.abs().max(p.1.abs()));
    let value = (0..3).map(|k| lam[k] * big[k]).sum::<f64>();
    gradient + value.max(big.iter().copied().fold(0.0, f64::max))
}

/// Two bounds of one value, intersected (`None`: the first alone). Both hold, so they meet;
/// should they not, their hull is returned rather than a verdict from one of them.
pub fn narrowed(bound: Iv, other: Option<Iv>) -> Iv {
    match other {
        None => bound,
        Some(o) if bound.full => o,
        Some(o) if o.full => bound,
        Some(o) if o.lo.max(bound.lo) <= o.hi.min(bound.hi) => {
            Iv::new(o.lo.max(bound.lo), o.hi.min(bound.hi))
        }
        Some(o) => bound.hull(o),
    }
}

//! One random conformant GPU's rasteriser: the soundness test of the rasteriser's envelope
//! (its parent module) without hardware.

use ocean_core::rng::SplitMix64;

use super::{CLIP_SLACK, DEPTH_ULPS, MIN_SUBPIXEL_BITS, plane_distances, to_screen_r};
use crate::envelope::{Jitter, JitterRules};

/// A depth-only `Less` pass (no culling) as one random conformant GPU draws it (the
/// envelope's soundness test; see [`jitter_pass`]).
pub fn jitter_depth_pass(
    tris: &[[[f32; 4]; 3]],
    width: u32,
    height: u32,
    clear: f32,
    rules: JitterRules,
    subpixel_bits: u32,
) -> Vec<f32> {
    let clear = [clear, 0.0, 0.0, 0.0];
    let target =
        jitter_pass_at(tris, width, height, false, clear, rules, subpixel_bits, |_, _, _, z| {
            Some([z, 0.0, 0.0, 0.0])
        });
    target.into_iter().map(|t| t[0]).collect()
}

/// A pass (no culling, no blending) as one random conformant GPU draws it: each vertex
/// transformed with random roundings and snapped to a 1/16-pixel grid, up or down at random;
/// each edge's tie-break drawn; the depth plane through the snapped or the unsnapped vertices,
/// evaluated with an error drawn within [`DEPTH_ULPS`]; the depth test `Less` (cleared to 1)
/// or, with `greater`, `Greater` (cleared to 0). `fragment(triangle, perspective-correct
/// barycentrics, depth)` shades a covered sample (`None`: discard). At `rules.scale` 2 the
/// snap may move a vertex twice as far and the depth error is doubled: the negative control.
pub fn jitter_pass(
    tris: &[[[f32; 4]; 3]],
    width: u32,
    height: u32,
    greater: bool,
    clear: [f32; 4],
    rules: JitterRules,
    mut fragment: impl FnMut(usize, [f64; 3], f32) -> Option<[f32; 4]>,
) -> Vec<[f32; 4]> {
    let bits = MIN_SUBPIXEL_BITS;
    jitter_pass_at(tris, width, height, greater, clear, rules, bits, |_, k, w, z| fragment(k, w, z))
}

/// [`jitter_pass`] whose `fragment(pixel, triangle, barycentrics, depth)` is also told the
/// pixel (its index in the target), on a device of `subpixel_bits`.
#[allow(clippy::too_many_arguments, reason = "jitter_pass's, and the device's snap")]
pub fn jitter_pass_at(
    tris: &[[[f32; 4]; 3]],
    width: u32,
    height: u32,
    greater: bool,
    clear: [f32; 4],
    rules: JitterRules,
    subpixel_bits: u32,
    mut fragment: impl FnMut(usize, usize, [f64; 3], f32) -> Option<[f32; 4]>,
) -> Vec<[f32; 4]> {
    let n = (width as usize) * (height as usize);
    let mut target = Target {
        width,
        greater,
        write_depth: true,
        out: vec![clear; n],
        depth: vec![if greater { 0.0 } else { 1.0 }; n],
    };
    target.run(tris, height, rules, subpixel_bits, &mut fragment);
    target.out
}

/// A `Greater` pass over a depth buffer it does not write (`depth`, what the passes before
/// left), as one random conformant GPU draws it (see [`jitter_pass`]): `fragment(pixel,
/// triangle, barycentrics, depth)` is called for each sample that passes the test, in
/// submission order, and blends into a target of its own.
pub fn jitter_blend_pass(
    tris: &[[[f32; 4]; 3]],
    width: u32,
    height: u32,
    depth: &[f32],
    rules: JitterRules,
    subpixel_bits: u32,
    mut fragment: impl FnMut(usize, usize, [f64; 3], f32),
) {
    let mut target = Target {
        width,
        greater: true,
        write_depth: false,
        out: vec![[0.0; 4]; depth.len()],
        depth: depth.iter().map(|&d| f64::from(d)).collect(),
    };
    target.run(tris, height, rules, subpixel_bits, &mut |i, k, w, z| {
        fragment(i, k, w, z);
        Some([0.0; 4])
    });
}

impl Target {
    /// Clips, snaps and draws `tris` in order.
    fn run(
        &mut self,
        tris: &[[[f32; 4]; 3]],
        height: u32,
        rules: JitterRules,
        subpixel_bits: u32,
        fragment: &mut impl FnMut(usize, usize, [f64; 3], f32) -> Option<[f32; 4]>,
    ) {
        let width = self.width;
        let mut draws = Draws(SplitMix64::new(rules.seed ^ 0x005e_ed0f_da7a));
        let drawn = clip(tris, &mut draws);
        for (s_index, &(k, t, bary)) in drawn.iter().enumerate() {
            let raw: [[f64; 3]; 3] = t.map(|v| {
                Jitter::reseed(rules, vertex_hash(rules.seed, &v, 1));
                to_screen_r(v.map(Jitter), width, height).map(|c| f64::from(c.0))
            });
            Jitter::reseed(rules, s_index as u64);
            let inv_w = t.map(|v| 1.0 / f64::from(v[3]));
            let snapped = snap(raw, &t, rules, subpixel_bits);
            let area = (snapped[1][0] - snapped[0][0]) * (snapped[2][1] - snapped[0][1])
                - (snapped[2][0] - snapped[0][0]) * (snapped[1][1] - snapped[0][1]);
            if area == 0.0 {
                continue;
            }
            let sign = area.signum();
            let ties = edge_ties(snapped, sign, rules.seed);
            // The depth plane and the barycentrics through the snapped or the unsnapped vertices.
            let plane_of = if draws.unit() < 0.5 { snapped } else { raw };
            let plane = DepthPlane::new(plane_of, rules, width, height);
            let Some(bounds) = sample_bounds(snapped, width, height) else { continue };
            let setup = Setup { k, bary, inv_w, snapped, sign, ties, plane };
            self.draw(&setup, bounds, &mut draws, fragment);
        }
    }
}

/// The pass's own draws (the clipper's roundings, each triangle's choice of depth plane, each
/// sample's depth error), one stream in the order the pass makes them.
struct Draws(SplitMix64);

impl Draws {
    /// A uniform draw in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A triangle after the clipper: (original triangle, clip positions, barycentrics in the
/// original).
type Part = (usize, [[f32; 4]; 3], [[f64; 3]; 3]);

/// A clipped polygon's vertex: (clip position, barycentrics in the original triangle).
type PolyVertex = ([f64; 4], [f64; 3]);

/// The clipper (near z ≤ w, far z ≥ 0), each new vertex rounded to f32 either way; a
/// sub-triangle keeps its vertices' barycentrics in the original.
fn clip(tris: &[[[f32; 4]; 3]], draws: &mut Draws) -> Vec<Part> {
    let mut drawn: Vec<Part> = Vec::new();
    for (k, t) in tris.iter().enumerate() {
        let mut poly: Vec<PolyVertex> = (0..3)
            .map(|i| {
                let mut b = [0.0; 3];
                b[i] = 1.0;
                (t[i].map(f64::from), b)
            })
            .collect();
        for p in 0..2 {
            poly = clip_to_plane(&poly, p, draws);
        }
        if poly.len() < 3 || poly.iter().any(|(v, _)| v[3] <= 0.0) {
            continue;
        }
        for i in 1..poly.len() - 1 {
            let tri = [poly[0], poly[i], poly[i + 1]];
            drawn.push((k, tri.map(|(v, _)| v.map(|c| c as f32)), tri.map(|(_, b)| b)));
        }
    }
    drawn
}

/// `poly`'s part on the inner side of clip plane `p` ([`plane_distances`]).
fn clip_to_plane(poly: &[PolyVertex], p: usize, draws: &mut Draws) -> Vec<PolyVertex> {
    let mut out = Vec::new();
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (da, db) = (plane_distances(&a.0)[p], plane_distances(&b.0)[p]);
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let tt = da / (da - db);
            let v = std::array::from_fn(|c| {
                let m = a.0[c] + tt * (b.0[c] - a.0[c]);
                f64::from((m * (1.0 + (draws.unit() * 2.0 - 1.0) * CLIP_SLACK * 0.5)) as f32)
            });
            out.push((v, std::array::from_fn(|j| a.1[j] + tt * (b.1[j] - a.1[j]))));
        }
    }
    out
}

/// A vertex's draws for its viewport transform and snap. They are a function of the vertex:
/// a GPU transforms and snaps the same clip position alike in every triangle that shares it,
/// which is what keeps a mesh's shared edges watertight.
fn vertex_hash(seed: u64, v: &[f32; 4], salt: u64) -> u64 {
    let mut h = seed ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    for c in v {
        h = ocean_core::rng::mix64(h ^ u64::from(c.to_bits()));
    }
    h
}

/// A hash as a uniform draw in [0, 1).
fn coin(h: u64) -> f64 {
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// The screen positions `raw` of triangle `t`'s vertices snapped to the grid of
/// `subpixel_bits`, up or down at random (and at `rules.scale` above 1, further by up to
/// `scale - 1` steps); depth is not snapped.
fn snap(
    raw: [[f64; 3]; 3],
    t: &[[f32; 4]; 3],
    rules: JitterRules,
    subpixel_bits: u32,
) -> [[f64; 3]; 3] {
    let grid = f64::from(1u32 << subpixel_bits);
    let snap = |c: f64, h: u64| {
        let s = if coin(h) < 0.5 { (c * grid).floor() } else { (c * grid).ceil() };
        let r = coin(ocean_core::rng::mix64(h));
        let extra = if rules.scale > 1.0 { (r * 2.0 - 1.0) * (rules.scale - 1.0) } else { 0.0 };
        (s + extra.round()) / grid
    };
    std::array::from_fn(|i| {
        let v = raw[i];
        [
            snap(v[0], vertex_hash(rules.seed, &t[i], 2)),
            snap(v[1], vertex_hash(rules.seed, &t[i], 3)),
            v[2],
        ]
    })
}

/// Each edge's tie-break: whether a sample exactly on it is covered.
fn edge_ties(snapped: [[f64; 3]; 3], sign: f64, seed: u64) -> [bool; 3] {
    // The tie-break is a rule of the edge (as top-left is): a sample on an edge two
    // triangles share goes to exactly one of them. Edge e runs from vertex e + 1 to
    // e + 2, in the direction that makes the triangle counter-clockwise after `sign`.
    std::array::from_fn(|e| {
        let (mut p, mut q) = (snapped[(e + 1) % 3], snapped[(e + 2) % 3]);
        if sign < 0.0 {
            std::mem::swap(&mut p, &mut q);
        }
        let key = |v: [f64; 3]| (v[0].to_bits(), v[1].to_bits());
        let (a, b) = if key(p) < key(q) { (p, q) } else { (q, p) };
        let h = [a[0], a[1], b[0], b[1]]
            .iter()
            .fold(seed ^ 0x7e_ed9e, |h, c| ocean_core::rng::mix64(h ^ c.to_bits()));
        (key(p) < key(q)) != (h & 1 == 1)
    })
}

/// The depth plane through a triangle's screen vertices (the barycentrics are through the
/// same ones), and the error its evaluation may make.
struct DepthPlane {
    /// The vertices, (x, y, z).
    v: [[f64; 3]; 3],
    det: f64,
    gx: f64,
    gy: f64,
    err: f64,
}

impl DepthPlane {
    fn new(v: [[f64; 3]; 3], rules: JitterRules, width: u32, height: u32) -> Self {
        let [a, b, c] = v;
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let gx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / det;
        let gy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / det;
        let magnitude = [a[2], b[2], c[2]].iter().fold(0.0f64, |m, z| m.max(z.abs()))
            + gx.abs() * f64::from(width)
            + gy.abs() * f64::from(height);
        let err = DEPTH_ULPS * rules.scale * crate::envelope::f32_ulp(magnitude);
        Self { v, det, gx, gy, err }
    }

    /// The depth at sample (sx, sy), with an error drawn within the allowance.
    fn z(&self, sx: f64, sy: f64, draws: &mut Draws) -> f64 {
        let [a, _, _] = self.v;
        let (gx, gy, err) = (self.gx, self.gy, self.err);
        a[2] + gx * (sx - a[0]) + gy * (sy - a[1]) + (draws.unit() * 2.0 - 1.0) * err
    }

    /// The screen-space barycentrics of sample (sx, sy).
    fn barycentrics(&self, sx: f64, sy: f64) -> [f64; 3] {
        let [a, b, c] = self.v;
        let det = self.det;
        [
            ((b[0] - sx) * (c[1] - sy) - (c[0] - sx) * (b[1] - sy)) / det,
            ((c[0] - sx) * (a[1] - sy) - (a[0] - sx) * (c[1] - sy)) / det,
            ((a[0] - sx) * (b[1] - sy) - (b[0] - sx) * (a[1] - sy)) / det,
        ]
    }
}

/// The pixels whose centres a triangle's snapped bounding box may hold, (x0, x1, y0, y1)
/// inclusive; `None` where it lies off the target.
fn sample_bounds(snapped: [[f64; 3]; 3], width: u32, height: u32) -> Option<[u32; 4]> {
    let fold = |v: [f64; 3], f: fn(f64, f64) -> f64, init: f64| v.iter().copied().fold(init, f);
    let xs = snapped.map(|v| v[0]);
    let ys = snapped.map(|v| v[1]);
    let first = |lo: f64| (lo - 0.5).ceil().max(0.0) as u32;
    let last = |hi: f64, n: u32| (hi - 0.5).floor().min(f64::from(n) - 1.0);
    let (lx, hx) = (
        first(fold(xs, f64::min, f64::INFINITY)),
        last(fold(xs, f64::max, f64::NEG_INFINITY), width),
    );
    let (ly, hy) = (
        first(fold(ys, f64::min, f64::INFINITY)),
        last(fold(ys, f64::max, f64::NEG_INFINITY), height),
    );
    if hx < 0.0 || hy < 0.0 {
        return None;
    }
    Some([lx, hx as u32, ly, hy as u32])
}

/// A triangle set up for the samples: which it is, its vertices' barycentrics in the
/// original and 1/w, its snapped screen vertices with their winding and ties, and its depth
/// plane.
struct Setup {
    k: usize,
    bary: [[f64; 3]; 3],
    inv_w: [f64; 3],
    snapped: [[f64; 3]; 3],
    sign: f64,
    ties: [bool; 3],
    plane: DepthPlane,
}

impl Setup {
    /// Whether sample (sx, sy) is inside the snapped triangle (on an edge: by its tie-break).
    fn covers(&self, sx: f64, sy: f64) -> bool {
        let (snapped, sign) = (self.snapped, self.sign);
        (0..3).all(|e| {
            let (p, q) = (snapped[(e + 1) % 3], snapped[(e + 2) % 3]);
            let f = sign * ((q[0] - p[0]) * (sy - p[1]) - (q[1] - p[1]) * (sx - p[0]));
            f > 0.0 || (f == 0.0 && self.ties[e])
        })
    }

    /// Sample (sx, sy)'s barycentrics in the original triangle, perspective-corrected.
    fn weights(&self, sx: f64, sy: f64) -> [f64; 3] {
        let (inv_w, bary) = (self.inv_w, self.bary);
        let lam = self.plane.barycentrics(sx, sy);
        let pw = [lam[0] * inv_w[0], lam[1] * inv_w[1], lam[2] * inv_w[2]];
        let sum = pw[0] + pw[1] + pw[2];
        let pw = pw.map(|v| v / sum);
        std::array::from_fn(|j| (0..3).map(|v| pw[v] * bary[v][j]).sum())
    }
}

/// The colour and depth targets, and the depth test.
struct Target {
    width: u32,
    /// `Greater` (else `Less`).
    greater: bool,
    /// Whether a passing sample stores its depth.
    write_depth: bool,
    out: Vec<[f32; 4]>,
    depth: Vec<f64>,
}

impl Target {
    /// Triangle `s` on the samples within `bounds` ([`sample_bounds`]).
    fn draw(
        &mut self,
        s: &Setup,
        [lx, hx, ly, hy]: [u32; 4],
        draws: &mut Draws,
        fragment: &mut impl FnMut(usize, usize, [f64; 3], f32) -> Option<[f32; 4]>,
    ) {
        for py in ly..=hy {
            for px in lx..=hx {
                let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                if !s.covers(sx, sy) {
                    continue;
                }
                let z = s.plane.z(sx, sy, draws);
                if !(0.0..=1.0).contains(&z) {
                    continue;
                }
                let i = py as usize * self.width as usize + px as usize;
                let stored = z as f32;
                let passes = if self.greater {
                    f64::from(stored) > self.depth[i]
                } else {
                    f64::from(stored) < self.depth[i]
                };
                if !passes {
                    continue;
                }
                let Some(color) = fragment(i, s.k, s.weights(sx, sy), stored) else { continue };
                if self.write_depth {
                    self.depth[i] = f64::from(stored);
                }
                self.out[i] = color;
            }
        }
    }
}

//! One random conformant GPU's rasteriser: the soundness test of the rasteriser's envelope
//! (its parent module) without hardware.

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
) -> Vec<f32> {
    let target =
        jitter_pass(tris, width, height, false, [clear, 0.0, 0.0, 0.0], rules, |_, _, z| {
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
    use ocean_core::rng::SplitMix64;
    let mut g = SplitMix64::new(rules.seed ^ 0x005e_ed0f_da7a);
    let mut unit = move || (g.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let n = (width as usize) * (height as usize);
    let mut out = vec![clear; n];
    let mut depth = vec![if greater { 0.0 } else { 1.0 }; n];
    // The clipper first (near z ≤ w, far z ≥ 0), each new vertex rounded to f32 either way;
    // a sub-triangle keeps its vertices' barycentrics in the original.
    // (original triangle, clip positions, barycentrics in the original).
    type Part = (usize, [[f32; 4]; 3], [[f64; 3]; 3]);
    let mut drawn: Vec<Part> = Vec::new();
    for (k, t) in tris.iter().enumerate() {
        let mut poly: Vec<([f64; 4], [f64; 3])> = (0..3)
            .map(|i| {
                let mut b = [0.0; 3];
                b[i] = 1.0;
                (t[i].map(f64::from), b)
            })
            .collect();
        for p in 0..2 {
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
                        f64::from((m * (1.0 + (unit() * 2.0 - 1.0) * CLIP_SLACK * 0.5)) as f32)
                    });
                    out.push((v, std::array::from_fn(|j| a.1[j] + tt * (b.1[j] - a.1[j]))));
                }
            }
            poly = out;
        }
        if poly.len() < 3 || poly.iter().any(|(v, _)| v[3] <= 0.0) {
            continue;
        }
        for i in 1..poly.len() - 1 {
            let tri = [poly[0], poly[i], poly[i + 1]];
            drawn.push((k, tri.map(|(v, _)| v.map(|c| c as f32)), tri.map(|(_, b)| b)));
        }
    }
    // A vertex's viewport transform and snap are a function of the vertex (a GPU transforms
    // and snaps the same clip position alike in every triangle that shares it, which is what
    // keeps a mesh's shared edges watertight): their draws come from a hash of its bits.
    let hash = |v: &[f32; 4], salt: u64| {
        let mut h = rules.seed ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        for c in v {
            h = ocean_core::rng::mix64(h ^ u64::from(c.to_bits()));
        }
        h
    };
    let coin = |h: u64| (h >> 11) as f64 / (1u64 << 53) as f64;
    for (s_index, &(k, t, bary)) in drawn.iter().enumerate() {
        let raw: [[f64; 3]; 3] = t.map(|v| {
            Jitter::reseed(rules, hash(&v, 1));
            to_screen_r(v.map(Jitter), width, height).map(|c| f64::from(c.0))
        });
        Jitter::reseed(rules, s_index as u64);
        let inv_w = t.map(|v| 1.0 / f64::from(v[3]));
        let grid = f64::from(1u32 << subpixel_bits);
        let snap = |c: f64, h: u64| {
            let s = if coin(h) < 0.5 { (c * grid).floor() } else { (c * grid).ceil() };
            let r = coin(ocean_core::rng::mix64(h));
            let extra = if rules.scale > 1.0 { (r * 2.0 - 1.0) * (rules.scale - 1.0) } else { 0.0 };
            (s + extra.round()) / grid
        };
        let snapped: [[f64; 3]; 3] = std::array::from_fn(|i| {
            let v = raw[i];
            [snap(v[0], hash(&t[i], 2)), snap(v[1], hash(&t[i], 3)), v[2]]
        });
        let area = (snapped[1][0] - snapped[0][0]) * (snapped[2][1] - snapped[0][1])
            - (snapped[2][0] - snapped[0][0]) * (snapped[1][1] - snapped[0][1]);
        if area == 0.0 {
            continue;
        }
        let sign = area.signum();
        // The tie-break is a rule of the edge (as top-left is): a sample on an edge two
        // triangles share goes to exactly one of them. Edge e runs from vertex e + 1 to
        // e + 2, in the direction that makes the triangle counter-clockwise after `sign`.
        let ties: [bool; 3] = std::array::from_fn(|e| {
            let (mut p, mut q) = (snapped[(e + 1) % 3], snapped[(e + 2) % 3]);
            if sign < 0.0 {
                std::mem::swap(&mut p, &mut q);
            }
            let key = |v: [f64; 3]| (v[0].to_bits(), v[1].to_bits());
            let (a, b) = if key(p) < key(q) { (p, q) } else { (q, p) };
            let h = [a[0], a[1], b[0], b[1]]
                .iter()
                .fold(rules.seed ^ 0x7e_ed9e, |h, c| ocean_core::rng::mix64(h ^ c.to_bits()));
            (key(p) < key(q)) != (h & 1 == 1)
        });
        // The depth plane and the barycentrics through the snapped or the unsnapped vertices.
        let plane_of = if unit() < 0.5 { snapped } else { raw };
        let [a, b, c] = plane_of;
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let gx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / det;
        let gy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / det;
        let magnitude = [a[2], b[2], c[2]].iter().fold(0.0f64, |m, z| m.max(z.abs()))
            + gx.abs() * f64::from(width)
            + gy.abs() * f64::from(height);
        let err = DEPTH_ULPS * rules.scale * crate::envelope::f32_ulp(magnitude);
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
                let passes = if greater {
                    f64::from(stored) > depth[i]
                } else {
                    f64::from(stored) < depth[i]
                };
                if !passes {
                    continue;
                }
                // Screen-space barycentrics of the sample, then perspective-corrected.
                let lam = [
                    ((b[0] - sx) * (c[1] - sy) - (c[0] - sx) * (b[1] - sy)) / det,
                    ((c[0] - sx) * (a[1] - sy) - (a[0] - sx) * (c[1] - sy)) / det,
                    ((a[0] - sx) * (b[1] - sy) - (b[0] - sx) * (a[1] - sy)) / det,
                ];
                let pw = [lam[0] * inv_w[0], lam[1] * inv_w[1], lam[2] * inv_w[2]];
                let sum = pw[0] + pw[1] + pw[2];
                let pw = pw.map(|v| v / sum);
                let weights = std::array::from_fn(|j| (0..3).map(|v| pw[v] * bary[v][j]).sum());
                let Some(color) = fragment(i, k, weights, stored) else { continue };
                depth[i] = f64::from(stored);
                out[i] = color;
            }
        }
    }
    out
}

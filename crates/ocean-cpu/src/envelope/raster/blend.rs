//! The envelope of an additive pass of quads (the spray's sprites): blend One + One over
//! what the target holds, reversed-Z `Greater` against a depth buffer the pass does not
//! write, no culling.
//!
//! A quad is two triangles, (0, 1, 2) and (0, 2, 3), drawn one after the other and sharing
//! the diagonal 0–2, whose vertices are the same values in both (each is the same function
//! of the same inputs on one GPU). So at a sample at most one of them lands, and where the
//! bounds leave only the diagonal undecided in both, exactly one does (Vulkan's tie-break):
//! the sum then certainly gains one of their colours, not perhaps nothing. Without that,
//! every sprite's brightest pixels, on its diagonal, would be open to 0.

use ocean_core::frame_format::FrameFormat;

use super::mesh::cover_edges;
use super::{Cover, Interp, ScreenIv, barycentrics, setup};
use crate::envelope::{Iv, Real};

/// Adds the envelope of the quads' pass to `target` (per texel, the interval of what any
/// conformant GPU leaves there, given that it held a value of `target` before the pass) in
/// submission order. `depth` holds per texel the interval the stored depth lies in (what the
/// passes before left; this one writes none). `shade(quad, triangle, interpolation)` is the
/// fragment shader's envelope (the colour it outputs), `snap` the device's snap (px). False
/// (and `target` untouched) where a vertex may be anything.
///
/// Per sample, a quad's fragment may land when a triangle may cover it and its depth may
/// pass the test; it certainly lands when one certainly covers it (or the shared diagonal
/// gives it to one of the two) and its depth certainly passes. The sum is then
/// `store(held + colour)`; where the fragment may not land, the hull of that and what was
/// held. Blending is carried out at no less than the target's precision: the sum's
/// rounding, then the store's, bound both.
#[allow(clippy::too_many_arguments, reason = "the pass's target, its depth and its state")]
pub fn additive_quads(
    quads: &[[ScreenIv; 4]],
    width: u32,
    height: u32,
    snap: f64,
    target: &mut [[Iv; 4]],
    depth: &[Iv],
    format: FrameFormat,
    shade: impl Fn(usize, usize, &Interp) -> [Iv; 4],
) -> bool {
    if quads.iter().flatten().any(|v| v.x.full || v.y.full || v.z.full) {
        return false;
    }
    for (q, v) in quads.iter().enumerate() {
        let tris = [[v[0], v[1], v[2]], [v[0], v[2], v[3]]];
        let setups = tris.map(|t| setup(&t, width, height, snap));
        let orientation = setups.each_ref().map(|s| match s {
            Some(s) if s.area.0 > 0.0 => 1.0,
            Some(s) if s.area.1 < 0.0 => -1.0,
            _ => 0.0,
        });
        let boxes: Vec<[u32; 4]> = setups.iter().flatten().map(|s| s.bbox).collect();
        let Some(&first) = boxes.first() else { continue };
        let [x0, y0, x1, y1] = boxes
            .iter()
            .fold(first, |a, b| [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])]);
        // The diagonal is the edge opposite vertex 1 in the first triangle and opposite
        // vertex 2 in the second; the two lie on its two sides when they turn alike.
        let shares_diagonal = orientation[0] != 0.0 && orientation[0] == orientation[1];
        for py in y0..=y1 {
            for px in x0..=x1 {
                let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                let covers = [0, 1].map(|t| match &setups[t] {
                    Some(s) => cover_edges(s, orientation[t], sx, sy),
                    None => (Cover::No, None),
                });
                let certain_of = |t: usize| match covers[t].0 {
                    Cover::Certain(z) => Some(z),
                    _ => None,
                };
                // (triangle, depth) of each fragment that may land, and whether one surely does.
                let (frags, sure): (Vec<(usize, Iv)>, bool) = if let Some(z) = certain_of(0) {
                    (vec![(0, z)], true)
                } else if let Some(z) = certain_of(1) {
                    (vec![(1, z)], true)
                } else {
                    let possible: Vec<(usize, Iv)> = (0..2)
                        .filter_map(|t| match covers[t].0 {
                            Cover::Possible(z) => Some((t, z)),
                            _ => None,
                        })
                        .collect();
                    let diagonal = shares_diagonal
                        && possible.len() == 2
                        && covers[0].1 == Some(1)
                        && covers[1].1 == Some(2);
                    (possible, diagonal)
                };
                if frags.is_empty() {
                    continue;
                }
                let i = py as usize * width as usize + px as usize;
                let stored = depth[i];
                let z = frags.iter().skip(1).fold(frags[0].1, |a, f| a.hull(f.1));
                // `Greater`: the fragment passes where its depth exceeds the stored one.
                if z.full || stored.full {
                    target[i] = [Iv::FULL; 4];
                    continue;
                }
                if z.hi <= stored.lo {
                    continue;
                }
                let lands = sure && z.lo > stored.hi;
                let colors: Vec<[Iv; 4]> = frags
                    .iter()
                    .filter_map(|&(t, _)| {
                        setups[t].as_ref().map(|s| shade(q, t, &barycentrics(s, sx, sy)))
                    })
                    .collect();
                let held = target[i];
                let sum: [Iv; 4] = std::array::from_fn(|c| {
                    colors
                        .iter()
                        .map(|col| (held[c] + col[c].store(format)).store(format))
                        .reduce(Iv::hull)
                        .unwrap_or(held[c])
                });
                target[i] = if lands { sum } else { std::array::from_fn(|c| sum[c].hull(held[c])) };
            }
        }
    }
    true
}

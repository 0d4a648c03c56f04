//! A colour pass of one connected mesh (the water's): where a sample lies within the snapping's
//! reach of an edge two triangles share, it is covered by one of the two, whichever way the
//! GPU snaps and breaks the tie — the shared vertices are the same values in both (one vertex
//! shaded once, or a vertex-index draw whose vertices are the same function of the same
//! lattice point), so the edge is one line and Vulkan's tie-break gives its samples to exactly
//! one side. So such a sample is certainly drawn, with a depth at least the lesser of the two,
//! and the background does not show through it.

use rayon::prelude::*;

use super::{Cover, Interp, ScreenIv, Setup, Span, barycentrics, edge, setup};
use crate::envelope::Iv;

/// What [`color_pass_mesh`] leaves in its target.
#[derive(Clone, Debug)]
pub struct MeshEnvelope {
    /// Per texel, the interval of the colour any conformant GPU leaves there.
    pub color: Vec<[Iv; 4]>,
    /// Whether the mesh's coverage of the texel is ambiguous (the background may show).
    pub open: Vec<bool>,
    /// The depth (reversed Z) that a fragment certainly drawn at the texel guarantees: the
    /// stored depth is at least this after the pass (−∞: no fragment is certain there).
    pub nearest: Vec<f64>,
    /// The largest depth (reversed Z) any fragment that may land at the texel may have: a
    /// later or earlier pass's fragment stored at least this deep cannot be passed (−∞: none
    /// may land there).
    pub reach: Vec<f64>,
}

impl MeshEnvelope {
    /// A target of `n` texels of which nothing is known.
    pub fn anything(n: usize) -> Self {
        Self {
            color: vec![[Iv::FULL; 4]; n],
            open: vec![true; n],
            nearest: vec![f64::NEG_INFINITY; n],
            reach: vec![f64::INFINITY; n],
        }
    }
}

/// A triangle of the mesh on screen, with the mesh's vertex ids (`None` for a piece the
/// clipper made, whose edges are the clipper's own).
#[derive(Clone, Copy, Debug)]
pub struct MeshTri {
    /// The vertices after the viewport transform.
    pub screen: [ScreenIv; 3],
    /// The mesh's ids of the vertices (equal ids: equal values on the GPU).
    pub ids: Option<[u32; 3]>,
    /// Whether the piece is drawn for certain where it covers (false for a piece of one of
    /// two clippings the bounds cannot choose between: possible only).
    pub drawn: bool,
}

/// Where a sample lies against a triangle: its cover, and the one edge (opposite vertex i)
/// whose side is undecided while the other two certainly hold it, for a triangle of certain
/// orientation whose depth certainly lies in [0, 1] there.
pub(super) fn cover_edges(t: &Setup, orientation: f64, px: f64, py: f64) -> (Cover, Option<usize>) {
    let c = super::cover(t, px, py);
    let Cover::Possible(z) = c else { return (c, None) };
    if orientation == 0.0 || z.lo < 0.0 || z.hi > 1.0 {
        return (c, None);
    }
    let (p, q) = (Span(px, px), Span(py, py));
    let e = [
        edge(t.x[1], t.y[1], t.x[2], t.y[2], p, q),
        edge(t.x[2], t.y[2], t.x[0], t.y[0], p, q),
        edge(t.x[0], t.y[0], t.x[1], t.y[1], p, q),
    ];
    let inside = |e: Span| (orientation * e.0).min(orientation * e.1) > 0.0;
    let undecided: Vec<usize> = (0..3).filter(|&i| !inside(e[i])).collect();
    (c, (undecided.len() == 1).then(|| undecided[0]))
}

/// Each triangle's orientation where its area's sign is certain (1 or −1), else 0.
pub(super) fn orientations(setups: &[Option<Setup>]) -> Vec<f64> {
    setups
        .iter()
        .map(|s| match s {
            Some(s) if s.area.0 > 0.0 => 1.0,
            Some(s) if s.area.1 < 0.0 => -1.0,
            _ => 0.0,
        })
        .collect()
}

/// What [`each_sample`] visits: (pixel, triangle, sample x, sample y, cover, the one
/// undecided edge).
pub(super) type Visit<'a> = dyn FnMut(usize, usize, f64, f64, Cover, Option<usize>) + 'a;

/// Every sample each set-up triangle may cover, triangle by triangle in submission order,
/// with [`cover_edges`]' cover and undecided edge.
pub(super) fn each_sample(
    setups: &[Option<Setup>],
    orientation: &[f64],
    width: u32,
    visit: &mut Visit<'_>,
) {
    for (k, s) in setups.iter().enumerate() {
        let Some(s) = s else { continue };
        let [x0, y0, x1, y1] = s.bbox;
        for py in y0..=y1 {
            for px in x0..=x1 {
                let (sx, sy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                let (c, e) = cover_edges(s, orientation[k], sx, sy);
                if c != Cover::No {
                    visit(py as usize * width as usize + px as usize, k, sx, sy, c, e);
                }
            }
        }
    }
}

/// The envelope of a colour pass (reversed-Z `Greater`, depth cleared to 0, no blending, no
/// discard) of one mesh over a `background` (what the target holds where no fragment
/// lands): per texel the hull of every colour that may win, with the background where the
/// mesh may leave the sample uncovered; and whether it may (the mesh's own coverage is
/// ambiguous there). `shade(triangle, pixel, interpolation)` is the fragment shader's
/// envelope, run in parallel; `snap` is the device's snap (px).
pub fn color_pass_mesh(
    tris: &[MeshTri],
    width: u32,
    height: u32,
    background: &[[Iv; 4]],
    snap: f64,
    shade: impl Fn(usize, usize, &Interp) -> [Iv; 4] + Sync,
) -> MeshEnvelope {
    let n = (width as usize) * (height as usize);
    if tris.iter().flat_map(|t| t.screen).any(|v| v.x.full || v.y.full || v.z.full) {
        return MeshEnvelope::anything(n);
    }
    let setups: Vec<Option<Setup>> =
        tris.iter().map(|t| setup(&t.screen, width, height, snap)).collect();
    let orientation = orientations(&setups);
    let mut sure = vec![f64::NEG_INFINITY; n];
    // Samples by an undecided shared edge: (pixel, lower id, higher id) → (triangle, the
    // edge's direction in it times its orientation, its least depth).
    let mut pending: std::collections::HashMap<(usize, u32, u32), (usize, f64, f64)> =
        std::collections::HashMap::new();
    let each = |visit: &mut Visit<'_>| each_sample(&setups, &orientation, width, visit);
    each(&mut |i, k, _, _, c, e| match (c, e, tris[k].ids) {
        (Cover::Certain(z), _, _) if z.lo > 0.0 && tris[k].drawn => sure[i] = sure[i].max(z.lo),
        (Cover::Possible(z), Some(e), Some(ids)) => {
            let (a, b) = (ids[(e + 1) % 3], ids[(e + 2) % 3]);
            let dir = if a < b { 1.0 } else { -1.0 } * orientation[k];
            let key = (i, a.min(b), a.max(b));
            match pending.get(&key) {
                Some(&(other, d, zo)) if other != k && d == -dir => {
                    let zl = zo.min(z.lo);
                    if zl > 0.0 {
                        sure[i] = sure[i].max(zl);
                    }
                }
                _ => {
                    pending.insert(key, (k, dir, z.lo));
                }
            }
        }
        _ => {}
    });
    drop(pending);
    let mut candidates: Vec<(usize, usize, Interp)> = Vec::new();
    let mut reach = vec![f64::NEG_INFINITY; n];
    each(&mut |i, k, sx, sy, c, _| {
        let z = match c {
            Cover::No => return,
            Cover::Possible(z) | Cover::Certain(z) => z,
        };
        reach[i] = reach[i].max(z.hi);
        if z.hi <= 0.0 || z.hi < sure[i] {
            return;
        }
        let Some(s) = &setups[k] else { return };
        candidates.push((i, k, barycentrics(s, sx, sy)));
    });
    let colours: Vec<[Iv; 4]> =
        candidates.par_iter().map(|(i, k, interp)| shade(*k, *i, interp)).collect();
    let mut env: Vec<Option<[Iv; 4]>> = vec![None; n];
    for ((i, _, _), c) in candidates.iter().zip(colours) {
        env[*i] = Some(match env[*i] {
            None => c,
            Some(e) => std::array::from_fn(|j| e[j].hull(c[j])),
        });
    }
    let mut open = vec![false; n];
    let env = env
        .into_iter()
        .enumerate()
        .map(|(i, e)| match (e, sure[i] > f64::NEG_INFINITY) {
            (None, _) => background[i],
            (Some(e), true) => e,
            (Some(e), false) => {
                open[i] = true;
                std::array::from_fn(|c| e[c].hull(background[i][c]))
            }
        })
        .collect();
    MeshEnvelope { color: env, open, nearest: sure, reach }
}

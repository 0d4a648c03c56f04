//! The envelope of a colour pass of separate triangles (the objects' passes): reversed-Z
//! `Greater`, depth cleared to 0, no blending, `discard` allowed.
//!
//! Triangles that share an edge (the same two vertices, bit for bit: a GPU transforms them
//! alike) leave no gap along it: a sample on it that the bounds give to neither is covered by
//! exactly one of the two (Vulkan's tie-break), as in a mesh's pass ([`super::mesh`]). Where
//! both certainly keep their fragment there, the sample is certainly drawn.

use std::collections::{HashMap, HashSet};

use super::mesh::{Visit, each_sample, orientations};
use super::{Cover, Interp, ScreenIv, Setup, barycentrics, setup};
use crate::envelope::Iv;

/// What a fragment writes in a colour pass: the stored colour, and whether the fragment
/// shader keeps it (`Some(true)`), discards it (`Some(false)`) or may do either (`None`).
#[derive(Clone, Copy, Debug)]
pub struct Shaded {
    /// The colour as the target stores it.
    pub color: [Iv; 4],
    /// Whether the fragment survives the shader's `discard`.
    pub kept: Option<bool>,
}

/// A sample by an undecided edge two triangles share: (pixel, lower id, higher id).
type EdgeKey = (usize, u32, u32);

/// The envelope of a colour pass with reversed-Z (`Greater`, depth cleared to 0) and no
/// blending: per texel the hull of every colour that may win the depth test (a fragment that
/// may cover the texel, may be kept, and may lie nearer than every fragment certain to be
/// there), with `clear` where no fragment is certain; and whether its coverage is ambiguous.
/// `ids[k]` are triangle k's vertex ids where it is drawn whole (equal ids: equal vertices on
/// the GPU; `None`, or an empty slice, for a clipper's piece), for the shared edges' rule.
/// `shade(triangle, interpolation)` is the fragment shader's envelope at a sample; `snap` is
/// the device's snap (px).
#[allow(clippy::too_many_arguments)]
pub fn color_pass_greater(
    tris: &[[ScreenIv; 3]],
    ids: &[Option<[u32; 3]>],
    width: u32,
    height: u32,
    snap: f64,
    clear: [f32; 4],
    shade: impl Fn(usize, &Interp) -> Shaded,
) -> (Vec<[Iv; 4]>, Vec<bool>) {
    let n = (width as usize) * (height as usize);
    if tris.iter().flatten().any(|v| v.x.full || v.y.full || v.z.full) {
        return (vec![[Iv::FULL; 4]; n], vec![true; n]);
    }
    let setups: Vec<Option<Setup>> = tris.iter().map(|t| setup(t, width, height, snap)).collect();
    let orientation = orientations(&setups);
    let each = |visit: &mut Visit<'_>| each_sample(&setups, &orientation, width, visit);
    // The key of a sample on triangle k's undecided shared edge e, and the edge's direction
    // in it times its orientation (the two triangles run it opposite ways).
    let shared = |i: usize, k: usize, e: Option<usize>| -> Option<(EdgeKey, f64)> {
        let tri = ids.get(k).copied().flatten()?;
        let e = e?;
        let (a, b) = (tri[(e + 1) % 3], tri[(e + 2) % 3]);
        let dir = if a < b { 1.0 } else { -1.0 } * orientation[k];
        Some(((i, a.min(b), a.max(b)), dir))
    };
    let interp = |k: usize, sx: f64, sy: f64| setups[k].as_ref().map(|s| barycentrics(s, sx, sy));
    // The nearest depth a fragment certain to be drawn there guarantees (−∞: none), and the
    // shared edges whose sample one of the two certainly draws.
    let mut sure = vec![f64::NEG_INFINITY; n];
    let mut pending: HashMap<EdgeKey, (usize, f64, f64)> = HashMap::new();
    let mut paired: HashSet<EdgeKey> = HashSet::new();
    each(&mut |i, k, sx, sy, c, e| {
        let kept = || interp(k, sx, sy).is_some_and(|b| shade(k, &b).kept == Some(true));
        match (c, shared(i, k, e)) {
            (Cover::Certain(z), _) if z.lo > sure[i] && z.lo > 0.0 && kept() => sure[i] = z.lo,
            (Cover::Possible(z), Some((key, dir))) if kept() => match pending.get(&key) {
                Some(&(other, d, zo)) if other != k && d == -dir => {
                    let zl = zo.min(z.lo);
                    if zl > 0.0 {
                        sure[i] = sure[i].max(zl);
                        paired.insert(key);
                    }
                }
                _ => {
                    pending.insert(key, (k, dir, z.lo));
                }
            },
            _ => {}
        }
    });
    drop(pending);
    let mut env: Vec<Option<[Iv; 4]>> = vec![None; n];
    let mut ambiguous = vec![false; n];
    each(&mut |i, k, sx, sy, c, e| {
        let (z, certain) = match c {
            Cover::No => return,
            Cover::Possible(z) => (z, false),
            Cover::Certain(z) => (z, true),
        };
        if z.hi <= 0.0 || z.hi < sure[i] {
            return;
        }
        let Some(b) = interp(k, sx, sy) else { return };
        let f = shade(k, &b);
        if f.kept == Some(false) {
            return;
        }
        let on_pair = shared(i, k, e).is_some_and(|(key, _)| paired.contains(&key));
        ambiguous[i] |= !(certain || on_pair) || f.kept.is_none();
        env[i] = Some(match env[i] {
            None => f.color,
            Some(e) => std::array::from_fn(|c| e[c].hull(f.color[c])),
        });
    });
    let clear = clear.map(Iv::point);
    let env = env
        .into_iter()
        .zip(&sure)
        .map(|(e, &s)| match (e, s > f64::NEG_INFINITY) {
            (None, _) => clear,
            (Some(e), true) => e,
            (Some(e), false) => std::array::from_fn(|c| e[c].hull(clear[c])),
        })
        .collect();
    (env, ambiguous)
}

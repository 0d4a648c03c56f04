//! The envelope of a colour pass of separate triangles (the objects' passes): reversed-Z
//! `Greater`, depth cleared to 0, no blending, `discard` allowed.

use super::{Cover, Interp, ScreenIv, fragments};
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

/// A colour pass's envelope over a background ([`color_pass_over`]).
#[derive(Clone, Debug)]
pub struct ColorPass {
    /// Per texel, the hull of every colour that may be left there.
    pub color: Vec<[Iv; 4]>,
    /// Whether a fragment's coverage or discard is ambiguous at the texel.
    pub ambiguous: Vec<bool>,
    /// The depth (reversed Z) that a fragment certainly drawn at the texel guarantees: the
    /// stored depth is at least this after the pass (−∞: no fragment is certain there).
    pub sure: Vec<f64>,
}

/// The envelope of a colour pass with reversed-Z (`Greater`, depth cleared to 0) and no
/// blending: per texel the hull of every colour that may win the depth test (a fragment that
/// may cover the texel, may be kept, and may lie nearer than every fragment certain to be
/// there), with `clear` where no fragment is certain; and whether its coverage is ambiguous.
/// `shade(triangle, interpolation)` is the fragment shader's envelope at a sample.
pub fn color_pass_greater(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    clear: [f32; 4],
    shade: impl Fn(usize, &Interp) -> Shaded,
) -> (Vec<[Iv; 4]>, Vec<bool>) {
    let n = (width as usize) * (height as usize);
    let background = vec![clear.map(Iv::point); n];
    match color_pass_over(tris, width, height, &background, shade) {
        Some(p) => (p.color, p.ambiguous),
        None => (vec![[Iv::FULL; 4]; n], vec![true; n]),
    }
}

/// [`color_pass_greater`] over a target that holds `background` (one interval per texel:
/// what an earlier pass may have left there) instead of a clear colour; with the depth
/// each texel's certain fragments guarantee. `None` where a vertex may be anything (the
/// pass is unbounded).
///
/// # Panics
/// If `background` is not `width` × `height` texels.
pub fn color_pass_over(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    background: &[[Iv; 4]],
    shade: impl Fn(usize, &Interp) -> Shaded,
) -> Option<ColorPass> {
    let n = (width as usize) * (height as usize);
    assert_eq!(background.len(), n, "the background is not the target's size");
    // The nearest depth a fragment certain to be drawn there guarantees (−∞: none).
    let mut sure = vec![f64::NEG_INFINITY; n];
    let bounded = fragments(tris, width, height, |i, k, c, bary| {
        if let Cover::Certain(z) = c
            && z.lo > sure[i]
            && z.lo > 0.0
            && shade(k, &bary()).kept == Some(true)
        {
            sure[i] = z.lo;
        }
    });
    if !bounded {
        return None;
    }
    let mut env: Vec<Option<[Iv; 4]>> = vec![None; n];
    let mut ambiguous = vec![false; n];
    fragments(tris, width, height, |i, k, c, bary| {
        let (z, certain) = match c {
            Cover::No => return,
            Cover::Possible(z) => (z, false),
            Cover::Certain(z) => (z, true),
        };
        if z.hi <= 0.0 || z.hi < sure[i] {
            return;
        }
        let f = shade(k, &bary());
        if f.kept == Some(false) {
            return;
        }
        ambiguous[i] |= !certain || f.kept.is_none();
        env[i] = Some(match env[i] {
            None => f.color,
            Some(e) => std::array::from_fn(|c| e[c].hull(f.color[c])),
        });
    });
    let color = env
        .into_iter()
        .zip(&sure)
        .zip(background)
        .map(|((e, &s), bg)| match (e, s > f64::NEG_INFINITY) {
            (None, _) => *bg,
            (Some(e), true) => e,
            (Some(e), false) => std::array::from_fn(|c| e[c].hull(bg[c])),
        })
        .collect();
    Some(ColorPass { color, ambiguous, sure })
}

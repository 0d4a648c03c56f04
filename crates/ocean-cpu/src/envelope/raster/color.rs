//! The envelope of a colour pass of separate triangles (the objects' passes): reversed-Z
//! `Greater`, depth cleared to 0, no blending, `discard` allowed.

use super::{Cover, Interp, ScreenIv, fragments_at};
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

/// The envelope of a colour pass with reversed-Z (`Greater`, depth cleared to 0) and no
/// blending: per texel the hull of every colour that may win the depth test (a fragment that
/// may cover the texel, may be kept, and may lie nearer than every fragment certain to be
/// there), with `clear` where no fragment is certain; and whether its coverage is ambiguous.
/// `shade(triangle, interpolation)` is the fragment shader's envelope at a sample; `snap` is
/// the device's snap (px).
pub fn color_pass_greater(
    tris: &[[ScreenIv; 3]],
    width: u32,
    height: u32,
    snap: f64,
    clear: [f32; 4],
    shade: impl Fn(usize, &Interp) -> Shaded,
) -> (Vec<[Iv; 4]>, Vec<bool>) {
    let n = (width as usize) * (height as usize);
    // The nearest depth a fragment certain to be drawn there guarantees (−∞: none).
    let mut sure = vec![f64::NEG_INFINITY; n];
    let bounded = fragments_at(tris, width, height, snap, |i, k, c, bary| {
        if let Cover::Certain(z) = c
            && z.lo > sure[i]
            && z.lo > 0.0
            && shade(k, &bary()).kept == Some(true)
        {
            sure[i] = z.lo;
        }
    });
    if !bounded {
        return (vec![[Iv::FULL; 4]; n], vec![true; n]);
    }
    let mut env: Vec<Option<[Iv; 4]>> = vec![None; n];
    let mut ambiguous = vec![false; n];
    fragments_at(tris, width, height, snap, |i, k, c, bary| {
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

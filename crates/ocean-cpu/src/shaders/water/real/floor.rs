//! `shared/floor.wgsl`'s height and depth of the sea floor and `shore_weight` (`[terrain]
//! wave_damping`), over any [`Real`]: the relief map read through [`Inputs::sample`].

use super::inputs::{Inputs, Tex};
use crate::envelope::Real;

/// `floor_height(x, z)`: the plane plus the relief map (bilinear, clamped to its edge).
pub(super) fn floor_height<R: Real>(x: R, z: R, inp: &Inputs<'_, R>) -> R {
    let l = R::lit;
    let f = inp.frame.terrain.floor;
    let r = inp.frame.terrain.relief;
    let uv = [x * l(r[0]) + l(r[2]), z * l(r[1]) + l(r[3])];
    let relief = (inp.sample)(Tex::FloorMap, uv, l(0.0))[0];
    let terms = [l(f[2]), l(f[0]) * x, l(f[1]) * z, relief];
    R::sum_as_written(&terms, |t| ((t[0] + t[1]) + t[2]) + t[3])
}

/// `shore_weight(x, z, inv)`: the share of the waves kept over the floor (1 for `inv` 0).
pub(super) fn shore_weight<R: Real>(x: R, z: R, inv: f32, inp: &Inputs<'_, R>) -> R {
    let l = R::lit;
    if inv == 0.0 {
        return l(1.0);
    }
    ((-floor_height(x, z, inp)).max(l(0.0)) * l(inv)).clamp(l(0.0), l(1.0))
}

/// `floor_depth(rel)`: the floor's depth below the sea plane under `rel` (≥ 0).
pub(super) fn floor_depth<R: Real>(rel: [R; 3], inp: &Inputs<'_, R>) -> R {
    (-floor_height(rel[0], rel[2], inp)).max(R::lit(0.0))
}

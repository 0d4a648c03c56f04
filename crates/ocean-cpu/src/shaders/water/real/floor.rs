//! `shared/floor.wgsl`'s height and depth of the sea floor and `shore_weight` (`[terrain]
//! wave_damping`), over any [`Real`]: the relief map read through [`Inputs::sample`].

use super::inputs::{Inputs, Tex};
use crate::envelope::Real;

/// `floor_height(x, z)`: the plane plus the relief map (bilinear, clamped to its edge).
pub(super) fn floor_height<R: Real>(x: R, z: R, inp: &Inputs<'_, R>) -> R {
    let relief_at = |uv: [R; 2]| (inp.sample)(Tex::FloorMap, uv, R::lit(0.0))[0];
    crate::shaders::shared::floor::floor_height_r(x, z, inp.frame, &relief_at)
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

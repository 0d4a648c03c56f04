//! The foam techniques' `foam_coverage` (`shaders/foam/*.wgsl`) and `shared/foam.wgsl`'s
//! texture, coverage and light, over any [`Real`]. The texture's lattice cell is where
//! `floor` puts the point (both cells, united, where an interval crosses a lattice line: the
//! noise is continuous there).

use ocean_core::foam::{FOAM_INV_PI, FOAM_MIN_JACOBIAN, foam_hash};
use ocean_core::frame::FrameUniforms;
use ocean_core::switch::SWITCH_ON;

use super::inputs::{Inputs, Tex, Varyings};
use crate::envelope::{Real, choose_n, dot3, length2, on_floor};
use crate::shaders::shared::gerstner::gerstner_jacobian_r;
use crate::shaders::shared::shadow::sun_visibility_r;

/// The foam techniques (`technique/foam`'s `foam_coverage`): the envelope carries each.
pub use ocean_core::plan::Foam;

/// `foam_value_noise(x, z, octave, seed)`.
fn value_noise<R: Real>(x: R, z: R, octave: u32, seed: u32) -> R {
    let l = R::lit;
    // Outside one cell: a blend of hashes in [0, 1) by weights in [0, 1], a few roundings
    // past [0, 1] at most.
    let any = [l(-1e-6).hull(l(1.0 + 1e-6))];
    let [v] = on_floor(x, any, |fx, tx| {
        on_floor(z, any, |fz, tz| {
            let (i, j) = (fx as i32, fz as i32);
            let ux = tx * tx * (l(3.0) - l(2.0) * tx);
            let uz = tz * tz * (l(3.0) - l(2.0) * tz);
            let a = l(foam_hash(i, j, octave, seed));
            let b = l(foam_hash(i.wrapping_add(1), j, octave, seed));
            let c = l(foam_hash(i, j.wrapping_add(1), octave, seed));
            let d = l(foam_hash(i.wrapping_add(1), j.wrapping_add(1), octave, seed));
            let ab = a * (l(1.0) - ux) + b * ux;
            let cd = c * (l(1.0) - ux) + d * ux;
            [ab * (l(1.0) - uz) + cd * uz]
        })
    });
    v
}

/// `foam_texture_at(pos)`: two octaves on axes along and across the wind.
fn texture_at<R: Real>(pos: [R; 2], frame: &FrameUniforms) -> R {
    let l = R::lit;
    let f = &frame.foam;
    let along = R::sum_as_written(
        &[pos[0] * l(f.wind[0]), l(f.noise_origin[0]), pos[1] * l(f.wind[1])],
        |t| (t[0] + t[1]) + t[2],
    );
    let across = R::sum_as_written(
        &[pos[1] * l(f.wind[0]), l(f.noise_origin[1]), -(pos[0] * l(f.wind[1]))],
        |t| (t[0] + t[1]) + t[2],
    );
    let (x, z) = (along * l(f.inv_noise_cell_along), across * l(f.inv_noise_cell));
    let n0 = value_noise(x, z, 0, f.seed);
    let n1 = value_noise(x * l(2.0), z * l(2.0), 1, f.seed);
    (n0 * l(2.0) + n1) * l(1.0 / 3.0)
}

/// `foam_mix(t, n)`: the share of the pixel the foam covers.
fn mix<R: Real>(t: R, n: R, frame: &FrameUniforms) -> R {
    let l = R::lit;
    ((t - l(0.6) * n) * l(2.5)).clamp(l(0.0), l(1.0)) * l(frame.foam.intensity)
}

/// `surface_jacobian(in)` under waves `fft` and `gerstner`.
fn surface_jacobian<R: Real>(v: &Varyings<R>, inp: &Inputs<'_, R>) -> R {
    let l = R::lit;
    let frame = inp.frame;
    let weight = v[7];
    // Waves `coastal` move the surface vertically only.
    if frame.coastal.shape[0] == SWITCH_ON {
        return l(1.0);
    }
    if frame.gerstner.count > 0.0 {
        return l(1.0) + (gerstner_jacobian_r([v[8], v[9]], frame) - l(1.0)) * weight;
    }
    let j = (inp.sample)(Tex::Displacement, [v[3], v[4]], l(0.0))[3];
    l(1.0) + (j - l(1.0)) * (weight * l(frame.passes.waves))
}

/// The foam technique's `foam_coverage(in, p)`, `slopes` being `p.slopes`.
pub(super) fn coverage<R: Real>(v: &Varyings<R>, slopes: [R; 3], inp: &Inputs<'_, R>) -> R {
    let l = R::lit;
    let frame = inp.frame;
    let f = &frame.foam;
    let pos = [v[8], v[9]];
    let t = match inp.foam {
        Foam::None => return l(0.0),
        Foam::Heuristic => {
            let h = v[1] + l(frame.view.eye_height);
            // Squares (`length2`): a product of two independent intervals reached below 0
            // where a slope may be 0, and its root was anything.
            let s = length2([slopes[0], slopes[1]]);
            let j = surface_jacobian(v, inp);
            let slope = s / j.max(l(FOAM_MIN_JACOBIAN));
            let high = (h * l(f.inv_crest_height)).clamp(l(0.0), l(1.0));
            let steep = (slope * l(f.inv_crest_slope)).clamp(l(0.0), l(1.0));
            let compressed = ((l(1.0) - j) * l(f.inv_softness)).clamp(l(0.0), l(1.0));
            high * steep * compressed
        }
        Foam::Jacobian => {
            let j = surface_jacobian(v, inp);
            ((l(f.threshold) - j) * l(f.inv_softness)).clamp(l(0.0), l(1.0))
        }
        Foam::Accumulated => {
            let uv: [R; 2] = std::array::from_fn(|c| {
                (pos[c] + l(f.field_origin[c])) * l(f.inv_field_size) + l(f.field_half_texel)
            });
            let t = (inp.sample)(Tex::FoamField, uv, l(0.0))[0].clamp(l(0.0), l(1.0));
            if f.window_outer > 0.0 {
                let d = length2([v[0], v[2]]);
                t * ((l(f.window_outer) - d) * l(f.inv_window_band)).clamp(l(0.0), l(1.0))
            } else {
                t
            }
        }
    };
    mix(t, texture_at(pos, frame), frame)
}

/// The shore's foam of waves `coastal` over `cover`: max(cover, foam_mix(t, texture)).
pub(super) fn shore_cover<R: Real>(cover: R, t: R, pos: [R; 2], frame: &FrameUniforms) -> R {
    cover.max(mix(t, texture_at(pos, frame), frame))
}

/// `foam_over(c, cover, n, rel)`: the water's colour `c` with the foam over it, lit as the
/// objects are (Lambertian, albedo `[foam] color`).
pub(super) fn over<R: Real>(
    c: [R; 3],
    cover: R,
    n: [R; 3],
    rel: [R; 3],
    inp: &Inputs<'_, R>,
) -> [R; 3] {
    let l = R::lit;
    let frame = inp.frame;
    choose_n(
        cover.le(l(0.0)),
        || c,
        || {
            let sd = frame.sun.direction;
            let vis = sun_visibility_r(rel, frame, inp.shadow_dims, inp.occluder);
            let cos_sun =
                dot3(n, [l(sd[0]), l(sd[1]), l(sd[2])]).max(l(0.0)) * (l(frame.sun.lit) * vis);
            let direct = cos_sun * l(FOAM_INV_PI);
            std::array::from_fn(|i| {
                let light = l(frame.sun.radiance[i]) * direct + l(frame.ambient.sky[i]);
                c[i] * (l(1.0) - cover) + l(frame.foam.color[i]) * light * cover
            })
        },
    )
}

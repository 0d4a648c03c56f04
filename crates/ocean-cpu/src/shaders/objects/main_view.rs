//! The objects in the main view (`vs_main`, `fs_main`) as a conformant GPU may draw them:
//! their envelope over the sky pass's, one random conformant GPU's pass for the soundness
//! test, and how the water pass drawn after them composes with them pixel by pixel.
//!
//! The main view draws the sky (depth cleared to 0), then the objects, then the water, each
//! with reversed-Z `Greater`. A pixel therefore shows the water's nearest fragment if it lies
//! nearer than every object fragment there, else what the objects' pass left (an object, or
//! the sky where none covers it). [`compose`] sorts each pixel into the case the depth
//! bounds decide, and takes the hull of both passes where they cannot.

use ocean_core::frame::{FrameUniforms, ObjectVertex};
use ocean_core::frame_format::FrameFormat;

use super::super::shared::floor::{ReliefMarch, sun_reaches_r};
use super::{Drawn, Varyings, jitter_varyings, jitter_vertices, shade_r, vs_main_r};
use crate::envelope::raster::{self, MeshEnvelope};
use crate::envelope::{Iv, Jitter, JitterRules, Precision, Real};
use crate::sampler::Texture2D;

/// What the main view's objects read besides their triangles, for a scalar `R`.
pub struct MainInputs<'a, R> {
    /// The frame's uniforms.
    pub frame: &'a FrameUniforms,
    /// The frame's size.
    pub size: [u32; 2],
    /// The HDR frame's format.
    pub format: FrameFormat,
    /// The device's precision: its snap is the rasteriser's (the water pass's: the same
    /// device draws both).
    pub precision: Precision,
    /// The shadow map's size (binding 3).
    pub shadow_dims: [u32; 2],
    /// The shadow map's texel (x, y): the GPU's own, or for an envelope the interval its map
    /// may hold there.
    pub occluder: &'a (dyn Fn(u32, u32) -> R + Sync),
    /// The sea floor's relief (`ocean_core::terrain::relief_texels`), marched towards the
    /// sun under the water by each scalar type's [`ReliefMarch`].
    pub floor_map: &'a Texture2D,
}

/// `shade_main` (what `fs_main` returns) over any [`Real`] after interpolation: the colour
/// before it is stored.
fn shade_main_r<R: ReliefMarch>(v: Varyings<R>, m: &MainInputs<'_, R>) -> [R; 4] {
    let (normal, color, rel, world_y) = v;
    let relief = |p: [R; 3]| R::relief_sun(p, m.frame, m.floor_map);
    let sun = sun_reaches_r(rel, world_y, m.frame, m.shadow_dims, m.occluder, &relief);
    let [r, g, b] = shade_r(m.frame, normal, color, sun);
    [r, g, b, R::lit(1.0)]
}

/// The envelope of the objects' pass in the main view over `background` (the sky pass's
/// envelope): per pixel the hull of every colour that may be left there, whether coverage
/// is ambiguous, the depth its certain fragments guarantee and the nearest any may have.
/// `None` where a triangle the clipper's bounds cannot place (the pass may be anything).
///
/// Two triangles with a vertex at the same position (bit for bit) transform it alike, so an
/// edge they share leaves no gap: a sample on it that the bounds cannot give to either is
/// certainly covered by one of them (`color_pass_mesh`'s shared edges). Without that, every
/// pixel on an interior edge of a finely tessellated object would be open to the sky.
pub fn main_envelope(
    triangles: &[[ObjectVertex; 3]],
    m: &MainInputs<'_, Iv>,
    background: &[[Iv; 4]],
) -> Option<MeshEnvelope> {
    let [w, h] = m.size;
    let drawn = Drawn::new(triangles, m.frame, m.size, vs_main_r::<Iv>)?;
    let tris: Vec<raster::MeshTri> = drawn
        .screen
        .iter()
        .zip(drawn.whole_ids(triangles))
        .map(|(s, ids)| raster::MeshTri { screen: *s, ids, drawn: true })
        .collect();
    let shade = |k: usize, _: usize, interp: &raster::Interp| {
        shade_main_r(drawn.varyings(k, interp), m).map(|c| c.store(m.format))
    };
    let snap = m.precision.snap_px();
    Some(raster::color_pass_mesh(&tris, w, h, background, snap, shade))
}

/// The objects' pass in the main view as one random conformant GPU draws it (`rules.scale`
/// times the rules) over `background` (its sky pass): the colour, and the depth stored at
/// each pixel (0 where no object landed).
pub fn main_jitter(
    triangles: &[[ObjectVertex; 3]],
    m: &MainInputs<'_, f32>,
    background: &[[f32; 4]],
    rules: JitterRules,
) -> (Vec<[f32; 4]>, Vec<f32>) {
    let [w, h] = m.size;
    let (verts, clip) = jitter_vertices(triangles, m.frame, rules, vs_main_r::<Jitter>);
    let occ = |x: u32, y: u32| Jitter((m.occluder)(x, y));
    let mj = MainInputs {
        frame: m.frame,
        size: m.size,
        format: m.format,
        precision: m.precision,
        shadow_dims: m.shadow_dims,
        occluder: &occ,
        floor_map: m.floor_map,
    };
    let mut depth = vec![0.0f32; background.len()];
    let out = raster::jitter_pass_at(
        &clip,
        w,
        h,
        true,
        [f32::NAN; 4],
        rules,
        m.precision.subpixel_bits,
        |i, k, wts, z| {
            let color = shade_main_r(jitter_varyings(&verts[k], wts), &mj);
            // The pass shades only a sample that passes the depth test: the last one at a
            // pixel is what it stores.
            depth[i] = z;
            Some(color.map(|c| c.store(m.format).0))
        },
    );
    let color = out.into_iter().zip(background).map(|(o, b)| if o[0].is_nan() { *b } else { o });
    (color.collect(), depth)
}

/// What decides a pixel of the main view after the water pass ([`compose`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shows {
    /// No object's fragment can win against the water's certain one, or none lands: the
    /// water pass's envelope (over the sky).
    Water,
    /// No water fragment can pass the depth the objects certainly left (or none lands):
    /// the objects' envelope (over the sky).
    Objects,
    /// Either may win: the hull of both envelopes.
    Either,
}

/// The main view's envelope after the water pass, per pixel, given the water pass's
/// envelope over the sky (`water`), the nearest depth an object may have there
/// (`objects_reach`, `depth_reach`) and the objects' pass over the sky (`objects`, `None`
/// where it is not carried): the envelope and what decided it, or `None` where an object
/// may show and its colour is not carried.
///
/// The water pass keeps its nearest fragment where that lies nearer than the stored depth
/// (`Greater`), so with objects drawn first a pixel holds that fragment's colour or the
/// objects' pass's: the water's envelope where no object may be nearer than its certain
/// fragment, the objects' where the water's farthest reach cannot pass the depth their
/// certain fragments left, and the hull of both otherwise.
pub fn compose(
    water: &MeshEnvelope,
    objects_reach: &[f64],
    objects: Option<&MeshEnvelope>,
) -> Vec<Option<([Iv; 4], Shows)>> {
    (0..water.color.len())
        .map(|i| {
            if !super::may_show(objects_reach[i], water.nearest[i]) {
                return Some((water.color[i], Shows::Water));
            }
            let o = objects?;
            // A water fragment passes only where its depth is greater than the stored one,
            // which is at least what the objects' certain fragments left.
            if water.reach[i] <= o.nearest[i] {
                return Some((o.color[i], Shows::Objects));
            }
            let hull = std::array::from_fn(|c| water.color[i][c].hull(o.color[i][c]));
            Some((hull, Shows::Either))
        })
        .collect()
}

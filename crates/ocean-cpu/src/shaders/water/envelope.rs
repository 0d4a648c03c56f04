//! The water pass's envelope (what any conformant GPU draws of the sea into the HDR frame,
//! given its own input maps) and the pass as one random conformant GPU draws it, for the
//! configurations [`super::real::carried`] names. The mesh is rasterised by the rasteriser's
//! envelope ([`crate::envelope::raster::color_pass_mesh`]), each fragment shaded by
//! [`super::real::fs_main`] over intervals of its varyings.

use ocean_core::atmosphere::SkyLut;
use ocean_core::frame::FrameUniforms;
use ocean_core::frame_format::FrameFormat;
use ocean_core::geometry::WaterVertex;

use super::real::{self, Inputs, Tex, Varyings};
use super::{CLAMP_LINEAR, WRAP_LINEAR};
pub use crate::envelope::raster::MeshEnvelope;
use crate::envelope::raster::{self, MeshTri};
use crate::envelope::{Af, Iv, Jitter, JitterRules, Precision, Real, filter};
use crate::mip::MipChain;
use crate::sampler::{Sampler, Texture2D};
use crate::shaders::shared::preetham::SkyUniforms;

/// The maps the water pass reads: for a verdict, the GPU's own (each judged on its own).
#[derive(Clone, Copy)]
pub struct WaterTextures<'a> {
    /// Binding 1.
    pub displacement: &'a Texture2D,
    /// Binding 2 (a chain under far fields `mip` and `variance`, else one level).
    pub displacement_slopes: &'a MipChain,
    /// Binding 3 (likewise).
    pub bump: &'a MipChain,
    /// Binding 4.
    pub fresnel_above: &'a Texture2D,
    /// Binding 5.
    pub fresnel_below: &'a Texture2D,
    /// Binding 6.
    pub reflection_map: &'a Texture2D,
    /// Binding 7.
    pub refraction_map: &'a Texture2D,
    /// Binding 11.
    pub fresnel_filter: &'a Texture2D,
    /// Binding 8.
    pub shadow_map: &'a Texture2D,
    /// Binding 12, the sea floor's relief (`ocean_core::terrain::relief_texels`).
    pub floor_map: &'a Texture2D,
    /// Binding 13, foam `accumulated`'s field (one zero texel under the other foams).
    pub foam_field: &'a Texture2D,
}

/// One water pass: the frame, the environment, the maps, the mesh and the target.
#[derive(Clone, Copy)]
pub struct WaterPass<'a> {
    /// The frame's uniforms.
    pub frame: &'a FrameUniforms,
    /// The sky's uniforms (group 1).
    pub sky: &'a SkyUniforms,
    /// The sky-view table (`atmosphere`).
    pub lut: &'a SkyLut,
    /// The sky technique.
    pub sky_technique: ocean_core::plan::Sky,
    /// The maps.
    pub textures: WaterTextures<'a>,
    /// Surface `hu_patches`' vertices (unused under `projected_grid`).
    pub vertices: &'a [WaterVertex],
    /// Its triangles.
    pub indices: &'a [[u32; 3]],
    /// The HDR frame's size.
    pub size: [u32; 2],
    /// The HDR frame's storage.
    pub format: FrameFormat,
    /// The device's precision (its snap, filter weights and level blend).
    pub precision: Precision,
    /// The shading technique.
    pub shading: real::Shading,
    /// The foam technique.
    pub foam: real::Foam,
    /// Judge every `every`-th pixel along each axis (1: all); the others are left anything
    /// ([`Iv::FULL`]), unshaded: a quick verdict's saving.
    pub every: u32,
}

/// `textureSampleLevel` as each scalar type samples (level 0 of a texture, a chain at an
/// LOD) on a device of precision `p`.
pub(crate) trait Sampling<R> {
    fn level0(t: &Texture2D, s: &Sampler, uv: [R; 2], p: Precision) -> [R; 4];
    fn mip(c: &MipChain, s: &Sampler, uv: [R; 2], lod: R, p: Precision) -> [R; 4];
    /// [`filter::spread_floor`] for an interval, −∞ otherwise.
    fn spread_floor(_: &MipChain, _: &Sampler, _: [R; 2], _: R, _: Precision) -> [f64; 2] {
        [f64::NEG_INFINITY; 2]
    }
}

impl Sampling<f32> for f32 {
    fn level0(t: &Texture2D, s: &Sampler, uv: [f32; 2], _: Precision) -> [f32; 4] {
        crate::sampler::texture_sample_level(t, s, uv, 0.0)
    }
    fn mip(c: &MipChain, s: &Sampler, uv: [f32; 2], lod: f32, _: Precision) -> [f32; 4] {
        crate::mip::texture_sample_level_mip(c, s, uv, lod)
    }
}

impl Sampling<Iv> for Iv {
    fn level0(t: &Texture2D, s: &Sampler, uv: [Iv; 2], p: Precision) -> [Iv; 4] {
        filter::sample_level0_p(t, s, uv, p)
    }
    fn mip(c: &MipChain, s: &Sampler, uv: [Iv; 2], lod: Iv, p: Precision) -> [Iv; 4] {
        filter::sample_mip(c, s, uv, lod, p)
    }
    fn spread_floor(c: &MipChain, s: &Sampler, uv: [Iv; 2], lod: Iv, p: Precision) -> [f64; 2] {
        filter::spread_floor(c, s, uv, lod, p)
    }
}

impl Sampling<Af> for Af {
    fn level0(t: &Texture2D, s: &Sampler, uv: [Af; 2], p: Precision) -> [Af; 4] {
        crate::envelope::affine_filter::sample_level0(t, s, uv, p)
    }
    fn mip(c: &MipChain, s: &Sampler, uv: [Af; 2], lod: Af, p: Precision) -> [Af; 4] {
        crate::envelope::affine_filter::sample_mip(c, s, uv, lod, p)
    }
    fn spread_floor(c: &MipChain, s: &Sampler, uv: [Af; 2], lod: Af, p: Precision) -> [f64; 2] {
        filter::spread_floor(c, s, uv.map(Af::to_iv), lod.to_iv(), p)
    }
}

impl Sampling<Jitter> for Jitter {
    fn level0(t: &Texture2D, s: &Sampler, uv: [Jitter; 2], p: Precision) -> [Jitter; 4] {
        filter::sample_level0_jitter_p(t, s, uv, p)
    }
    fn mip(c: &MipChain, s: &Sampler, uv: [Jitter; 2], lod: Jitter, p: Precision) -> [Jitter; 4] {
        filter::sample_mip_jitter(c, s, uv, lod, p)
    }
}

/// `textureSampleLevel` on one of the pass's maps.
fn sample<R: Real + Sampling<R>>(
    t: &WaterTextures<'_>,
    tex: Tex,
    uv: [R; 2],
    lod: R,
    p: Precision,
) -> [R; 4] {
    match tex {
        Tex::Displacement => R::level0(t.displacement, &WRAP_LINEAR, uv, p),
        Tex::DisplacementSlopes => R::mip(t.displacement_slopes, &WRAP_LINEAR, uv, lod, p),
        Tex::Bump => R::mip(t.bump, &WRAP_LINEAR, uv, lod, p),
        Tex::FresnelAbove => R::level0(t.fresnel_above, &CLAMP_LINEAR, uv, p),
        Tex::FresnelBelow => R::level0(t.fresnel_below, &CLAMP_LINEAR, uv, p),
        Tex::ReflectionMap => R::level0(t.reflection_map, &CLAMP_LINEAR, uv, p),
        Tex::RefractionMap => R::level0(t.refraction_map, &CLAMP_LINEAR, uv, p),
        Tex::FresnelFilter => R::level0(t.fresnel_filter, &CLAMP_LINEAR, uv, p),
        Tex::FloorMap => R::level0(t.floor_map, &CLAMP_LINEAR, uv, p),
        Tex::FoamField => R::level0(t.foam_field, &WRAP_LINEAR, uv, p),
    }
}

/// Runs `f` with the pass's [`Inputs`] over `R`, the shadow map's texels read by `texel`.
fn with_inputs<R: Real + Sampling<R> + Send + Sync, T>(
    p: &WaterPass<'_>,
    texel: fn(f32) -> R,
    f: impl FnOnce(&Inputs<'_, R>) -> T,
) -> T {
    let t = p.textures;
    let pr = p.precision;
    let sampler = move |tex: Tex, uv: [R; 2], lod: R| sample(&t, tex, uv, lod, pr);
    let floor = move |tex: Tex, uv: [R; 2], lod: R| match tex {
        Tex::DisplacementSlopes => {
            R::spread_floor(t.displacement_slopes, &WRAP_LINEAR, uv, lod, pr)
        }
        Tex::Bump => R::spread_floor(t.bump, &WRAP_LINEAR, uv, lod, pr),
        _ => [f64::NEG_INFINITY; 2],
    };
    let (technique, sky, lut) = (p.sky_technique, p.sky, p.lut);
    let sky_fn = move |dir: [R; 3]| crate::shaders::sky::sky_radiance_r(technique, sky, lut, dir);
    let map = t.shadow_map;
    let occluder = move |x: u32, y: u32| texel(map.texel(x, y)[0]);
    f(&Inputs {
        frame: p.frame,
        shading: p.shading,
        foam: p.foam,
        sample: &sampler,
        spread_floor: &floor,
        sky: &sky_fn,
        shadow_dims: [map.width, map.height],
        occluder: &occluder,
    })
}

/// A vertex after the vertex shader: its clip position and varyings.
type Shaded<R> = ([R; 4], Varyings<R>);

/// A piece the rasteriser draws: its triangle, and its vertices' barycentrics in it (each
/// with its error).
type Piece = (usize, [([f64; 3], f64); 3]);

/// The mesh's vertices (each `vertex(id)`, one per id) and its triangles in draw order.
fn mesh<R>(
    p: &WaterPass<'_>,
    vertex: impl Fn(usize) -> Shaded<R> + Sync,
) -> (Vec<Shaded<R>>, Vec<[u32; 3]>)
where
    R: Send,
{
    use rayon::prelude::*;
    let clip = p.frame.clip.vertex_count();
    if clip > 0 {
        // Surface `clipmap`: six vertex indices a quad, each vertex computed from its lattice
        // point alone (one id each); a hole's quads collapse to a point and draw nothing.
        let f = p.frame;
        let ids = f.clip.levels as u32 * real::clipmap::points_per_level(f);
        let verts = (0..ids as usize).into_par_iter().map(&vertex).collect();
        let tris = (0..clip / 3)
            .map(|t| [0, 1, 2].map(|c| real::clipmap::point_id(3 * t + c, f)))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
        return (verts, tris);
    }
    let g = &p.frame.grid;
    if g.vertex_count() > 0 {
        // The vertex-index draw's vertices are the lattice points (i, j), one id each.
        let (cols, rows) = (g.cols as u32, g.rows as u32);
        let verts = (0..((cols + 1) * (rows + 1)) as usize).into_par_iter().map(&vertex).collect();
        let id = |i: u32, j: u32| j * (cols + 1) + i;
        let tris = (0..rows)
            .flat_map(|j| (0..cols).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                [
                    [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                    [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                ]
            })
            .collect();
        return (verts, tris);
    }
    let verts = (0..p.vertices.len()).into_par_iter().map(&vertex).collect();
    (verts, p.indices.to_vec())
}

/// Vertex `id` of the pass over `R`.
fn vertex<R: Real>(p: &WaterPass<'_>, inp: &Inputs<'_, R>, id: usize) -> ([R; 4], Varyings<R>) {
    if p.frame.clip.vertex_count() > 0 {
        return real::clipmap::vertex(id as u32, inp);
    }
    let g = &p.frame.grid;
    if g.vertex_count() > 0 {
        let cols = g.cols as u32 + 1;
        return real::grid_vertex(id as u32 % cols, id as u32 / cols, inp);
    }
    let v = &p.vertices[id];
    real::water_vertex(v.pos.map(R::lit), R::lit(v.weight), inp)
}

/// The water pass's envelope over `background` (the HDR frame before it, as intervals): per
/// texel the interval of what any conformant GPU leaves there, whether the mesh's coverage
/// of it is ambiguous (the background may show), and the depth its certain fragments
/// guarantee. The pass must be one that [`real::carried`] accepts.
pub fn envelope(p: &WaterPass<'_>, background: &[[Iv; 4]]) -> raster::MeshEnvelope {
    let [w, h] = p.size;
    with_inputs(p, Iv::point, |inp| {
        with_inputs(p, Af::lit, |inp_af| {
            let (verts, tris) = mesh(p, |id| vertex(p, inp, id));
            let mut screen: Vec<MeshTri> = Vec::with_capacity(tris.len());
            // Per drawn piece: its triangle, and its vertices' barycentrics in it.
            let mut owner: Vec<Piece> = Vec::with_capacity(tris.len());
            for (t, ids) in tris.iter().enumerate() {
                let clip = ids.map(|i| verts[i as usize].0);
                if raster::outside_a_side(clip) {
                    continue;
                }
                let Some((parts, drawn)) = raster::clip_near_far_either(clip) else {
                    return raster::MeshEnvelope::anything((w as usize) * (h as usize));
                };
                let whole = drawn && parts.len() == 1 && parts[0].iter().all(|v| v.bary_err == 0.0);
                for part in parts {
                    let Some(s) = raster::piece_to_screen(&part, &clip, w, h) else {
                        return raster::MeshEnvelope::anything((w as usize) * (h as usize));
                    };
                    screen.push(MeshTri { screen: s, ids: whole.then_some(*ids), drawn });
                    owner.push((t, part.map(|v| (v.bary, v.bary_err))));
                }
            }
            let shade = |k: usize, pixel: usize, interp: &raster::Interp| -> [Iv; 4] {
                let (t, bary) = owner[k];
                let ids = tris[t];
                let clip = ids.map(|i| verts[i as usize].0);
                // A clipper's piece: also from the original triangle's values near the sample
                // (its own vertices may slide along the cut edge by hundreds of pixels).
                let v: Varyings<Iv> = std::array::from_fn(|c| {
                    let vals = ids.map(|i| verts[i as usize].1[c]);
                    let piece = bary.map(|(b, err)| raster::part_value(vals, b, err));
                    raster::narrowed(
                        interp.varying(piece),
                        interp.from_original(&clip, vals, piece),
                    )
                });
                let (x, y) = (pixel % w as usize, pixel / w as usize);
                if p.every > 1 && (x % p.every as usize != 0 || y % p.every as usize != 0) {
                    return [Iv::FULL; 4];
                }
                let frag = [x as f32 + 0.5, y as f32 + 0.5];
                fragment_envelope(frag, &v, inp_af).map(|c| c.store(p.format))
            };
            raster::color_pass_mesh(&screen, w, h, background, p.precision.snap_px(), shade)
        })
    })
}

/// The fragment shader's envelope from its varyings' intervals, in affine arithmetic (each
/// varying an input of its own: [`Af`]).
fn fragment_envelope(frag: [f32; 2], v: &Varyings<Iv>, inp: &Inputs<'_, Af>) -> [Iv; 4] {
    real::fs_main(frag, &v.map(Af::input), inp).map(Af::to_iv)
}

/// The water pass over `background` (the HDR frame before it) as one random conformant GPU
/// draws it (`rules`).
pub fn jitter(p: &WaterPass<'_>, background: &[[f32; 4]], rules: JitterRules) -> Vec<[f32; 4]> {
    jitter_with_depth(p, background, rules).0
}

/// [`jitter`], with the depth the pass stores at each pixel (0 where no fragment landed):
/// what decides, pixel by pixel, whether it passes an earlier pass's depth.
pub fn jitter_with_depth(
    p: &WaterPass<'_>,
    background: &[[f32; 4]],
    rules: JitterRules,
) -> (Vec<[f32; 4]>, Vec<f32>) {
    let [w, h] = p.size;
    let mut depth = vec![0.0f32; background.len()];
    let out = with_inputs(p, Jitter, |inp| {
        let (verts, tris) = mesh(p, |id| {
            Jitter::reseed(rules, (id as u64) << 24 | 0xff_ffff);
            let (c, v) = vertex(p, inp, id);
            (c.map(|x| Jitter(x.0)), v)
        });
        let clip: Vec<[[f32; 4]; 3]> =
            tris.iter().map(|t| t.map(|i| verts[i as usize].0.map(|c| c.0))).collect();
        let bits = p.precision.subpixel_bits;
        raster::jitter_pass_at(&clip, w, h, true, [f32::NAN; 4], rules, bits, |i, k, wts, z| {
            let ids = tris[k];
            // The interpolation with random roundings: Σ wₖ·vₖ in f32 operations.
            let v: Varyings<Jitter> = std::array::from_fn(|c| {
                Jitter::sum(&[0, 1, 2].map(|j| Jitter(wts[j] as f32) * verts[ids[j] as usize].1[c]))
            });
            let frag = [(i % w as usize) as f32 + 0.5, (i / w as usize) as f32 + 0.5];
            // Called only for a sample that passes the depth test: the last call stores.
            depth[i] = z;
            Some(real::fs_main(frag, &v, inp).map(|c| c.store(p.format).0))
        })
    });
    let color =
        out.into_iter().zip(background).map(|(o, b)| if o[0].is_nan() { *b } else { o }).collect();
    (color, depth)
}

/// The fragment shader over `f32` through the same inputs (the exact mirror's arithmetic:
/// the test that holds [`real`] to it bit for bit).
pub fn exact_fragment(p: &WaterPass<'_>, frag: [f32; 2], v: &Varyings<f32>) -> [f32; 4] {
    with_inputs(p, |x| x, |inp| real::fs_main(frag, v, inp))
}

/// Vertex `id` over `f32` (the lattice point id of a projected grid or a clipmap
/// (`real::clipmap::point_id`), else the mesh's vertex).
pub fn exact_vertex(p: &WaterPass<'_>, id: usize) -> ([f32; 4], Varyings<f32>) {
    with_inputs(p, |x| x, |inp| vertex(p, inp, id))
}

/// The water pass's maps, owned: made from a frame's resources (a GPU's read back or dumped,
/// or the oracle's).
pub struct OwnedTextures {
    displacement: Texture2D,
    displacement_slopes: MipChain,
    bump: MipChain,
    fresnel_above: Texture2D,
    fresnel_below: Texture2D,
    reflection_map: Texture2D,
    refraction_map: Texture2D,
    fresnel_filter: Texture2D,
    shadow_map: Texture2D,
    floor_map: Texture2D,
    foam_field: Texture2D,
}

/// A resource's texels: (width, height, texels).
pub type Resource<'a> = (u32, u32, &'a [[f32; 4]]);

impl OwnedTextures {
    /// The maps from `get(resource)`, the slope maps as chains where `wave_mips` ran (its
    /// atlas under the chain's id); a map whose pass did not run is the zero texel both back
    /// ends bind; `floor_map` is the scene's relief (not a frame's resource). `Err(name)` for a
    /// map the pass reads that `get` lacks.
    ///
    /// # Errors
    /// The name of a missing map.
    pub fn from_resources<'a>(
        get: impl Fn(ocean_core::plan::ResourceId) -> Option<Resource<'a>>,
        wave_mips: bool,
        runs: impl Fn(ocean_core::plan::ResourceId) -> bool,
        floor_map: Texture2D,
    ) -> Result<Self, &'static str> {
        use ocean_core::plan::ResourceId as Id;
        let need = |id: Id| -> Result<Texture2D, &'static str> {
            let (w, h, t) = get(id).ok_or(id.name())?;
            Ok(Texture2D::new(w, h, t.to_vec()))
        };
        let maybe = |id: Id| -> Result<Texture2D, &'static str> {
            if runs(id) { need(id) } else { Ok(Texture2D::new(1, 1, vec![[0.0; 4]])) }
        };
        let chain = |map: Id, mips: Id| -> Result<MipChain, &'static str> {
            let (w, h, texels) = get(map).ok_or(map.name())?;
            if !wave_mips {
                return Ok(MipChain::single(Texture2D::new(w, h, texels.to_vec())));
            }
            let (aw, rows, atlas) = get(mips).ok_or(mips.name())?;
            let levels = crate::mip::level_count(w, h);
            if aw != w || rows != crate::mip::level_row(h, levels) {
                return Err(mips.name());
            }
            Ok(MipChain {
                width: w,
                height: h,
                levels,
                atlas: Texture2D::new(aw, rows, atlas.to_vec()),
            })
        };
        Ok(Self {
            displacement: need(Id::Displacement)?,
            displacement_slopes: chain(Id::DisplacementSlopes, Id::DisplacementSlopeMips)?,
            bump: chain(Id::Bump, Id::BumpMips)?,
            fresnel_above: need(Id::FresnelAbove)?,
            fresnel_below: need(Id::FresnelBelow)?,
            reflection_map: maybe(Id::ReflectionMap)?,
            refraction_map: maybe(Id::RefractionMap)?,
            fresnel_filter: maybe(Id::FresnelFilter)?,
            shadow_map: maybe(Id::ShadowMap)?,
            floor_map,
            foam_field: maybe(Id::FoamField)?,
        })
    }

    /// The maps as the pass binds them.
    pub fn textures(&self) -> WaterTextures<'_> {
        WaterTextures {
            displacement: &self.displacement,
            displacement_slopes: &self.displacement_slopes,
            bump: &self.bump,
            fresnel_above: &self.fresnel_above,
            fresnel_below: &self.fresnel_below,
            reflection_map: &self.reflection_map,
            refraction_map: &self.refraction_map,
            fresnel_filter: &self.fresnel_filter,
            shadow_map: &self.shadow_map,
            floor_map: &self.floor_map,
            foam_field: &self.foam_field,
        }
    }
}

/// The fragment shader's envelope at `frag` from the varyings' envelope `v` (a probe for
/// tests and tools).
pub fn envelope_fragment(p: &WaterPass<'_>, frag: [f32; 2], v: &Varyings<Iv>) -> [Iv; 4] {
    with_inputs(p, Af::lit, |inp| fragment_envelope(frag, v, inp))
}

/// The fragment shader at `frag` from the varyings `v` as one random conformant GPU computes
/// it (`rules`, reseeded for `index`).
pub fn jitter_fragment(
    p: &WaterPass<'_>,
    frag: [f32; 2],
    v: &Varyings<f32>,
    rules: JitterRules,
    index: u64,
) -> [f32; 4] {
    with_inputs(p, Jitter, |inp| {
        Jitter::reseed(rules, index);
        real::fs_main(frag, &v.map(Jitter), inp).map(|c| c.0)
    })
}

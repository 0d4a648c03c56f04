//! CPU mirror of `shaders/objects.wgsl`: the objects in the main view, mirrored into the
//! reflection map, and scaled and fogged into the refraction map (eq. 4).

pub mod main_view;

use ocean_core::frame::{FrameUniforms, ObjectVertex};

use super::shared::floor::{FloorMaps, ReliefMarch, sun_reaches, sun_reaches_r};
use super::shared::frame::transform_point;
use super::shared::optics::water_volume_colour_r;
use super::water::WRAP_LINEAR;
use super::wgsl::{Vec3, Vec4, texture_sample_level, vec3};
use crate::envelope::raster::{self, Shaded};
use crate::envelope::{Cond, Iv, Jitter, JitterRules, Real, mat4_mul_vec4, normalize3};
use crate::sampler::Texture2D;

/// `VertexOut` of objects.wgsl (clip position and the varyings, in declaration order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexOut {
    /// `@builtin(position)`.
    pub clip: Vec4,
    /// `@location(0)`.
    pub normal: Vec3,
    /// `@location(1)`.
    pub color: Vec3,
    /// `@location(2)`: camera-relative position as drawn.
    pub rel: Vec3,
    /// `@location(3)`: height of the original point above the sea plane.
    pub world_y: f32,
}

/// Number of f32 varyings of [`VertexOut`].
pub const VARYINGS: usize = 10;

impl VertexOut {
    /// The varyings as the rasterizer interpolates them.
    pub fn varyings(&self) -> [f32; VARYINGS] {
        let (n, c, r) = (self.normal, self.color, self.rel);
        [n.x, n.y, n.z, c.x, c.y, c.z, r.x, r.y, r.z, self.world_y]
    }

    /// A fragment's interpolated varyings back in the struct (clip unused).
    pub fn from_varyings(v: &[f32; VARYINGS]) -> Self {
        Self {
            clip: Vec4::splat(0.0),
            normal: vec3(v[0], v[1], v[2]),
            color: vec3(v[3], v[4], v[5]),
            rel: vec3(v[6], v[7], v[8]),
            world_y: v[9],
        }
    }
}

/// WGSL `INV_PI` (0.31830988618 rounds to the same f32).
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;

/// The stage's textures: binding 1 (`displacement`), 3 (`shadow_map`) and 4 (`floor_map`).
#[derive(Clone, Copy)]
pub struct Maps<'a> {
    /// binding 1.
    pub displacement: &'a Texture2D,
    /// bindings 3 and 4.
    pub floor: FloorMaps<'a>,
}

/// A vertex entry point of the stage.
pub type VertexEntry = fn(&ObjectVertex, &FrameUniforms) -> VertexOut;
/// A map pass's fragment entry point (`None` is `discard`).
pub type MapFragmentEntry = fn(&VertexOut, &FrameUniforms, Maps<'_>) -> Option<[f32; 4]>;

/// `shade(normal, color, sun)`: Lambert under the share `sun` of the sun plus the sky's ambient.
fn shade(frame: &FrameUniforms, normal: Vec3, color: Vec3, sun: f32) -> Vec3 {
    let [n, c] = [normal, color].map(|v| [v.x, v.y, v.z]);
    let [x, y, z] = shade_r(frame, n, c, sun);
    vec3(x, y, z)
}

/// `shade(normal, color, sun)` over any [`Real`]: Lambert under the share `sun` of the sun
/// plus the sky's ambient.
pub fn shade_r<R: Real>(frame: &FrameUniforms, normal: [R; 3], color: [R; 3], sun: R) -> [R; 3] {
    let l = R::lit;
    let n = normalize3(normal);
    let cos_sun =
        crate::envelope::dot3(n, frame.sun.direction.map(l)).max(l(0.0)) * (l(frame.sun.lit) * sun);
    let s = cos_sun * l(INV_PI);
    std::array::from_fn(|i| color[i] * (l(frame.sun.radiance[i]) * s + l(frame.ambient.sky[i])))
}

/// `vs_main`.
pub fn vs_main(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let position = Vec3::from(v.position);
    VertexOut {
        clip: transform_point(&frame.view.view_proj, position),
        normal: v.normal.into(),
        color: v.color.into(),
        rel: position,
        world_y: position.y + frame.view.eye_height,
    }
}

/// `fs_main`.
pub fn fs_main(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> [f32; 4] {
    let sun = sun_reaches(input.rel, input.world_y, frame, maps.floor);
    shade(frame, input.normal, input.color, sun).extend(1.0).into()
}

/// `vs_reflect`.
pub fn vs_reflect(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let (position, normal) = (Vec3::from(v.position), Vec3::from(v.normal));
    let mirrored = vec3(position.x, -position.y - 2.0 * frame.view.eye_height, position.z);
    VertexOut {
        clip: transform_point(&frame.view.view_proj, mirrored),
        normal: vec3(normal.x, -normal.y, normal.z),
        color: v.color.into(),
        rel: mirrored,
        world_y: position.y + frame.view.eye_height,
    }
}

/// `clip_height(rel)`: where the maps clip the objects (the wave height under the point for
/// shading `chiu`, else 0); `displacement` is binding 1.
pub fn clip_height(rel: Vec3, frame: &FrameUniforms, displacement: &Texture2D) -> f32 {
    let sample =
        |uv: [f32; 2]| texture_sample_level(displacement, &WRAP_LINEAR, uv.into(), 0.0).into();
    clip_height_r([rel.x, rel.y, rel.z], frame, &sample)
}

/// [`clip_height`] over any [`Real`], `sample` the displacement map's `textureSampleLevel`
/// (wrapping, linear, level 0).
pub fn clip_height_r<R: Real>(
    rel: [R; 3],
    frame: &FrameUniforms,
    sample: &dyn Fn([R; 2]) -> [R; 4],
) -> R {
    let l = R::lit;
    if frame.chiu.clip_waves == 0.0 {
        return l(0.0);
    }
    let t = &frame.tiling;
    let pos = [rel[0] - l(t.mesh_offset[0]), rel[2] - l(t.mesh_offset[1])];
    let uv: [R; 2] = std::array::from_fn(|i| {
        (pos[i] + l(t.displacement_origin[i])) * l(t.inv_displacement_size)
            + l(t.displacement_half_texel)
    });
    sample(uv)[1] * l(frame.passes.waves)
}

/// `reflect_discards`: only what is above the water is reflected.
pub fn reflect_discards(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> bool {
    input.world_y < clip_height(input.rel, frame, maps.displacement)
}

/// `fs_reflect`; `None` is `discard`.
pub fn fs_reflect(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> Option<[f32; 4]> {
    if reflect_discards(input, frame, maps) {
        return None;
    }
    let n = vec3(input.normal.x, -input.normal.y, input.normal.z);
    Some(shade(frame, n, input.color, 1.0).extend(1.0).into())
}

/// `vs_refract`.
pub fn vs_refract(v: &ObjectVertex, frame: &FrameUniforms) -> VertexOut {
    let position = Vec3::from(v.position);
    let world_y = position.y + frame.view.eye_height;
    let scaled =
        vec3(position.x, world_y * frame.water.inv_eta - frame.view.eye_height, position.z);
    VertexOut {
        clip: transform_point(&frame.view.view_proj, scaled),
        normal: v.normal.into(),
        color: v.color.into(),
        rel: scaled,
        world_y,
    }
}

/// `refract_discards`: only what is under the water is seen through it.
pub fn refract_discards(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> bool {
    input.world_y > clip_height(input.rel, frame, maps.displacement)
}

/// `fs_refract`; `None` is `discard`.
pub fn fs_refract(input: &VertexOut, frame: &FrameUniforms, maps: Maps<'_>) -> Option<[f32; 4]> {
    if refract_discards(input, frame, maps) {
        return None;
    }
    let v = |v: Vec3| [v.x, v.y, v.z];
    let sun = |at: [f32; 3], world_y: f32| {
        sun_reaches(vec3(at[0], at[1], at[2]), world_y, frame, maps.floor)
    };
    let varyings = (v(input.normal), v(input.color), v(input.rel), input.world_y);
    Some(refract_colour_r(varyings, frame, &sun))
}

/// A fragment's varyings over any [`Real`]: (normal, colour, rel, world_y).
pub type Varyings<R> = ([R; 3], [R; 3], [R; 3], R);

/// `shade_refract`, `fs_refract`'s colour after its `discard` (eq. 4: the object fogged by the
/// water between it and the eye) over any [`Real`]; `sun_at(at, world_y)` is `sun_reaches`.
pub fn refract_colour_r<R: Real>(
    (normal, color, rel, world_y): Varyings<R>,
    frame: &FrameUniforms,
    sun_at: &dyn Fn([R; 3], R) -> R,
) -> [R; 4] {
    let l = R::lit;
    let eye = l(frame.view.eye_height);
    let ext = l(frame.water.extinction_per_m);
    let depth_below = (-(rel[1] + eye)).max(l(0.0));
    let height_above = eye.max(l(0.0));
    let dist = crate::envelope::dot3(rel, rel).sqrt();
    let d = dist * (depth_below / (depth_below + height_above));
    let fog = l(1.0) - (-ext * d).exp();
    let sun = sun_at([rel[0], world_y - eye, rel[2]], world_y);
    let lit = shade_r(frame, normal, color, sun);
    let atten = (-ext * (-world_y).max(l(0.0))).exp();
    let water = water_volume_colour_r(-world_y, frame);
    let [r, g, b]: [R; 3] =
        std::array::from_fn(|i| water[i] * fog + (lit[i] * atten) * (l(1.0) - fog));
    [r, g, b, l(1.0)]
}

/// What the stage's vertex entry points output, over any [`Real`]: the clip position and the
/// varyings.
pub type ObjectOut<R> = ([R; 4], Varyings<R>);

/// [`vs_main`] over any [`Real`].
pub fn vs_main_r<R: Real>(v: &ObjectVertex, frame: &FrameUniforms) -> ObjectOut<R> {
    let l = R::lit;
    let [x, y, z] = v.position.map(l);
    let clip = mat4_mul_vec4(&frame.view.view_proj, [x, y, z, l(1.0)]);
    (clip, (v.normal.map(l), v.color.map(l), [x, y, z], y + l(frame.view.eye_height)))
}

/// [`vs_reflect`] over any [`Real`].
pub fn vs_reflect_r<R: Real>(v: &ObjectVertex, frame: &FrameUniforms) -> ObjectOut<R> {
    let l = R::lit;
    let [x, y, z] = v.position.map(l);
    let eye = l(frame.view.eye_height);
    let mirrored = [x, -y - l(2.0) * eye, z];
    let clip =
        mat4_mul_vec4(&frame.view.view_proj, [mirrored[0], mirrored[1], mirrored[2], l(1.0)]);
    let normal = [l(v.normal[0]), -l(v.normal[1]), l(v.normal[2])];
    (clip, (normal, v.color.map(l), mirrored, y + eye))
}

/// [`vs_refract`] over any [`Real`].
pub fn vs_refract_r<R: Real>(v: &ObjectVertex, frame: &FrameUniforms) -> ObjectOut<R> {
    let l = R::lit;
    let [x, y, z] = v.position.map(l);
    let eye = l(frame.view.eye_height);
    let world_y = y + eye;
    let scaled = [x, world_y * l(frame.water.inv_eta) - eye, z];
    let clip = mat4_mul_vec4(&frame.view.view_proj, [scaled[0], scaled[1], scaled[2], l(1.0)]);
    (clip, (v.normal.map(l), v.color.map(l), scaled, world_y))
}

/// Which of the stage's two maps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObjectMap {
    /// `vs_reflect` / `fs_reflect`.
    Reflection,
    /// `vs_refract` / `fs_refract`.
    Refraction,
}

/// What one of the stage's maps reads besides its triangles, for a scalar `R`.
pub struct MapInputs<'a, R> {
    /// The frame's uniforms.
    pub frame: &'a FrameUniforms,
    /// The map's size.
    pub size: [u32; 2],
    /// The map's format.
    pub format: ocean_core::frame_format::FrameFormat,
    /// Its clear colour.
    pub clear: [f32; 4],
    /// The shadow map's size (binding 3).
    pub shadow_dims: [u32; 2],
    /// The shadow map's texel (x, y): the GPU's own, or for an envelope the interval its map
    /// may hold there.
    pub occluder: &'a dyn Fn(u32, u32) -> R,
    /// The displacement map (binding 1), read by shading `chiu`'s clip height.
    pub displacement: &'a Texture2D,
    /// The sea floor's relief (`ocean_core::terrain::relief_texels`), marched towards the
    /// sun under the water by each scalar type's [`ReliefMarch`].
    pub floor_map: &'a Texture2D,
    /// The device's precision: the rasteriser's snap.
    pub precision: crate::envelope::Precision,
}

/// A map's fragment shader over any [`Real`] after interpolation: whether it discards, and
/// the colour; `sample` is the displacement map's `textureSampleLevel`.
fn map_fragment<R: ReliefMarch>(
    map: ObjectMap,
    v: Varyings<R>,
    m: &MapInputs<'_, R>,
    sample: &dyn Fn([R; 2]) -> [R; 4],
) -> (R::Cond, [R; 4]) {
    let l = R::lit;
    let (frame, dims, occluder) = (m.frame, m.shadow_dims, m.occluder);
    let (normal, color, rel, world_y) = v;
    let clip = clip_height_r(rel, frame, sample);
    match map {
        ObjectMap::Reflection => {
            // The mirrored normal lit by the mirrored sun is the original normal lit by the sun.
            let n = [normal[0], -normal[1], normal[2]];
            let [r, g, b] = shade_r(frame, n, color, l(1.0));
            (world_y.lt(clip), [r, g, b, l(1.0)])
        }
        ObjectMap::Refraction => {
            let relief = |p: [R; 3]| R::relief_sun(p, frame, m.floor_map);
            let sun = |at: [R; 3], wy: R| sun_reaches_r(at, wy, frame, dims, occluder, &relief);
            (clip.lt(world_y), refract_colour_r(v, frame, &sun))
        }
    }
}

/// A piece's vertex in its original triangle: barycentrics, and their largest error.
type Barycentric = ([f64; 3], f64);

/// A pass's triangles on screen as the rasteriser's envelope sees them: each piece the
/// clipper may make, and the varyings of the triangle it came from.
struct Drawn {
    /// The pieces after the viewport transform.
    screen: Vec<[raster::ScreenIv; 3]>,
    /// Per piece: its triangle, and its vertices' barycentrics in it (with their error).
    owner: Vec<(usize, [Barycentric; 3])>,
    /// Per triangle, its vertices' varyings.
    verts: Vec<[Varyings<Iv>; 3]>,
    /// Per triangle, its vertices' clip positions (a piece's varyings are bounded from them).
    clips: Vec<[[Iv; 4]; 3]>,
}

impl Drawn {
    /// `triangles` through the vertex entry point `vs`, clipped at the near and far planes;
    /// `None` where the clipper's bounds cannot place a piece (the pass may be anything).
    fn new(
        triangles: &[[ObjectVertex; 3]],
        frame: &FrameUniforms,
        size: [u32; 2],
        vs: fn(&ObjectVertex, &FrameUniforms) -> ObjectOut<Iv>,
    ) -> Option<Self> {
        let mut d = Self {
            screen: Vec::with_capacity(triangles.len()),
            owner: Vec::with_capacity(triangles.len()),
            verts: Vec::with_capacity(triangles.len()),
            clips: Vec::with_capacity(triangles.len()),
        };
        for t in triangles {
            let v = t.each_ref().map(|v| vs(v, frame));
            // Past the near or far plane: the clipper's polygon, each part with its
            // vertices' barycentrics in the original.
            let clip = v.map(|(clip, _)| clip);
            for part in raster::clip_near_far(clip)? {
                d.screen.push(raster::piece_to_screen(&part, &clip, size[0], size[1])?);
                d.owner.push((d.verts.len(), part.map(|p| (p.bary, p.bary_err))));
            }
            d.verts.push(v.map(|(_, var)| var));
            d.clips.push(clip);
        }
        Some(d)
    }

    /// Per piece, its triangle's vertex ids where it is drawn whole (two vertices at the same
    /// position, bit for bit, have one id: the GPU transforms them alike, so an edge two
    /// triangles share leaves no gap), `None` for a piece the clipper cut (its edges are the
    /// clipper's own).
    fn whole_ids(&self, triangles: &[[ObjectVertex; 3]]) -> Vec<Option<[u32; 3]>> {
        let mut ids = std::collections::HashMap::new();
        let mut id = |p: [f32; 3]| {
            let next = ids.len() as u32;
            *ids.entry(p.map(f32::to_bits)).or_insert(next)
        };
        let vertex_ids: Vec<[u32; 3]> =
            triangles.iter().map(|t| t.each_ref().map(|v| id(v.position))).collect();
        let mut pieces = vec![0u32; triangles.len()];
        for (t, _) in &self.owner {
            pieces[*t] += 1;
        }
        self.owner
            .iter()
            .map(|(t, bary)| {
                let whole = pieces[*t] == 1
                    && bary.iter().enumerate().all(|(i, (b, err))| *err == 0.0 && b[i] == 1.0);
                whole.then_some(vertex_ids[*t])
            })
            .collect()
    }

    /// Piece `k`'s varyings at a sample, as the rasteriser's envelope interpolates them.
    fn varyings(&self, k: usize, interp: &raster::Interp) -> Varyings<Iv> {
        let (t, bary) = self.owner[k];
        let v = &self.verts[t];
        // A piece's vertices hold convex combinations of the original triangle's values.
        let at = |f: &dyn Fn(usize) -> Iv| -> [Iv; 3] {
            bary.map(|(b, err)| raster::part_value([f(0), f(1), f(2)], b, err))
        };
        // A clipper's piece: also from the original triangle's values over a small box around
        // the sample (its own vertices may slide along the cut edge by hundreds of pixels).
        let clip = &self.clips[t];
        let mix = |f: &dyn Fn(usize) -> Iv| {
            let piece = at(f);
            let original = interp.from_original(clip, [f(0), f(1), f(2)], piece);
            raster::narrowed(interp.varying(piece), original)
        };
        (
            std::array::from_fn(|c| mix(&|j| v[j].0[c])),
            std::array::from_fn(|c| mix(&|j| v[j].1[c])),
            std::array::from_fn(|c| mix(&|j| v[j].2[c])),
            mix(&|j| v[j].3),
        )
    }
}

/// The envelope of one of the stage's maps a conformant GPU draws of `triangles`
/// (reversed-Z `Greater`): per texel its colour interval and whether its coverage or discard
/// is ambiguous. Each fragment is shaded from its varyings' envelope at the sample, the
/// displacement map filtered by the filter's envelope, the relief's shadow march step by step
/// ([`ReliefMarch`]).
pub fn map_envelope(
    map: ObjectMap,
    triangles: &[[ObjectVertex; 3]],
    m: &MapInputs<'_, Iv>,
) -> (Vec<[Iv; 4]>, Vec<bool>) {
    let (frame, size, format, clear) = (m.frame, m.size, m.format, m.clear);
    let sample =
        |uv: [Iv; 2]| crate::envelope::filter::sample_level0(m.displacement, &WRAP_LINEAR, uv);
    let vs = match map {
        ObjectMap::Reflection => vs_reflect_r::<Iv>,
        ObjectMap::Refraction => vs_refract_r::<Iv>,
    };
    let Some(drawn) = Drawn::new(triangles, frame, size, vs) else {
        // A triangle the clipper's bounds cannot place: anything.
        let n = (size[0] as usize) * (size[1] as usize);
        return (vec![[Iv::FULL; 4]; n], vec![true; n]);
    };
    let shade = |k: usize, interp: &raster::Interp| {
        let var = drawn.varyings(k, interp);
        let (discard, color) = map_fragment(map, var, m, &sample);
        let kept = discard.decided().map(|d| !d);
        Shaded { color: color.map(|c| c.store(format)), kept }
    };
    let (ids, snap) = (drawn.whole_ids(triangles), m.precision.snap_px());
    raster::color_pass_greater(&drawn.screen, &ids, size[0], size[1], snap, clear, shade)
}

/// One of the stage's maps as one random conformant GPU draws it (`rules.scale` times the
/// rules), under the same conditions as [`map_envelope`].
pub fn map_jitter(
    map: ObjectMap,
    triangles: &[[ObjectVertex; 3]],
    m: &MapInputs<'_, f32>,
    rules: JitterRules,
) -> Vec<[f32; 4]> {
    let (frame, size, format, clear) = (m.frame, m.size, m.format, m.clear);
    let vs = match map {
        ObjectMap::Reflection => vs_reflect_r::<Jitter>,
        ObjectMap::Refraction => vs_refract_r::<Jitter>,
    };
    let (verts, clip) = jitter_vertices(triangles, frame, rules, vs);
    let occ = |x: u32, y: u32| Jitter((m.occluder)(x, y));
    let mj = MapInputs {
        frame,
        size,
        format,
        clear,
        shadow_dims: m.shadow_dims,
        occluder: &occ,
        displacement: m.displacement,
        floor_map: m.floor_map,
        precision: m.precision,
    };
    let sample = |uv: [Jitter; 2]| {
        crate::envelope::filter::sample_level0_jitter(m.displacement, &WRAP_LINEAR, uv)
    };
    let bits = m.precision.subpixel_bits;
    raster::jitter_pass_at(&clip, size[0], size[1], true, clear, rules, bits, |_, k, w, _| {
        let var = jitter_varyings(&verts[k], w);
        let (discard, color) = map_fragment(map, var, &mj, &sample);
        (!discard).then(|| color.map(|c| c.store(format).0))
    })
}

/// A vertex entry point over [`Jitter`]: one random GPU's vertex shader.
type JitterVertex = fn(&ObjectVertex, &FrameUniforms) -> ObjectOut<Jitter>;

/// A random GPU's triangles after the vertex shader: each vertex's clip position and
/// varyings, and the clip positions apart (what the rasteriser reads).
type JitteredTriangles = (Vec<[ObjectOut<f32>; 3]>, Vec<[[f32; 4]; 3]>);

/// `triangles` through `vs` with random roundings: each vertex's clip position and varyings,
/// and the clip positions apart. The roundings are drawn per vertex position, since a GPU
/// transforms equal positions alike (what keeps an edge two triangles share free of gaps).
fn jitter_vertices(
    triangles: &[[ObjectVertex; 3]],
    frame: &FrameUniforms,
    rules: JitterRules,
    vs: JitterVertex,
) -> JitteredTriangles {
    let verts: Vec<[ObjectOut<f32>; 3]> = triangles
        .iter()
        .map(|t| {
            t.each_ref().map(|v| {
                let seed = v
                    .position
                    .iter()
                    .fold(rules.seed, |h, c| ocean_core::rng::mix64(h ^ u64::from(c.to_bits())));
                Jitter::reseed(rules, seed);
                let (clip, (n, c, r, y)) = vs(v, frame);
                let f = |a: [Jitter; 3]| a.map(|x| x.0);
                (clip.map(|x| x.0), (f(n), f(c), f(r), y.0))
            })
        })
        .collect();
    let clip = verts.iter().map(|t| t.map(|v| v.0)).collect();
    (verts, clip)
}

/// A triangle's varyings at perspective-correct weights `w`, interpolated with random
/// roundings: Σ wₖ·vₖ in f32 operations.
fn jitter_varyings(t: &[ObjectOut<f32>; 3], w: [f64; 3]) -> Varyings<Jitter> {
    let mix = |f: &dyn Fn(usize) -> f32| -> Jitter {
        Jitter::sum(&[0, 1, 2].map(|j| Jitter(w[j] as f32) * Jitter(f(j))))
    };
    (
        std::array::from_fn(|c| mix(&|j| t[j].1.0[c])),
        std::array::from_fn(|c| mix(&|j| t[j].1.1[c])),
        std::array::from_fn(|c| mix(&|j| t[j].1.2[c])),
        mix(&|j| t[j].1.3),
    )
}

/// Whether an object's fragment may be what a pixel shows after the water pass: one may land
/// there (`objects`, the nearest depth any may have, [`depth_reach`]; −∞: none) and the
/// water's certain fragments (`water`, the depth they guarantee; −∞: none certain) do not lie
/// nearer.
pub fn may_show(objects: f64, water: f64) -> bool {
    objects > f64::NEG_INFINITY && objects >= water
}

/// Per pixel of a `width` × `height` view, the nearest depth (reversed Z: the largest z) that
/// any conformant GPU may give a fragment of the objects' `triangles` in the main view
/// (`vs_main`): −∞ where none may land. Each vertex's clip position is carried as an
/// interval ([`vs_main_r`]), clipped and rasterised by the rasteriser's envelope at the
/// device's snap (`snap` px), so coverage and depth are bounds, not estimates. +∞ everywhere
/// where a vertex cannot be bounded (w possibly ≤ 0 after the clipper).
///
/// The water pass draws after the objects with the `Greater` test: where its certain
/// fragment lies nearer than this bound, the objects cannot show, and the water's verdict
/// judges the pixel although an object's triangle covers it.
pub fn depth_reach(
    triangles: &[[ObjectVertex; 3]],
    frame: &FrameUniforms,
    width: u32,
    height: u32,
    snap: f64,
) -> Vec<f64> {
    let n = (width as usize) * (height as usize);
    let mut screen: Vec<[raster::ScreenIv; 3]> = Vec::with_capacity(triangles.len());
    for t in triangles {
        let clip = t.each_ref().map(|v| vs_main_r::<Iv>(v, frame).0);
        if raster::outside_a_side(clip) {
            continue;
        }
        let Some((parts, _)) = raster::clip_near_far_either(clip) else {
            return vec![f64::INFINITY; n];
        };
        for part in parts {
            let Some(s) = raster::piece_to_screen(&part, &clip, width, height) else {
                return vec![f64::INFINITY; n];
            };
            screen.push(s);
        }
    }
    let mut near = vec![f64::NEG_INFINITY; n];
    let bounded = raster::fragments_at(&screen, width, height, snap, |i, _, c, _| {
        if let raster::Cover::Possible(z) | raster::Cover::Certain(z) = c {
            near[i] = near[i].max(z.hi);
        }
    });
    if !bounded {
        return vec![f64::INFINITY; n];
    }
    near
}

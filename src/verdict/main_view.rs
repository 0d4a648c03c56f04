//! The HDR frame's verdicts: the main view (the water, the objects and the sea floor, the
//! spray's sprites over them) and its sky pixels, given the inputs the GPU itself read.

use anyhow::bail;
use ocean_core::plan::{FramePlan, Pass, ResourceId};
use ocean_core::scene::Scene;

use super::GpuSide;
use super::passes::shadow_occluder;

/// The water pass's envelope where the water shows: how many pixels, and the relative
/// half-width of their channels at p50 and p99 (`None`: no pixel).
pub(super) struct WaterWidths {
    pub(super) pixels: usize,
    pub(super) p50: Option<f64>,
    pub(super) p99: Option<f64>,
    /// Pixels judged by the objects' envelope: no water fragment can pass them.
    pub(super) objects: usize,
    /// The relative half-width of their channels at p50.
    pub(super) objects_p50: Option<f64>,
    /// Pixels where an object or the water may show: judged by the hull of both.
    pub(super) either: usize,
    /// Pixels left out because their colour's envelope is unbounded.
    pub(super) unbounded: usize,
    /// Judged pixels where a sprite of the spray may add light (`None`: the sprites are not
    /// carried, and where one may land is left out).
    pub(super) sprites: Option<usize>,
}

/// What the main view's depth buffer may hold after the water pass: the water's and the
/// objects' certain and farthest-reaching fragments.
struct MainDepths<'a> {
    water: &'a ocean_cpu::envelope::raster::MeshEnvelope,
    objects: Option<&'a ocean_cpu::envelope::raster::MeshEnvelope>,
    objects_reach: &'a [f64],
}

impl MainDepths<'_> {
    /// Per pixel, the interval the stored depth (reversed Z, cleared to 0) lies in: at least
    /// what a certain fragment guarantees, at most the largest depth any may have.
    fn bounds(&self) -> Vec<ocean_cpu::envelope::Iv> {
        let n = self.water.nearest.len();
        (0..n)
            .map(|i| {
                let objects_near = self.objects.map_or(f64::NEG_INFINITY, |o| o.nearest[i]);
                let lo = 0f64.max(self.water.nearest[i]).max(objects_near);
                let hi = 0f64.max(self.water.reach[i]).max(self.objects_reach[i]);
                if hi.is_finite() {
                    ocean_cpu::envelope::Iv::new(lo, hi.max(lo))
                } else {
                    ocean_cpu::envelope::Iv::FULL
                }
            })
            .collect()
    }
}

/// Adds the spray's sprites to the main view's envelope `env`, drawn from the pool the GPU
/// held (the spray probe's `before`, whose step uniforms are the frame's draw's: step k's
/// uniforms are the draw after k steps) over the depth the main view may have left: per
/// pixel, whether a sprite may add light there. `None` where the frame has no spray, no pool
/// was read back, or a sprite may lie past the near or far plane (then where a sprite may
/// land is left out).
fn sprites_over(
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
    uniforms: &ocean_core::frame::FrameUniforms,
    (w, h): (u32, u32),
    depths: &MainDepths<'_>,
    env: &mut [[ocean_cpu::envelope::Iv; 4]],
) -> Option<Vec<bool>> {
    let probe = gpu.spray.filter(|_| plan.runs(Pass::Spray))?;
    let before = env.to_vec();
    let drawn = ocean_cpu::shaders::spray::sprites_envelope(
        &probe.before,
        uniforms,
        &probe.params,
        [w, h],
        plan.frame_format,
        gpu.precision.0.snap_px(),
        env,
        &depths.bounds(),
    );
    drawn
        .then(|| env.iter().zip(&before).map(|(a, b)| (0..3).any(|c| a[c].hi != b[c].hi)).collect())
}

/// The HDR frame's water and object pixels against the water pass's envelope (ocean-cpu
/// `shaders::water::envelope`) composed with the objects' (`objects::main_view`), given the
/// GPU's own input maps and the sky pass's envelope behind both: the water's where no object
/// may show (none lands there, or the water is certainly drawn nearer: the objects'
/// envelope's `reach`, ocean-cpu `objects::depth_reach`), the objects' where no water
/// fragment can pass them, the hull of both where either may show (`main_view::compose`); the
/// spray's sprites added over it from the pool the GPU drew ([`sprites_over`]), or, where
/// that pool is not known, no sprite may land on a judged pixel.
/// `Err(why)` where it is not judged: a configuration the envelope does not carry, a pass
/// after the water that draws into the frame, a missing input.
#[allow(clippy::type_complexity, reason = "a verdict, its open share, cost and widths, or why not")]
pub(super) fn water_verdict(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
) -> anyhow::Result<
    Result<(ocean_verify::envelope::RegionVerdict, f64, std::time::Duration, WaterWidths), String>,
> {
    use ocean_cpu::envelope::Iv;
    use ocean_cpu::shaders::objects::main_view::Shows;
    use ocean_cpu::shaders::{sky, water};
    if !plan.runs(Pass::Water) {
        return Ok(Err("no water pass".into()));
    }
    let Some(((w, h), hdr)) = gpu.map(ResourceId::Hdr) else {
        return Ok(Err("the GPU's HDR frame is missing".into()));
    };
    let technique = plan.techniques.sky();
    let frame =
        ocean_core::graph::FrameInputs::new(scene, plan, &ocean_core::graph::FrameState::new(0.0))?;
    let u = &frame.uniforms;
    if let Some(why) = water::real::carried(u) {
        return Ok(Err(why.into()));
    }
    let (fw, fh, floor) = ocean_core::terrain::relief_texels(scene.terrain.as_ref());
    let owned = match water_inputs(scene, plan, gpu, (fw, fh, floor.clone())) {
        Ok(o) => o,
        Err(name) => return Ok(Err(format!("its input {name} is not in the frame"))),
    };
    let format = plan.frame_format;
    let pass = water::envelope::WaterPass {
        frame: u,
        sky: &frame.environment,
        lut: &frame.sky_lut,
        sky_technique: technique,
        textures: owned.textures(),
        vertices: &frame.mesh.vertices,
        indices: &frame.mesh.indices,
        size: [w, h],
        format,
        precision: gpu.precision.0,
        shading: plan.techniques.shading(),
        foam: plan.techniques.foam(),
        every: gpu.water_every.max(1),
    };
    let inputs = sky::SkyInputs {
        camera: &frame.camera_uniforms,
        sky: &frame.environment,
        lut: &frame.sky_lut,
    };
    let sky_env = sky::envelope(technique, inputs, (w, h), format);
    let background: Vec<[Iv; 4]> =
        sky_env.into_iter().map(|c| [c[0], c[1], c[2], Iv::point(1.0)]).collect();
    if hdr.len() != background.len() {
        bail!("hdr: {} texels, the frame {w}x{h}", hdr.len());
    }
    let started = std::time::Instant::now();
    let mesh = water::envelope::envelope(&pass, &background);
    let took = started.elapsed();
    let planned = plan.pass(Pass::Objects).filter(|_| plan.runs(Pass::Objects));
    let tris = planned
        .map(|p| ocean_core::frame::pass_triangles(scene, &frame.poses, p, frame.camera.eye));
    // The objects' colour over the sky, with the shadow map they read: the GPU's own where
    // the frame holds it, else its envelope.
    let (dims, shadow) = shadow_occluder(scene, plan, &frame, gpu);
    let occluder = |x: u32, y: u32| shadow[y as usize * dims[0] as usize + x as usize];
    let floor_map = ocean_cpu::sampler::Texture2D::new(fw, fh, floor);
    let inputs = ocean_cpu::shaders::objects::main_view::MainInputs {
        frame: u,
        size: [w, h],
        format,
        precision: gpu.precision.0,
        shadow_dims: dims,
        occluder: &occluder,
        floor_map: &floor_map,
    };
    let objects = tris.as_ref().and_then(|t| {
        ocean_cpu::shaders::objects::main_view::main_envelope(t, &inputs, &background)
    });
    // The nearest depth an object may have: the objects' envelope rasterised it already
    // (`tests/envelope_water.rs` holds it to `objects::depth_reach` bit for bit); that alone
    // where the envelope cannot be made (a vertex the clipper cannot place: +∞ everywhere).
    let objects_reach = match (&tris, &objects) {
        (_, Some(o)) => o.reach.clone(),
        (Some(t), None) => {
            ocean_cpu::shaders::objects::depth_reach(t, u, w, h, gpu.precision.0.snap_px())
        }
        (None, None) => vec![f64::NEG_INFINITY; mesh.color.len()],
    };
    let composed =
        ocean_cpu::shaders::objects::main_view::compose(&mesh, &objects_reach, objects.as_ref());
    let mut env: Vec<[Iv; 4]> =
        composed.iter().map(|c| c.map_or([Iv::FULL; 4], |(e, _)| e)).collect();
    // The spray's sprites over it, from the pool the GPU drew; without that pool, the pixels
    // where a sprite may land are left out.
    let depths =
        MainDepths { water: &mesh, objects: objects.as_ref(), objects_reach: &objects_reach };
    let sprites = sprites_over(plan, gpu, &frame.uniforms, (w, h), &depths, &mut env);
    let spray = match sprites {
        Some(_) => vec![false; env.len()],
        None => spray_reach(plan, &frame, (w, h), gpu),
    };
    // The pixels judged: those whose envelope is carried (an object may show only where its
    // colour is) where the sprites' colour is carried or none may land, on the quick
    // verdict's lattice.
    let every = gpu.water_every.max(1) as usize;
    let on =
        |i: usize| (i % w as usize).is_multiple_of(every) && (i / w as usize).is_multiple_of(every);
    // A pixel whose colour may be anything (a vertex the clipper's bounds cannot place, a
    // sub-pixel triangle whose varyings are unbounded) would be passed, not judged.
    let bounded = |e: &[Iv; 4]| e[..3].iter().any(|c| !c.full);
    let candidates =
        |i: usize| composed[i].map(|(_, s)| (env[i], s)).filter(|_| !spray[i] && on(i));
    let unbounded =
        (0..composed.len()).filter(|&i| candidates(i).is_some_and(|(e, _)| !bounded(&e)));
    let unbounded = unbounded.count();
    let shows: Vec<Option<Shows>> = (0..composed.len())
        .map(|i| candidates(i).filter(|(e, _)| bounded(e)).map(|(_, s)| s))
        .collect();
    let sprite_pixels =
        sprites.map(|lit| (0..lit.len()).filter(|&i| lit[i] && shows[i].is_some()).count());
    let region: Vec<Option<bool>> = shows.iter().map(|s| s.map(|_| true)).collect();
    let judged = shows.iter().flatten().count();
    if judged == 0 {
        let why = "no pixel has a bounded envelope (a vertex the clipper's bounds cannot \
                   place leaves the pass unbounded; without the pool the GPU drew, where a \
                   sprite may land is left out)";
        return Ok(Err(why.into()));
    }
    let count = |s: Shows| shows.iter().filter(|x| **x == Some(s)).count();
    let open_water = (0..shows.len()).filter(|&i| shows[i] == Some(Shows::Water) && mesh.open[i]);
    let open_share = (open_water.count() + count(Shows::Either)) as f64 / judged as f64;
    let f = ocean_verify::envelope::judge_region("hdr (water, objects)", &env, &region, hdr, w);
    let widths = WaterWidths {
        unbounded,
        sprites: sprite_pixels,
        ..WaterWidths::of(&env, &shows, &background)
    };
    Ok(Ok((f, open_share, took, widths)))
}

/// The maps the water pass read, as the GPU held them; `Err(name)` for one the frame lacks.
/// What a dump (`--dump-passes`) does not hold, the GPU bound all the same: a map the plan
/// does not write is a 1×1 zero map (the waves' maps under Gerstner waves), and the far
/// field's Fresnel filter is an upload, the plan's table bit for bit (`ocean compare` checks
/// that on the device).
fn water_inputs(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
    (fw, fh, floor): (u32, u32, Vec<[f32; 4]>),
) -> Result<ocean_cpu::shaders::water::envelope::OwnedTextures, &'static str> {
    let filter = plan.fresnel_filter(scene);
    const NONE: [[f32; 4]; 1] = [[0.0; 4]];
    let get = |id: ResourceId| {
        if let Some(((w, h), t)) = gpu.map(id) {
            return Some((w, h, t));
        }
        if let (ResourceId::FresnelFilter, Some(f)) = (id, &filter) {
            let (w, h) =
                (ocean_core::far_field::FILTER_RADII, ocean_core::far_field::FILTER_SIGMAS);
            return Some((w, h, &f.texels[..]));
        }
        let written = plan.resource(id).is_some_and(|r| r.written);
        (!written).then_some((1, 1, &NONE[..]))
    };
    let runs = |id: ResourceId| id.writer().is_some_and(|p| plan.runs(p));
    ocean_cpu::shaders::water::envelope::OwnedTextures::from_resources(
        get,
        plan.runs(Pass::WaveMips),
        runs,
        ocean_cpu::sampler::Texture2D::new(fw, fh, floor),
    )
}

impl WaterWidths {
    /// The widths of `env` where each pass shows (`shows`; the water's only where its
    /// envelope is not the sky's alone, `background`), with no pixel unbounded or lit by a
    /// sprite yet.
    fn of(
        env: &[[ocean_cpu::envelope::Iv; 4]],
        shows: &[Option<ocean_cpu::shaders::objects::main_view::Shows>],
        background: &[[ocean_cpu::envelope::Iv; 4]],
    ) -> Self {
        use ocean_cpu::shaders::objects::main_view::Shows;
        let count = |s: Shows| shows.iter().filter(|x| **x == Some(s)).count();
        let rel_of = |keep: &dyn Fn(usize) -> bool| {
            let mut rel: Vec<f64> = (0..env.len())
                .filter(|&i| keep(i))
                .flat_map(|i| {
                    env[i][..3].iter().filter_map(|c| c.rel_half_width()).collect::<Vec<_>>()
                })
                .collect();
            rel.sort_by(f64::total_cmp);
            rel
        };
        let rel = rel_of(&|i| {
            shows[i] == Some(Shows::Water) && (0..3).any(|c| env[i][c] != background[i][c])
        });
        let on_objects = rel_of(&|i| shows[i] == Some(Shows::Objects));
        let q =
            |rel: &[f64], p: f64| rel.get(((rel.len().max(1) - 1) as f64 * p) as usize).copied();
        WaterWidths {
            pixels: rel.len() / 3,
            p50: q(&rel, 0.5),
            p99: q(&rel, 0.99),
            objects: count(Shows::Objects),
            objects_p50: q(&on_objects, 0.5),
            either: count(Shows::Either),
            unbounded: 0,
            sprites: None,
        }
    }
}

/// The HDR frame's sky pixels against the sky pass's envelope: the pixels where the oracle's
/// final frame still holds its exact sky pass and no sprite may land, and so do their eight
/// neighbours (a pixel next
/// to geometry is ambiguous: the GPU's rasteriser may cover it within its sub-pixel
/// precision, and it is counted apart). `None` for a sky technique without an envelope yet, or
/// a frame without a sky pixel.
pub(super) fn sky_verdict(
    scene: &Scene,
    plan: &FramePlan,
    (w, h): (u32, u32),
    (hdr, oracle): (&[[f32; 4]], &[[f32; 4]]),
    gpu: &GpuSide<'_>,
) -> anyhow::Result<Option<ocean_verify::envelope::RegionVerdict>> {
    use ocean_cpu::shaders::sky;
    let technique = plan.techniques.sky();
    // The sky's uniforms and table as the frame hands them to both back ends.
    let frame =
        ocean_core::graph::FrameInputs::new(scene, plan, &ocean_core::graph::FrameState::new(0.0))?;
    let inputs = sky::SkyInputs {
        camera: &frame.camera_uniforms,
        sky: &frame.environment,
        lut: &frame.sky_lut,
    };
    let format = plan.frame_format;
    let env = sky::envelope(technique, inputs, (w, h), format);
    let exact = sky::exact(technique, inputs, (w, h), format);
    if hdr.len() != env.len() || oracle.len() != env.len() {
        bail!("hdr: {} texels, the frame {w}x{h}", hdr.len());
    }
    // A sprite may land anywhere the spray reaches, on a GPU whose particles took another
    // branch than the oracle's: those pixels are not the sky's to judge.
    let spray = spray_reach(plan, &frame, (w, h), gpu);
    let holds_sky: Vec<bool> = oracle
        .iter()
        .zip(&exact)
        .zip(&spray)
        .map(|((o, e), s)| !s && (0..3).all(|c| o[c].to_bits() == e[c].to_bits()))
        .collect();
    let (wi, hi) = (w as i64, h as i64);
    let region: Vec<Option<bool>> = (0..env.len())
        .map(|i| {
            if !holds_sky[i] {
                return None;
            }
            let (x, y) = ((i % w as usize) as i64, (i / w as usize) as i64);
            let inner = (-1..=1).all(|dy| {
                (-1..=1).all(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    !(0..wi).contains(&nx)
                        || !(0..hi).contains(&ny)
                        || holds_sky[(ny * wi + nx) as usize]
                })
            });
            Some(inner)
        })
        .collect();
    // A frame without a sky pixel (looking down at the sea) leaves the sky unjudged.
    if !region.contains(&Some(true)) {
        return Ok(None);
    }
    Ok(Some(ocean_verify::envelope::judge_region("hdr (sky pixels)", &env, &region, hdr, w)))
}

/// Per pixel of a `w` × `h` frame, whether a sprite of the frame's spray may land there on
/// any conformant GPU (ocean-cpu `spray::reach`); nowhere without a spray pass.
/// The step's water heights come from the GPU's own displacement map: the lowest texel
/// bounds them from below.
fn spray_reach(
    plan: &FramePlan,
    frame: &ocean_core::graph::FrameInputs<'_>,
    (w, h): (u32, u32),
    gpu: &GpuSide<'_>,
) -> Vec<bool> {
    if !plan.runs(Pass::Spray) {
        return vec![false; w as usize * h as usize];
    }
    let draw = ocean_core::spray::SprayFrame::new(frame.scene, plan, &frame.camera, 0, 0).draw;
    let lowest_water = if draw.waves == 0.0 {
        Some(0.0)
    } else {
        gpu.map(ResourceId::Displacement).map(|(_, t)| {
            t.iter().map(|t| f64::from(t[1]) * f64::from(draw.waves)).fold(f64::INFINITY, f64::min)
        })
    };
    let emitters = &plan.spray_emitters;
    ocean_cpu::shaders::spray::reach(emitters, &draw, lowest_water, &frame.uniforms, w, h)
}

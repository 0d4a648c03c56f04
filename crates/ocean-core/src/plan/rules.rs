//! The planner's rules: for each pass, whether a scene's frame runs it and why
//! ([`super::PlannedPass::reason`], what `ocean plan` prints). Every rule leaves out only a pass
//! whose contribution is exactly zero (the module doc of [`super`]).

use glam::DVec3;

use super::{
    FramePlan, OutputKind, Pass, PassObjects, PlannedPass, WavesKernel, bounds, floor_reason,
    footprint_inside_near_patch, object_name, outside_view, y_range,
};
use crate::camera::Camera;
use crate::objects::Object;
use crate::scene::Scene;
use crate::tables::TextureMapping;
use crate::technique::{Post, Surface, Techniques, Waves};

/// How a plan is built: the number of frames it is for, and whether the pruning rules apply.
#[derive(Clone, Copy, Debug)]
pub(super) struct Options {
    /// Frames the plan is for (a looping sea precomputes its cycle for more than one).
    pub(super) frames: u64,
    /// Whether the pruning rules apply ([`FramePlan::full`] turns them off).
    pub(super) prune: bool,
}

/// The reason of a pass that runs only because the plan is the full one.
const FULL: &str = "full plan: every pass the scene can use";

/// What the rules read: the scene, the options, and what several rules share (the objects
/// each object pass keeps and culls).
struct Rules<'a> {
    scene: &'a Scene,
    output: OutputKind,
    opt: Options,
    techniques: Techniques,
    waves_kernel: WavesKernel,
    objs: &'a [Object],
    above: Vec<usize>,
    below: Vec<usize>,
    in_view: Vec<usize>,
    culled_view: Vec<String>,
    mirrored: Vec<usize>,
    culled_mirror: Vec<String>,
    refracted: Vec<usize>,
    culled_refract: Vec<String>,
    sun_up: bool,
    waves_on: bool,
    looping: bool,
    far_hidden: Option<([f64; 4], [f64; 3])>,
    waves: Waves,
    gerstner: bool,
}

impl<'a> Rules<'a> {
    fn new(scene: &'a Scene, output: OutputKind, opt: Options) -> Self {
        let camera = Camera::from_scene(&scene.camera).ok();
        let objs = &scene.objects;
        let above: Vec<usize> = (0..objs.len()).filter(|&i| y_range(&objs[i]).1 > 0.0).collect();
        let below: Vec<usize> = (0..objs.len()).filter(|&i| y_range(&objs[i]).0 < 0.0).collect();
        // Per-pass culling: (kept, culled names).
        let cull = |list: &[usize], image: &dyn Fn(DVec3, DVec3) -> (DVec3, DVec3)| {
            let mut kept = Vec::new();
            let mut culled = Vec::new();
            for &i in list {
                let outside = |c: &Camera| {
                    bounds(&objs[i]).is_some_and(|(lo, hi)| {
                        let (lo, hi) = image(lo, hi);
                        outside_view(c, lo, hi)
                    })
                };
                match &camera {
                    Some(c) if opt.prune && outside(c) => culled.push(object_name(i, &objs[i])),
                    _ => kept.push(i),
                }
            }
            (kept, culled)
        };
        let all: Vec<usize> = (0..objs.len()).collect();
        let (in_view, culled_view) = cull(&all, &|lo, hi| (lo, hi));
        // The reflection map draws the mirror image y → −y.
        let (mirrored, culled_mirror) =
            cull(&above, &|lo, hi| (DVec3::new(lo.x, -hi.y, lo.z), DVec3::new(hi.x, -lo.y, hi.z)));
        // The refraction map draws the objects with y scaled by 1/η (vs_refract).
        let inv_eta = 1.0 / scene.water.ior;
        let (refracted, culled_refract) = cull(&below, &|lo, hi| {
            (DVec3::new(lo.x, lo.y * inv_eta, lo.z), DVec3::new(hi.x, hi.y * inv_eta, hi.z))
        });
        let techniques = scene.techniques();
        // Waves `gerstner` and `coastal` are summed per vertex in the water pass: no maps.
        let waves = techniques.waves();
        Self {
            scene,
            output,
            opt,
            techniques,
            waves_kernel: WavesKernel::for_ocean(&scene.ocean),
            objs,
            above,
            below,
            in_view,
            culled_view,
            mirrored,
            culled_mirror,
            refracted,
            culled_refract,
            sun_up: scene.sun.as_ref().is_some_and(|s| s.direction[1] > 0.0 && s.intensity > 0.0),
            waves_on: scene.ocean.wind_speed > 0.0 || !opt.prune,
            looping: scene.ocean.loop_period_s > 0.0,
            far_hidden: camera
                .as_ref()
                .filter(|_| opt.prune)
                .and_then(|c| footprint_inside_near_patch(scene, c)),
            waves,
            gerstner: waves.per_vertex(),
        }
    }

    /// Why the map passes are out under waves summed per vertex.
    fn gerstner_reason(&self) -> String {
        let scene = self.scene;
        match self.waves {
            Waves::Coastal => {
                return format!(
                    "waves = coastal: radial waves + {} correction wave(s) summed per vertex \
                     and per fragment in the water pass, no maps",
                    scene.coastal.corrections.len()
                );
            }
            Waves::Gerstner | Waves::Fft => {}
        }
        format!(
            "waves = gerstner: {} wave(s) summed per vertex and per fragment in the water \
             pass, no maps",
            scene.gerstner.wave_count()
        )
    }

    /// Whether `pass` runs, and why; an object pass's objects go into `objects`.
    fn rule(&self, pass: Pass, plan: &FramePlan, objects: &mut PassObjects) -> (bool, String) {
        match pass {
            Pass::Cycle | Pass::Waves | Pass::WaveMips if self.gerstner => {
                (false, self.gerstner_reason())
            }
            Pass::Cycle => cycle(self),
            Pass::Waves => waves_pass(self),
            Pass::WaveMips => wave_mips(self),
            Pass::FresnelTable => fresnel_table(self),
            Pass::ShadowMap => shadow_map(self, objects),
            Pass::ReflectionMap => reflection_map(self, plan, objects),
            Pass::RefractionMap => refraction_map(self, objects),
            Pass::Sky => sky(self),
            Pass::Objects => objects_pass(self, objects),
            Pass::FarPatch => far_patch(self),
            Pass::Water => water(self),
            Pass::Spray => spray(self, plan),
            Pass::Foam => foam(self),
            Pass::Bloom => bloom(self),
            Pass::Tonemap => tonemap(self),
        }
    }
}

/// "a, b, c".
fn list_of(names: &[String]) -> String {
    names.join(", ")
}

/// Pass `cycle`: a looping sea's maps, precomputed once for an animation.
fn cycle(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    let opt = r.opt;
    let waves_on = r.waves_on;
    let looping = r.looping;
    let full = FULL;
    match (looping, waves_on, opt.frames) {
        (false, _, _) => {
            (false, "loop_period_s = 0: the sea does not loop, nothing to cycle".into())
        }
        (true, false, _) => (false, "no wind: the sea is flat".into()),
        (true, true, 0..=1) => {
            (false, "a single frame: synthesised at its time, no cyclic precompute".into())
        }
        (true, true, n) if opt.prune => (
            true,
            format!(
                "{n} frames of a {} s loop: its maps precomputed once, played cyclically",
                scene.ocean.loop_period_s
            ),
        ),
        (true, true, _) => (true, full.into()),
    }
}

/// Pass `waves`: the FFT maps of waves `fft`.
fn waves_pass(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    let opt = r.opt;
    let waves_kernel = r.waves_kernel;
    let waves_on = r.waves_on;
    let looping = r.looping;
    let full = FULL;
    let how = match (looping && opt.frames > 1 && waves_on, waves_kernel) {
        (true, _) => "the cycle's maps",
        (false, WavesKernel::Shader) => "waves.wgsl (GPU FFT; its CPU mirror on the oracle)",
        (false, WavesKernel::Synthesis) if looping => {
            "ocean-core's FFT synthesis (a looping sea: as its cycle)"
        }
        (false, WavesKernel::Synthesis) => {
            "ocean-core's FFT synthesis (a side that is not a power of two)"
        }
    };
    if scene.ocean.wind_speed > 0.0 {
        (true, format!("wind {} m/s: {how}", scene.ocean.wind_speed))
    } else if !opt.prune {
        (true, full.into())
    } else {
        (false, "no wind: the sea is flat".to_string())
    }
}

/// Pass `wave_mips`: the slope maps' mip chains of far field `mip` and `variance`.
fn wave_mips(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    let techniques = r.techniques;
    let waves_on = r.waves_on;
    let far = techniques.far_field();
    if !far.mip_chains() {
        (false, "far_field = none: the slope maps are sampled at level 0".into())
    } else if !waves_on {
        (false, "no wind: the sea is flat, nothing to filter".into())
    } else {
        (
            true,
            format!(
                "far_field = {far}: mip chains of the slope maps with their \
                 second moments ({0}², {1}²), sampled at the footprint's LOD",
                scene.ocean.resolution, scene.ocean.bump_resolution
            ),
        )
    }
}

/// Pass `fresnel_table`: the Fresnel table the water looks F up in.
fn fresnel_table(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    (
        true,
        format!(
            "the water pass looks F up in it ({0}×{0}, {1} mapping)",
            scene.quality.fresnel_table_size,
            TextureMapping::Grazing.name()
        ),
    )
}

/// Pass `shadow_map`: the sun's shadow of the objects above the water.
fn shadow_map(r: &Rules<'_>, objects: &mut PassObjects) -> (bool, String) {
    let opt = r.opt;
    let sun_up = r.sun_up;
    let above = &r.above;
    let full = FULL;
    objects.shadow_map = above.clone();
    match (sun_up || !opt.prune, above.len()) {
        (false, _) => (false, "no sun above the horizon: no specular to shadow".into()),
        (true, 0) => (false, "no object above the water casts a shadow".into()),
        (true, n) if opt.prune => {
            (true, format!("{n} object(s) above the water under the sun (in view or not)"))
        }
        (true, _) => (true, full.into()),
    }
}

/// Pass `reflection_map`: the mirror images of the objects above the water.
fn reflection_map(r: &Rules<'_>, plan: &FramePlan, objects: &mut PassObjects) -> (bool, String) {
    let opt = r.opt;
    let above = &r.above;
    let mirrored = &r.mirrored;
    let culled_mirror = &r.culled_mirror;
    let full = FULL;
    objects.reflection_map = mirrored.clone();
    let size = plan.reflection_map_size;
    match (above.len(), mirrored.len()) {
        (0, _) if opt.prune => {
            (false, "no object above the water: the sky alone is reflected".into())
        }
        (_, 0) if opt.prune => (
            false,
            format!(
                "every mirror image is outside the view ({}): the sky alone is \
                 reflected",
                list_of(culled_mirror)
            ),
        ),
        (n, k) => (
            true,
            if !opt.prune {
                format!("{full} ({}×{})", size[0], size[1])
            } else if culled_mirror.is_empty() {
                format!("{n} object(s) above the water ({}×{})", size[0], size[1])
            } else {
                format!(
                    "{k} of {n} object(s) above the water ({}×{}); culled, mirror \
                     image outside the view: {}",
                    size[0],
                    size[1],
                    list_of(culled_mirror)
                )
            },
        ),
    }
}

/// Pass `refraction_map`: the objects under the water, as the water bends them.
fn refraction_map(r: &Rules<'_>, objects: &mut PassObjects) -> (bool, String) {
    let opt = r.opt;
    let below = &r.below;
    let refracted = &r.refracted;
    let culled_refract = &r.culled_refract;
    let full = FULL;
    objects.refraction_map = refracted.clone();
    match (below.len(), refracted.len()) {
        (0, _) if opt.prune => {
            (false, "nothing under the water: the water volume colour alone".into())
        }
        (_, 0) if opt.prune => (
            false,
            format!(
                "every refracted image is outside the view ({}): the water \
                 volume colour alone",
                list_of(culled_refract)
            ),
        ),
        (_, _) if !opt.prune => (true, full.into()),
        (n, k) if culled_refract.is_empty() => {
            debug_assert_eq!(n, k);
            (true, format!("{n} object(s) under the water"))
        }
        (n, k) => (
            true,
            format!(
                "{k} of {n} object(s) under the water; culled, refracted image \
                 outside the view: {}",
                list_of(culled_refract)
            ),
        ),
    }
}

/// Pass `sky`: the background.
fn sky(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    if scene.camera.position[1] < 0.0 {
        (false, "camera under the water: the water volume fills the background".into())
    } else {
        (true, "the background".into())
    }
}

/// Pass `objects`: the objects in the main view.
fn objects_pass(r: &Rules<'_>, objects: &mut PassObjects) -> (bool, String) {
    let opt = r.opt;
    let objs = r.objs;
    let in_view = &r.in_view;
    let culled_view = &r.culled_view;
    let full = FULL;
    objects.objects = in_view.clone();
    match (objs.len(), in_view.len()) {
        (0, _) if opt.prune => (false, "the scene has no objects".into()),
        (_, 0) if opt.prune => {
            (false, format!("every object is outside the view ({})", list_of(culled_view)))
        }
        (_, _) if !opt.prune => (true, full.into()),
        (n, _) if culled_view.is_empty() => (true, format!("{n} object(s)")),
        (n, k) => (
            true,
            format!("{k} of {n} object(s); culled, outside the view: {}", list_of(culled_view)),
        ),
    }
}

/// Pass `far_patch`: surface `hu_patches`' far polar patch, unless the view ends inside the near one.
fn far_patch(r: &Rules<'_>) -> (bool, String) {
    let opt = r.opt;
    let techniques = r.techniques;
    let far_hidden = r.far_hidden;
    let full = FULL;
    if !techniques.surface().has_far_patch() {
        return (
            false,
            format!(
                "surface {} has no far patch: its grid reaches the horizon",
                techniques.surface()
            ),
        );
    }
    match far_hidden {
        Some((b, sq)) => (
            false,
            format!(
                "the view meets the sea in x ∈ [{:.1}, {:.1}], z ∈ [{:.1}, {:.1}] m, \
                 inside the near patch ({:.0} m square about ({:.1}, {:.1})): the far \
                 patch would be clipped whole",
                b[0],
                b[2],
                b[1],
                b[3],
                2.0 * sq[2],
                sq[0],
                sq[1]
            ),
        ),
        None if opt.prune => (true, "the view reaches beyond the near patch".into()),
        None => (true, full.into()),
    }
}

/// Pass `water`: the sea surface, on the surface technique's mesh.
fn water(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    let techniques = r.techniques;
    let shading = techniques.shading();
    let (cols, rows) = crate::geometry::ProjectedGridBlock::quads(
        scene.camera.width,
        scene.camera.height,
        scene.quality.projected_grid_cell_px,
    );
    let on = match techniques.surface() {
        // Both screen-space grids: ⌈w/cell⌉ × ⌈h/cell⌉ quads, one vertex-index draw.
        Surface::ShoreGrid => format!(
            ", on the shore grid of {cols}×{rows} quads ahead of the eye (rows of equal screen \
             height, seed 004)"
        ),
        Surface::ProjectedGrid => {
            format!(", on a projected grid of {cols}×{rows} quads from the vertex index")
        }
        Surface::Clipmap => {
            let q = &scene.quality;
            let levels = crate::geometry::Clipmap::levels_for(
                scene.camera.position[1],
                q.clipmap_cell_m,
                q.clipmap_cells,
            );
            format!(
                ", on a clipmap of {levels} levels of {n}×{n} quads ({} m to {} m) from the \
                 vertex index",
                q.clipmap_cell_m,
                q.clipmap_cell_m * (1u64 << (levels - 1)) as f64,
                n = q.clipmap_cells,
            )
        }
        Surface::HuPatches => String::new(),
    };
    (true, format!("the sea surface, shading {shading}{on}"))
}

/// Pass `spray`: the particles of spray `particles`.
fn spray(r: &Rules<'_>, plan: &FramePlan) -> (bool, String) {
    let scene = r.scene;
    let opt = r.opt;
    let techniques = r.techniques;
    let t = techniques.spray();
    if !t.particles() {
        (false, format!("spray = {t}"))
    } else {
        let n = plan.spray_emitters.len();
        if n == 0 && opt.prune {
            (
                false,
                "no object surface lies between the waves' lower and upper \
                 bounds: nothing emits spray"
                    .into(),
            )
        } else {
            (
                true,
                format!(
                    "{} particles from {n} emitter(s) on the objects in the \
                     waves' band, one {:.4} s step a frame ({} before the first), \
                     drawn as additive sprites",
                    scene.spray.particles, scene.spray.step_s, scene.spray.warmup_steps
                ),
            )
        }
    }
}

/// Pass `foam`: the field foam `accumulated` keeps from frame to frame.
fn foam(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    let techniques = r.techniques;
    let waves = r.waves;
    let t = techniques.foam();
    if !t.keeps_a_field() {
        (false, format!("foam = {t}: the water pass draws it, no state"))
    } else {
        let g = crate::foam::FieldGrid::of(scene, waves);
        let on = if g.windowed {
            format!("a {0}×{0} lattice of {1} m around the camera", g.size, g.cell_m)
        } else {
            format!("the displacement map's {0}×{0} grid", g.size)
        };
        (
            true,
            format!(
                "foam = accumulated: grows where J < {}, decays over {} s, on {on}; \
                 one {:.4} s step a frame ({} before the first)",
                scene.foam.threshold,
                scene.foam.decay_s,
                scene.foam.step_s,
                scene.foam.warmup_steps
            ),
        )
    }
}

/// Pass `bloom`: post `bloom`'s bright pass and blur pyramid.
fn bloom(r: &Rules<'_>) -> (bool, String) {
    let scene = r.scene;
    let output = r.output;
    let opt = r.opt;
    let techniques = r.techniques;
    let post = &scene.post;
    let [w, h] = [scene.camera.width, scene.camera.height];
    let levels = crate::bloom::level_count(w, h, post.bloom_levels);
    let base = crate::bloom::base_size(w, h);
    match (techniques.post(), output) {
        (Post::Bloom, OutputKind::Hdr) => {
            (false, "EXR output keeps linear HDR (the tonemap composites the bloom)".into())
        }
        (Post::Bloom, OutputKind::Ldr) if post.bloom_strength > 0.0 || !opt.prune => (
            true,
            format!(
                "post = bloom: light above {} (exposed) blurred over {levels} \
                 level(s) from {}×{}, added × {} before the tonemap",
                post.bloom_threshold, base[0], base[1], post.bloom_strength
            ),
        ),
        (Post::Bloom, OutputKind::Ldr) => {
            (false, "bloom_strength = 0: the bloom adds nothing".into())
        }
        (t @ Post::Tonemap, _) => (false, format!("post = {t}")),
    }
}

/// Pass `tonemap`: the 8-bit picture.
fn tonemap(r: &Rules<'_>) -> (bool, String) {
    let output = r.output;
    match output {
        OutputKind::Ldr => (true, "8-bit sRGB output".into()),
        OutputKind::Hdr => (false, "EXR output keeps linear HDR".into()),
    }
}

impl FramePlan {
    /// The plan of `scene` for `output` under `opt`: the rules of this module, pass by pass.
    pub(super) fn build(scene: &Scene, output: OutputKind, opt: Options) -> Self {
        let rules = Rules::new(scene, output, opt);
        let (techniques, waves) = (rules.techniques, rules.waves);
        let waves_kernel = rules.waves_kernel;
        let mut plan = FramePlan {
            system: techniques.system,
            techniques,
            waves_kernel,
            resources: Vec::new(),
            passes: Vec::new(),
            skipped: Vec::new(),
            frame_format: scene.frame_format(),
            fresnel_table_size: scene.quality.fresnel_table_size,
            fresnel_mapping: TextureMapping::Grazing,
            reflection_map_size: [scene.camera.width, scene.camera.height].map(|side| {
                ((f64::from(side) * scene.quality.reflection_map_scale).round() as u32).max(1)
            }),
            wave_bound_m: match waves {
                Waves::Coastal => {
                    // Vertical only; a scene whose dispersion fails validation has no sea.
                    let v = crate::scene::coastal_sea(scene, scene.ocean.time_s)
                        .map_or(0.0, |s| s.bound_m());
                    [v, 0.0]
                }
                Waves::Gerstner => {
                    let (v, h) = scene.gerstner.bounds();
                    [v, h]
                }
                Waves::Fft
                    if techniques.surface().needs_wave_bound()
                        || techniques.spray().particles() =>
                {
                    // A validated scene's spectrum exists; without one the sea is flat.
                    let hs =
                        scene.ocean.wave_spectrum().map_or(0.0, |s| s.significant_wave_height());
                    let a = crate::geometry::ProjectedGridBlock::BOUND_OVER_HS * hs;
                    [a, a * scene.ocean.choppiness]
                }
                Waves::Fft => [0.0; 2],
            },
            spray_emitters: std::sync::Arc::default(),
        };
        if techniques.spray().particles() {
            plan.spray_emitters = std::sync::Arc::new(crate::spray::emitters(
                &scene.objects,
                scene.ocean.patch_size_m,
                plan.wave_bound_m[0],
            ));
        }
        let mut objects = PassObjects::default();
        for pass in Pass::ALL {
            let (run, reason) = rules.rule(pass, &plan, &mut objects);
            // The sea floor: in the main view, in the refraction map where it lies under the
            // water and in the reflection map where it rises above it (never culled).
            let terrain = scene.terrain.as_ref().is_some_and(|t| {
                let (lo, hi) = t.y_range();
                match pass {
                    Pass::Objects => true,
                    Pass::RefractionMap => lo < 0.0,
                    Pass::ReflectionMap => hi > 0.0,
                    _ => false,
                }
            });
            let (run, reason) = match (terrain, run) {
                (false, _) => (run, reason),
                (true, false) => (true, floor_reason(scene)),
                (true, true) => (true, format!("{reason}; and {}", floor_reason(scene))),
            };
            let planned = PlannedPass {
                name: pass,
                reason,
                stage: pass.stage(),
                technique: pass.stage().map(|s| techniques.of(s).name),
                shader: pass.shader(),
                reads: pass.reads(),
                writes: pass.writes(),
                objects: objects.of(pass).to_vec(),
                terrain,
            };
            if run { plan.passes.push(planned) } else { plan.skipped.push(planned) }
        }
        plan.resources = plan.size_resources(scene);
        plan
    }
}

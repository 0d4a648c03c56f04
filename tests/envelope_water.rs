//! The water pass's envelope (ocean-cpu `shaders::water::envelope`) and the main view's after
//! it, objects included (`shaders::objects::main_view`): the oracle's HDR frame and random
//! conformant GPUs stay inside on every reference scene the envelope carries, and GPUs twice
//! as loose as the rules leave it.

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[path = "support/reference_scenes.rs"]
mod reference_scenes;

use ocean_core::plan::{FramePlan, OutputKind, Pass, ResourceId};
use ocean_cpu::envelope::{Iv, Jitter, JitterRules};
use ocean_cpu::shaders::water::envelope as we;

/// The device the main view is drawn on: lavapipe (the water's [`Oracle::pass`] precision).
const DEVICE: ocean_cpu::envelope::Precision = ocean_cpu::envelope::Precision::LAVAPIPE;

/// A scene's oracle frame and what its water pass reads.
struct Oracle<'s> {
    frame: ocean_core::graph::FrameInputs<'s>,
    buffers: ocean_cpu::frame::FrameBuffers,
    owned: we::OwnedTextures,
}

impl<'s> Oracle<'s> {
    /// The oracle's frame of `scene` (its first, at t = the scene's time).
    fn new(scene: &'s ocean_core::scene::Scene, plan: &'s FramePlan) -> Self {
        let mut state = ocean_core::graph::FrameState::new(0.0);
        let frame = ocean_core::graph::FrameInputs::new(scene, plan, &state).unwrap();
        let buffers = ocean_cpu::frame::render_frame(
            &frame,
            ocean_cpu::frame::Environment::Planned,
            &mut state,
            &mut |_| {},
        )
        .unwrap();
        let owned = we::OwnedTextures::from_resources(
            |id| buffers.map(id),
            plan.runs(Pass::WaveMips),
            |id| buffers.map(id).is_some(),
            {
                let (fw, fh, t) = ocean_core::terrain::relief_texels(scene.terrain.as_ref());
                ocean_cpu::sampler::Texture2D::new(fw, fh, t)
            },
        )
        .unwrap();
        Self { frame, buffers, owned }
    }

    /// The water pass at `(w, h)` on lavapipe's precision, reading the oracle's maps.
    fn pass(&self, plan: &FramePlan, (w, h): (u32, u32)) -> we::WaterPass<'_> {
        let frame = &self.frame;
        we::WaterPass {
            frame: &frame.uniforms,
            sky: &frame.environment,
            lut: &frame.sky_lut,
            sky_technique: plan.techniques.sky(),
            textures: self.owned.textures(),
            vertices: &frame.mesh.vertices,
            indices: &frame.mesh.indices,
            size: [w, h],
            format: plan.frame_format,
            precision: ocean_cpu::envelope::Precision::LAVAPIPE,
            shading: plan.techniques.shading(),
            foam: plan.techniques.foam(),
            every: 1,
        }
    }

    fn sky_inputs(&self) -> ocean_cpu::shaders::sky::SkyInputs<'_> {
        ocean_cpu::shaders::sky::SkyInputs {
            camera: &self.frame.camera_uniforms,
            sky: &self.frame.environment,
            lut: &self.frame.sky_lut,
        }
    }
}

/// The sky pass's envelope, alpha 1: what the main view holds before the objects and water.
fn sky_envelope(o: &Oracle<'_>, plan: &FramePlan, size: (u32, u32)) -> Vec<[Iv; 4]> {
    let (tech, format) = (plan.techniques.sky(), plan.frame_format);
    ocean_cpu::shaders::sky::envelope(tech, o.sky_inputs(), size, format)
        .into_iter()
        .map(|c| [c[0], c[1], c[2], Iv::point(1.0)])
        .collect()
}

/// A random conformant GPU's sky pass, alpha 1.
fn sky_jitter(
    o: &Oracle<'_>,
    plan: &FramePlan,
    size: (u32, u32),
    rules: JitterRules,
) -> Vec<[f32; 4]> {
    let (tech, format) = (plan.techniques.sky(), plan.frame_format);
    ocean_cpu::shaders::sky::jitter(tech, o.sky_inputs(), size, format, rules)
        .into_iter()
        .map(|c| [c[0], c[1], c[2], 1.0])
        .collect()
}

/// The water pass's configurations the envelope carries, among the reference scenes at
/// `size`: (name, scene, plan).
fn water_scenes(size: (u32, u32)) -> Vec<(String, ocean_core::scene::Scene, FramePlan)> {
    let mut out = Vec::new();
    for (name, mut scene) in reference_scenes::reference_scenes() {
        (scene.camera.width, scene.camera.height) = size;
        let plan = FramePlan::new(&scene, OutputKind::Ldr);
        let state = ocean_core::graph::FrameState::new(0.0);
        let frame = ocean_core::graph::FrameInputs::new(&scene, &plan, &state).unwrap();
        if plan.runs(Pass::Spray)
            || ocean_cpu::shaders::water::real::carried(&frame.uniforms).is_some()
        {
            continue;
        }
        out.push((name, scene, plan));
    }
    out
}

/// The water pass: its mirror over `Real` at f32 is the exact mirror bit for bit (every
/// vertex, and fragments at the vertices and between them); the oracle's HDR frame and 8
/// random conformant GPUs' main views (sky, objects, water, each GPU's own) stay inside the
/// envelope of the water composed with the objects (`main_view::compose`) on every reference
/// scene it carries; a GPU twice as loose as the rules leaves it, and so do the objects'
/// pixels 2 % too bright.
/// Random conformant GPUs draw the objects of the main view (`vs_main`) no nearer than
/// `objects::depth_reach` bounds them (`near`), which the water verdict trusts where the
/// water is certainly nearer. Returns how many of their depths a bound 1 % nearer would
/// leave (the caller's negative control: the bound is the depth, not a blanket; a scene of
/// small triangles may have none, whose depth planes' f32 allowance is large).
fn object_depths_within(
    tris: &[[ocean_core::frame::ObjectVertex; 3]],
    u: &ocean_core::frame::FrameUniforms,
    (w, h): (u32, u32),
    near: &[f64],
    name: &str,
) -> usize {
    use ocean_cpu::shaders::objects;
    let mut tighter = 0;
    for seed in 0..4 {
        let rules = JitterRules { seed, scale: 1.0 };
        let clip: Vec<[[f32; 4]; 3]> = tris
            .iter()
            .enumerate()
            .map(|(k, t)| {
                Jitter::reseed(rules, (k as u64) << 32 | 0xffff_ffff);
                t.each_ref().map(|v| objects::vs_main_r::<Jitter>(v, u).0.map(|x| x.0))
            })
            .collect();
        let depth = ocean_cpu::envelope::raster::jitter_pass_at(
            &clip,
            w,
            h,
            true,
            [0.0; 4],
            rules,
            DEVICE.subpixel_bits,
            |_, _, _, z| Some([z, 0.0, 0.0, 0.0]),
        );
        for (i, d) in depth.iter().enumerate().filter(|(_, d)| d[0] > 0.0) {
            let z = f64::from(d[0]);
            assert!(
                z <= near[i],
                "{name} seed {seed}: an object's depth {z} at {i}, bound {}",
                near[i]
            );
            tighter += usize::from(z > near[i] - 1e-2 * near[i].abs());
        }
    }
    tighter
}

#[test]
fn random_conformant_gpus_stay_inside_the_water_envelope() {
    use ocean_cpu::shaders::objects::{self, main_view};
    use ocean_cpu::shaders::{sky, water};
    let (w, h) = (160u32, 90u32);
    let scenes = water_scenes((w, h));
    let (mut runs, mut loose, mut judged, mut open, mut water_px) = (0, 0, 0usize, 0usize, 0usize);
    let (mut objects_tight, mut objects_brighter, mut object_px, mut either_px) = (0, 0, 0, 0);
    let mut reach_compared = 0;
    let mut rel = Vec::new();
    let mut names = Vec::new();
    let mut unjudged: Vec<String> = Vec::new();
    for (name, scene, plan) in &scenes {
        let oracle = Oracle::new(scene, plan);
        let (frame, o, u) = (&oracle.frame, &oracle.buffers, oracle.frame.uniforms);
        let (tech, format) = (plan.techniques.sky(), plan.frame_format);
        let pass = oracle.pass(plan, (w, h));
        let owned = &oracle.owned;
        // The generic mirror at f32 against the exact one.
        let t = owned.textures();
        let radiance = sky::environment_radiance(tech);
        let (env_u, lut) = (&frame.environment, &*frame.sky_lut);
        let sky_fn = move |d: [f32; 3]| radiance(env_u, lut, d);
        let bindings = water::Bindings {
            frame: &u,
            displacement: t.displacement,
            displacement_slopes: t.displacement_slopes,
            bump: t.bump,
            fresnel_above: t.fresnel_above,
            fresnel_below: t.fresnel_below,
            reflection_map: t.reflection_map,
            refraction_map: t.refraction_map,
            shadow_map: t.shadow_map,
            fresnel_filter: t.fresnel_filter,
            floor_map: t.floor_map,
            foam_field: t.foam_field,
            sky_radiance: &sky_fn,
            shade_above: ocean_cpu::shaders::shading::shade_above(plan.techniques.shading()),
            foam_coverage: ocean_cpu::shaders::foam::foam_coverage(plan.techniques.foam()),
        };
        let grid = u.grid.vertex_count() > 0;
        let clipmap = u.clip.vertex_count() as usize;
        let count = if clipmap > 0 {
            clipmap
        } else if grid {
            (u.grid.cols as usize + 1) * (u.grid.rows as usize + 1)
        } else {
            frame.mesh.vertices.len()
        };
        let mut checked = 0;
        for id in (0..count).step_by((count / 3000).max(1)) {
            // A clipmap's vertex index k names its lattice point's id.
            let point = if clipmap > 0 {
                water::real::clipmap::point_id(id as u32, &u) as usize
            } else {
                id
            };
            let (clip, v) = we::exact_vertex(&pass, point);
            let exact = if clipmap > 0 {
                water::vs_clipmap(id as u32, &bindings)
            } else if grid {
                // Lattice point (i, j): corner 0 of quad (i, j), or the last row/column's.
                let cols = u.grid.cols as u32;
                let (i, j) = (id as u32 % (cols + 1), id as u32 / (cols + 1));
                let (qi, di) = if i == cols { (i - 1, 1) } else { (i, 0) };
                let (qj, dj) = if j == u.grid.rows as u32 { (j - 1, 1) } else { (j, 0) };
                let corner = [[0, 5], [1, 2]][di][dj];
                water::vs_projected_grid(6 * (qj * cols + qi) + corner, &bindings)
            } else {
                water::vs_main(&frame.mesh.vertices[id], &bindings)
            };
            assert_eq!(
                clip.map(f32::to_bits),
                <[f32; 4]>::from(exact.clip).map(f32::to_bits),
                "{name} {id}"
            );
            assert_eq!(v.map(f32::to_bits), exact.varyings().map(f32::to_bits), "{name} {id}");
            for frag in [[10.5, 20.5], [80.5, 60.5]] {
                let e = we::envelope_fragment(&pass, frag, &v.map(Iv::point));
                for seed in 0..8 {
                    let j = we::jitter_fragment(
                        &pass,
                        frag,
                        &v,
                        JitterRules { seed, scale: 1.0 },
                        id as u64,
                    );
                    assert!(
                        (0..4).all(|c| e[c].contains(j[c])),
                        "{name} vertex {id} seed {seed}: {j:?} not in {e:?}"
                    );
                }
                let a = we::exact_fragment(&pass, frag, &v);
                let b = water::fs_main(
                    &water::VertexOut::from_fragment([frag[0], frag[1], 0.5, 1.0], &v),
                    &bindings,
                );
                assert_eq!(
                    a.map(f32::to_bits),
                    b.map(f32::to_bits),
                    "{name} vertex {id} at {frag:?}"
                );
                checked += 1;
            }
        }
        assert!(checked > 100, "{name}: {checked} fragments compared");
        // The background: the sky pass's envelope, and a random GPU's sky.
        let bg_env = sky_envelope(&oracle, plan, (w, h));
        let started = std::time::Instant::now();
        let mesh = we::envelope(&pass, &bg_env);
        let took = started.elapsed();
        let (env, amb) = (&mesh.color, &mesh.open);
        let objects = plan
            .pass(Pass::Objects)
            .filter(|_| plan.runs(Pass::Objects))
            .map(|p| ocean_core::frame::pass_triangles(scene, &frame.poses, p, frame.camera.eye));
        // The nearest depth an object may have. Every random GPU's objects stay within it.
        let near = objects.as_ref().map_or(vec![f64::NEG_INFINITY; env.len()], |t| {
            objects::depth_reach(t, &u, w, h, DEVICE.snap_px())
        });
        if let Some(t) = &objects {
            objects_tight += object_depths_within(t, &u, (w, h), &near, name);
        }
        // The objects' colour over the sky, reading the oracle's shadow map.
        let (sw, sh, shadow) = o.map(ResourceId::ShadowMap).unwrap_or((1, 1, &[[1.0; 4]]));
        let occ = |x: u32, y: u32| shadow[y as usize * sw as usize + x as usize][0];
        let occ_iv = |x: u32, y: u32| Iv::point(occ(x, y));
        let floor_map = owned.textures().floor_map;
        let main_iv = main_view::MainInputs {
            frame: &u,
            size: [w, h],
            format,
            precision: DEVICE,
            shadow_dims: [sw, sh],
            occluder: &occ_iv,
            floor_map,
        };
        let main_f = main_view::MainInputs {
            frame: &u,
            size: [w, h],
            format,
            precision: DEVICE,
            shadow_dims: [sw, sh],
            occluder: &occ,
            floor_map,
        };
        let object_env =
            objects.as_ref().and_then(|t| main_view::main_envelope(t, &main_iv, &bg_env));
        // The verdict reads the objects' reach from their envelope: the same bound as
        // `depth_reach`'s own rasterisation, bit for bit.
        if let Some(o) = &object_env {
            let differ = o.reach.iter().zip(&near).filter(|(a, b)| a.to_bits() != b.to_bits());
            assert_eq!(differ.count(), 0, "{name}: the envelope's reach is not depth_reach's");
            reach_compared += 1;
        }
        let composed = main_view::compose(&mesh, &near, object_env.as_ref());
        let shows: Vec<Option<main_view::Shows>> =
            composed.iter().map(|c| c.map(|(_, s)| s)).collect();
        let outside = |g: &[[f32; 4]]| -> usize {
            composed
                .iter()
                .zip(g)
                .filter_map(|(c, g)| {
                    c.map(|(e, _)| (0..4).filter(|&c| !e[c].contains(g[c])).count())
                })
                .sum()
        };
        // What a random GPU leaves in the main view: its objects over its sky, then its water
        // where the water's stored depth is greater than the objects'.
        let main_view_of = |rules: JitterRules,
                            bg: &[[f32; 4]]|
         -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
            let (wc, wd) = we::jitter_with_depth(&pass, bg, rules);
            let (oc, od) = match &objects {
                Some(t) => main_view::main_jitter(t, &main_f, bg, rules),
                None => (bg.to_vec(), vec![0.0; bg.len()]),
            };
            let shown = (0..wc.len()).map(|i| if wd[i] > od[i] { wc[i] } else { oc[i] }).collect();
            (shown, wc)
        };
        let (_, _, hdr) = o.map(ResourceId::Hdr).unwrap();
        assert_eq!(outside(hdr), 0, "{name}: the oracle's HDR frame");
        // The negative control of the objects' colour: 2 % more light on their pixels leaves.
        let brighter: Vec<[f32; 4]> = hdr
            .iter()
            .zip(&shows)
            .map(|(c, s)| match s {
                Some(main_view::Shows::Objects) => [c[0] * 1.02, c[1] * 1.02, c[2] * 1.02, c[3]],
                _ => *c,
            })
            .collect();
        objects_brighter += outside(&brighter);
        // The spread of the random GPUs' water per texel, against the envelope's width there.
        let mut spread = vec![[(f32::INFINITY, f32::NEG_INFINITY); 3]; env.len()];
        for seed in 0..8 {
            let rules = JitterRules { seed, scale: 1.0 };
            let bg = sky_jitter(&oracle, plan, (w, h), rules);
            let (shown, j) = main_view_of(rules, &bg);
            assert_eq!(outside(&shown), 0, "{name} seed {seed}");
            for (s, g) in spread.iter_mut().zip(&j) {
                for c in 0..3 {
                    s[c] = (s[c].0.min(g[c]), s[c].1.max(g[c]));
                }
            }
            runs += 1;
        }
        let rules = JitterRules { seed: 99, scale: 2.0 };
        let bg = sky_jitter(&oracle, plan, (w, h), rules);
        loose += outside(&main_view_of(rules, &bg).0);
        let count = |k: main_view::Shows| shows.iter().filter(|s| **s == Some(k)).count();
        object_px += count(main_view::Shows::Objects);
        either_px += count(main_view::Shows::Either);
        let reach: Vec<bool> = shows.iter().map(|s| *s != Some(main_view::Shows::Water)).collect();
        let water: Vec<usize> = (0..env.len())
            .filter(|&i| {
                !reach[i]
                    && (0..3)
                        .any(|c| env[i][c].lo != bg_env[i][c].lo || env[i][c].hi != bg_env[i][c].hi)
            })
            .collect();
        water_px += water.len();
        if water.is_empty() {
            // `coastal_boat`'s, before the projected grid's weights were made ≥ 0 on any GPU:
            // its horizon row could fall behind the eye, and the pass was anything.
            unjudged.push(name.clone());
        }
        judged += shows.iter().flatten().count();
        open += water.iter().filter(|&&i| amb[i]).count();
        let mut ratio: Vec<f64> = water
            .iter()
            .flat_map(|&i| (0..3).map(move |c| (i, c)))
            .filter(|&(i, c)| !env[i][c].full && spread[i][c].1 > spread[i][c].0)
            .map(|(i, c)| {
                (env[i][c].hi - env[i][c].lo) / f64::from(spread[i][c].1 - spread[i][c].0)
            })
            .collect();
        ratio.sort_by(f64::total_cmp);
        let looseness = ratio.get(ratio.len() / 2).copied().unwrap_or(f64::NAN);
        let mut r: Vec<f64> = water
            .iter()
            .flat_map(|&i| env[i][..3].iter().filter_map(|c| c.rel_half_width()))
            .collect();
        r.sort_by(f64::total_cmp);
        let q =
            |p: f64| r.get(((r.len().max(1) - 1) as f64 * p) as usize).copied().unwrap_or(f64::NAN);
        println!(
            "{name}: {} water pixels, envelope {took:.2?}, rel half-width p50 {:.1e} p90 {:.1e} \
             p99 {:.1e}, {} channels unbounded; envelope width / 8 GPUs' spread p50 {looseness:.0}",
            water.len(),
            q(0.5),
            q(0.9),
            q(0.99),
            r.iter().filter(|x| x.is_infinite()).count()
        );
        rel.extend(r);
        names.push(name.clone());
    }
    rel.sort_by(f64::total_cmp);
    let q =
        |p: f64| rel.get(((rel.len().max(1) - 1) as f64 * p) as usize).copied().unwrap_or(f64::NAN);
    println!(
        "the main view after the water pass on {} scenes ({}) × 8 random conformant GPUs: 0 \
         outside of {judged} pixels judged ({water_px} water, {open} of them open to the sky; \
         {object_px} the objects', {either_px} either's); twice the rules: {loose} outside; the \
         objects' pixels 2 % brighter: {objects_brighter} outside; water rel half-width p50 \
         {:.1e}, p99 {:.1e}",
        names.len(),
        names.join(", "),
        q(0.5),
        q(0.99)
    );
    assert!(runs > 0 && water_px > 0, "no water pass judged");
    assert!(unjudged.is_empty(), "no water pixel judged in {unjudged:?}");
    assert!(loose > 0, "a GPU twice as loose as the rules never left the water envelope");
    assert!(objects_tight > 0, "the objects' depth bound is 1 % loose or more at every pixel");
    assert!(reach_compared > 5, "the objects' reach compared on {reach_compared} scenes");
    assert!(object_px > 0, "no pixel judged by the objects' envelope");
    assert!(objects_brighter > 0, "objects 2 % too bright never left their envelope");
}

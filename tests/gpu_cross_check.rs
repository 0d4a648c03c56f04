//! CPU ↔ GPU cross-check (issue 4): every reference scene at 160×90 through the CPU oracle and
//! the wgpu path, every float buffer within docs/design.md's rel 1e-5 / abs 1e-6, the 8-bit picture
//! within the tolerance row of the adapter that ran (lavapipe: ≥ 99.5 % of pixels within
//! 1/255, FLIP mean ≤ 0.005). On a failure the CPU and GPU pictures, difference images and a
//! JSON summary go to `target/gpu-cross-check/`.
//!
//! The adapter that ran is printed, and must be a real wgpu adapter (never the CPU compared
//! with itself). Without any adapter the GPU tests fail under `OCEAN_REQUIRE_GPU=1` (CI) and
//! are otherwise reported ignored, with why (tests/support/gpu_harness.rs). The comparators'
//! own tests and negative controls are ocean-verify's (`crates/ocean-verify/tests/comparators.rs`).

#![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;
#[path = "support/reference_scenes.rs"]
mod reference_scenes;

use std::path::PathBuf;

use ocean_core::scene::Scene;
use ocean_gpu::{FrameMap, Renderer, WaveSynthesis};
use ocean_verify::compare::compare_float;
use ocean_verify::cross_check::{check_scene, cpu_map, write_artefacts};

/// Small enough for CI on lavapipe with 2 cores, large enough to show every pass.
const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The GPU renderer (the harness runs the GPU tests only where there is an adapter).
fn renderer() -> Renderer {
    renderer_with(WaveSynthesis::GpuFft)
}

/// The GPU renderer with a given wave-map source (see [`renderer`]).
fn renderer_with(waves: WaveSynthesis) -> Renderer {
    match ocean_gpu::Gpu::new().and_then(|g| Renderer::with_gpu(g, waves)) {
        Ok(r) => {
            let a = r.adapter().clone();
            eprintln!("gpu_cross_check: adapter {a}");
            // A real adapter: a wgpu backend, not the no-op one, and the one CI pinned.
            assert!(!a.name.is_empty(), "the adapter has no name: {a}");
            assert_ne!(a.backend, "Noop", "the no-op backend renders nothing: {a}");
            if let Ok(want) = std::env::var("WGPU_BACKEND") {
                assert!(
                    a.backend.to_lowercase().contains(&want.to_lowercase().replace("vk", "vulkan")),
                    "WGPU_BACKEND={want} but the adapter is {a}"
                );
            }
            r
        }
        Err(e) => panic!("gpu_cross_check: no GPU renderer: {e}"),
    }
}

/// The reference scenes, plus the default scene seen from under the water (the plan skips the
/// sky; the water pass takes its branch for a surface seen from below, with Fresnel for 1/η
/// and Snell's window).
fn reference_scenes() -> Vec<(String, Scene)> {
    let mut scenes = reference_scenes::reference_scenes();
    for (_, s) in &mut scenes {
        (s.camera.width, s.camera.height) = (WIDTH, HEIGHT);
    }
    let mut under = Scene::builtin();
    (under.camera.width, under.camera.height) = (WIDTH, HEIGHT);
    under.camera.position = [0.0, -2.5, 20.0];
    under.camera.look_at = [0.0, 25.0, -15.0];
    scenes.push(("default_underwater".into(), under));
    // An object behind the camera: every object pass culls it (the plan's per-pass lists),
    // on both back ends.
    let mut culled = Scene::builtin();
    (culled.camera.width, culled.camera.height) = (WIDTH, HEIGHT);
    let mut behind = culled.objects[0].clone();
    behind.center = [0.0, 3.0, 80.0];
    culled.objects.push(behind);
    assert!(
        !ocean_core::plan::FramePlan::new(&culled, ocean_core::plan::OutputKind::Ldr)
            .objects()
            .objects
            .contains(&2)
    );
    scenes.push(("default_culled".into(), culled));
    // The final pass with Hable's curve and a strong vignette (`[post]`): the tonemap's
    // arithmetic on both back ends.
    let mut post = Scene::builtin();
    (post.camera.width, post.camera.height) = (WIDTH, HEIGHT);
    post.post.curve = ocean_core::tonemap::Curve::Hable;
    post.post.vignette = 0.8;
    scenes.push(("default_hable_vignette".into(), post));
    scenes
}

fn reference_scenes_match_the_cpu_oracle() {
    let mut renderer = renderer();
    let scenes = reference_scenes();
    assert!(scenes.len() >= 6, "expected the reference scenes, found {}", scenes.len());
    let out = root().join("target/gpu-cross-check");
    let mut failures = Vec::new();
    for (name, scene) in &scenes {
        let (check, renders) = check_scene(&mut renderer, name, scene).expect("both renders");
        assert_eq!(check.adapter, *renderer.adapter(), "the GPU side ran on the adapter");
        eprintln!("{name} ({}x{}, waves: {:?}):", WIDTH, HEIGHT, check.wave_source);
        for line in check.lines() {
            eprintln!("  {line}");
        }
        let f = check.failures();
        if !f.is_empty() {
            write_artefacts(&out, &check, &renders).expect("writable target dir");
            failures.extend(f);
        }
    }
    assert!(
        failures.is_empty(),
        "CPU and GPU differ beyond docs/design.md's tolerances (images and JSON in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}

/// A small deterministic generator for the raster test.
struct Lcg(u64);

impl Lcg {
    fn unit(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The CPU rasterizer against lavapipe on random triangles, half of them cut by the view
/// volume's planes (behind the eye, beside and beyond the viewport): every covered pixel's
/// depth, 1/w and perspective-correct varyings agree bit for bit, in a 160×90 target (not a
/// power of two, so the viewport transform's rounding shows). This pins the interpolation and
/// clipping rules of `ocean_cpu::raster` to what the GPU does.
fn rasterizer_matches_lavapipe_bit_for_bit() {
    use ocean_cpu::raster::{BlendMode, CompareFunction, RasterState, RenderTarget, Vertex, draw};
    use ocean_gpu::common::{Load, begin_render_pass, primitive, replace_target};
    use ocean_gpu::readback::{Readbacks, TexelData};
    use ocean_gpu::texture::{GpuTexture, MAP_FORMAT};
    use wgpu::util::DeviceExt;

    let renderer = renderer();
    let gpu = renderer.gpu();
    let mut rng = Lcg(7);
    let mut tris: Vec<[Vertex<2>; 3]> = Vec::new();
    for i in 0..400 {
        let (spread, z_lo) = if i % 2 == 0 { (0.9, 0.0) } else { (3.0, -0.5) };
        tris.push(std::array::from_fn(|_| {
            let w = 0.2 + rng.unit() * 30.0;
            let x = (rng.unit() * 2.0 - 1.0) * spread * w;
            let y = (rng.unit() * 2.0 - 1.0) * spread * w;
            let z = (z_lo + rng.unit() * (1.0 - 2.0 * z_lo)) * w;
            Vertex::new([x, y, z, w], [rng.unit() * 200.0 - 100.0, rng.unit()])
        }));
    }
    let (w, h) = (160u32, 90u32);
    // CPU: no depth test, last triangle wins, as on the GPU without a depth buffer.
    let state = RasterState {
        depth_compare: CompareFunction::Always,
        depth_write: false,
        blend: BlendMode::Replace,
        ..RasterState::default()
    };
    let mut cpu = RenderTarget::new(w, h);
    draw(&mut cpu, &state, &tris, |f| {
        Some([f.frag_coord[2], f.frag_coord[3], f.varyings[0], f.varyings[1]])
    });
    // GPU.
    let d = &gpu.device;
    let src = "struct VOut { @builtin(position) p: vec4<f32>, @location(0) a: vec2<f32> }\n\
        @vertex fn vs(@location(0) pos: vec4<f32>, @location(1) a: vec2<f32>) -> VOut {\n\
            var o: VOut; o.p = pos; o.a = a; return o; }\n\
        @fragment fn fs(i: VOut) -> @location(0) vec4<f32> {\n\
            return vec4<f32>(i.p.z, i.p.w, i.a.x, i.a.y); }\n";
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("raster-check"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let vertex_data: Vec<[f32; 6]> = tris
        .iter()
        .flatten()
        .map(|v| [v.clip[0], v.clip[1], v.clip[2], v.clip[3], v.varyings[0], v.varyings[1]])
        .collect();
    let pipeline = d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("raster-check"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 24,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x2],
            })],
        },
        primitive: primitive(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &replace_target(MAP_FORMAT),
        }),
        multiview_mask: None,
        cache: None,
    });
    let vertices = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("raster-check"),
        contents: bytemuck::cast_slice(&vertex_data),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let target = GpuTexture::target(d, "raster-check", w, h, MAP_FORMAT);
    let mut encoder = d.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = begin_render_pass(
            &mut encoder,
            "raster-check",
            &target.view,
            Load::Clear([0.0; 4]),
            None,
            None,
        );
        pass.set_pipeline(&pipeline);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.draw(0..vertex_data.len() as u32, 0..1);
    }
    let mut readback: Readbacks<()> = Readbacks::default();
    readback.copy(d, &mut encoder, (), "raster-check", &target, MAP_FORMAT);
    gpu.queue.submit([encoder.finish()]);
    let data = readback.finish(gpu).expect("readback");
    let TexelData::Float(g) = &data[0].1 else { panic!("a float target") };
    let covered = cpu.color.iter().filter(|c| **c != [0.0; 4]).count();
    let differing: Vec<usize> = (0..cpu.color.len())
        .filter(|&i| (0..4).any(|k| cpu.color[i][k].to_bits() != g.texels[i][k].to_bits()))
        .collect();
    eprintln!("raster check: {covered} covered pixels, {} differ", differing.len());
    assert!(covered > (w * h / 2) as usize, "the triangles cover the target");
    assert!(
        differing.is_empty(),
        "{} of {} pixels differ, first at {:?}: cpu {:?} gpu {:?}",
        differing.len(),
        w * h,
        differing.first().map(|&i| (i as u32 % w, i as u32 / w)),
        differing.first().map(|&i| cpu.color[i]),
        differing.first().map(|&i| g.texels[i])
    );
}

/// `textureSampleLevel` with a linear mip filter, lavapipe against `ocean_cpu::mip` on 16 384
/// random coordinates (repeat addressing, several periods either side) and explicit LODs
/// (below 0, fractional, whole, beyond the last level, and a bias folded in), on a 64×32
/// texture whose 7 levels hold unrelated random values (so a wrong level or weight shows):
/// every channel bit for bit. This is the measurement behind the module doc of
/// `ocean_cpu::mip` (clamp, ⌊λ⌋ and f = λ − ⌊λ⌋, fused blend).
fn trilinear_sampling_matches_lavapipe_bit_for_bit() {
    use ocean_cpu::mip::{MipChain, level_count, level_size, texture_sample_level_mip};
    use ocean_cpu::sampler::{AddressMode, FilterMode, Sampler, Texture2D};
    use ocean_gpu::readback::{Readbacks, TexelData};
    use ocean_gpu::texture::{GpuTexture, MAP_FORMAT, map_usage};

    let renderer = renderer();
    let gpu = renderer.gpu();
    let d = &gpu.device;
    let mut rng = Lcg(11);
    let (w, h) = (64u32, 32u32);
    let levels: Vec<Texture2D> = (0..level_count(w, h))
        .map(|k| {
            let [lw, lh] = level_size(w, h, k);
            let texels = (0..lw * lh).map(|_| std::array::from_fn(|_| rng.unit() * 4.0 - 2.0));
            Texture2D::new(lw, lh, texels.collect())
        })
        .collect();
    let chain = MipChain::from_levels(&levels);
    let n = 128u32;
    let inputs: Vec<[f32; 4]> = (0..n * n)
        .map(|i| {
            let u = rng.unit() * 5.0 - 2.0;
            let v = rng.unit() * 5.0 - 2.0;
            let lod = match i % 8 {
                0 => (rng.unit() * 10.0).floor() - 1.0,
                1 => -rng.unit() * 3.0,
                2 => 6.0 + rng.unit() * 4.0,
                _ => rng.unit() * 7.0,
            };
            [u, v, lod, 0.0]
        })
        .collect();
    let sampler = Sampler {
        address_mode_u: AddressMode::Repeat,
        address_mode_v: AddressMode::Repeat,
        filter: FilterMode::Linear,
    };
    let cpu: Vec<[f32; 4]> = inputs
        .iter()
        .map(|p| texture_sample_level_mip(&chain, &sampler, [p[0], p[1]], p[2]))
        .collect();

    let texture = d.create_texture(&wgpu::TextureDescriptor {
        label: Some("trilinear-check"),
        size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: MAP_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (k, level) in levels.iter().enumerate() {
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: k as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&level.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(level.width * 16),
                rows_per_image: Some(level.height),
            },
            wgpu::Extent3d { width: level.width, height: level.height, depth_or_array_layers: 1 },
        );
    }
    let input = GpuTexture::upload_map(gpu, "trilinear-input", n, n, &inputs);
    let output = GpuTexture::new(d, "trilinear-output", n, n, MAP_FORMAT, map_usage());
    let src = "@group(0) @binding(0) var tex: texture_2d<f32>;\n\
        @group(0) @binding(1) var samp: sampler;\n\
        @group(0) @binding(2) var input: texture_2d<f32>;\n\
        @group(0) @binding(3) var output: texture_storage_2d<rgba32float, write>;\n\
        @compute @workgroup_size(8, 8, 1) fn main(@builtin(global_invocation_id) id: vec3<u32>) {\n\
            let p = textureLoad(input, vec2<i32>(id.xy), 0);\n\
            textureStore(output, vec2<i32>(id.xy), textureSampleLevel(tex, samp, p.xy, p.z)); }\n";
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("trilinear-check"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("trilinear-check"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let samp = d.create_sampler(&wgpu::SamplerDescriptor {
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("trilinear-check"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            },
            wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&samp) },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&input.view),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::TextureView(&output.view),
            },
        ],
    });
    let mut encoder = d.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(n / 8, n / 8, 1);
    }
    let mut readback: Readbacks<()> = Readbacks::default();
    readback.copy(d, &mut encoder, (), "trilinear-check", &output, MAP_FORMAT);
    gpu.queue.submit([encoder.finish()]);
    let data = readback.finish(gpu).expect("readback");
    let TexelData::Float(g) = &data[0].1 else { panic!("a float target") };
    let differing: Vec<usize> = (0..cpu.len())
        .filter(|&i| (0..4).any(|c| cpu[i][c].to_bits() != g.texels[i][c].to_bits()))
        .collect();
    eprintln!("trilinear check: {} samples, {} differ", cpu.len(), differing.len());
    assert!(
        differing.is_empty(),
        "{} of {} samples differ; first: input {:?} cpu {:?} gpu {:?}",
        differing.len(),
        cpu.len(),
        differing.first().map(|&i| inputs[i]),
        differing.first().map(|&i| cpu[i]),
        differing.first().map(|&i| g.texels[i])
    );
}

/// Stage `wave_mips`: the GPU's mip chain of a random 64×32 slope map (level 0 the moments,
/// each level the 2×2 box of the one below, clamped at the 1-texel-wide levels), packed into
/// the atlas both back ends share, against the CPU mirror's: every texel bit for bit.
fn wave_mips_match_the_cpu_mirror_bit_for_bit() {
    use ocean_cpu::sampler::Texture2D;
    use ocean_cpu::shaders::wave_mips;
    use ocean_gpu::readback::{Readbacks, TexelData};
    use ocean_gpu::texture::{GpuTexture, MAP_FORMAT};
    use ocean_gpu::wave_mips::{GpuMipChain, WaveMipsStage};

    let renderer = renderer();
    let gpu = renderer.gpu();
    let d = &gpu.device;
    let mut rng = Lcg(5);
    let (w, h) = (64u32, 32u32);
    let texels: Vec<[f32; 4]> =
        (0..w * h).map(|_| std::array::from_fn(|_| rng.unit() * 2.0 - 1.0)).collect();
    let cpu = wave_mips::dispatch(&Texture2D::new(w, h, texels.clone()));
    let slopes = GpuTexture::upload_map(gpu, "wave-mips-check", w, h, &texels);
    let chain = GpuMipChain::new(d, "wave-mips-check", w, h);
    let stage = WaveMipsStage::new(d).expect("the wave_mips pipelines");
    let mut encoder = d.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    let kept = ocean_gpu::pool::FramePool::new(d, &gpu.queue);
    stage.encode(&kept, &mut encoder, &[(&slopes, &chain)]);
    let atlas = chain.pack(d, &mut encoder);
    let mut readback: Readbacks<()> = Readbacks::default();
    readback.copy(d, &mut encoder, (), "wave-mips-check", &atlas, MAP_FORMAT);
    gpu.queue.submit([encoder.finish()]);
    let data = readback.finish(gpu).expect("readback");
    let TexelData::Float(g) = &data[0].1 else { panic!("a float target") };
    assert_eq!((g.width, g.height), (cpu.atlas.width, cpu.atlas.height));
    let differing = (0..g.texels.len())
        .filter(|&i| (0..4).any(|c| g.texels[i][c].to_bits() != cpu.atlas.texels[i][c].to_bits()))
        .count();
    eprintln!(
        "wave_mips check: {} levels, {differing} of {} atlas texels differ",
        cpu.levels,
        g.texels.len()
    );
    assert_eq!(differing, 0);
}

/// The renderer as `ocean render --backend gpu` runs it: the wave maps from the GPU FFT every
/// frame. lavapipe's `sin`/`cos` differ from the CPU's by up to 1 ulp (tests/gpu_waves.rs
/// measures it over 65,536 angles), so the maps differ from the CPU synthesis by a few 1e-7 of
/// each field's magnitude — docs/design.md's FFT tolerance is rel 1e-5 of the field (max norm) — and
/// the differences are then amplified through the bumped normal and the sun's (V·R)^400, so
/// the HDR frame is held to docs/design.md's final-image tolerances (≥ 99.5 % of pixels within 1/255,
/// FLIP mean ≤ 0.005), not the float-buffer ones. Every other map must still meet those.
fn gpu_fft_frames_meet_the_image_tolerances() {
    let mut renderer = renderer_with(WaveSynthesis::GpuFft);
    let wave_maps = [FrameMap::Displacement, FrameMap::DisplacementSlopes, FrameMap::Bump];
    let mut failures = Vec::new();
    for (name, scene) in reference_scenes() {
        let (check, renders) = check_scene(&mut renderer, &name, &scene).expect("both renders");
        // The source follows the plan's kernel: the GPU FFT, or (a looping sea) the synthesis.
        let plan = ocean_core::plan::FramePlan::new(&scene, ocean_core::plan::OutputKind::Ldr);
        // Waves `gerstner` make no maps: the water pass sums the waves itself.
        let want = match plan.waves_kernel {
            _ if !plan.runs(ocean_core::plan::Pass::Waves) => None,
            ocean_core::plan::WavesKernel::Shader => Some("gpu-fft"),
            ocean_core::plan::WavesKernel::Synthesis => Some("cpu-upload"),
        };
        assert_eq!(check.wave_source, want, "{name}");
        let image = check.image.as_ref().expect("8-bit output on both sides");
        failures.extend(
            image.failures(&check.image_limits).into_iter().map(|f| format!("{name}: {f}")),
        );
        for f in check.failures() {
            let prefix = format!("{name}: ");
            let map = f.strip_prefix(&prefix).unwrap_or(&f).split_whitespace().next().unwrap_or("");
            let exempt = map == "hdr" || wave_maps.iter().any(|m| m.name() == map);
            if !exempt {
                failures.push(f);
            }
        }
        for which in wave_maps {
            let Some(g) = renders.gpu.map(which) else { continue };
            let (_, cpu) = cpu_map(&renders.cpu.buffers, which);
            for c in 0..4 {
                let scale = cpu.iter().map(|t| t[c].abs()).fold(0.0f32, f32::max);
                let worst = cpu
                    .iter()
                    .zip(&g.texels)
                    .map(|(a, b)| (a[c] - b[c]).abs())
                    .fold(0.0f32, f32::max);
                if worst > 1e-5 * scale {
                    failures.push(format!(
                        "{name}: {} channel {c}: {worst} > 1e-5 × {scale}",
                        which.name()
                    ));
                }
            }
        }
        eprintln!(
            "{name} ({}): within 1/255 {:.3} %, FLIP mean {:.5}",
            want.unwrap_or("no wave maps"),
            100.0 * image.within_1,
            image.flip_mean
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The viewer's sliders change the sea every frame: the GPU FFT then takes the new modes into
/// its buffers in place (`WaveMapSource::update`). That must give the same frame, bit for bit,
/// as a renderer that never saw the old sea; a new map size makes a new source.
fn a_new_sea_on_a_running_renderer_equals_a_fresh_renderer() {
    let mut kept = renderer_with(WaveSynthesis::GpuFft);
    let mut first = Scene::builtin();
    (first.camera.width, first.camera.height) = (WIDTH, HEIGHT);
    let mut windier = first.clone();
    windier.ocean.wind_speed = 21.0;
    windier.ocean.spectrum = ocean_core::spectrum::SpectrumKind::Tma;
    windier.ocean.depth_m = 6.0;
    windier.ocean.fetch_km = 40.0;
    let mut finer = windier.clone();
    finer.ocean.resolution = 128;

    let bits = |f: &ocean_gpu::GpuFrame, m: FrameMap| -> Vec<u32> {
        f.map(m).expect("map read back").texels.iter().flatten().map(|v| v.to_bits()).collect()
    };
    let maps =
        [FrameMap::Displacement, FrameMap::DisplacementSlopes, FrameMap::Bump, FrameMap::Hdr];
    let run = |r: &mut Renderer, s: &Scene| {
        let plan = ocean_core::plan::FramePlan::new(s, ocean_core::plan::OutputKind::Ldr);
        r.run(s, &plan).expect("frame")
    };
    let before = run(&mut kept, &first);
    for next in [&windier, &finer] {
        let updated = run(&mut kept, next);
        let mut fresh = renderer_with(WaveSynthesis::GpuFft);
        let reference = run(&mut fresh, next);
        for m in maps {
            assert!(bits(&updated, m) == bits(&reference, m), "{}: in place ≠ fresh", m.name());
            // Negative control: the old sea's map is not the new one.
            assert!(
                bits(&before, m) != bits(&reference, m),
                "{}: the sea did not change",
                m.name()
            );
        }
        assert_eq!(updated.ldr, reference.ldr);
    }
}

/// The bloom chains are compared on the same input, the CPU mirror run on the GPU's HDR
/// frame (`ocean_verify::cross_check`); that comparison still fails when the pass differs
/// (a threshold 1e-3 higher), and fed the CPU's own HDR frame the cancellation of the
/// threshold takes the chains beyond the float tolerance although both HDR frames are within
/// it — why the cross-check feeds the same frame.
fn bloom_chains_are_compared_on_the_same_input_and_can_fail() {
    use ocean_core::graph::BloomInputs;
    use ocean_core::plan::{FramePlan, OutputKind};
    use ocean_cpu::sampler::Texture2D;
    use ocean_cpu::shaders::bloom;
    let mut renderer = renderer();
    let mut scene = Scene::load(&root().join("reference/scenes/bloom_glitter.toml")).unwrap();
    // 320 × 180: at 160 × 90 the glitter's texels near the threshold are too few to show
    // the cancellation.
    (scene.camera.width, scene.camera.height) = (320, 180);
    let plan = FramePlan::new(&scene, OutputKind::Ldr);
    let gpu = renderer.run(&scene, &plan).unwrap();
    let hdr = gpu.map(FrameMap::Hdr).unwrap();
    let g = gpu.map(FrameMap::BloomDown).unwrap();
    let compare = |s: &Scene, frame: &Texture2D| {
        let (down, _) = bloom::dispatch(frame, &BloomInputs::new(s));
        let cpu = ((down.atlas.width, down.atlas.height), &down.atlas.texels[..]);
        compare_float("bloom_down", true, cpu, ((g.width, g.height), &g.texels))
    };
    let same = Texture2D::new(hdr.width, hdr.height, hdr.texels.clone());
    let stats = compare(&scene, &same);
    eprintln!("same input: {}", stats.line());
    assert!(stats.passed());
    let mut shifted = scene.clone();
    shifted.post.bloom_threshold += 1e-3;
    let stats = compare(&shifted, &same);
    eprintln!("threshold + 1e-3: {}", stats.line());
    assert!(!stats.passed());
    let cpu = ocean_cpu::render_scene_with_plan(&scene, plan, &mut |_| {}).unwrap();
    let own = Texture2D::new(hdr.width, hdr.height, cpu.buffers.hdr.color.clone());
    let stats = compare(&scene, &own);
    eprintln!("the CPU's own HDR frame: {}", stats.line());
    assert!(!stats.passed());
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        gpu: reference_scenes_match_the_cpu_oracle, rasterizer_matches_lavapipe_bit_for_bit,
            gpu_fft_frames_meet_the_image_tolerances,
            a_new_sea_on_a_running_renderer_equals_a_fresh_renderer,
            trilinear_sampling_matches_lavapipe_bit_for_bit, wave_mips_match_the_cpu_mirror_bit_for_bit,
            bloom_chains_are_compared_on_the_same_input_and_can_fail;
    )
}

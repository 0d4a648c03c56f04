//! The `rgba16float` frame buffers (`ocean_core::frame_format`): what the GPU stores when a
//! fragment or a compute shader writes an f32 value to an f16 texel, against the oracle's
//! [`FrameFormat::store`] (round toward zero; finite magnitudes beyond 65504 give 65504).
//!
//! Vulkan leaves the rounding of a conversion to f16 to the implementation, so this measures
//! the adapter's: on lavapipe it must agree bit for bit on every finite value (the oracle
//! mirrors lavapipe's truncation); on a hardware GPU one binary16 step is allowed (the
//! cross-check's allowance; round-to-nearest-even is one step from truncation), and the test
//! prints how many values took it. What ±inf become is printed, not asserted (no pass of the
//! frame writes an infinity).

#[macro_use]
#[path = "support/gpu_harness.rs"]
mod gpu_harness;

use ocean_core::frame_format::{FrameFormat, HALF_MAX, half_step};
use ocean_core::rng::SplitMix64;

/// Texels per row of the test targets.
const WIDTH: u32 = 64;

/// The values written: the rounding's edge cases, then pseudo-random values spread over
/// the binary16 range (both signs, 2⁻²⁶ … 2¹⁶), each rounding case of the mantissa likely.
fn values() -> Vec<f32> {
    let p = |e: i32| f32::powi(2.0, e);
    let mut v = vec![
        0.0,
        -0.0,
        1.0,
        1.0 + p(-11),          // midpoint of 1 and 1 + 2⁻¹⁰
        1.0 + 3.0 * p(-11),    // midpoint of 1 + 2⁻¹⁰ and 1 + 2⁻⁹
        1.0 + p(-11) + p(-20), // just above a midpoint
        1.0 + p(-10) - p(-23), // just below a binary16 value
        -(1.0 + p(-11)),       // a negative midpoint
        p(-24),                // smallest subnormal
        p(-25),                // half of it
        3.0 * p(-25),          // midpoint of 2⁻²⁴ and 2⁻²³
        p(-14) - p(-30),       // just below the smallest normal
        HALF_MAX,
        65519.0, // below round-to-nearest's overflow midpoint
        65520.0, // at it
        1e6,
        -f32::MAX,
        0.1,
        1.0 / 3.0,
        2.0 / 3.0,
    ];
    let mut rng = SplitMix64::new(0x016f_10a7);
    while v.len() < (WIDTH * 64 * 4) as usize {
        // A binary exponent in −26 … 15 and a mantissa in [1, 2): every binade alike.
        let e = (rng.next_u64() % 42) as i32 - 26;
        let m = 1.0 + rng.next_open_closed();
        let s = if rng.next_u64() & 1 == 0 { -1.0 } else { 1.0 };
        v.push((s * m.min(1.999_999) * 2f64.powi(e)) as f32);
    }
    v
}

/// What the adapter's conversion does with these is reported.
const INFINITE: [f32; 4] = [f32::INFINITY, f32::NEG_INFINITY, f32::INFINITY, f32::INFINITY];

const SHADER: &str = r"
@group(0) @binding(0) var<storage, read> values: array<vec4<f32>>;
@group(0) @binding(1) var dst: texture_storage_2d<rgba16float, write>;

struct Out { @builtin(position) position: vec4<f32> };

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> Out {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return Out(vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0));
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let p = vec2<u32>(in.position.xy);
    return values[p.y * 64u + p.x];
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    textureStore(dst, id.xy, values[id.y * 64u + id.x]);
}
";

/// Writes `texels` (WIDTH wide) to an `Rgba16Float` texture by a full-screen draw
/// (`render`) or a compute shader's `textureStore`, and reads it back as f32.
fn gpu_store(gpu: &ocean_gpu::Gpu, texels: &[[f32; 4]], render: bool) -> Vec<[f32; 4]> {
    use wgpu::util::DeviceExt;
    let d = &gpu.device;
    let height = texels.len() as u32 / WIDTH;
    let format = wgpu::TextureFormat::Rgba16Float;
    let texture = d.create_texture(&wgpu::TextureDescriptor {
        label: Some("precision"),
        size: wgpu::Extent3d { width: WIDTH, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let values = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("precision.values"),
        contents: bytemuck::cast_slice(texels),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("precision"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let stages = if render { wgpu::ShaderStages::FRAGMENT } else { wgpu::ShaderStages::COMPUTE };
    let mut entries = vec![wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }];
    if !render {
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 1,
            visibility: stages,
            ty: wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
            count: None,
        });
    }
    let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("precision"),
        entries: &entries,
    });
    let mut bindings =
        vec![wgpu::BindGroupEntry { binding: 0, resource: values.as_entire_binding() }];
    if !render {
        bindings.push(wgpu::BindGroupEntry {
            binding: 1,
            resource: wgpu::BindingResource::TextureView(&view),
        });
    }
    let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("precision"),
        layout: &layout,
        entries: &bindings,
    });
    let pipeline_layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("precision"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let mut encoder = d.create_command_encoder(&Default::default());
    if render {
        let pipeline = d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("precision"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("precision"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    } else {
        let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("precision"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("cs_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(WIDTH / 8, height.div_ceil(8), 1);
    }
    let mut readbacks: ocean_gpu::readback::Readbacks<()> = Default::default();
    readbacks.copy_texture(d, &mut encoder, (), "precision", &texture, format);
    gpu.queue.submit([encoder.finish()]);
    let back = readbacks.finish(gpu).unwrap_or_else(|e| panic!("read-back: {e}"));
    match back.into_iter().next() {
        Some(((), ocean_gpu::readback::TexelData::Float(m))) => m.texels,
        _ => panic!("no float read-back"),
    }
}

fn texels_of(v: &[f32]) -> Vec<[f32; 4]> {
    v.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect()
}

/// Compares the adapter's stores of `values()` with the oracle's, for a draw or a compute
/// write; overflow is printed.
fn check_stores(render: bool) {
    let gpu = ocean_gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let software = gpu.report.is_software;
    let what = if render { "fragment output" } else { "storage write" };
    let mut inf: Vec<f32> = INFINITE.to_vec();
    inf.resize(4 * (WIDTH * 8) as usize, 0.0);
    let got = gpu_store(&gpu, &texels_of(&inf), render);
    eprintln!("{what}: {INFINITE:?} stored as {:?}", &got[0]);
    let v = values();
    let got = gpu_store(&gpu, &texels_of(&v), render);
    let (mut exact, mut one_step, mut worse) = (0, 0, Vec::new());
    for (&x, g) in v.iter().zip(got.iter().flatten()) {
        let want = FrameFormat::Rgba16Float.store(x);
        if want.to_bits() == g.to_bits() || (want == 0.0 && *g == 0.0) {
            exact += 1;
        } else if (want - g).abs() <= half_step(want) {
            one_step += 1;
            if one_step <= 5 {
                eprintln!("{what}: {x:e} stored as {g:e}, the oracle {want:e}");
            }
        } else {
            worse.push((x, *g, want));
        }
    }
    eprintln!(
        "{what} on {}: {exact} of {} values as the oracle stores them, {one_step} one binary16 \
         step away",
        gpu.report.name,
        v.len()
    );
    assert!(worse.is_empty(), "{what}: stores more than one step from the oracle: {worse:?}");
    if software {
        assert_eq!(one_step, 0, "{what}: lavapipe rounds unlike the oracle (toward zero)");
    }
}

fn fragment_outputs_round_to_f16_as_the_oracle_stores() {
    check_stores(true);
}

fn storage_writes_round_to_f16_as_the_oracle_stores() {
    check_stores(false);
}

/// The oracle's stores themselves, against binary16 truncation written here from the
/// definition: every value in [v, next(v)) of two consecutive binary16 values v > 0 stores as
/// v (bit patterns decoded by hand, not by the code under test), over every interval.
fn oracle_store_truncates_to_binary16() {
    let half_bits_to_f32 = |h: u16| -> f32 {
        let e = i32::from((h >> 10) & 0x1f);
        let m = f32::from(h & 0x3ff);
        if e == 0 { m * f32::powi(2.0, -24) } else { (1.0 + m / 1024.0) * f32::powi(2.0, e - 15) }
    };
    let store = |x: f32| FrameFormat::Rgba16Float.store(x);
    let mut checked = 0;
    for h in 0u16..0x7bff {
        let (lo, hi) = (half_bits_to_f32(h), half_bits_to_f32(h + 1));
        let mid = ((f64::from(lo) + f64::from(hi)) / 2.0) as f32; // exact: one more bit
        for x in [lo, mid, f32::from_bits(mid.to_bits() + 1), f32::from_bits(hi.to_bits() - 1)] {
            assert_eq!(store(x), lo, "x = {x:e} in [{lo:e}, {hi:e})");
            assert_eq!(store(-x), -lo, "x = -{x:e}");
            checked += 1;
        }
    }
    assert!(checked > 100_000);
    assert_eq!(store(HALF_MAX * 1.0001), HALF_MAX);
    // Negative control: round-to-nearest would store the value just past a midpoint as the
    // upper neighbour.
    let past_mid = 1.0 + 3.0 * f32::powi(2.0, -11);
    assert_ne!(store(past_mid), half::f16::from_f32(past_mid).to_f32());
}

fn main() -> std::process::ExitCode {
    run_tests!(gpu_harness::GPU_ADAPTER;
        cpu: oracle_store_truncates_to_binary16;
        gpu: fragment_outputs_round_to_f16_as_the_oracle_stores, storage_writes_round_to_f16_as_the_oracle_stores)
}

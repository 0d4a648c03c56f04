//! What the stage modules share: shader modules from the embedded WGSL, the fixed-function
//! state the CPU rasterizer mirrors, bind-group-layout entries and uniform buffers.

use crate::created::Counted;

use crate::device::Error;
use crate::texture::DEPTH_FORMAT;

/// The label of a stage's objects: `"ocean.<stage>"` (docs/design.md, one name per stage).
pub fn label(stage: &str) -> String {
    format!("ocean.{stage}")
}

/// The techniques a renderer's pipelines are first assembled for: system `hu`'s. The stages
/// that compose a technique's WGSL (`sky`, `water`: techniques of the sky and of the shading)
/// are assembled again when a plan asks for other ones (`Renderer::run_frame`).
pub fn pipeline_techniques() -> ocean_core::plan::Techniques {
    ocean_core::plan::Techniques::of_system(ocean_core::plan::System::Hu)
}

/// The technique stages whose technique is composed into a stage's WGSL
/// (`// #import technique/<stage>`).
pub const COMPOSED: [ocean_core::plan::Stage; 3] =
    [ocean_core::plan::Stage::Sky, ocean_core::plan::Stage::Shading, ocean_core::plan::Stage::Foam];

/// The shader module of `stage` (one that imports no technique), from
/// `ocean_core::shader_source::stage_source_with` (imports resolved), labelled
/// `"ocean.<stage>"`.
///
/// # Errors
/// [`Error::Core`] if the source cannot be assembled (an unknown stage or import).
pub fn shader_module(device: &wgpu::Device, stage: &str) -> Result<wgpu::ShaderModule, Error> {
    shader_module_with(device, stage, &pipeline_techniques())
}

/// The shader module of `stage` with the files of `techniques` composed in.
///
/// # Errors
/// [`Error::Core`] if the source cannot be assembled (an unknown stage or import, a technique
/// without WGSL).
pub fn shader_module_with(
    device: &wgpu::Device,
    stage: &str,
    techniques: &ocean_core::plan::Techniques,
) -> Result<wgpu::ShaderModule, Error> {
    let source = ocean_core::shader_source::stage_source_with(stage, techniques)?;
    Ok(device.new_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&label(stage)),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    }))
}

/// The module of a stage that stores into the frame from compute (`sky`, `water`, `objects`), for a
/// frame of `target` format: WGSL has no preprocessor, so the rgba16float module is the
/// assembled source with its one storage declaration's format replaced (the line says so in
/// the stage's WGSL).
///
/// # Errors
/// [`Error::Core`] if the WGSL cannot be assembled; [`Error::Unavailable`] for a format other
/// than `Rgba32Float` and `Rgba16Float`, or a source that does not declare the storage once.
pub fn frame_storage_module(
    device: &wgpu::Device,
    stage: &str,
    techniques: &ocean_core::plan::Techniques,
    target: wgpu::TextureFormat,
) -> Result<wgpu::ShaderModule, Error> {
    let source = ocean_core::shader_source::stage_source_with(stage, techniques)?;
    let declared = "texture_storage_2d<rgba32float, write>";
    let source = match target {
        wgpu::TextureFormat::Rgba32Float => source,
        wgpu::TextureFormat::Rgba16Float if source.matches(declared).count() == 1 => {
            source.replace(declared, "texture_storage_2d<rgba16float, write>")
        }
        other => {
            return Err(Error::Unavailable(format!(
                "stage `{stage}` stores into rgba32float or rgba16float frames (declared once \
                 as `{declared}` in {stage}.wgsl), not {other:?}"
            )));
        }
    };
    Ok(device.new_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(&label(stage)),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    }))
}

/// The entry point `name` of `stage` as the stage registry lists it
/// (`ocean_core::registry::STAGES`): pipelines take their entry points from there, so an entry
/// the registry does not list cannot be used, and one it lists that the WGSL lacks fails to
/// validate.
///
/// # Errors
/// [`Error::Core`] for a stage or entry point the registry does not list.
pub fn entry(stage: &str, name: &str) -> Result<&'static str, Error> {
    ocean_core::registry::stage(stage).and_then(|s| s.entry(name)).ok_or_else(|| {
        Error::Core(ocean_core::Error::ShaderSource {
            stage: stage.to_owned(),
            reason: format!("the stage registry lists no entry point `{name}`"),
        })
    })
}

/// Triangle lists, counter-clockwise front faces, no culling: the CPU's
/// `RasterState::default()` (`ocean_cpu::raster::state`).
pub fn primitive() -> wgpu::PrimitiveState {
    wgpu::PrimitiveState {
        topology: wgpu::PrimitiveTopology::TriangleList,
        strip_index_format: None,
        front_face: wgpu::FrontFace::Ccw,
        cull_mode: None,
        unclipped_depth: false,
        polygon_mode: wgpu::PolygonMode::Fill,
        conservative: false,
    }
}

/// `Depth32Float` with the given test and writes.
pub fn depth_state(compare: wgpu::CompareFunction, write: bool) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias: wgpu::DepthBiasState::default(),
    }
}

/// The views from the eye: reversed Z, `Greater`, depth writes (cleared to 0).
pub fn eye_depth() -> wgpu::DepthStencilState {
    depth_state(wgpu::CompareFunction::Greater, true)
}

/// One colour target without blending (the CPU's `BlendMode::Replace`).
pub fn replace_target(format: wgpu::TextureFormat) -> [Option<wgpu::ColorTargetState>; 1] {
    [Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })]
}

/// A uniform-buffer entry of a bind group layout.
pub fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A `texture_2d<f32>` entry; `filterable` when a filtering sampler reads it.
pub fn texture_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    filterable: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A write-only `texture_storage_2d<rgba32float, write>` entry of a compute stage.
pub fn storage_map_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    storage_entry_of(binding, crate::texture::MAP_FORMAT)
}

/// A write-only 2D storage texture entry of `format` of a compute stage.
pub fn storage_entry_of(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        count: None,
    }
}

/// A bilinear sampler with one address mode on every axis: the CPU mirror's `WRAP_LINEAR`
/// (repeat) and `CLAMP_LINEAR` (clamp to edge); the CPU's `Sampler` has one filter for
/// magnification and minification.
pub fn linear_sampler(
    device: &wgpu::Device,
    label: &str,
    mode: wgpu::AddressMode,
) -> wgpu::Sampler {
    device.new_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        address_mode_u: mode,
        address_mode_v: mode,
        address_mode_w: mode,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        // Linear between levels: the slope maps' chains (far fields `mip`, `variance`) are
        // sampled at explicit LODs; every other map has one level.
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    })
}

/// A filtering sampler entry.
pub fn sampler_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// A bind group of buffers and views in binding order 0, 1, 2, …
pub fn bind_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry { binding: i as u32, resource: r.clone() })
        .collect();
    device.new_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A pipeline layout of the given bind group layouts.
pub fn pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    groups: &[&wgpu::BindGroupLayout],
) -> wgpu::PipelineLayout {
    let groups: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().map(|g| Some(*g)).collect();
    device.new_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &groups,
        immediate_size: 0,
    })
}

/// What a render pass does with its colour target first: clear to a colour (f32 values, held
/// exactly by wgpu's f64 `Color`) or keep what an earlier pass drew.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Load<T> {
    /// Clear to this value.
    Clear(T),
    /// Keep the contents.
    Keep,
}

/// Begins a render pass on one colour target and an optional depth buffer.
pub fn begin_render_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    color: &wgpu::TextureView,
    color_load: Load<[f32; 4]>,
    depth: Option<(&wgpu::TextureView, Load<f32>)>,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    let load = match color_load {
        Load::Clear(c) => wgpu::LoadOp::Clear(wgpu::Color {
            r: f64::from(c[0]),
            g: f64::from(c[1]),
            b: f64::from(c[2]),
            a: f64::from(c[3]),
        }),
        Load::Keep => wgpu::LoadOp::Load,
    };
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: color,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
        })],
        depth_stencil_attachment: depth.map(|(view, l)| depth_attachment(view, l)),
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// A depth buffer attachment, `load`ed and stored.
pub fn depth_attachment(
    view: &wgpu::TextureView,
    load: Load<f32>,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: match load {
                Load::Clear(d) => wgpu::LoadOp::Clear(d),
                Load::Keep => wgpu::LoadOp::Load,
            },
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    }
}

/// The render pipeline of a full-screen pass (`shared/fullscreen.wgsl`): `vs_main` and
/// `fs_main` of `stage`'s `module`, no vertex buffers, no depth, one unblended target of
/// `format`.
///
/// # Errors
/// [`Error::Core`] if the registry does not list the entry points.
pub fn fullscreen_pipeline(
    device: &wgpu::Device,
    stage: &str,
    module: &wgpu::ShaderModule,
    layout: &wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
) -> Result<wgpu::RenderPipeline, Error> {
    let name = &label(stage);
    Ok(device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(name),
        layout: Some(&pipeline_layout(device, name, &[layout])),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(entry(stage, "vs_main")?),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: primitive(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(entry(stage, "fs_main")?),
            compilation_options: Default::default(),
            targets: &replace_target(format),
        }),
        multiview_mask: None,
        cache: None,
    }))
}

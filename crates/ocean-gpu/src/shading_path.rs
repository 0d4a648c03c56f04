//! How a stage that draws the scene's surfaces (`water`, `objects`) shades them: in a compute
//! pass from a visibility buffer, or in the fragment stage. Both store the same bits
//! (`tests/gpu_frame_graph.rs` compares them on every reference scene).
//!
//! On the compute path the raster pass writes, for each pixel's last fragment that passes the
//! depth test, the fragment's interpolated inputs (three `rgba32float` colour attachments:
//! each f32 held exactly, and a coverage flag) instead of its colour, and a compute pass of
//! one invocation per pixel shades what that fragment would have, at the pixel centre. On GPUs
//! whose fragment work runs on a few units (Hopper's two graphics TPCs, docs/design.md "One
//! frame, two back ends") the shading then uses the whole chip, and overdrawn fragments
//! cost a depth test, not a shading. Interpolated inputs rather than a triangle id and
//! barycentrics: the shading reads the very values a fragment would, so the two paths agree
//! bit for bit and no vertex is transformed twice. The CPU oracle shades each pixel's last
//! passing fragment once, which is what both paths compute.

/// The visibility buffer's bytes per pixel: three `rgba32float` colour attachments.
pub(crate) const VISIBILITY_BYTES: u32 = 48;

/// The visibility buffer's format (each f32 input held exactly).
pub(crate) const VISIBILITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// `@workgroup_size(8, 8, 1)` of the shading entry points.
const WORKGROUP_SIZE: u32 = 8;

/// How a stage shades its surfaces: the same bits either way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadingPath {
    /// The raster pass writes a visibility buffer, a compute pass shades it.
    Compute,
    /// Each fragment shaded where it is rasterised.
    Fragment,
}

impl ShadingPath {
    /// [`ShadingPath::Compute`] where the device's colour attachments hold the visibility
    /// buffer (WebGPU's default limit, 32 bytes a sample, does not; Vulkan devices report
    /// 128), else [`ShadingPath::Fragment`].
    pub fn for_device(device: &wgpu::Device) -> Self {
        let l = device.limits();
        if l.max_color_attachments >= 3
            && l.max_color_attachment_bytes_per_sample >= VISIBILITY_BYTES
        {
            Self::Compute
        } else {
            Self::Fragment
        }
    }

    /// Both paths.
    pub const ALL: [ShadingPath; 2] = [Self::Compute, Self::Fragment];

    /// `compute` or `fragment`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Compute => "compute",
            Self::Fragment => "fragment",
        }
    }

    /// The path of that [`Self::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

/// The water's visibility buffer's labels.
pub(crate) const WATER_VISIBILITY: [&str; 3] =
    ["ocean.water.vis_a", "ocean.water.vis_b", "ocean.water.vis_cover"];
/// The objects' visibility buffer's labels.
pub(crate) const OBJECTS_VISIBILITY: [&str; 3] =
    ["ocean.objects.vis_a", "ocean.objects.vis_b", "ocean.objects.vis_cover"];

/// The visibility buffer's three targets, kept in `kept` under `labels` (constants: a
/// steady frame formats no label), `size`.
pub(crate) fn visibility_targets(
    kept: &crate::pool::FramePool,
    labels: [&str; 3],
    [width, height]: [u32; 2],
) -> [crate::texture::GpuTexture; 3] {
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
    labels.map(|l| kept.texture(l, width, height, VISIBILITY_FORMAT, usage).0)
}

/// The colour targets of a pipeline writing the visibility buffer.
pub(crate) fn visibility_color_targets() -> [Option<wgpu::ColorTargetState>; 3] {
    std::array::from_fn(|_| {
        Some(wgpu::ColorTargetState {
            format: VISIBILITY_FORMAT,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })
    })
}

/// Begins the raster pass into the visibility buffer `vis` (only the coverage target is
/// cleared: the others are read where it says a fragment was written) over `depth` loaded as
/// `depth_load`.
pub(crate) fn begin_visibility_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    vis: &[crate::texture::GpuTexture; 3],
    (depth, depth_load): (&wgpu::TextureView, crate::common::Load<f32>),
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    fn attachment(
        v: &wgpu::TextureView,
        load: wgpu::LoadOp<wgpu::Color>,
    ) -> Option<wgpu::RenderPassColorAttachment<'_>> {
        Some(wgpu::RenderPassColorAttachment {
            view: v,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
        })
    }
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[
            attachment(&vis[0].view, wgpu::LoadOp::Load),
            attachment(&vis[1].view, wgpu::LoadOp::Load),
            attachment(&vis[2].view, wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)),
        ],
        depth_stencil_attachment: Some(crate::common::depth_attachment(depth, depth_load)),
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// One timed span over a raster pass and the compute pass after it: the raster pass writes
/// the span's beginning, the compute pass its end.
pub(crate) fn split_timestamps(
    ts: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> (Option<wgpu::RenderPassTimestampWrites<'_>>, Option<wgpu::ComputePassTimestampWrites<'_>>) {
    match ts {
        Some(ts) => (
            Some(wgpu::RenderPassTimestampWrites { end_of_pass_write_index: None, ..ts }),
            Some(wgpu::ComputePassTimestampWrites {
                query_set: ts.query_set,
                beginning_of_pass_write_index: None,
                end_of_pass_write_index: ts.end_of_pass_write_index,
            }),
        ),
        None => (None, None),
    }
}

/// The bind group layout of a shading pass's visibility group: the buffer's three textures
/// (`textureLoad` only) and the pass's target as a write-only storage texture of `target`
/// format (bindings 0–3, as the WGSL declares them).
pub(crate) fn visibility_layout(
    device: &wgpu::Device,
    label: &str,
    target: wgpu::TextureFormat,
) -> wgpu::BindGroupLayout {
    use crate::created::Counted;
    let compute = wgpu::ShaderStages::COMPUTE;
    device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            crate::common::texture_entry(0, compute, false),
            crate::common::texture_entry(1, compute, false),
            crate::common::texture_entry(2, compute, false),
            crate::common::storage_entry_of(3, target),
        ],
    })
}

/// What a shading pass reads and writes: the visibility buffer, the pass's target (`size`
/// texels) and the layout of the group that binds them.
pub(crate) struct Shading<'a> {
    /// The visibility buffer the raster pass wrote.
    pub vis: &'a [crate::texture::GpuTexture; 3],
    /// The pass's colour target, bound as storage.
    pub target: &'a wgpu::TextureView,
    /// The target's size, texels.
    pub size: [u32; 2],
    /// [`visibility_layout`] of the stage.
    pub layout: &'a wgpu::BindGroupLayout,
}

/// Records the compute pass `label` that shades the visibility buffer into the target:
/// `groups` bound first (the stage's own), the visibility group after them, one invocation
/// per texel.
pub(crate) fn encode_shading(
    kept: &crate::pool::FramePool,
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    (pipeline, groups): (&wgpu::ComputePipeline, &[&wgpu::BindGroup]),
    s: &Shading<'_>,
    timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
) {
    let vis_group = kept.bind_group(
        label,
        s.layout,
        &[
            wgpu::BindingResource::TextureView(&s.vis[0].view),
            wgpu::BindingResource::TextureView(&s.vis[1].view),
            wgpu::BindingResource::TextureView(&s.vis[2].view),
            wgpu::BindingResource::TextureView(s.target),
        ],
    );
    let mut pass = encoder
        .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(label), timestamp_writes });
    pass.set_pipeline(pipeline);
    for (i, g) in groups.iter().enumerate() {
        pass.set_bind_group(i as u32, *g, &[]);
    }
    pass.set_bind_group(groups.len() as u32, &vis_group, &[]);
    pass.dispatch_workgroups(
        s.size[0].div_ceil(WORKGROUP_SIZE),
        s.size[1].div_ceil(WORKGROUP_SIZE),
        1,
    );
}

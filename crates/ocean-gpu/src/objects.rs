//! Stage `objects` (`shaders/objects.wgsl`): the scene's spheres and boxes with three pairs of
//! entry points — `vs_main`/`fs_main` (main view, into the HDR frame), `vs_reflect`/`fs_reflect`
//! (the reflection map) and `vs_refract`/`fs_refract` (the refraction map). Bindings: group 0,
//! binding 0 = `FrameUniforms`, 1 = `displacement`, 2 = `wrap_linear` (the maps' clipping at
//! the wave height, shading `chiu`), 3 = `shadow_map` (`textureLoad` only), 4 = `floor_map`,
//! 5 = `clamp_linear` (the sun under the water, shared/floor.wgsl). Vertices: ocean-core's `ObjectVertex` (36 bytes), drawn as a
//! triangle list in the order `object_triangles` gives. State: reversed-Z `Greater` with depth
//! writes, no blending, no culling (the CPU's `eye_state`).
//!
//! Two paths ([`ShadingPath`], the same bits): each pass's raster pass writes the visibility
//! buffer (`fs_visibility_*`, the discards of the maps kept there) and a compute pass shades it
//! into the pass's target (`cs_shade_*`; group 1: the buffer's three textures and the target
//! as storage), or each fragment is shaded where it is rasterised (`fs_*`).
//! CPU mirror: `ocean-cpu/src/shaders/objects.rs`.

use crate::created::Counted;
use ocean_core::frame::{ObjectVertex, ObjectsKey};

use crate::common::{
    Load, begin_render_pass, entry, eye_depth, frame_storage_module, label, linear_sampler,
    pipeline_layout, primitive, replace_target, sampler_entry, texture_entry, uniform_entry,
};
use crate::device::Error;
use crate::shading_path::{
    OBJECTS_VISIBILITY, Shading, ShadingPath, begin_visibility_pass, encode_shading,
    split_timestamps, visibility_color_targets, visibility_layout, visibility_targets,
};

/// Which pair of entry points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObjectsEntry {
    /// `vs_main` / `fs_main`: the objects in the main view.
    Main,
    /// `vs_reflect` / `fs_reflect`: mirrored, above the water only.
    Reflect,
    /// `vs_refract` / `fs_refract`: scaled by 1/η, under the water only, fogged.
    Refract,
}

impl ObjectsEntry {
    /// The vertex, fragment, visibility-buffer fragment and compute shading entry points.
    fn entry_points(self) -> [&'static str; 4] {
        match self {
            Self::Main => ["vs_main", "fs_main", "fs_visibility_main", "cs_shade_main"],
            Self::Reflect => {
                ["vs_reflect", "fs_reflect", "fs_visibility_reflect", "cs_shade_reflect"]
            }
            Self::Refract => {
                ["vs_refract", "fs_refract", "fs_visibility_refract", "cs_shade_refract"]
            }
        }
    }

    /// What the compute path's shading stores where nothing was drawn: the maps' clear
    /// colour (`cs_shade_reflect`, `cs_shade_refract`), nothing in the main view.
    fn stored_where_undrawn(self) -> Option<[f32; 4]> {
        match self {
            Self::Main => None,
            Self::Reflect | Self::Refract => Some([0.0; 4]),
        }
    }

    fn index(self) -> usize {
        match self {
            Self::Main => 0,
            Self::Reflect => 1,
            Self::Refract => 2,
        }
    }
}

/// One entry pair's pipelines: the fragment path's, or the compute path's raster pass into
/// the visibility buffer and its shading.
enum EntryPipelines {
    Fragment(wgpu::RenderPipeline),
    Compute { visibility: wgpu::RenderPipeline, shade: wgpu::ComputePipeline },
}

/// The vertex buffer layout of `ObjectVertex`: position, normal, colour (Float32x3 each).
pub const OBJECT_VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<ObjectVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3],
};

/// The stage's pipelines, one set per entry pair.
pub struct ObjectsStage {
    pipelines: [EntryPipelines; 3],
    /// Group 0: the frame's uniforms, the displacement map and its sampler, the shadow map,
    /// the floor's relief and its sampler.
    pub frame_layout: wgpu::BindGroupLayout,
    /// Group 1 of the compute path: the visibility buffer and the target as storage.
    vis_layout: wgpu::BindGroupLayout,
    wrap_linear: wgpu::Sampler,
    clamp_linear: wgpu::Sampler,
}

impl ObjectsStage {
    /// Creates the pipelines `"ocean.objects"` (one set per entry pair), drawing into colour
    /// buffers of `target` format (the frame's: its HDR frame, reflection and refraction maps),
    /// on `path`.
    ///
    /// # Errors
    /// [`Error::Core`] if the WGSL cannot be assembled.
    pub fn new(
        device: &wgpu::Device,
        target: wgpu::TextureFormat,
        path: ShadingPath,
    ) -> Result<Self, Error> {
        let name = label("objects");
        let module =
            frame_storage_module(device, "objects", &crate::common::pipeline_techniques(), target)?;
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let fragment = wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let frame_layout = device.new_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&name),
            entries: &[
                uniform_entry(0, vf),
                texture_entry(1, fragment, true),
                sampler_entry(2, fragment),
                texture_entry(3, fragment, false),
                texture_entry(4, fragment, true),
                sampler_entry(5, fragment),
            ],
        });
        let vis_layout = visibility_layout(device, "ocean.objects.visibility", target);
        // The CPU mirror's WRAP_LINEAR and CLAMP_LINEAR (the water's samplers).
        let wrap_linear =
            linear_sampler(device, "ocean.objects.wrap_linear", wgpu::AddressMode::Repeat);
        let clamp_linear =
            linear_sampler(device, "ocean.objects.clamp_linear", wgpu::AddressMode::ClampToEdge);
        let layout = pipeline_layout(device, &name, &[&frame_layout]);
        let shade_layout = pipeline_layout(device, &name, &[&frame_layout, &vis_layout]);
        let shaded = replace_target(target);
        let visibility_targets = visibility_color_targets();
        let raster = |vs: &str, fs: &str, targets: &[Option<wgpu::ColorTargetState>]| {
            let (vs, fs) = (entry("objects", vs)?, entry("objects", fs)?);
            Ok::<_, Error>(device.new_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&name),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[Some(OBJECT_VERTEX_LAYOUT)],
                },
                primitive: primitive(),
                depth_stencil: Some(eye_depth()),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets,
                }),
                multiview_mask: None,
                cache: None,
            }))
        };
        let pipelines = |which: ObjectsEntry| -> Result<EntryPipelines, Error> {
            let [vs, fs, fs_vis, cs] = which.entry_points();
            Ok(match path {
                ShadingPath::Fragment => EntryPipelines::Fragment(raster(vs, fs, &shaded)?),
                ShadingPath::Compute => EntryPipelines::Compute {
                    visibility: raster(vs, fs_vis, &visibility_targets)?,
                    shade: device.new_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(&name),
                        layout: Some(&shade_layout),
                        module: &module,
                        entry_point: Some(entry("objects", cs)?),
                        compilation_options: Default::default(),
                        cache: None,
                    }),
                },
            })
        };
        Ok(Self {
            pipelines: [
                pipelines(ObjectsEntry::Main)?,
                pipelines(ObjectsEntry::Reflect)?,
                pipelines(ObjectsEntry::Refract)?,
            ],
            frame_layout,
            vis_layout,
            wrap_linear,
            clamp_linear,
        })
    }

    /// Group 0 of every pass: the frame's uniforms, the displacement map under the
    /// fragments for the exact-height clipping of shading `chiu`, and the shadow map and the
    /// floor's relief for the sun under the water.
    pub fn group(
        &self,
        kept: &crate::pool::FramePool,
        frame: &wgpu::Buffer,
        displacement: &wgpu::TextureView,
        shadow_map: &wgpu::TextureView,
        floor_map: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        kept.bind_group(
            "ocean.objects",
            &self.frame_layout,
            &[
                frame.as_entire_binding(),
                wgpu::BindingResource::TextureView(displacement),
                wgpu::BindingResource::Sampler(&self.wrap_linear),
                wgpu::BindingResource::TextureView(shadow_map),
                wgpu::BindingResource::TextureView(floor_map),
                wgpu::BindingResource::Sampler(&self.clamp_linear),
            ],
        )
    }

    /// Records one pass drawing every chunk of `vertices` with `entry` into
    /// `target`/`depth` (`size`: the target's). The reflection and refraction maps start
    /// cleared (colour 0, depth 0); the main view draws over the sky (its colour kept, its
    /// depth cleared by the first pass after the sky, as `load.1` says). On the
    /// compute path: the target's clear (where asked), the raster pass into the visibility
    /// buffer (kept in `kept`) and the shading into `target`, timed as one span.
    #[expect(clippy::too_many_arguments, reason = "one argument per binding and attachment")]
    pub fn encode(
        &self,
        kept: &crate::pool::FramePool,
        encoder: &mut wgpu::CommandEncoder,
        entry: ObjectsEntry,
        frame: &wgpu::BindGroup,
        vertices: &[VertexChunk],
        (target, size): (&wgpu::TextureView, [u32; 2]),
        depth: &wgpu::TextureView,
        load: (Load<[f32; 4]>, Load<f32>),
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let draw = |pass: &mut wgpu::RenderPass<'_>, pipeline: &wgpu::RenderPipeline| {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, frame, &[]);
            for chunk in vertices {
                pass.set_vertex_buffer(0, chunk.buffer.slice(..));
                pass.draw(0..chunk.count, 0..1);
            }
        };
        match &self.pipelines[entry.index()] {
            EntryPipelines::Fragment(pipeline) => {
                let mut pass = begin_render_pass(
                    encoder,
                    "ocean.objects",
                    target,
                    load.0,
                    Some((depth, load.1)),
                    timestamps,
                );
                draw(&mut pass, pipeline);
            }
            EntryPipelines::Compute { visibility, shade } => {
                let (raster_ts, shade_ts) = split_timestamps(timestamps);
                // A clear the shading does not store itself is a pass of its own.
                if let Load::Clear(c) = load.0
                    && entry.stored_where_undrawn() != Some(c)
                {
                    drop(begin_render_pass(
                        encoder,
                        "ocean.objects.clear",
                        target,
                        load.0,
                        None,
                        None,
                    ));
                }
                let vis = visibility_targets(kept, OBJECTS_VISIBILITY, size);
                {
                    let mut pass = begin_visibility_pass(
                        encoder,
                        "ocean.objects.visibility",
                        &vis,
                        (depth, load.1),
                        raster_ts,
                    );
                    draw(&mut pass, visibility);
                }
                let shading = Shading { vis: &vis, target, size, layout: &self.vis_layout };
                encode_shading(
                    kept,
                    encoder,
                    "ocean.objects.shade",
                    (shade, &[frame]),
                    &shading,
                    shade_ts,
                );
            }
        }
    }
}

/// One vertex buffer of the objects' triangles and how many vertices it holds. The triangles
/// are cut into buffers no larger than the device's `max_buffer_size`, drawn in order in one
/// pass, so any number of objects that fits the memory limit draws the same picture.
#[derive(Clone)]
pub struct VertexChunk {
    /// Whole triangles of [`ocean_core::frame::ObjectVertex`].
    pub buffer: wgpu::Buffer,
    /// Vertices in `buffer` (a multiple of 3; 0 for the one-vertex placeholder).
    pub count: u32,
}

/// Vertex buffers of at most `max_bytes` each holding `vertices` (whole triangles), or one
/// placeholder vertex when there are none (a buffer cannot be empty), in the pool's buffers
/// of `label`.
pub fn labelled_vertex_chunks(
    kept: &crate::pool::FramePool,
    label: &str,
    vertices: &[ocean_core::frame::ObjectVertex],
    max_bytes: u64,
) -> Vec<VertexChunk> {
    let triangle = 3 * std::mem::size_of::<ocean_core::frame::ObjectVertex>() as u64;
    // u32 vertex counts bound a draw too.
    let per_chunk = (max_bytes / triangle).clamp(1, u64::from(u32::MAX / 3)) as usize * 3;
    let placeholder = [bytemuck::Zeroable::zeroed()];
    let chunks: Vec<&[ocean_core::frame::ObjectVertex]> = if vertices.is_empty() {
        vec![&placeholder[..]]
    } else {
        vertices.chunks(per_chunk).collect()
    };
    chunks
        .into_iter()
        .map(|c| VertexChunk {
            buffer: kept.data(label, wgpu::BufferUsages::VERTEX, bytemuck::cast_slice(c)),
            count: if vertices.is_empty() { 0 } else { c.len() as u32 },
        })
        .collect()
}

/// The object passes' vertex buffers, kept across frames while what they hold is what would be
/// made again ([`ocean_core::frame::ObjectsKey`]): a still camera over still objects builds and
/// uploads each pass's triangles once, and the passes of a frame that draw the same objects
/// build them once. Each pass writes only its own buffers (a label of its own in the pool), so
/// a pass whose objects change never overwrites what another pass keeps.
#[derive(Default)]
pub struct KeptObjects {
    /// Per object pass: the key of what its buffers hold, the size they were cut to, the
    /// buffers.
    slots: Vec<(ocean_core::plan::Pass, ObjectsKey, u64, Vec<VertexChunk>)>,
    /// The last list built and its key.
    built: (ObjectsKey, Vec<[ObjectVertex; 3]>),
    /// This call's key (its allocation kept).
    key: ObjectsKey,
}

/// What a pass's objects are drawn from: the scene, the boats' poses, the eye.
pub struct ObjectsSource<'a> {
    /// The validated scene.
    pub scene: &'a ocean_core::scene::Scene,
    /// The boats' poses this frame.
    pub poses: &'a ocean_core::frame::ObjectPoses,
    /// The eye (the triangles are relative to it).
    pub eye: glam::DVec3,
}

impl KeptObjects {
    /// The vertex buffers of `pass`'s objects (`ocean_core::frame::pass_object_triangles`),
    /// cut at `max_bytes`: the kept ones while their key holds, else made and uploaded.
    pub fn chunks(
        &mut self,
        kept: &crate::pool::FramePool,
        from: &ObjectsSource<'_>,
        pass: &ocean_core::plan::PlannedPass,
        max_bytes: u64,
    ) -> Vec<VertexChunk> {
        self.key.set(from.scene, from.poses, pass, from.eye);
        let slot = self.slots.iter().find(|s| s.0 == pass.name);
        if let Some((_, key, cut, chunks)) = slot
            && *key == self.key
            && *cut == max_bytes
        {
            return chunks.clone();
        }
        if self.built.0 != self.key {
            self.built.1 =
                ocean_core::frame::pass_object_triangles(from.scene, from.poses, pass, from.eye);
            self.built.0.clone_from(&self.key);
        }
        let chunks = labelled_vertex_chunks(
            kept,
            pass_vertices_label(pass.name),
            bytemuck::cast_slice(&self.built.1),
            max_bytes,
        );
        self.slots.retain(|s| s.0 != pass.name);
        self.slots.push((pass.name, self.key.clone(), max_bytes, chunks.clone()));
        chunks
    }
}

/// The pool label of an object pass's vertex buffers.
fn pass_vertices_label(pass: ocean_core::plan::Pass) -> &'static str {
    use ocean_core::plan::Pass;
    match pass {
        Pass::ShadowMap => "ocean.shadow_map.object_vertices",
        Pass::ReflectionMap => "ocean.reflection_map.object_vertices",
        Pass::RefractionMap => "ocean.refraction_map.object_vertices",
        _ => "ocean.objects.vertices",
    }
}

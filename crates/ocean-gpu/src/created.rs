//! Every GPU object this crate makes, counted: the `new_*` methods of [`Counted`] stand in for
//! wgpu's `create_*` (the source test `tests/gpu_objects.rs` fails on a `create_*` call
//! anywhere else in the crate), so that [`created`] tells how many textures, buffers, bind
//! groups … a stretch of frames made. A steady frame of [`crate::Renderer`] makes none
//! (`tests/gpu_hygiene.rs`). The counts are the calling thread's (a renderer makes its objects
//! on the thread that calls it), so tests on other threads do not disturb them.

use std::cell::Cell;

use wgpu::util::DeviceExt;

/// How many GPU objects of each kind the crate has made so far on this thread, and how many
/// uniform-block and vertex/index uploads it has issued ([`crate::pool::FramePool::uniform`],
/// [`crate::pool::FramePool::data`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ObjectCounts {
    /// Textures.
    pub textures: u64,
    /// Texture views.
    pub views: u64,
    /// Buffers.
    pub buffers: u64,
    /// Bind groups.
    pub bind_groups: u64,
    /// Timestamp query sets.
    pub query_sets: u64,
    /// Samplers.
    pub samplers: u64,
    /// Pipelines, pipeline and bind-group layouts, shader modules.
    pub pipelines: u64,
    /// `Queue::write_buffer` calls of uniform blocks (not an object: the uploads).
    pub uniform_writes: u64,
    /// `Queue::write_buffer` calls of vertex and index lists (the objects', the floor's, the
    /// water mesh's): none in a frame whose lists are the kept ones.
    pub data_writes: u64,
}

impl ObjectCounts {
    /// What was made between `earlier` and `self`.
    #[must_use]
    pub fn since(self, earlier: Self) -> Self {
        Self {
            textures: self.textures - earlier.textures,
            views: self.views - earlier.views,
            buffers: self.buffers - earlier.buffers,
            bind_groups: self.bind_groups - earlier.bind_groups,
            query_sets: self.query_sets - earlier.query_sets,
            samplers: self.samplers - earlier.samplers,
            pipelines: self.pipelines - earlier.pipelines,
            uniform_writes: self.uniform_writes - earlier.uniform_writes,
            data_writes: self.data_writes - earlier.data_writes,
        }
    }

    /// Objects of every kind together (uploads are not objects).
    pub fn objects(&self) -> u64 {
        self.textures
            + self.views
            + self.buffers
            + self.bind_groups
            + self.query_sets
            + self.samplers
            + self.pipelines
    }
}

impl std::fmt::Display for ObjectCounts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} textures, {} views, {} buffers, {} bind groups, {} query sets, {} samplers, \
             {} pipeline objects; {} uniform uploads, {} vertex/index uploads",
            self.textures,
            self.views,
            self.buffers,
            self.bind_groups,
            self.query_sets,
            self.samplers,
            self.pipelines,
            self.uniform_writes,
            self.data_writes
        )
    }
}

#[derive(Clone, Copy)]
enum Kind {
    Texture,
    View,
    Buffer,
    BindGroup,
    QuerySet,
    Sampler,
    Pipeline,
    UniformWrite,
    DataWrite,
}

thread_local! {
    static COUNTS: Cell<[u64; 9]> = const { Cell::new([0; 9]) };
}

fn count(kind: Kind) {
    COUNTS.with(|c| {
        let mut n = c.get();
        n[kind as usize] += 1;
        c.set(n);
    });
}

pub(crate) fn count_uniform_write() {
    count(Kind::UniformWrite);
}

pub(crate) fn count_data_write() {
    count(Kind::DataWrite);
}

/// The counts so far on this thread.
pub fn created() -> ObjectCounts {
    let n = COUNTS.with(Cell::get);
    let c = |k: Kind| n[k as usize];
    ObjectCounts {
        textures: c(Kind::Texture),
        views: c(Kind::View),
        buffers: c(Kind::Buffer),
        bind_groups: c(Kind::BindGroup),
        query_sets: c(Kind::QuerySet),
        samplers: c(Kind::Sampler),
        pipelines: c(Kind::Pipeline),
        uniform_writes: c(Kind::UniformWrite),
        data_writes: c(Kind::DataWrite),
    }
}

/// wgpu's `Device::create_*`, counted.
pub trait Counted {
    /// `create_texture`.
    fn new_texture(&self, desc: &wgpu::TextureDescriptor<'_>) -> wgpu::Texture;
    /// `create_buffer`.
    fn new_buffer(&self, desc: &wgpu::BufferDescriptor<'_>) -> wgpu::Buffer;
    /// `create_buffer_init`.
    fn new_buffer_init(&self, desc: &wgpu::util::BufferInitDescriptor<'_>) -> wgpu::Buffer;
    /// `create_bind_group`.
    fn new_bind_group(&self, desc: &wgpu::BindGroupDescriptor<'_>) -> wgpu::BindGroup;
    /// `create_query_set`.
    fn new_query_set(&self, desc: &wgpu::QuerySetDescriptor<'_>) -> wgpu::QuerySet;
    /// `create_sampler`.
    fn new_sampler(&self, desc: &wgpu::SamplerDescriptor<'_>) -> wgpu::Sampler;
    /// `create_render_pipeline`.
    fn new_render_pipeline(
        &self,
        desc: &wgpu::RenderPipelineDescriptor<'_>,
    ) -> wgpu::RenderPipeline;
    /// `create_compute_pipeline`.
    fn new_compute_pipeline(
        &self,
        desc: &wgpu::ComputePipelineDescriptor<'_>,
    ) -> wgpu::ComputePipeline;
    /// `create_shader_module`.
    fn new_shader_module(&self, desc: wgpu::ShaderModuleDescriptor<'_>) -> wgpu::ShaderModule;
    /// `create_bind_group_layout`.
    fn new_bind_group_layout(
        &self,
        desc: &wgpu::BindGroupLayoutDescriptor<'_>,
    ) -> wgpu::BindGroupLayout;
    /// `create_pipeline_layout`.
    fn new_pipeline_layout(
        &self,
        desc: &wgpu::PipelineLayoutDescriptor<'_>,
    ) -> wgpu::PipelineLayout;
}

impl Counted for wgpu::Device {
    fn new_texture(&self, desc: &wgpu::TextureDescriptor<'_>) -> wgpu::Texture {
        count(Kind::Texture);
        self.create_texture(desc)
    }
    fn new_buffer(&self, desc: &wgpu::BufferDescriptor<'_>) -> wgpu::Buffer {
        count(Kind::Buffer);
        self.create_buffer(desc)
    }
    fn new_buffer_init(&self, desc: &wgpu::util::BufferInitDescriptor<'_>) -> wgpu::Buffer {
        count(Kind::Buffer);
        self.create_buffer_init(desc)
    }
    fn new_bind_group(&self, desc: &wgpu::BindGroupDescriptor<'_>) -> wgpu::BindGroup {
        count(Kind::BindGroup);
        self.create_bind_group(desc)
    }
    fn new_query_set(&self, desc: &wgpu::QuerySetDescriptor<'_>) -> wgpu::QuerySet {
        count(Kind::QuerySet);
        self.create_query_set(desc)
    }
    fn new_sampler(&self, desc: &wgpu::SamplerDescriptor<'_>) -> wgpu::Sampler {
        count(Kind::Sampler);
        self.create_sampler(desc)
    }
    fn new_render_pipeline(
        &self,
        desc: &wgpu::RenderPipelineDescriptor<'_>,
    ) -> wgpu::RenderPipeline {
        count(Kind::Pipeline);
        self.create_render_pipeline(desc)
    }
    fn new_compute_pipeline(
        &self,
        desc: &wgpu::ComputePipelineDescriptor<'_>,
    ) -> wgpu::ComputePipeline {
        count(Kind::Pipeline);
        self.create_compute_pipeline(desc)
    }
    fn new_shader_module(&self, desc: wgpu::ShaderModuleDescriptor<'_>) -> wgpu::ShaderModule {
        count(Kind::Pipeline);
        self.create_shader_module(desc)
    }
    fn new_bind_group_layout(
        &self,
        desc: &wgpu::BindGroupLayoutDescriptor<'_>,
    ) -> wgpu::BindGroupLayout {
        count(Kind::Pipeline);
        self.create_bind_group_layout(desc)
    }
    fn new_pipeline_layout(
        &self,
        desc: &wgpu::PipelineLayoutDescriptor<'_>,
    ) -> wgpu::PipelineLayout {
        count(Kind::Pipeline);
        self.create_pipeline_layout(desc)
    }
}

/// wgpu's `Texture::create_view`, counted.
pub trait CountedView {
    /// `create_view`.
    fn new_view(&self, desc: &wgpu::TextureViewDescriptor<'_>) -> wgpu::TextureView;
}

impl CountedView for wgpu::Texture {
    fn new_view(&self, desc: &wgpu::TextureViewDescriptor<'_>) -> wgpu::TextureView {
        count(Kind::View);
        self.create_view(desc)
    }
}

//! The frame's GPU objects, kept from one frame to the next: after the first frame a steady
//! frame of [`crate::Renderer`] makes no texture, buffer, bind group or query set
//! (`tests/gpu_hygiene.rs` counts them with [`crate::created`]).
//!
//! Each request names what it wants (a label and a description); the `n`-th request of a
//! label in a frame gets the object the `n`-th request of that label got in the frames before,
//! when its description still matches, else a new one. So a frame asks for what it needs, in
//! its own order, and the plan's sizes decide when a target is made again (a resize); objects
//! no frame asked for lately are let go ([`KEEP_TARGETS`], [`KEEP_SMALL`]).
//!
//! Uniform blocks are written through `Queue::write_buffer` only when their bytes change, and
//! a block asked for twice in a frame with the same bytes under the same label (the sky's, read
//! by passes `sky` and `water`) is one buffer, uploaded once. `write_buffer` takes effect at the
//! next submission, before its command buffers: a frame's uniforms must be submitted before
//! the next frame of the same renderer is recorded (every path of this crate does so; an
//! embedding program that records two frames of one [`crate::EmbeddedOcean`] into one encoder
//! would see the second frame's uniforms in both).

use std::collections::HashMap;
use std::num::NonZeroU64;
use std::sync::{Arc, Mutex};

use crate::created::Counted;
use crate::texture::GpuMipChain;
use crate::texture::GpuTexture;

/// Frames a render target, depth buffer or mip chain is kept after the last frame that asked
/// for it: a resize lets the old sizes go two frames later.
pub const KEEP_TARGETS: u64 = 2;
/// Frames a buffer or bind group is kept after the last frame that asked for it: long enough
/// that a pass whose step count varies (foam, spray) keeps its spares.
pub const KEEP_SMALL: u64 = 16;

#[derive(Clone, PartialEq, Eq)]
struct TextureKey {
    label: String,
    n: u32,
    size: [u32; 2],
    levels: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
}

impl TextureKey {
    /// Whether this is the key of these fields (compared without making a key).
    fn is(
        &self,
        label: &str,
        n: u32,
        size: [u32; 2],
        levels: u32,
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> bool {
        self.n == n
            && self.size == size
            && self.levels == levels
            && self.format == format
            && self.usage == usage
            && self.label == label
    }
}

#[derive(Clone, PartialEq, Eq)]
enum Resource {
    Buffer(wgpu::Buffer, u64, Option<NonZeroU64>),
    View(wgpu::TextureView),
    Sampler(wgpu::Sampler),
}

#[derive(Clone, PartialEq, Eq)]
struct GroupKey {
    layout: wgpu::BindGroupLayout,
    resources: Vec<(u32, Resource)>,
}

impl Resource {
    /// The kept form of a binding (`None` for the kinds the pool does not keep).
    fn of(r: &wgpu::BindingResource<'_>) -> Option<Resource> {
        Some(match r {
            wgpu::BindingResource::Buffer(b) => {
                Resource::Buffer(b.buffer.clone(), b.offset, b.size)
            }
            wgpu::BindingResource::TextureView(v) => Resource::View((*v).clone()),
            wgpu::BindingResource::Sampler(s) => Resource::Sampler((*s).clone()),
            _ => return None,
        })
    }

    /// Whether `r` is this binding (compared without cloning its handles).
    fn is(&self, r: &wgpu::BindingResource<'_>) -> bool {
        match (self, r) {
            (Resource::Buffer(buffer, offset, size), wgpu::BindingResource::Buffer(b)) => {
                *buffer == *b.buffer && *offset == b.offset && *size == b.size
            }
            (Resource::View(view), wgpu::BindingResource::TextureView(v)) => view == *v,
            (Resource::Sampler(sampler), wgpu::BindingResource::Sampler(s)) => sampler == *s,
            _ => false,
        }
    }
}

impl GroupKey {
    /// Whether this is the key of `layout` with `resources`.
    fn is(
        &self,
        layout: &wgpu::BindGroupLayout,
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> bool {
        self.layout == *layout
            && self.resources.len() == resources.len()
            && self.resources.iter().zip(resources).all(|((i, kept), (j, r))| i == j && kept.is(r))
    }
}

struct Slot<K, V> {
    key: K,
    value: V,
    used: u64,
}

struct KeptBuffer {
    label: String,
    n: u32,
    usage: wgpu::BufferUsages,
    buffer: wgpu::Buffer,
    /// A uniform block's bytes as last written (empty for vertex and index data).
    bytes: Vec<u8>,
    used: u64,
}

#[derive(Default)]
struct Inner {
    frame: u64,
    /// Requests per label in this frame, by kind (kept from frame to frame, so that a steady
    /// frame's requests allocate nothing).
    uses: HashMap<String, [u32; 3]>,
    textures: Vec<Slot<TextureKey, GpuTexture>>,
    chains: Vec<Slot<TextureKey, GpuMipChain>>,
    buffers: Vec<KeptBuffer>,
    groups: Vec<Slot<GroupKey, wgpu::BindGroup>>,
}

impl Inner {
    fn next(&mut self, kind: u8, label: &str) -> u32 {
        let counts = match self.uses.get_mut(label) {
            Some(c) => c,
            None => self.uses.entry(label.to_owned()).or_default(),
        };
        let n = &mut counts[usize::from(kind)];
        *n += 1;
        *n - 1
    }
}

/// The objects one renderer's frames reuse (a handle: clones share them).
#[derive(Clone)]
pub struct FramePool {
    device: wgpu::Device,
    queue: wgpu::Queue,
    inner: Arc<Mutex<Inner>>,
}

const TEXTURE: u8 = 0;
const CHAIN: u8 = 1;
const BUFFER: u8 = 2;

impl FramePool {
    /// An empty pool on `device`, writing through `queue`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self { device: device.clone(), queue: queue.clone(), inner: Arc::default() }
    }

    /// The device the objects are made on.
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Inner> {
        // A panic while the lock was held left nothing half-made: every entry is pushed whole.
        self.inner.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Starts a frame: requests count from zero again, and what no recent frame asked for is
    /// let go.
    pub fn begin_frame(&self) {
        let mut g = self.lock();
        g.frame += 1;
        // Labels the last frame did not use are let go; the others count from zero again.
        g.uses.retain(|_, n| *n != [0; 3]);
        g.uses.values_mut().for_each(|n| *n = [0; 3]);
        let frame = g.frame;
        let fresh = |used: u64, keep: u64| used + keep >= frame;
        g.textures.retain(|s| fresh(s.used, KEEP_TARGETS));
        g.chains.retain(|s| fresh(s.used, KEEP_TARGETS));
        g.buffers.retain(|b| fresh(b.used, KEEP_SMALL));
        g.groups.retain(|s| fresh(s.used, KEEP_SMALL));
    }

    /// How many objects the pool holds (textures and chains, buffers, bind groups).
    pub fn held(&self) -> [usize; 3] {
        let g = self.lock();
        [g.textures.len() + g.chains.len(), g.buffers.len(), g.groups.len()]
    }

    /// A `width × height` texture of `format` and `usage` (contents as the last frame left
    /// them, or zero when new) and whether it is new.
    pub fn texture(
        &self,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> (GpuTexture, bool) {
        let mut g = self.lock();
        let n = g.next(TEXTURE, label);
        let frame = g.frame;
        if let Some(s) =
            g.textures.iter_mut().find(|s| s.key.is(label, n, [width, height], 1, format, usage))
        {
            s.used = frame;
            return (s.value.clone(), false);
        }
        let key = TextureKey {
            label: label.to_owned(),
            n,
            size: [width, height],
            levels: 1,
            format,
            usage,
        };
        let value = GpuTexture::new(&self.device, label, width, height, format, usage);
        g.textures.push(Slot { key, value: value.clone(), used: frame });
        (value, true)
    }

    /// A 1×1 `Rgba32Float` map of zeros (what a skipped pass's map reads as).
    pub fn empty_map(&self, label: &str) -> GpuTexture {
        let (t, new) =
            self.texture(label, 1, 1, crate::texture::MAP_FORMAT, crate::texture::map_usage());
        if new {
            self.queue.write_texture(
                t.texture.as_image_copy(),
                &[0u8; 16],
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(16),
                    rows_per_image: Some(1),
                },
                wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
            );
        }
        t
    }

    /// A mip chain of `count` levels from `width × height`, in `format`.
    pub fn chain(
        &self,
        label: &str,
        width: u32,
        height: u32,
        count: u32,
        format: wgpu::TextureFormat,
    ) -> GpuMipChain {
        let mut g = self.lock();
        let n = g.next(CHAIN, label);
        let usage = crate::texture::map_usage();
        let frame = g.frame;
        if let Some(s) =
            g.chains.iter_mut().find(|s| s.key.is(label, n, [width, height], count, format, usage))
        {
            s.used = frame;
            return s.value.clone();
        }
        let key = TextureKey {
            label: label.to_owned(),
            n,
            size: [width, height],
            levels: count,
            format,
            usage,
        };
        let value = GpuMipChain::with_format(&self.device, label, width, height, count, format);
        g.chains.push(Slot { key, value: value.clone(), used: frame });
        value
    }

    /// A uniform buffer holding `value`: uploaded only when its bytes differ from what the
    /// buffer holds, and shared with an earlier request of this frame under the same label
    /// with the same bytes.
    pub fn uniform<T: bytemuck::Pod>(&self, label: &str, value: &T) -> wgpu::Buffer {
        let bytes = bytemuck::bytes_of(value);
        let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let mut g = self.lock();
        let frame = g.frame;
        if let Some(b) = g
            .buffers
            .iter()
            .find(|b| b.used == frame && b.usage == usage && b.label == label && b.bytes == bytes)
        {
            return b.buffer.clone();
        }
        let n = g.next(BUFFER, label);
        let found = g.buffers.iter_mut().find(|b| {
            b.label == label && b.n == n && b.usage == usage && b.bytes.len() == bytes.len()
        });
        if let Some(b) = found {
            b.used = frame;
            if b.bytes != bytes {
                self.queue.write_buffer(&b.buffer, 0, bytes);
                crate::created::count_uniform_write();
                b.bytes.copy_from_slice(bytes);
            }
            return b.buffer.clone();
        }
        let buffer = self.device.new_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage,
        });
        crate::created::count_uniform_write();
        g.buffers.push(KeptBuffer {
            label: label.to_owned(),
            n,
            usage,
            buffer: buffer.clone(),
            bytes: bytes.to_vec(),
            used: frame,
        });
        buffer
    }

    /// A buffer of `usage` (vertex, index) holding `bytes` from offset 0 (a multiple of 4
    /// bytes; the buffer may be longer, so draw by count), written each frame; made again only
    /// when `bytes` outgrow it (to the next power of two).
    pub fn data(&self, label: &str, usage: wgpu::BufferUsages, bytes: &[u8]) -> wgpu::Buffer {
        let len = (bytes.len() as u64).max(4);
        let buffer = self.keep_buffer(
            label,
            usage | wgpu::BufferUsages::COPY_DST,
            |size| size >= len,
            len.next_power_of_two(),
        );
        if !bytes.is_empty() {
            self.queue.write_buffer(&buffer, 0, bytes);
            crate::created::count_data_write();
        }
        buffer
    }

    /// This frame's next request of a `usage` buffer under `label`: the buffer the same request
    /// got before while `fits` its size, else a new one of `size` bytes (replacing it).
    fn keep_buffer(
        &self,
        label: &str,
        usage: wgpu::BufferUsages,
        fits: impl Fn(u64) -> bool,
        size: u64,
    ) -> wgpu::Buffer {
        let mut g = self.lock();
        let frame = g.frame;
        let n = g.next(BUFFER, label);
        let same = |b: &KeptBuffer| b.label == label && b.n == n && b.usage == usage;
        if let Some(b) = g.buffers.iter_mut().find(|b| same(b) && fits(b.buffer.size())) {
            b.used = frame;
            return b.buffer.clone();
        }
        g.buffers.retain(|b| !same(b));
        let buffer = self.device.new_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage,
            mapped_at_creation: false,
        });
        g.buffers.push(KeptBuffer {
            label: label.to_owned(),
            n,
            usage,
            buffer: buffer.clone(),
            bytes: Vec::new(),
            used: frame,
        });
        buffer
    }

    /// A readback buffer of exactly `size` bytes (`COPY_DST | MAP_READ`): the one this request
    /// got in earlier frames, which their reads unmapped ([`crate::readback::Readbacks`] lets
    /// every staging buffer go, [`Self::drop_staging`], when a read fails), else a new one.
    pub fn staging(&self, label: &str, size: u64) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ;
        self.keep_buffer(label, usage, |s| s == size, size)
    }

    /// Lets every readback buffer go (one may still be mapped after a failed read).
    pub fn drop_staging(&self) {
        let staging = wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ;
        self.lock().buffers.retain(|b| b.usage != staging);
    }

    /// A bind group of `resources` in binding order 0, 1, 2, … on `layout`: the one made for
    /// the same layout and the same objects in an earlier frame, else a new one.
    pub fn bind_group(
        &self,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        resources: &[wgpu::BindingResource<'_>],
    ) -> wgpu::BindGroup {
        let numbered: Vec<(u32, wgpu::BindingResource<'_>)> =
            resources.iter().enumerate().map(|(i, r)| (i as u32, r.clone())).collect();
        self.bind_group_numbered(label, layout, &numbered)
    }

    /// [`Self::bind_group`] with each resource's binding number given.
    pub fn bind_group_numbered(
        &self,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        resources: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let mut g = self.lock();
        let frame = g.frame;
        if let Some(s) = g.groups.iter_mut().find(|s| s.key.is(layout, resources)) {
            s.used = frame;
            return s.value.clone();
        }
        let key = resources
            .iter()
            .map(|(i, r)| Some((*i, Resource::of(r)?)))
            .collect::<Option<Vec<_>>>()
            .map(|resources| GroupKey { layout: layout.clone(), resources });
        let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
            .iter()
            .map(|(i, r)| wgpu::BindGroupEntry { binding: *i, resource: r.clone() })
            .collect();
        let group = self.device.new_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        });
        if let Some(key) = key {
            g.groups.push(Slot { key, value: group.clone(), used: frame });
        }
        group
    }
}

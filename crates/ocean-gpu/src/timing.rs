//! GPU time per pass from timestamp queries (`Features::TIMESTAMP_QUERY`): each compute or
//! render pass of the frame writes a timestamp at its beginning and end; a [`Pass`] made of
//! several GPU passes (two Fresnel tables) gets the sum. Without the feature every call is a
//! no-op and [`PassTimer::finish`] returns nothing.

use crate::created::Counted;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use ocean_core::plan::Pass;

use crate::device::{Error, Gpu};
use crate::readback::{MapState, map_for_reading};
use std::sync::atomic::{AtomicBool, Ordering};

/// Most GPU passes a frame can time (9 plan passes, the Fresnel stage twice).
const MAX_GPU_PASSES: u32 = 16;

/// The timestamp queries of one frame.
pub struct PassTimer {
    queries: Option<Queries>,
    slots: Vec<Pass>,
    home: Option<TimerPool>,
}

/// Most dropped, unread timers a pool waits for (the oldest is let go past it).
const MAX_DRAINING: usize = 8;

/// Query sets and their buffers a renderer keeps: a frame's timer comes back to the pool once
/// its timestamps are read, or once a frame whose timestamps nobody read has dropped them and
/// their buffer has finished mapping, so that a steady frame makes no query set.
#[derive(Clone, Default)]
pub struct TimerPool(Arc<Mutex<Timers>>);

#[derive(Default)]
struct Timers {
    free: Vec<Queries>,
    /// Dropped unread: free again once their readback buffer has mapped.
    draining: Vec<(Queries, MapState)>,
}

impl TimerPool {
    fn take(&self) -> Option<Queries> {
        let mut t = self.0.lock().ok()?;
        if let Some(q) = t.free.pop() {
            return Some(q);
        }
        let done = t
            .draining
            .iter()
            .position(|(_, state)| state.lock().is_ok_and(|s| s.as_ref().is_some()))?;
        let (q, _) = t.draining.swap_remove(done);
        // Mapped or failed, the buffer may be used again once unmapped (unmapping a buffer
        // whose map failed does nothing).
        q.readback.unmap();
        Some(q)
    }

    fn give(&self, q: Queries) {
        if let Ok(mut t) = self.0.lock() {
            t.free.push(q);
        }
    }

    fn drain(&self, q: Queries, state: MapState) {
        if let Ok(mut t) = self.0.lock() {
            // A caller that never polls the device never sees a map end: keep a few, not all.
            if t.draining.len() >= MAX_DRAINING {
                t.draining.remove(0);
            }
            t.draining.push((q, state));
        }
    }
}

#[derive(Clone)]
struct Queries {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f32,
}

impl PassTimer {
    /// A timer for the next frame, made afresh; inert without timestamp support.
    pub fn new(gpu: &Gpu) -> Self {
        Self::from_pool(gpu, &TimerPool::default())
    }

    /// A timer for the next frame, from `pool` when it holds a free one.
    pub fn from_pool(gpu: &Gpu, pool: &TimerPool) -> Self {
        let queries = gpu.timestamps.then(|| pool.take().unwrap_or_else(|| Self::queries(gpu)));
        Self { queries, slots: Vec::new(), home: Some(pool.clone()) }
    }

    fn queries(gpu: &Gpu) -> Queries {
        let count = 2 * MAX_GPU_PASSES;
        let size = u64::from(count) * 8;
        Queries {
            set: gpu.device.new_query_set(&wgpu::QuerySetDescriptor {
                label: Some("ocean.timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: gpu.device.new_buffer(&wgpu::BufferDescriptor {
                label: Some("ocean.timestamps.resolve"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: gpu.device.new_buffer(&wgpu::BufferDescriptor {
                label: Some("ocean.timestamps.readback"),
                size,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            }),
            period_ns: gpu.queue.get_timestamp_period(),
        }
    }

    /// A timer that times nothing: for frames recorded into a caller's encoder
    /// ([`crate::embed`]), whose submission this crate does not see.
    pub fn off() -> Self {
        Self { queries: None, slots: Vec::new(), home: None }
    }

    /// Reserves the begin/end queries of one GPU pass of `pass`; `None` without timestamps
    /// (or beyond the query set's size).
    pub fn slot(&mut self, pass: Pass) -> Option<u32> {
        self.queries.as_ref()?;
        let i = self.slots.len() as u32;
        if i >= MAX_GPU_PASSES {
            return None;
        }
        self.slots.push(pass);
        Some(i)
    }

    /// The timestamp writes of a render pass in `slot`.
    pub fn render_writes(&self, slot: Option<u32>) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let (q, i) = (self.queries.as_ref()?, slot?);
        Some(wgpu::RenderPassTimestampWrites {
            query_set: &q.set,
            beginning_of_pass_write_index: Some(2 * i),
            end_of_pass_write_index: Some(2 * i + 1),
        })
    }

    /// The timestamp writes of a compute pass in `slot`.
    pub fn compute_writes(
        &self,
        slot: Option<u32>,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let (q, i) = (self.queries.as_ref()?, slot?);
        Some(wgpu::ComputePassTimestampWrites {
            query_set: &q.set,
            beginning_of_pass_write_index: Some(2 * i),
            end_of_pass_write_index: Some(2 * i + 1),
        })
    }

    /// Records the resolve of the used queries and their copy to the readback buffer (call
    /// after the last pass, before submitting `encoder`).
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        let Some(q) = &self.queries else { return };
        let n = 2 * self.slots.len() as u32;
        if n == 0 {
            return;
        }
        encoder.resolve_query_set(&q.set, 0..n, &q.resolve, 0);
        encoder.copy_buffer_to_buffer(&q.resolve, 0, &q.readback, 0, u64::from(n) * 8);
    }

    /// GPU time of each timed pass (summed over its GPU passes), in first-timed order. Call
    /// after the submission holding [`Self::resolve`]; waits for the GPU.
    ///
    /// # Errors
    /// [`Error::Readback`] if the query buffer cannot be mapped.
    pub fn finish(self, gpu: &Gpu) -> Result<Vec<(Pass, Duration)>, Error> {
        let Some(pending) = self.finish_later() else { return Ok(Vec::new()) };
        gpu.wait()?;
        pending.try_take().unwrap_or_else(|| {
            Err(Error::Readback {
                what: "timestamps".into(),
                message: "the buffer was not mapped after the wait".into(),
            })
        })
    }

    /// Starts reading the timestamps back without waiting (after the submission holding
    /// [`Self::resolve`]): the real-time viewer collects them a frame or two later, so that
    /// the CPU never waits for the GPU to finish a frame. `None` without timed passes.
    pub fn finish_later(self) -> Option<PendingTimings> {
        let q = self.queries?;
        if self.slots.is_empty() {
            if let Some(home) = &self.home {
                home.give(q);
            }
            return None;
        }
        let bytes = 2 * self.slots.len() as u64 * 8;
        let state = map_for_reading(q.readback.slice(..bytes));
        Some(PendingTimings {
            period_ns: q.period_ns,
            queries: q,
            home: self.home,
            bytes,
            slots: self.slots,
            state,
            returned: AtomicBool::new(false),
        })
    }
}

/// Timestamps on their way back from the GPU ([`PassTimer::finish_later`]).
pub struct PendingTimings {
    queries: Queries,
    home: Option<TimerPool>,
    bytes: u64,
    slots: Vec<Pass>,
    period_ns: f32,
    state: MapState,
    /// Whether the queries went back to the pool when they were read.
    returned: AtomicBool,
}

impl PendingTimings {
    /// The GPU time per pass once the GPU has finished the frame and the device was polled
    /// since (`Device::poll`); `None` before.
    pub fn try_take(&self) -> Option<Result<Vec<(Pass, Duration)>, Error>> {
        let fail = |message: String| Error::Readback { what: "timestamps".into(), message };
        let status = match self.state.lock() {
            Ok(mut s) => s.take()?,
            Err(_) => return Some(Err(fail("poisoned lock".into()))),
        };
        let ticks: Result<Vec<u64>, String> = match status {
            Err(e) => Err(e.to_string()),
            Ok(()) => match self.queries.readback.slice(..self.bytes).get_mapped_range() {
                Ok(view) => Ok(view
                    .chunks_exact(8)
                    .map(|c| u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
                    .collect()),
                Err(e) => Err(e.to_string()),
            },
        };
        // The map has ended either way: the queries can serve another frame.
        self.queries.readback.unmap();
        if let Some(home) = &self.home
            && !self.returned.swap(true, Ordering::Relaxed)
        {
            home.give(self.queries.clone());
        }
        let ticks = match ticks {
            Ok(t) => t,
            Err(e) => return Some(Err(fail(e))),
        };
        let mut out: Vec<(Pass, Duration)> = Vec::new();
        for (i, pass) in self.slots.iter().enumerate() {
            let dt = ticks[2 * i + 1].saturating_sub(ticks[2 * i]);
            let d = Duration::from_nanos((dt as f64 * f64::from(self.period_ns)) as u64);
            match out.iter_mut().find(|(p, _)| p == pass) {
                Some((_, total)) => *total += d,
                None => out.push((*pass, d)),
            }
        }
        Some(Ok(out))
    }
}

impl Drop for PendingTimings {
    /// Timestamps nobody read (a benchmark's frames, a viewer closing) still give their
    /// queries back: the pool hands them out again once their buffer has mapped.
    fn drop(&mut self) {
        if let Some(home) = self.home.take()
            && !self.returned.load(Ordering::Relaxed)
        {
            home.drain(self.queries.clone(), Arc::clone(&self.state));
        }
    }
}

//! `--memory-limit`: the most memory a command's frame may need (estimated from its plan
//! before anything is allocated; `ocean_core::plan::memory`).

use ocean_core::plan::FramePlan;
use ocean_core::plan::memory::{MemoryBackend, MemoryEstimate, default_limit, parse_bytes};
use ocean_core::scene::Scene;

/// `--memory-limit SIZE`, shared by `render` and `compare`.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct MemoryArg {
    /// The most memory the frame may need, e.g. `4G`, `512M` (powers of 1024). Default: three
    /// quarters of the machine's physical memory. A frame whose estimate exceeds it is
    /// refused before any work, naming the scene key that drives the estimate.
    #[arg(long, value_name = "SIZE", value_parser = parse_bytes)]
    pub memory_limit: Option<u64>,
}

impl MemoryArg {
    /// The limit in bytes.
    pub fn limit(&self) -> u64 {
        self.memory_limit.unwrap_or_else(default_limit)
    }

    /// Holds every image the command reads (a heightmap, a dump's maps) to the limit, checked
    /// from its header before it is decoded (`ocean_core::input`).
    pub fn limit_inputs(&self) {
        ocean_core::input::set_decode_budget(self.limit());
    }

    /// Refuses the frame when its estimate on `backends` together exceeds the limit.
    ///
    /// # Errors
    /// The estimate, the limit, the largest item and its key.
    pub fn check(
        &self,
        scene: &Scene,
        plan: &FramePlan,
        backends: &[MemoryBackend],
    ) -> anyhow::Result<()> {
        let mut all = MemoryEstimate { items: Vec::new() };
        for b in backends {
            all.items.extend(MemoryEstimate::of(scene, plan, *b).items);
        }
        let limit = self.limit();
        all.check(limit).map_err(|e| {
            let source = if self.memory_limit.is_some() {
                "given by --memory-limit"
            } else {
                "the default, 3/4 of this machine's memory"
            };
            anyhow::anyhow!("{e} [the limit is {source}]")
        })
    }
}

/// The process's peak resident memory (since it started, or since `ocean bench` reset it),
/// MiB; Linux only.
pub fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

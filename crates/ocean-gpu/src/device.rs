//! Headless device setup: one wgpu instance, adapter, device and queue, no window.
//!
//! Which backend: `WGPU_BACKEND` (e.g. `vulkan`; CI pins it so that wgpu cannot fall back to
//! GL silently), else every backend wgpu was built with. Which adapter: `WGPU_ADAPTER_NAME`
//! (a case-insensitive substring of the adapter's name), else wgpu's default for
//! `WGPU_POWER_PREF`. On a machine without a GPU, Mesa's lavapipe (`mesa-vulkan-drivers`) is
//! a Vulkan adapter that runs every stage on the CPU.
//!
//! Features the frame needs: `FLOAT32_FILTERABLE` (the water stage filters its `Rgba32Float`
//! maps bilinearly, docs/design.md: "intermediate textures use float formats"). `TIMESTAMP_QUERY`
//! is requested when the adapter has it, for GPU time per pass, and `FLOAT32_BLENDABLE` for
//! the spray's additive sprites (pass `spray` is refused without it). Errors never panic: an absent
//! adapter or feature is an [`Error`] that says what to install or to use `--backend cpu`.

use std::fmt;

/// Errors of the GPU back end.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No adapter for the requested backends.
    #[error(
        "no GPU adapter found (WGPU_BACKEND={backend_env}): {reason}. Install Mesa's software \
         Vulkan driver (`apt-get install mesa-vulkan-drivers libvulkan1`) and set \
         WGPU_BACKEND=vulkan, or render with `--backend cpu`"
    )]
    NoAdapter {
        /// The value of `WGPU_BACKEND`, or "unset".
        backend_env: String,
        /// wgpu's explanation.
        reason: String,
    },
    /// The adapter lacks a feature the renderer needs.
    #[error(
        "the GPU adapter {adapter} lacks {feature} ({why}); try another adapter \
         (WGPU_ADAPTER_NAME), Mesa's lavapipe (mesa-vulkan-drivers), or `--backend cpu`"
    )]
    MissingFeature {
        /// The adapter's description.
        adapter: String,
        /// The feature's name.
        feature: &'static str,
        /// What the renderer needs it for.
        why: &'static str,
    },
    /// The adapter refused to open a device.
    #[error("cannot open a device on the GPU adapter {adapter}: {source}")]
    RequestDevice {
        /// The adapter's description.
        adapter: String,
        /// wgpu's error.
        #[source]
        source: wgpu::RequestDeviceError,
    },
    /// wgpu reported an error while `what` ran (a validation error is a bug in this crate; an
    /// out-of-memory error means the image is too large for the adapter).
    #[error("GPU error during {what}: {message}")]
    Wgpu {
        /// What was being done.
        what: String,
        /// wgpu's message.
        message: String,
    },
    /// Reading a texture back failed.
    #[error("cannot read the GPU's {what} back: {message}")]
    Readback {
        /// Which texture.
        what: String,
        /// Why.
        message: String,
    },
    /// The image is larger than the adapter's textures may be.
    #[error(
        "image {width}×{height} exceeds the GPU adapter's largest 2D texture ({max} pixels a side)"
    )]
    TooLarge {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// The adapter's limit.
        max: u32,
    },
    /// A part of the GPU path that does not exist yet.
    #[error("{0}")]
    Unavailable(String),
    /// The scene's physics could not be set up.
    #[error(transparent)]
    Core(#[from] ocean_core::Error),
}

/// What an adapter is, for reports (printed by the tests and `ocean compare`, so that a
/// cross-check always says which implementation it held the CPU against).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdapterReport {
    /// The adapter's name, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub name: String,
    /// The vendor's PCI id as hex ("0x10de" for NVIDIA; lavapipe reports "0x10005", Mesa's).
    pub vendor: String,
    /// The backend, e.g. "Vulkan".
    pub backend: String,
    /// Integrated, discrete, virtual, CPU or other.
    pub device_type: String,
    /// The driver and its version.
    pub driver: String,
    /// Whether the adapter is a software rasterizer on the CPU (lavapipe, SwiftShader, WARP):
    /// docs/design.md's "lavapipe" tolerance row applies, else the hardware row.
    pub is_software: bool,
}

impl AdapterReport {
    fn new(info: &wgpu::AdapterInfo) -> Self {
        Self {
            name: info.name.clone(),
            vendor: format!("{:#x}", info.vendor),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver: format!("{} {}", info.driver, info.driver_info).trim().to_owned(),
            is_software: info.device_type == wgpu::DeviceType::Cpu,
        }
    }
}

impl fmt::Display for AdapterReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({}, {}, driver {})", self.name, self.backend, self.device_type, self.driver)
    }
}

/// An open device: everything the stages create their resources on.
pub struct Gpu {
    /// The adapter the device was opened on.
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// wgpu's description of the adapter.
    pub info: wgpu::AdapterInfo,
    /// The same, for reports.
    pub report: AdapterReport,
    /// Whether timestamp queries were enabled (the adapter has `TIMESTAMP_QUERY`).
    pub timestamps: bool,
}

impl Gpu {
    /// Opens the adapter the environment selects (module doc), headless.
    ///
    /// # Errors
    /// [`Error::NoAdapter`], [`Error::MissingFeature`] or [`Error::RequestDevice`].
    pub fn new() -> Result<Self, Error> {
        pollster::block_on(Self::open())
    }

    /// The renderer's view of a device someone else opened (an embedding program's,
    /// [`crate::embed`]): `adapter` is the one `device` was requested from. The device must
    /// have been requested with [`required_features`] of that adapter (and limits at least
    /// wgpu's defaults).
    ///
    /// # Errors
    /// [`Error::MissingFeature`] when the device lacks `FLOAT32_FILTERABLE`.
    pub fn from_device(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Self, Error> {
        let info = adapter.get_info();
        let report = AdapterReport::new(&info);
        if !device.features().contains(wgpu::Features::FLOAT32_FILTERABLE) {
            return Err(Error::MissingFeature {
                adapter: report.to_string(),
                feature: "FLOAT32_FILTERABLE",
                why: "the water stage filters its Rgba32Float wave, Fresnel and view maps; \
                      request the device with ocean_gpu::device::required_features(&adapter)",
            });
        }
        Ok(Self {
            adapter: adapter.clone(),
            device: device.clone(),
            queue: queue.clone(),
            info,
            report,
            timestamps: device.features().contains(wgpu::Features::TIMESTAMP_QUERY),
        })
    }

    async fn open() -> Result<Self, Error> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        Self::open_on(&instance, None).await
    }

    /// Opens the adapter the environment selects among those that can present to `surface`
    /// (a window's), on `instance`, the instance the surface was made by.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn for_surface(
        instance: &wgpu::Instance,
        surface: &wgpu::Surface<'_>,
    ) -> Result<Self, Error> {
        pollster::block_on(Self::open_on(instance, Some(surface)))
    }

    async fn open_on(
        instance: &wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Self, Error> {
        let adapter = wgpu::util::initialize_adapter_from_env_or_default(instance, surface)
            .await
            .map_err(|e| Error::NoAdapter {
            backend_env: std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "unset".into()),
            reason: e.to_string(),
        })?;
        let info = adapter.get_info();
        let report = AdapterReport::new(&info);
        // The spray's sprites add into the Rgba32Float frame; without FLOAT32_BLENDABLE,
        // pass `spray` is refused (the rest of the frame does not need it).
        let required_features = required_features(&adapter)?;
        let timestamps = required_features.contains(wgpu::Features::TIMESTAMP_QUERY);
        // The adapter's own limits: a 1080p frame and the 1024² shadow map fit the defaults,
        // but larger images may use whatever the adapter allows.
        let required_limits = adapter.limits();
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("ocean"),
                required_features,
                required_limits,
                ..Default::default()
            })
            .await
            .map_err(|source| Error::RequestDevice { adapter: report.to_string(), source })?;
        Ok(Self { adapter, device, queue, info, report, timestamps })
    }

    /// Runs `f` inside validation and out-of-memory error scopes and turns what they caught
    /// into [`Error::Wgpu`] (wgpu would otherwise hand it to the uncaptured-error handler,
    /// which panics).
    pub fn scoped<T>(&self, what: &str, f: impl FnOnce() -> T) -> Result<T, Error> {
        scoped(&self.device, what, f)
    }

    /// Blocks until the queue has finished every submission.
    ///
    /// # Errors
    /// [`Error::Wgpu`] if the device was lost or timed out.
    pub fn wait(&self) -> Result<(), Error> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| Error::Wgpu { what: "waiting for the GPU".into(), message: e.to_string() })
    }
}

/// [`Gpu::scoped`] on any device (a clone of the renderer's, so that `f` may borrow the
/// renderer mutably).
///
/// # Errors
/// [`Error::Wgpu`] with what the scopes caught.
pub fn scoped<T>(device: &wgpu::Device, what: &str, f: impl FnOnce() -> T) -> Result<T, Error> {
    let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = f();
    let errors = [validation.pop(), oom.pop()].map(pollster::block_on);
    match errors.into_iter().flatten().next() {
        None => Ok(value),
        Some(e) => Err(Error::Wgpu { what: what.to_owned(), message: e.to_string() }),
    }
}

/// The features a device must be requested with for the renderer on `adapter`
/// (`FLOAT32_FILTERABLE`), and those it uses where the adapter has them (`FLOAT32_BLENDABLE`
/// for the spray's sprites, `TIMESTAMP_QUERY` for GPU time per pass). An embedding program
/// adds them to its own.
///
/// # Errors
/// [`Error::MissingFeature`] when the adapter lacks `FLOAT32_FILTERABLE`.
pub fn required_features(adapter: &wgpu::Adapter) -> Result<wgpu::Features, Error> {
    let available = adapter.features();
    if !available.contains(wgpu::Features::FLOAT32_FILTERABLE) {
        return Err(Error::MissingFeature {
            adapter: AdapterReport::new(&adapter.get_info()).to_string(),
            feature: "FLOAT32_FILTERABLE",
            why: "the water stage filters its Rgba32Float wave, Fresnel and view maps",
        });
    }
    let optional = wgpu::Features::FLOAT32_BLENDABLE | wgpu::Features::TIMESTAMP_QUERY;
    Ok(wgpu::Features::FLOAT32_FILTERABLE | (available & optional))
}

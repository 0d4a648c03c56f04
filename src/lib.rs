//! The library half of the `ocean` package: what the command line (`src/main.rs`) and the
//! integration tests share.
//!
//! - [`animation`]: the frames, shards and file names of `ocean render --frames`.
//! - [`dump`]: per-pass dumps (`ocean render --dump-passes`, `ocean compare --against`).
//! - [`output`]: atomic output files, PNG/EXR encoding.
//! - [`scene_arg`]: the scene a command renders, and `--system`.
//! - [`verdict`]: the envelope's verdict on a frame a GPU made (`compare`, `selftest`).
//! - [`view`]: `ocean view`, the real-time viewer (winit window, egui panel), with its
//!   window-free parts (camera controller, parameter mapping) testable on their own.

pub mod animation;
pub mod dump;
pub mod memory_arg;
pub mod output;
pub mod scene_arg;
pub mod verdict;
pub mod view;

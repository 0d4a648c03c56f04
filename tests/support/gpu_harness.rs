//! The test harness of the test binaries with tests that need a GPU adapter (and, for the
//! viewer, a display): `harness = false` in the root `Cargo.toml`, `libtest-mimic` for
//! libtest's command line and output (`--exact`, filters, `--skip`, `--list`,
//! `--test-threads`, the `test result: ...` line).
//!
//! One probe at start-up decides whether what the GPU tests need is here. Where it is not,
//! each GPU test is reported `ignored` with the reason (never `ok`), and one line says why and
//! how to enable them; under `OCEAN_REQUIRE_GPU=1` (CI, `.ci/run`) each fails with the reason
//! instead. Tests that need no GPU run as usual.
//!
//! A test binary includes this file with
//! `#[macro_use] #[path = "support/gpu_harness.rs"] mod gpu_harness;` and its `main` is
//! `run_tests!(REQUIREMENT; cpu: a, b; gpu: c)`. libtest-mimic does not
//! capture the tests' output: what they print shows as they run.

use std::process::ExitCode;
use std::sync::Arc;

use libtest_mimic::{Arguments, Completion, Failed, Trial};

/// What a test needs besides the CPU.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Needs {
    /// Nothing: it always runs.
    Cpu,
    /// The binary's [`Requirement`]: without it the test is ignored (a failure under
    /// `OCEAN_REQUIRE_GPU=1`), and its function is not called.
    Gpu,
    /// A part that needs nothing and a part that needs the requirement (the function asks for
    /// the GPU itself and leaves that part out without it): without the requirement the CPU
    /// part runs and, if it passes, the test is reported ignored, as the rest did not run.
    GpuPart,
}

/// A test function of the binary, registered by [`run_tests!`].
pub struct Test {
    name: &'static str,
    run: fn(),
    needs: Needs,
}

impl Test {
    /// A test that needs only the CPU.
    #[allow(dead_code, reason = "only some test binaries have tests without a GPU")]
    pub fn cpu(name: &'static str, run: fn()) -> Self {
        Self { name, run, needs: Needs::Cpu }
    }

    /// A test that needs the binary's [`Requirement`].
    pub fn gpu(name: &'static str, run: fn()) -> Self {
        Self { name, run, needs: Needs::Gpu }
    }

    /// A test with a CPU part and a GPU part ([`Needs::GpuPart`]).
    #[allow(dead_code, reason = "only some test binaries have tests with a GPU part")]
    pub fn gpu_part(name: &'static str, run: fn()) -> Self {
        Self { name, run, needs: Needs::GpuPart }
    }
}

/// `run_tests!(REQUIREMENT; cpu: a, b; gpu: c, d; gpu_part: e)`: runs the binary's test
/// functions, each under its own name, with what it needs (see [`run`]); the exit status.
macro_rules! run_tests {
    ($requirement:expr; $($needs:ident: $($f:ident),+ $(,)?);+ $(;)?) => {
        $crate::gpu_harness::run(
            &$requirement,
            vec![$($($crate::gpu_harness::Test::$needs(stringify!($f), $f)),+),+],
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/", file!())),
        )
    };
}

/// What the GPU tests of a binary need, and how to tell whether this machine has it.
pub struct Requirement {
    /// What it is, for messages ("a GPU adapter").
    pub what: &'static str,
    /// How to get it.
    pub how: &'static str,
    /// `Err(why not)` where it is missing. Called once, before any test runs, and only when a
    /// test that needs it is selected.
    pub probe: fn() -> Result<(), String>,
}

/// A wgpu adapter and device as ocean-gpu opens them ([`adapter`]).
#[allow(dead_code, reason = "tests/view_window.rs has its own requirement")]
pub const GPU_ADAPTER: Requirement = Requirement {
    what: "a GPU adapter",
    how: "install a Vulkan driver (without a GPU, Mesa's lavapipe: apt-get install \
          mesa-vulkan-drivers libvulkan1) and set WGPU_BACKEND=vulkan",
    probe: adapter,
};

/// Whether ocean-gpu gets an adapter and a device with the renderer's features and limits in
/// this environment (`WGPU_BACKEND`, ...), as the renderer and the `ocean` binary ask for it,
/// and whether the tests may use that adapter ([`testable`]).
pub fn adapter() -> Result<(), String> {
    let gpu = ocean_gpu::Gpu::new().map_err(|e| e.to_string())?;
    testable(&gpu.info)
}

/// Whether the GPU tests may run on `info`'s adapter: any backend but wgpu's GL.
///
/// The tests hold the GPU to the CPU oracle with lavapipe's tolerances, and the oracle mirrors
/// a Vulkan (or Metal, DX12) pipeline; an OpenGL adapter such as Mesa's llvmpipe through EGL
/// is at best a different conformant GPU (the envelope's case, not the exact one). And wgpu's
/// GL backend has one context per adapter that the test threads would share: on a machine
/// with only Mesa GL, `tests/gpu_waves.rs` ran on it and failed at random with "Could not lock
/// adapter context. This is most-likely a deadlock." So a GL adapter is "missing", and its
/// tests are ignored with this reason (a failure under `OCEAN_REQUIRE_GPU=1`).
pub fn testable(info: &wgpu::AdapterInfo) -> Result<(), String> {
    if info.backend == wgpu::Backend::Gl {
        return Err(format!(
            "the only adapter is \"{}\" on wgpu's OpenGL backend, which the GPU tests do not \
             use (the oracle's tolerances are for a Vulkan pipeline such as lavapipe's, and \
             one GL context cannot be shared by the test threads)",
            info.name
        ));
    }
    Ok(())
}

/// `OCEAN_REQUIRE_GPU=1`: a missing requirement is a failure (CI).
pub fn gpu_required() -> bool {
    std::env::var_os("OCEAN_REQUIRE_GPU").is_some_and(|v| v == "1")
}

/// The name of this test binary.
const BINARY: &str = env!("CARGO_CRATE_NAME");

/// Runs the binary's `tests` as libtest would, with the command line's arguments, plus one
/// that fails where its `source` has a `#[test]` attribute (in a `harness = false` file it
/// compiles to nothing, and the test would never run). Returns the exit status (101 on a
/// failure, as libtest).
pub fn run(requirement: &Requirement, tests: Vec<Test>, source: &'static str) -> ExitCode {
    let args = Arguments::from_args();
    let selected = tests
        .iter()
        .filter(|t| t.needs != Needs::Cpu)
        .filter(|t| !args.is_filtered_out(&Trial::test(t.name, || Ok(()))))
        .count();
    // `None`: not probed, as no selected test needs it (or `--list`).
    let found: Option<Result<(), String>> =
        (selected > 0 && !args.list).then(|| (requirement.probe)());
    let required = gpu_required();
    let what = requirement.what;
    if let Some(Err(why)) = &found {
        if required {
            eprintln!(
                "{BINARY}: OCEAN_REQUIRE_GPU=1 and {selected} test(s) need {what}; missing \
                 here: {why}. They fail."
            );
        } else {
            eprintln!(
                "{BINARY}: {selected} test(s) need {what} and are IGNORED; missing here: {why}. \
                 To run them: {}. OCEAN_REQUIRE_GPU=1 makes a missing GPU a failure (as in \
                 .ci/run).",
                requirement.how
            );
        }
    }
    let found = Arc::new(found);
    let mut trials: Vec<Trial> = tests
        .into_iter()
        .map(|t| {
            let found = Arc::clone(&found);
            Trial::ignorable_test(t.name, move || outcome(&t, what, required, &found))
        })
        .collect();
    trials.push(Trial::test("every_test_is_registered_with_the_harness", move || {
        let stray: Vec<String> = source
            .lines()
            .enumerate()
            .filter(|(_, l)| l.trim_start().starts_with("#[test]"))
            .map(|(i, _)| format!("line {}", i + 1))
            .collect();
        if stray.is_empty() {
            return Ok(());
        }
        Err(format!(
            "#[test] at {} does nothing in this harness = false file (root Cargo.toml): list \
             the function in `run_tests!` in its main instead",
            stray.join(", ")
        )
        .into())
    }));
    libtest_mimic::run(&args, trials).exit_code()
}

/// Runs one test as its [`Needs`] say, given what the probe found.
fn outcome(
    t: &Test,
    what: &str,
    required: bool,
    found: &Option<Result<(), String>>,
) -> Result<Completion, Failed> {
    let missing = match (t.needs, found) {
        (Needs::Cpu, _) | (_, Some(Ok(()))) => None,
        (_, Some(Err(why))) => Some(why),
        (_, None) => return Err(format!("harness bug: {what} was not probed").into()),
    };
    match (missing, t.needs) {
        (None, _) => {
            (t.run)();
            Ok(Completion::Completed)
        }
        (Some(why), _) if required => {
            Err(format!("OCEAN_REQUIRE_GPU=1 and this test needs {what}; missing here: {why}")
                .into())
        }
        (Some(_), Needs::GpuPart) => {
            (t.run)();
            Ok(Completion::ignored_with(format!("only its CPU part ran; the rest needs {what}")))
        }
        (Some(_), _) => Ok(Completion::ignored_with(format!("needs {what}"))),
    }
}

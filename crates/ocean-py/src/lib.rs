//! `import ocean`: the physics of `ocean-core` and the CPU oracle's picture as numpy arrays.
//!
//! Every function takes scalars or array-likes (anything `numpy.asarray` takes) and returns
//! `float64` arrays of the broadcast shape, except the maps (`heightfield`: `float32`, as the
//! renderer keeps them) and `render` (`float32`, H × W × 4). Scenes are TOML text, as in a
//! scene file; a bad scene raises `ValueError` with the file's line, column and key.

use numpy::ndarray::{self, ArrayD, IxDyn};
use numpy::{IntoPyArray, PyArray3, PyArrayDyn, PyReadonlyArrayDyn};
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `numpy.asarray(x, dtype=float64)`.
fn array<'py>(py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    let np = py.import("numpy")?;
    np.call_method1("asarray", (x, "float64"))?.extract()
}

/// f applied to every element of x, as a new float64 array of x's shape.
fn map1<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    f: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let a = array(py, x)?;
    Ok(a.as_array().mapv(f).into_pyarray(py))
}

/// A validated scene from TOML text.
fn scene(text: &str) -> PyResult<Scene> {
    let s = Scene::from_toml(text, SceneSource::Text)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    s.validate()
        .map_err(|(key, message)| PyValueError::new_err(format!("key `{key}`: {message}")))?;
    Ok(s)
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// `eta` as the command line takes it (`ocean fresnel --eta`): finite and above 0.
fn check_eta(eta: f64) -> PyResult<()> {
    if eta > 0.0 && eta.is_finite() {
        Ok(())
    } else {
        Err(PyValueError::new_err(format!("eta must be finite and > 0, got {eta}")))
    }
}

/// fresnel(eta, cos_theta) -> ndarray: the exact unpolarised Fresnel reflectance of eq. 2
/// (Hu et al. 2004) for relative index `eta` = n_t/n_i at incidence cos θ (1 past the
/// critical angle when eta < 1: total internal reflection).
#[pyfunction]
fn fresnel<'py>(
    py: Python<'py>,
    eta: f64,
    cos_theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    check_eta(eta)?;
    map1(py, cos_theta, |c| ocean_core::fresnel::fresnel_exact(c, eta))
}

/// fresnel_schlick(eta, cos_theta) -> ndarray: Schlick's approximation
/// R0 + (1 − R0)(1 − cos θ)^5, R0 = ((eta − 1)/(eta + 1))², with the same orientation and
/// total-internal-reflection rules as `fresnel`.
#[pyfunction]
fn fresnel_schlick<'py>(
    py: Python<'py>,
    eta: f64,
    cos_theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    check_eta(eta)?;
    map1(py, cos_theta, |c| ocean_core::fresnel::fresnel_schlick(c, eta))
}

/// dispersion(k, depth=None, gravity=9.81) -> ndarray: the angular frequency ω (rad/s) of
/// gravity waves of wavenumber |k| (rad/m), ω² = g k tanh(k h) (deep water when depth is
/// None).
#[pyfunction]
#[pyo3(signature = (k, depth=None, gravity=9.81))]
fn dispersion<'py>(
    py: Python<'py>,
    k: &Bound<'py, PyAny>,
    depth: Option<f64>,
    gravity: f64,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let d = ocean_core::dispersion::Dispersion::new(gravity, depth.unwrap_or(f64::INFINITY), 0.0)
        .map_err(value_error)?;
    map1(py, k, |k| d.omega_continuous(k))
}

/// spectrum(scene_toml, omega) -> ndarray: the scene's frequency spectrum S(ω), m²·s (its
/// `[ocean]` spectrum, wind, fetch and depth; ∫ S dω is the surface's variance).
#[pyfunction]
fn spectrum<'py>(
    py: Python<'py>,
    scene_toml: &str,
    omega: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let s = scene(scene_toml)?.ocean.wave_spectrum().map_err(value_error)?;
    map1(py, omega, |w| s.frequency_spectrum(w))
}

/// spreading(scene_toml, k, theta) -> ndarray: the directional spreading D(k, θ) (1/rad,
/// ∫ D dθ over (−π, π] = 1) at wavenumber k (rad/m) and direction θ (rad, from +x towards +z)
/// relative to nothing: θ is the wave's own direction, the wind's is the scene's.
#[pyfunction]
fn spreading<'py>(
    py: Python<'py>,
    scene_toml: &str,
    k: &Bound<'py, PyAny>,
    theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let s = scene(scene_toml)?.ocean.wave_spectrum().map_err(value_error)?;
    let (k, t) = (array(py, k)?, array(py, theta)?);
    let (k, t) = (k.as_array(), t.as_array());
    if k.shape() != t.shape() {
        return Err(PyValueError::new_err(format!(
            "k and theta must have one shape, got {:?} and {:?}",
            k.shape(),
            t.shape()
        )));
    }
    let out: Vec<f64> = k.iter().zip(t.iter()).map(|(k, t)| s.spreading(*k, *t)).collect();
    Ok(ArrayD::from_shape_vec(IxDyn(k.shape()), out).map_err(value_error)?.into_pyarray(py))
}

/// amplitudes(scene_toml) -> ndarray: the seeded complex amplitudes h̃₀ of the scene's
/// displacement modes (Tessendorf's eq. 42: Gaussian draws of the project's counter-based
/// generator times √(S_k Δk²/2)), N × N complex128, element [j, i] for the wave vector of
/// bin (i, j) as the FFT orders it.
#[pyfunction]
fn amplitudes<'py>(
    py: Python<'py>,
    scene_toml: &str,
) -> PyResult<Bound<'py, PyArrayDyn<numpy::Complex64>>> {
    let s = scene(scene_toml)?;
    let modes = s.ocean.displacement_modes().map_err(value_error)?;
    let n = modes.resolution();
    let h0: Vec<numpy::Complex64> =
        modes.h0().iter().map(|c| numpy::Complex64::new(c.re, c.im)).collect();
    Ok(ArrayD::from_shape_vec(IxDyn(&[n, n]), h0).map_err(value_error)?.into_pyarray(py))
}

/// heightfield(scene_toml, time) -> dict: the maps of `ocean heightfield` at `time` s — keys
/// `height`, `disp_x`, `disp_z`, `slope_x`, `slope_z`, `jacobian`, each an N × N float32
/// array, element [j, i] at x = i·L/N, z = j·L/N (L the patch, N the resolution).
#[pyfunction]
fn heightfield<'py>(py: Python<'py>, scene_toml: &str, time: f64) -> PyResult<Bound<'py, PyDict>> {
    let mut s = scene(scene_toml)?;
    s.ocean.time_s = time;
    s.validate()
        .map_err(|(key, message)| PyValueError::new_err(format!("time: key `{key}`: {message}")))?;
    let (n, fields) =
        py.allow_threads(|| ocean_core::heightfield::channels(&s)).map_err(value_error)?;
    let dict = PyDict::new(py);
    for (name, data) in fields {
        let a = ArrayD::from_shape_vec(IxDyn(&[n, n]), data).map_err(value_error)?;
        dict.set_item(name, a.into_pyarray(py))?;
    }
    Ok(dict)
}

/// height(scene_toml, time, x, z) -> ndarray: the height query (what a floating object
/// rides on, the same surface both renderers draw) at world points (x, z), metres: the
/// height of the surface sample of the undisplaced point (x, z).
#[pyfunction]
fn height<'py>(
    py: Python<'py>,
    scene_toml: &str,
    time: f64,
    x: &Bound<'py, PyAny>,
    z: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let s = scene(scene_toml)?;
    let plan = FramePlan::new(&s, OutputKind::Hdr);
    let sea = ocean_core::frame::surface_query(&s, &plan, time).map_err(value_error)?;
    let (x, z) = (array(py, x)?, array(py, z)?);
    let (x, z) = (x.as_array(), z.as_array());
    if x.shape() != z.shape() {
        return Err(PyValueError::new_err(format!(
            "x and z must have one shape, got {:?} and {:?}",
            x.shape(),
            z.shape()
        )));
    }
    let out: Vec<f64> = x.iter().zip(z.iter()).map(|(x, z)| sea.sample(*x, *z).height).collect();
    Ok(ArrayD::from_shape_vec(IxDyn(x.shape()), out).map_err(value_error)?.into_pyarray(py))
}

/// render(scene_toml, backend="cpu", memory_limit=None) -> ndarray: the linear HDR frame
/// (H × W × 4 float32, row 0 at the top, before exposure and tonemap) of the scene by the CPU
/// oracle. As `ocean render`, a frame whose estimated memory exceeds `memory_limit` bytes
/// (default: three quarters of the machine's memory) raises `ValueError` before any work.
#[pyfunction]
#[pyo3(signature = (scene_toml, backend="cpu", memory_limit=None))]
fn render<'py>(
    py: Python<'py>,
    scene_toml: &str,
    backend: &str,
    memory_limit: Option<u64>,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    if backend != "cpu" {
        return Err(PyValueError::new_err(format!(
            "backend `{backend}`: the Python module renders on the CPU oracle (`cpu`); the GPU \
             path is `ocean render --backend gpu`"
        )));
    }
    let limit = memory_limit.unwrap_or_else(ocean_core::plan::memory::default_limit);
    if limit == 0 {
        return Err(PyValueError::new_err("memory_limit must be above 0 bytes"));
    }
    ocean_core::input::set_decode_budget(limit);
    let s = scene(scene_toml)?;
    let plan = FramePlan::new(&s, OutputKind::Hdr);
    ocean_core::plan::memory::MemoryEstimate::of(&s, &plan, ocean_core::plan::memory::MemoryBackend::Cpu)
        .check(limit)
        .map_err(|e| PyValueError::new_err(format!("memory_limit: {e}")))?;
    let (w, h) = (s.camera.width as usize, s.camera.height as usize);
    let r = py
        .allow_threads(|| ocean_cpu::render_scene(&s, OutputKind::Hdr, &mut |_| {}))
        .map_err(value_error)?;
    let flat: Vec<f32> = r.buffers.hdr.color.iter().flatten().copied().collect();
    let a = ndarray::Array3::from_shape_vec((h, w, 4), flat).map_err(value_error)?;
    Ok(a.into_pyarray(py))
}

/// The module `ocean`.
#[pymodule]
fn ocean(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fresnel, m)?)?;
    m.add_function(wrap_pyfunction!(fresnel_schlick, m)?)?;
    m.add_function(wrap_pyfunction!(dispersion, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(spreading, m)?)?;
    m.add_function(wrap_pyfunction!(amplitudes, m)?)?;
    m.add_function(wrap_pyfunction!(heightfield, m)?)?;
    m.add_function(wrap_pyfunction!(height, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    Ok(())
}

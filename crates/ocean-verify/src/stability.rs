//! Numerical stability on stiff and extreme inputs (issue 5): one table of cases, each with
//! whether the f32 result is finite, how far it is from an f64 reference, and the bound it
//! must stay within, with where that bound comes from. `ocean report` prints the table and
//! `tests/stability.rs` asserts every row; the older per-module tests (`tests/extremes_*.rs`,
//! `tests/fresnel.rs`, `tests/raster.rs`) keep their own, finer checks.
//!
//! Bounds, by kind of case:
//! - **Fresnel** (f32 eq. 2 against f64 eq. 2 at the same f32 inputs): backward stability. The
//!   bound is the spread of the f64 value over inputs within ±4 ulp of c and of η, plus 8 ulp
//!   of F for the rounding of its own ~15 f32 operations: where F is steep (the critical angle,
//!   where dF/dc is infinite) a forward bound would have to grow with the slope; this one does
//!   on its own.
//! - **Synthesis** (f32 maps against f64 maps of the same modes): docs/design.md's relative 1e-5
//!   for f32 synthesis, as RMS over the field relative to its RMS.
//! - **Cameras** (a flat sea under a uniform sky, F read back per pixel against the f64 table
//!   lookup of the pixel's own ray): the spread of the table's F over the rays the rasterizer's
//!   1/256-pixel snapping can move a pixel's surface point to, plus 1e-5 (as
//!   `tests/frame_physics.rs`).
//! - **Sky** (the f32 shader against the f64 model): `tests/sky.rs`'s 2e-5 relative + 1e-7.
//! - **Rasterizer**: coverage against the f64 edge functions; no pixel may differ.

use glam::DVec3;
use ocean_core::camera::Camera;
use ocean_core::fresnel::fresnel_exact;
use ocean_core::plan::{FramePlan, OutputKind};
use ocean_core::scene::{Scene, SceneSource, Sun};
use ocean_core::sky::{PreethamSky, SkyParams};
use ocean_core::tables::FresnelTexture;
use ocean_core::waves::{MapFloat, Synthesizer, WaveMaps, WaveModes};

use ocean_cpu::frame::{self, Error};
use ocean_cpu::raster::{self, BlendMode, CompareFunction, RasterState, RenderTarget, Vertex};
use ocean_cpu::shaders::sky::preetham;

/// One row of the stability table.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// What is stressed: `fresnel`, `spectrum`, `time`, `folding`, `camera`, `sun`, `raster`.
    pub group: &'static str,
    /// The case.
    pub name: String,
    /// Every value the case computed is finite.
    pub finite: bool,
    /// How far the f32 result is from the f64 reference, in `metric`.
    pub error: f64,
    /// The largest error allowed (see the module doc for where it comes from).
    pub bound: f64,
    /// What `error` measures.
    pub metric: &'static str,
    /// Anything else worth knowing (foam coverage, pixels compared, …).
    pub note: String,
}

impl Case {
    /// Finite and within its bound.
    pub fn passes(&self) -> bool {
        self.finite && self.error <= self.bound
    }
}

/// Every case, in table order. Takes a few seconds in a release build.
pub fn cases() -> Result<Vec<Case>, Error> {
    let mut out = fresnel_cases();
    out.extend(synthesis_cases()?);
    out.extend(camera_cases()?);
    out.extend(sun_cases()?);
    out.extend(raster_cases());
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Fresnel

/// (error, bound, finite) of f32 eq. 2 at (c, η) (both f32) against f64 eq. 2: the module
/// doc's backward-stability bound.
fn fresnel_point(c: f32, eta: f32) -> (f64, f64, bool) {
    fresnel_check(fresnel_exact, c, eta)
}

/// (error, bound, finite) of an f32 Fresnel function `f` at (c, η) against f64 eq. 2, with the
/// module doc's backward-stability bound. Public so that a test can show that an
/// approximation (Schlick's) fails it.
pub fn fresnel_check(f: fn(f32, f32) -> f32, c: f32, eta: f32) -> (f64, f64, bool) {
    let got = f(c, eta);
    let (c64, eta64) = (f64::from(c), f64::from(eta));
    let reference = fresnel_exact(c64, eta64);
    let ulp = |v: f64| (v.abs().max(f64::from(f32::MIN_POSITIVE))) * f64::from(f32::EPSILON);
    let (mut lo, mut hi) = (reference, reference);
    for dc in [-4.0, 0.0, 4.0] {
        for de in [-4.0, 0.0, 4.0] {
            let f = fresnel_exact((c64 + dc * ulp(c64)).clamp(0.0, 1.0), eta64 + de * ulp(eta64));
            (lo, hi) = (lo.min(f), hi.max(f));
        }
    }
    let error = (f64::from(got) - reference).abs();
    let own_rounding = 8.0 * f64::from(f32::EPSILON) / 2.0 * reference.abs();
    (error, hi - lo + own_rounding, got.is_finite())
}

/// The worst (by error / bound) of a set of points as one row.
fn fresnel_row(name: &str, eta: f32, cs: &[f32]) -> Case {
    let mut worst = (0.0, 1.0, true);
    let mut finite = true;
    for &c in cs {
        let p = fresnel_point(c, eta);
        finite &= p.2;
        if p.0 / p.1 >= worst.0 / worst.1 {
            worst = p;
        }
    }
    Case {
        group: "fresnel",
        name: name.to_string(),
        finite,
        error: worst.0,
        bound: worst.1,
        metric: "|F32 − F64|",
        note: format!("{} cosines", cs.len()),
    }
}

fn fresnel_cases() -> Vec<Case> {
    let water = 1.333f32;
    let ramp = |lo: f32, hi: f32, n: usize| -> Vec<f32> {
        (0..=n).map(|i| lo + (hi - lo) * i as f32 / n as f32).collect()
    };
    let inv = 1.0 / water;
    let critical = (1.0 - inv * inv).sqrt();
    let around = |rel: f32| -> Vec<f32> {
        (-20..=20).map(|k| critical * (1.0 + rel * k as f32 / 20.0)).collect()
    };
    let mut near_one: Vec<f32> = (0..32).map(|k| 1.0 - k as f32 * f32::EPSILON / 2.0).collect();
    near_one.push(1.0);
    vec![
        fresnel_row(
            "c → 0 (c = 0, 1e-30 … 1e-3), η = 1.333",
            water,
            &[0.0, 1e-30, 1e-20, 1e-12, 1e-7, 1e-5, 1e-4, 1e-3],
        ),
        fresnel_row("c = 1 and the 32 floats below it, η = 1.333", water, &near_one),
        fresnel_row("η = 1, c ∈ [0, 1]", 1.0, &ramp(0.0, 1.0, 64)),
        fresnel_row("η = 1 + 1e-5, c ∈ [1e-3, 1]", 1.0 + 1e-5, &ramp(1e-3, 1.0, 64)),
        fresnel_row("η = 1/1.333, c ∈ [0, 1]", inv, &ramp(0.0, 1.0, 256)),
        fresnel_row("η = 1/1.333, c within ±1e-3 of the critical angle", inv, &around(1e-3)),
        fresnel_row("η = 1/1.333, c within ±1e-6 of the critical angle", inv, &around(1e-6)),
    ]
}

// ---------------------------------------------------------------------------------------------
// Spectra, time, folding: f32 synthesis against f64 synthesis of the same modes.

/// Relative RMS of (a − b) over the six fields, each relative to the f64 field's RMS (0 for
/// a field that is 0 in both), the worst field; and whether a is finite.
fn maps_error(a: &WaveMaps<f32>, b: &WaveMaps<f64>) -> (f64, bool) {
    let mut worst = 0.0f64;
    let mut finite = true;
    for ((_, fa), (_, fb)) in a.fields().iter().zip(b.fields().iter()) {
        finite &= fa.iter().all(|v| v.is_finite());
        let (mut e2, mut r2) = (0.0, 0.0);
        for (x, y) in fa.iter().zip(fb.iter()) {
            e2 += (f64::from(*x) - y).powi(2);
            r2 += y * y;
        }
        if r2 > 0.0 {
            worst = worst.max((e2 / r2).sqrt());
        } else if e2 > 0.0 {
            worst = f64::INFINITY;
        }
    }
    (worst, finite)
}

fn synth<T: MapFloat>(modes: &WaveModes, t: f64, chop: f64) -> Result<WaveMaps<T>, Error> {
    Ok(Synthesizer::<T>::new(modes.resolution())?.synthesize(modes, t, chop)?)
}

fn ocean(text: &str) -> Result<Scene, Error> {
    let base = "[ocean]\nresolution = 64\npatch_size_m = 100.0\n";
    Scene::from_toml(&format!("{base}{text}"), SceneSource::Text).map_err(|e| {
        Error::Core(ocean_core::Error::InvalidParameter {
            name: "stability case",
            value: 0.0,
            reason: e.to_string(),
        })
    })
}

/// Relative RMS bound of f32 synthesis (docs/design.md's tolerance table).
const SYNTHESIS_REL: f64 = 1e-5;

fn synthesis_row(group: &'static str, name: &str, scene: &Scene) -> Result<Case, Error> {
    let o = &scene.ocean;
    let modes = o.displacement_modes()?;
    let a = synth::<f32>(&modes, o.time_s, o.choppiness)?;
    let b = synth::<f64>(&modes, o.time_s, o.choppiness)?;
    let (error, finite) = maps_error(&a, &b);
    let h_rms = (b.height.iter().map(|h| h * h).sum::<f64>() / b.height.len() as f64).sqrt();
    let j_min = b.jacobian.iter().copied().fold(f64::INFINITY, f64::min);
    let mut note = format!("Hs = {:.3} m, min J = {j_min:.2}", 4.0 * h_rms);
    let mut error = error;
    if group == "folding" {
        if j_min >= 0.0 {
            // The case exists to fold the surface; a sea that does not fold has not tested it.
            error = f64::INFINITY;
        }
        // The normal the water pass forms from the slopes, (−sx, 1, −sz)/‖·‖, is finite for
        // every finite slope; the foam mask marks J < 0.3.
        let normals_finite = a
            .slope_x
            .iter()
            .zip(&a.slope_z)
            .all(|(x, z)| (1.0 / (x * x + 1.0 + z * z).sqrt()).is_finite());
        note = format!(
            "{note}, folded {:.1} %, foam (J < 0.3) {:.1} %, normals finite: {normals_finite}",
            100.0 * a.foam_coverage(0.0),
            100.0 * a.foam_coverage(0.3)
        );
    }
    Ok(Case {
        group,
        name: name.to_string(),
        finite,
        error,
        bound: SYNTHESIS_REL,
        metric: "rel. RMS, worst map",
        note,
    })
}

fn synthesis_cases() -> Result<Vec<Case>, Error> {
    let mut out = Vec::new();
    // k → 0: every spectrum's density at and near k = 0 is finite and ≥ 0; its limit is 0.
    let mut worst = 0.0f64;
    let mut finite = true;
    for kind in ["phillips", "pierson-moskowitz", "jonswap", "tma"] {
        let s = ocean(&format!("spectrum = \"{kind}\"\ndepth_m = 20.0\n"))?;
        let spectrum = s.ocean.wave_spectrum()?;
        for k in [0.0, 1e-300, 1e-100, 1e-12, 1e-6] {
            let f = spectrum.density(k, 0.0);
            finite &= f.is_finite() && f >= 0.0;
            worst = worst.max(f.abs());
        }
    }
    out.push(Case {
        group: "spectrum",
        name: "F(k) at k = 0, 1e-300 … 1e-6, four spectra".into(),
        finite,
        error: worst,
        bound: 0.0,
        metric: "|F − lim F| (m⁴)",
        note: "the limit k → 0 is 0 for each spectrum".into(),
    });
    for (name, text) in [
        ("wind 0 (flat sea)", "wind_speed = 0.0\n"),
        ("wind 60 m/s on a 100 m patch", "wind_speed = 60.0\nfetch_km = 1000.0\n"),
        ("TMA, depth 1e-2 m", "spectrum = \"tma\"\ndepth_m = 0.01\n"),
        ("JONSWAP, fetch 10 m", "spectrum = \"jonswap\"\nfetch_km = 0.01\n"),
        ("JONSWAP, γ = 1", "spectrum = \"jonswap\"\npeak_enhancement = 1.0\n"),
        ("JONSWAP, γ = 20", "spectrum = \"jonswap\"\npeak_enhancement = 20.0\n"),
    ] {
        out.push(synthesis_row("spectrum", name, &ocean(text)?)?);
    }
    for t in [1e6, 1e9] {
        for period in [0.0, 20.0] {
            let name = if period > 0.0 {
                format!("t = {t:e} s, looping T = {period} s")
            } else {
                format!("t = {t:e} s, not looping")
            };
            let text = format!("time_s = {t}\nloop_period_s = {period}\n");
            out.push(synthesis_row("time", &name, &ocean(&text)?)?);
        }
    }
    let storm = "spectrum = \"jonswap\"\nwind_speed = 22.0\nfetch_km = 500.0\nchoppiness = 6.0\n";
    out.push(synthesis_row("folding", "storm, choppiness 6 (folds: J < 0)", &ocean(storm)?)?);
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Cameras: F read back from a flat sea under a uniform sky.

/// Renders the flat sea seen by `camera_toml` under a uniform sky S = 1 (no sun, no objects)
/// and compares each water pixel's F with the f64 table's F for the pixel's ray (the table for
/// η above the water, 1/η below). Above the water C = F·S + (1 − F)·W, so F = (C − W)/(1 − W);
/// below it C = F·W + (1 − F)·S through Snell's window (and F = 1, C = W outside it), so
/// F = (1 − C)/(1 − W). Returns (worst error beyond the snapping spread, pixels compared,
/// all finite).
fn flat_sea_readback(camera_toml: &str) -> Result<(f64, usize, bool), Error> {
    let text =
        format!("[ocean]\nwind_speed = 0.0\n[camera]\nwidth = 96\nheight = 54\n{camera_toml}");
    let scene = Scene::from_toml(&text, SceneSource::Text).map_err(|e| {
        Error::Core(ocean_core::Error::InvalidParameter {
            name: "camera case",
            value: 0.0,
            reason: e.to_string(),
        })
    })?;
    let plan = FramePlan::new(&scene, OutputKind::Hdr);
    let sky = |_: [f32; 3]| [1.0f32; 3];
    let mesh = |c: &Camera| Ok(plan.water_mesh(&scene, c)?.into());
    let buffers = frame::render(
        &scene,
        &plan,
        &sky,
        &|t: &mut RenderTarget| t.clear_color([1.0; 4]),
        &mesh,
        &mut |_| {},
    )?;
    let camera = Camera::from_scene(&scene.camera)?;
    let eta = scene.water.ior;
    let size = scene.quality.fresnel_table_size as usize;
    let above = FresnelTexture::new(size, eta, plan.fresnel_mapping)?;
    let below = FresnelTexture::new(size, 1.0 / eta, plan.fresnel_mapping)?;
    let w = f64::from(buffers.uniforms.water.color[0]);
    let (width, height) = (camera.width, camera.height);
    let finite = buffers.hdr.color.iter().all(|p| p.iter().all(|c| c.is_finite()));
    let table_f = |d: DVec3| {
        let v = -d;
        let t = if v.y >= 0.0 { &above } else { &below };
        f64::from(t.lookup_fresnel([v.x, v.z, v.y.abs()]))
    };
    // Snapping to 1/256 pixel moves the shaded point by up to √2/512 pixel; twice that.
    let e = 2.0 * 2f64.sqrt() / 512.0;
    let (ex, ey) = (2.0 * e / f64::from(width), 2.0 * e / f64::from(height));
    let mut worst = 0.0f64;
    let mut pixels = 0;
    for y in 0..height {
        for x in 0..width {
            let ndc_x = (f64::from(x) + 0.5) / f64::from(width) * 2.0 - 1.0;
            let ndc_y = 1.0 - (f64::from(y) + 0.5) / f64::from(height) * 2.0;
            let d = camera.ray_direction(ndc_x, ndc_y);
            // Only rays that meet the sea well away from grazing (θ < 88.85°).
            if d.y * camera.eye.y >= 0.0 || d.y.abs() < 0.02 {
                continue;
            }
            let c = f64::from(buffers.hdr.pixel(x, y)[0]);
            let f_pixel =
                if camera.eye.y > 0.0 { (c - w) / (1.0 - w) } else { (1.0 - c) / (1.0 - w) };
            let (mut lo, mut hi) = (f64::MAX, f64::MIN);
            for (ox, oy) in [(0.0, 0.0), (ex, 0.0), (-ex, 0.0), (0.0, ey), (0.0, -ey)]
                .into_iter()
                .chain([(ex, ey), (-ex, -ey), (ex, -ey), (-ex, ey)])
            {
                let f = table_f(camera.ray_direction(ndc_x + ox, ndc_y + oy));
                (lo, hi) = (lo.min(f), hi.max(f));
            }
            let beyond = if f_pixel < lo {
                lo - f_pixel
            } else if f_pixel > hi {
                f_pixel - hi
            } else {
                0.0
            };
            worst = worst.max(beyond);
            pixels += 1;
        }
    }
    Ok((worst, pixels, finite))
}

fn camera_cases() -> Result<Vec<Case>, Error> {
    let mut out = Vec::new();
    for (name, cam) in [
        ("at the horizon, 2 m up", "position = [0.0, 2.0, 0.0]\nlook_at = [0.0, 2.0, -100.0]\n"),
        ("straight down from 30 m", "position = [0.0, 30.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n"),
        ("10 km up", "position = [0.0, 10000.0, 0.0]\nlook_at = [100.0, 0.0, -3000.0]\n"),
        (
            "4 m below the water, looking up",
            "position = [0.0, -4.0, 0.0]\nlook_at = [0.0, 2.0, -30.0]\n",
        ),
        (
            "1e6 m from the origin",
            "position = [1.0e6, 6.0, -1.0e6]\nlook_at = [1.0e6, 1.0, -1.00006e6]\n",
        ),
    ] {
        let (error, pixels, finite) = flat_sea_readback(cam)?;
        out.push(Case {
            group: "camera",
            name: name.into(),
            finite: finite && pixels > 0,
            error,
            bound: 1e-5,
            metric: "|F_pixel − F64| beyond snapping",
            note: format!("{pixels} water pixels"),
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Sun at and below the horizon: the f32 sky shader against the f64 model, and a whole frame.

fn sun_cases() -> Result<Vec<Case>, Error> {
    let mut out = Vec::new();
    for elevation_deg in [0.0f64, -1e-6, -3.0, -30.0] {
        let el = elevation_deg.to_radians();
        let dir = [0.3 * el.cos(), el.sin(), -el.cos()];
        let model = PreethamSky::new(SkyParams::new(dir, 2.5, [1.0, 0.9, 0.8], 5.0)?);
        let u = model.uniforms();
        let (mut worst, mut finite) = (0.0f64, true);
        for i in 0..32 {
            let up = (f64::from(i) + 0.5) / 32.0;
            for j in 0..64 {
                let phi = std::f64::consts::TAU * f64::from(j) / 64.0;
                let r = (1.0 - up * up).sqrt();
                let d = DVec3::new(r * phi.cos(), up, r * phi.sin()).normalize();
                let want = model.sky_radiance(d.to_array());
                let got: [f32; 3] =
                    preetham::sky_radiance(&u, d.as_vec3().to_array().into()).into();
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for c in 0..3 {
                    finite &= got[c].is_finite();
                    // Relative to the largest channel, floored at 5e-3 (= 1e-7 / 2e-5: the
                    // absolute floor of tests/sky.rs).
                    let e = (f64::from(got[c]) - want[c]).abs() / scale.max(1e-7 / 2e-5);
                    worst = worst.max(e);
                }
            }
        }
        // And a whole frame of the default scene under that sun.
        let mut scene = Scene::builtin();
        scene.camera.width = 64;
        scene.camera.height = 36;
        scene.sun = Some(Sun { direction: dir, ..Sun::default() });
        let r = ocean_cpu::render_scene(&scene, OutputKind::Hdr, &mut |_| {})?;
        let frame_finite = r.buffers.hdr.color.iter().all(|p| p.iter().all(|c| c.is_finite()));
        out.push(Case {
            group: "sun",
            name: format!("sun {elevation_deg}° above the horizon"),
            finite: finite && frame_finite,
            error: worst,
            bound: 2e-5,
            metric: "sky rel. error (floor 5e-3)",
            note: "2048 directions; a 64×36 frame finite".into(),
        });
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Rasterizer: degenerate and enormous triangles.

fn coverage(tris: &[[Vertex<0>; 3]], width: u32, height: u32) -> Vec<u32> {
    let state = RasterState {
        depth_compare: CompareFunction::Always,
        depth_write: false,
        blend: BlendMode::Add,
        ..RasterState::default()
    };
    let mut target = RenderTarget::new(width, height);
    raster::draw(&mut target, &state, tris, |_| Some([1.0, 0.0, 0.0, 0.0]));
    target.color.iter().map(|c| c[0] as u32).collect()
}

/// A rasterizer case: name, triangles, expected coverage (empty: none asked).
type RasterCase = (&'static str, Vec<[Vertex<0>; 3]>, Vec<u32>);

fn raster_cases() -> Vec<Case> {
    let (w, h) = (64u32, 48u32);
    let v = |x: f32, y: f32, z: f32, ww: f32| Vertex::new([x, y, z, ww], []);
    // Expected coverage from f64 edge tests at pixel centres (no centre lies on an edge here).
    let expect = |inside: &dyn Fn(f64, f64) -> bool| -> Vec<u32> {
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let (ndc_x, ndc_y) = ocean_core::camera::pixel_centre_ndc(x, y, w, h);
                u32::from(inside(ndc_x, ndc_y))
            })
            .collect()
    };
    let none = vec![0u32; (w * h) as usize];
    let big = 1e30f32;
    let cases: Vec<RasterCase> = vec![
        (
            "zero-area triangle (three equal vertices)",
            vec![[v(0.1, 0.1, 0.5, 1.0); 3]],
            none.clone(),
        ),
        (
            "collinear vertices",
            vec![[v(-0.9, -0.9, 0.5, 1.0), v(0.0, 0.0, 0.5, 1.0), v(0.9, 0.9, 0.5, 1.0)]],
            none.clone(),
        ),
        (
            "NaN and infinite vertices",
            vec![
                [v(f32::NAN, 0.0, 0.5, 1.0), v(0.5, 0.5, 0.5, 1.0), v(0.0, 0.5, 0.5, 1.0)],
                [v(f32::INFINITY, 0.0, 0.5, 1.0), v(0.5, 0.5, 0.5, 1.0), v(0.0, 0.5, 0.5, 1.0)],
            ],
            none.clone(),
        ),
        (
            "enormous triangle (±1e30) covering the view",
            vec![[v(-big, -big, 0.5, 1.0), v(big, -big, 0.5, 1.0), v(0.0, big, 0.5, 1.0)]],
            vec![1; (w * h) as usize],
        ),
        (
            "large triangle (±1e6) cut by the diagonal y = x",
            vec![[v(1e6, -1e6, 0.5, 1.0), v(1e6, 1e6, 0.5, 1.0), v(-1e6, -1e6, 0.5, 1.0)]],
            expect(&|x, y| y < x),
        ),
        (
            "enormous triangle (±1e30) cut by the diagonal y = x",
            // Two vertices far out on the line y = x (no pixel centre of a 64 × 48 view lies
            // on it: 3x + 4y = 188.5 has no integer solution) and one far below it.
            vec![[v(big, -big, 0.5, 1.0), v(big, big, 0.5, 1.0), v(-big, -big, 0.5, 1.0)]],
            expect(&|x, y| y < x),
        ),
        (
            "vertex at w = 1e-30 (behind the near plane's reach)",
            vec![[v(0.0, 0.0, 0.5, 1e-30), v(0.5, -0.5, 0.5, 1.0), v(-0.5, -0.5, 0.5, 1.0)]],
            vec![],
        ),
    ];
    cases
        .into_iter()
        .map(|(name, tris, expected)| {
            let got = coverage(&tris, w, h);
            let finite = got.iter().all(|&c| c <= 1);
            let error = if expected.is_empty() {
                0.0 // Only finiteness and "no pixel twice" are asked of this one.
            } else {
                got.iter().zip(&expected).filter(|(a, b)| a != b).count() as f64
            };
            Case {
                group: "raster",
                name: name.into(),
                finite,
                error,
                bound: 0.0,
                metric: "pixels ≠ f64 coverage",
                note: format!("{} pixels covered", got.iter().sum::<u32>()),
            }
        })
        .collect()
}

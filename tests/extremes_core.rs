//! Extreme inputs to the whole ocean-core pipeline (scene → spectrum → modes → maps, and the
//! height query) give finite, documented results, never NaN (issue 2, "Extreme inputs").

use ocean_core::scene::Ocean;
use ocean_core::spectrum::SpectrumKind;
use ocean_core::waves::{SurfaceQuery, Synthesizer, WaveMaps};

fn maps(ocean: &Ocean) -> WaveMaps<f32> {
    let modes = ocean.displacement_modes().expect("valid ocean");
    Synthesizer::<f32>::new(modes.resolution())
        .expect("synthesizer")
        .synthesize(&modes, ocean.time_s, ocean.choppiness)
        .expect("maps")
}

fn all_finite(m: &WaveMaps<f32>) -> bool {
    m.fields().iter().all(|(_, f)| f.iter().all(|v| v.is_finite()))
}

fn max_abs(f: &[f32]) -> f32 {
    f.iter().fold(0.0, |a, v| a.max(v.abs()))
}

fn ocean(kind: SpectrumKind) -> Ocean {
    Ocean { spectrum: kind, resolution: 64, patch_size_m: 100.0, ..Ocean::default() }
}

const KINDS: [SpectrumKind; 4] = [
    SpectrumKind::Phillips,
    SpectrumKind::PiersonMoskowitz,
    SpectrumKind::Jonswap,
    SpectrumKind::Tma,
];

#[test]
fn zero_wind_is_a_flat_sea() {
    for kind in KINDS {
        let o = Ocean { wind_speed: 0.0, depth_m: 10.0, ..ocean(kind) };
        let m = maps(&o);
        // Flat, exactly: no wave has energy, displacement 0, J = 1.
        for (name, f) in m.fields() {
            let want = if name == "jacobian" { 1.0 } else { 0.0 };
            assert!(f.iter().all(|&v| v == want), "{kind:?}: {name} not flat");
        }
        let q = SurfaceQuery::new(&o.displacement_modes().unwrap(), 0.0, 1.0).unwrap();
        assert_eq!(q.height_at(3.0, 4.0), 0.0);
        assert_eq!(q.normal_at(3.0, 4.0), [0.0, 1.0, 0.0]);
    }
}

#[test]
fn hurricane_wind_on_a_small_patch_is_finite() {
    // 60 m/s: the spectral peak (λ_p ≈ 3 km) is far larger than the 100 m patch, which holds
    // only the spectrum's tail: finite heights of a few metres, not NaN or overflow.
    for kind in KINDS {
        let o = Ocean { wind_speed: 60.0, fetch_km: 1000.0, ..ocean(kind) };
        let m = maps(&o);
        assert!(all_finite(&m), "{kind:?}");
        let h = max_abs(&m.height);
        assert!(h > 0.0 && h < 100.0, "{kind:?}: max |h| = {h}");
    }
}

#[test]
fn depth_from_a_centimetre_to_infinity() {
    for depth in [0.01, 0.1, 5.0, 1e4, f64::INFINITY] {
        for kind in KINDS {
            let o = Ocean { depth_m: depth, ..ocean(kind) };
            let m = maps(&o);
            assert!(all_finite(&m), "{kind:?} depth {depth}");
        }
    }
    // TMA in 1 cm of water holds almost no energy (Kitaigorodskii factor → ω_h²/2).
    let deep = maps(&Ocean { depth_m: f64::INFINITY, ..ocean(SpectrumKind::Tma) });
    let shallow = maps(&Ocean { depth_m: 0.01, ..ocean(SpectrumKind::Tma) });
    assert!(max_abs(&shallow.height) < 0.1 * max_abs(&deep.height));
}

#[test]
fn resolutions_from_2_to_2048() {
    for n in [2u32, 3, 4, 5, 16, 100, 257, 2048] {
        let o = Ocean { resolution: n, patch_size_m: 200.0, ..ocean(SpectrumKind::Jonswap) };
        let m = maps(&o);
        assert_eq!(m.height.len(), (n * n) as usize);
        assert!(all_finite(&m), "N = {n}");
        if n == 2 {
            // Only k = 0 and the Nyquist modes fit, and both are empty: flat.
            assert!(m.height.iter().all(|&v| v == 0.0));
        }
    }
}

#[test]
fn huge_times_are_finite_and_loop_exactly() {
    for t in [1e6, 1e9, 1e12] {
        for period in [0.0, 20.0] {
            let o = Ocean { time_s: t, loop_period_s: period, ..ocean(SpectrumKind::Jonswap) };
            let m = maps(&o);
            assert!(all_finite(&m), "t = {t}, T = {period}");
            if period > 0.0 {
                let earlier = maps(&Ocean { time_s: t - 20.0 * 1000.0, ..o.clone() });
                let d = m
                    .height
                    .iter()
                    .zip(&earlier.height)
                    .fold(0.0f32, |a, (x, y)| a.max((x - y).abs()));
                // t and t − 1000 T reduce to the same phase up to the f64 rounding of t.
                assert!(d <= 1e-4 * max_abs(&m.height), "t = {t}: loop mismatch {d}");
            }
        }
    }
}

#[test]
fn spectra_are_finite_at_k_zero() {
    for kind in KINDS {
        let s = ocean(kind).wave_spectrum().unwrap();
        for k in [0.0, 1e-300, 1e-12] {
            let f = s.density(k, 0.0);
            assert!(f.is_finite() && f >= 0.0, "{kind:?}: F({k}) = {f}");
        }
        assert_eq!(s.density(0.0, 0.0), 0.0);
    }
}

//! The albedo of dry beach sand, from a measured reflectance spectrum.
//!
//! A renderer in linear sRGB multiplies light by an RGB albedo; a surface's albedo is a
//! spectrum. [`linear_srgb_albedo`] turns one into the other: the spectrum's tristimulus
//! values under a daylight illuminant (CIE 1931 2° observer) taken to linear sRGB, each
//! channel over that of a perfect white under the same light, so a flat spectrum R(λ) = r
//! gives (r, r, r) and the illuminant's own colour cancels.
//!
//! - **The spectrum** ([`CORAL_SAND`]): clean carbonate (coral) sand, the "sand" bottom of
//!   Maritorena, Morel & Gentili (1994), *Diffuse reflectance of oceanic shallow waters:
//!   influence of water depth and bottom albedo*, Limnol. Oceanogr. 39(7), 1689–1703, Fig. 6,
//!   in the digital form the authors gave HYDROLIGHT, as distributed with the OSOAA radiative
//!   transfer code (CNES, `fic/info_OSOAA_SEA_BOTTOM_REFLECTANCES.txt`, column `rsand`),
//!   400–700 nm every 5 nm. Its reflectance rises steadily from 0.28 in the blue to 0.61 in
//!   the red, which is what makes sand look yellow.
//! - **The observer**: the CIE 1931 colour-matching functions in the multi-lobe Gaussian fit
//!   of Wyman, Sloan & Shirley (2013), *Simple analytic approximations to the CIE XYZ color
//!   matching functions*, JCGT 2(2) (within the CIE table's own spread over the visible).
//! - **The light**: a 6504 K Planck spectrum (D65's correlated colour temperature); dividing
//!   by white under the same light removes most of the difference from D65's table.
//! - **XYZ → linear sRGB**: the matrix of IEC 61966-2-1.
//!
//! The result, [`DRY_SAND_ALBEDO`], is the default `[terrain] color`; the wet band darkens it
//! (`waves::coastal::WET_SAND_DARKENING`).

/// A reflectance spectrum sampled at `start_nm + i·step_nm`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum {
    /// The first sample's wavelength, nm.
    pub start_nm: f64,
    /// The spacing of the samples, nm.
    pub step_nm: f64,
    /// The reflectances, 0–1.
    pub values: &'static [f64],
}

/// Clean coral sand, 400–700 nm (Maritorena, Morel & Gentili 1994, Fig. 6; the module doc).
pub const CORAL_SAND: Spectrum = Spectrum {
    start_nm: 400.0,
    step_nm: 5.0,
    values: &[
        0.281, 0.285, 0.291, 0.296, 0.302, 0.308, 0.314, 0.320, 0.326, 0.333, // 400–445
        0.339, 0.346, 0.351, 0.357, 0.362, 0.368, 0.373, 0.378, 0.383, 0.389, // 450–495
        0.394, 0.400, 0.405, 0.411, 0.417, 0.423, 0.429, 0.436, 0.442, 0.449, // 500–545
        0.456, 0.463, 0.470, 0.477, 0.483, 0.490, 0.496, 0.502, 0.507, 0.513, // 550–595
        0.518, 0.523, 0.528, 0.533, 0.538, 0.542, 0.547, 0.552, 0.556, 0.560, // 600–645
        0.564, 0.568, 0.572, 0.575, 0.579, 0.582, 0.587, 0.592, 0.596, 0.601, // 650–695
        0.605, // 700
    ],
};

/// [`linear_srgb_albedo`] of [`CORAL_SAND`], to 6 digits (a test recomputes it): the default
/// `[terrain] color`. sRGB (197, 179, 155).
pub const DRY_SAND_ALBEDO: [f64; 3] = [0.560627, 0.449170, 0.325988];

/// The colour temperature of the light the albedo is computed under, K.
const DAYLIGHT_K: f64 = 6504.0;

/// One lobe of Wyman, Sloan & Shirley's fit: a Gaussian with one width left of its peak and
/// another right of it.
fn lobe(nm: f64, peak: f64, left: f64, right: f64) -> f64 {
    let s = if nm < peak { left } else { right };
    let t = (nm - peak) / s;
    (-0.5 * t * t).exp()
}

/// The CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `nm` (Wyman, Sloan & Shirley
/// 2013, the multi-lobe fit).
pub fn cie1931(nm: f64) -> [f64; 3] {
    let x = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7)
        - 0.065 * lobe(nm, 501.1, 20.4, 26.2);
    let y = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
    let z = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
    [x, y, z]
}

/// Planck's spectral radiance at `nm` and temperature `kelvin`, up to a constant factor.
fn planck(nm: f64, kelvin: f64) -> f64 {
    const C2: f64 = 1.438_776_877e-2; // h·c/k, m·K
    let m = nm * 1e-9;
    1.0 / (m.powi(5) * (C2 / (m * kelvin)).exp_m1())
}

/// XYZ to linear sRGB (IEC 61966-2-1).
fn xyz_to_linear_srgb([x, y, z]: [f64; 3]) -> [f64; 3] {
    [
        3.2406 * x - 1.5372 * y - 0.4986 * z,
        -0.9689 * x + 1.8758 * y + 0.0415 * z,
        0.0557 * x - 0.2040 * y + 1.0570 * z,
    ]
}

/// The linear sRGB of reflectance `r(λ)` over the samples of `s` under the daylight
/// illuminant (trapezoidal sums at the samples).
fn linear_srgb_under_daylight(s: &Spectrum, r: impl Fn(usize) -> f64) -> [f64; 3] {
    let n = s.values.len();
    let mut xyz = [0.0; 3];
    for i in 0..n {
        let nm = s.start_nm + s.step_nm * i as f64;
        let w = if i == 0 || i + 1 == n { 0.5 } else { 1.0 };
        let e = planck(nm, DAYLIGHT_K) * r(i) * w;
        for (acc, c) in xyz.iter_mut().zip(cie1931(nm)) {
            *acc += e * c;
        }
    }
    xyz_to_linear_srgb(xyz)
}

/// The linear sRGB albedo of reflectance spectrum `s` (the module doc): its colour under
/// daylight over that of a perfect white, per channel.
pub fn linear_srgb_albedo(s: &Spectrum) -> [f64; 3] {
    let surface = linear_srgb_under_daylight(s, |i| s.values[i]);
    let white = linear_srgb_under_daylight(s, |_| 1.0);
    [surface[0] / white[0], surface[1] / white[1], surface[2] / white[2]]
}

/// Wet sand's albedo over dry sand's.
pub const WET_SAND_DARKENING: f64 = 0.55;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_sand_is_the_measured_spectrum() {
        let a = linear_srgb_albedo(&CORAL_SAND);
        for (got, kept) in a.iter().zip(DRY_SAND_ALBEDO) {
            assert!((got - kept).abs() < 1e-6, "{a:?} vs {DRY_SAND_ALBEDO:?}");
        }
        // Rising from blue to red, as the spectrum does.
        assert!(a[0] > a[1] && a[1] > a[2], "{a:?}");
        assert_eq!(CORAL_SAND.values.len(), 61, "400–700 nm every 5 nm");
    }

    #[test]
    fn a_flat_spectrum_is_grey_and_the_fit_matches_cie_values() {
        static HALF: [f64; 61] = [0.5; 61];
        let grey = Spectrum { values: &HALF, ..CORAL_SAND };
        for c in linear_srgb_albedo(&grey) {
            assert!((c - 0.5).abs() < 1e-12, "{c}");
        }
        // Negative control: a spectrum falling towards the red is blue, not sand.
        static FALLING: [f64; 61] = {
            let mut v = [0.0; 61];
            let mut i = 0;
            while i < 61 {
                v[i] = 0.6 - 0.005 * i as f64;
                i += 1;
            }
            v
        };
        let blue = linear_srgb_albedo(&Spectrum { values: &FALLING, ..CORAL_SAND });
        assert!(blue[2] > blue[0], "{blue:?}");
        // The CIE 1931 2° table (CIE 015:2018) at its peaks: x̄(600) = 1.0622, ȳ(555) =
        // 1.0000 (0.99 at 560), z̄(445) = 1.7826; the fit is within 3 % there.
        for (nm, k, cie) in [(600.0, 0, 1.0622), (555.0, 1, 1.0), (445.0, 2, 1.7826)] {
            let fit = cie1931(nm)[k];
            assert!((fit - cie).abs() < 0.03 * cie, "{nm} nm: {fit} vs {cie}");
        }
    }
}

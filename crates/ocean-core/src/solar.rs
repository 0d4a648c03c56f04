//! The sun's position from a date, a time of day and a latitude (seed 002's sky "from a time of
//! day if asked"; `[sun] time_of_day_h`), in scene axes: y up, +x east, −z north.
//!
//! The declination is Spencer's (1971) Fourier series in the fractional year γ, accurate to
//! about 0.035° over the year; the time is local apparent solar time (noon when the sun
//! crosses the meridian), so neither the equation of time nor the time zone enters. For
//! latitude φ, declination δ and hour angle h = 15°·(t − 12), the direction towards the sun in
//! (east, up, north) is
//!
//! ```text
//! (−cos δ sin h,  sin φ sin δ + cos φ cos δ cos h,  cos φ sin δ − sin φ cos δ cos h),
//! ```
//!
//! a unit vector: the sun's equatorial direction turned by the latitude.

use std::f64::consts::{PI, TAU};

/// Spencer's declination, radians, on day `day_of_year` (1 = 1 January) at solar time
/// `solar_time_h`.
pub fn declination(day_of_year: f64, solar_time_h: f64) -> f64 {
    let g = TAU / 365.0 * (day_of_year - 1.0 + (solar_time_h - 12.0) / 24.0);
    0.006918 - 0.399912 * g.cos() + 0.070257 * g.sin() - 0.006758 * (2.0 * g).cos()
        + 0.000907 * (2.0 * g).sin()
        - 0.002697 * (3.0 * g).cos()
        + 0.00148 * (3.0 * g).sin()
}

/// The unit direction towards the sun, scene axes (y up, +x east, −z north), at latitude
/// `latitude_deg` (north positive) on day `day_of_year` at local apparent solar time
/// `solar_time_h` (0–24). Below the horizon its y is negative (night).
pub fn sun_direction(latitude_deg: f64, day_of_year: f64, solar_time_h: f64) -> [f64; 3] {
    let phi = latitude_deg.to_radians();
    let delta = declination(day_of_year, solar_time_h);
    let h = (solar_time_h - 12.0) * PI / 12.0;
    let east = -delta.cos() * h.sin();
    let up = phi.sin() * delta.sin() + phi.cos() * delta.cos() * h.cos();
    let north = phi.cos() * delta.sin() - phi.sin() * delta.cos() * h.cos();
    [east, up, -north]
}

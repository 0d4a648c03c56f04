//! The sun's position from a time of day (`ocean_core::solar`, `[sun] time_of_day_h`): Spencer's
//! declination against the almanac's solstices, the noon elevation 90° − |φ − δ|, sunrise where
//! the closed form cos h₀ = −tan φ tan δ puts it, east in the morning and west in the
//! afternoon, and the scene keys.

use ocean_core::scene::{Scene, SceneSource};
use ocean_core::solar::{declination, sun_direction};

fn elevation_deg(d: [f64; 3]) -> f64 {
    d[1].asin().to_degrees()
}

/// Spencer's series at the 2026 solstices against the almanac (δ = +23.44° on 21 June, day
/// 172, and −23.44° on 21 December, day 355; Spencer's stated accuracy is 0.035°), and the
/// noon elevation it gives at 40° N.
#[test]
fn declination_and_noon_elevation_match_the_almanac() {
    let june = declination(172.0, 12.0).to_degrees();
    let december = declination(355.0, 12.0).to_degrees();
    println!("declination: 21 June {june:.3}°, 21 December {december:.3}°");
    assert!((june - 23.44).abs() < 0.1, "{june}");
    assert!((december + 23.44).abs() < 0.1, "{december}");
    // A sign error in the series (the cos γ term) would swap the seasons.
    assert!(june > 20.0 && december < -20.0);
    for (lat, day) in [(40.0, 172.0), (40.0, 355.0), (-33.9, 172.0), (0.0, 80.0), (70.0, 355.0)] {
        let d = sun_direction(lat, day, 12.0);
        let delta = declination(day, 12.0).to_degrees();
        let want = 90.0 - (lat - delta).abs();
        let got = elevation_deg(d);
        assert!((got - want).abs() < 1e-9, "noon at {lat}°, day {day}: {got} vs {want}");
        // At noon the sun is on the meridian: due south when it is south of the zenith.
        assert!(d[0].abs() < 1e-12);
        assert_eq!(d[2] > 0.0, lat > delta, "south is +z at {lat}°, day {day}");
    }
    // 40° N at midsummer: 73.4° (the published value for the solstice is 73.44°).
    assert!((elevation_deg(sun_direction(40.0, 172.0, 12.0)) - 73.44).abs() < 0.1);
}

/// Sunrise: at the hour angle h₀ with cos h₀ = −tan φ tan δ the sun is on the horizon, and it
/// rises in the east and sets in the west; the direction is a unit vector at every time.
#[test]
fn sunrise_and_sunset_are_where_the_closed_form_puts_them() {
    for (lat, day) in [(45.0, 172.0), (45.0, 355.0), (-20.0, 100.0), (60.0, 250.0)] {
        // δ varies slightly over the day: iterate the closed form to the time it gives.
        let mut t: f64 = 6.0;
        for _ in 0..20 {
            let delta = declination(day, t);
            let cos_h0 = -(f64::to_radians(lat).tan() * delta.tan());
            let h0 = cos_h0.clamp(-1.0, 1.0).acos();
            t = 12.0 - h0.to_degrees() / 15.0;
        }
        let rise = sun_direction(lat, day, t);
        let set = sun_direction(lat, day, 24.0 - t);
        println!("{lat}°, day {day}: sunrise at {t:.3} h, elevation {:.2e}°", elevation_deg(rise));
        assert!(elevation_deg(rise).abs() < 1e-3, "{lat} {day}: {}", elevation_deg(rise));
        assert!(rise[0] > 0.0, "rises in the east (+x)");
        assert!(set[0] < 0.0, "sets in the west (−x)");
        assert!(elevation_deg(sun_direction(lat, day, t + 1.0)) > 5.0);
        assert!(elevation_deg(sun_direction(lat, day, t - 1.0)) < -5.0);
    }
    for i in 0..=96 {
        let d = sun_direction(52.0, 30.0, f64::from(i) / 4.0);
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-12);
    }
}

/// `[sun] time_of_day_h` sets the direction when the scene loads; without it the direction is
/// the scene's (the negative control); out-of-range values are refused naming the key.
#[test]
fn the_scene_keys_place_the_sun() {
    let scene = |text: &str| Scene::from_toml(text, SceneSource::Text);
    let s = scene("[sun]\ntime_of_day_h = 12.0\nlatitude_deg = 40.0\nday_of_year = 172\n")
        .expect("valid");
    let d = s.sun.as_ref().unwrap().direction;
    assert!((elevation_deg(d) - 73.44).abs() < 0.1, "{d:?}");
    let evening = scene("[sun]\ntime_of_day_h = 19.5\nlatitude_deg = 40.0\n").expect("valid");
    let d = evening.sun.as_ref().unwrap().direction;
    assert!(d[0] < 0.0 && elevation_deg(d) < 10.0, "a summer evening sun, low in the west: {d:?}");
    let fixed = scene("[sun]\ndirection = [0.0, 1.0, -1.0]\nlatitude_deg = 40.0\n").expect("valid");
    assert_eq!(fixed.sun.as_ref().unwrap().direction, [0.0, 1.0, -1.0]);
    for (text, key) in [
        ("[sun]\ntime_of_day_h = 25.0\n", "sun.time_of_day_h"),
        ("[sun]\ntime_of_day_h = 12.0\nlatitude_deg = 95.0\n", "sun.latitude_deg"),
        ("[sun]\nday_of_year = 0\n", "sun.day_of_year"),
    ] {
        let e = scene(text).unwrap_err().to_string();
        assert!(e.contains(key), "{e}");
    }
}

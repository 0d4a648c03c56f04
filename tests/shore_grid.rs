//! Surface `shore_grid` (issue 15, seed 004): the grid laid ahead of the camera covers every
//! pixel whose ray meets the sea plane within the grid's reach, for cameras looking ahead,
//! down, straight down and sideways; its rows follow the seed's spacing.

use glam::DVec3;
use ocean_core::camera::Camera;
use ocean_core::frame::ProjectedGridBlock;
use ocean_core::geometry::shore_grid::{block, row_distance};

/// The pixels (sampled every 8) whose ray meets the plane y = 0 within 0.9 D but outside the
/// grid of `g`, and the pixels checked.
fn uncovered(camera: &Camera, g: &ProjectedGridBlock) -> (usize, usize) {
    let [a, s, w, _] = g.corners.map(|c| c.map(f64::from));
    let (f, r) = ((a[0], a[1]), (a[2], a[3]));
    let far = s[0] * (s[1] - 1.0);
    let (mut missed, mut checked) = (0, 0);
    let tan = (0.5 * camera.fov_y).tan();
    for py in (0..camera.height).step_by(8) {
        for px in (0..camera.width).step_by(8) {
            let sx = (2.0 * (f64::from(px) + 0.5) / f64::from(camera.width) - 1.0)
                * tan
                * camera.aspect();
            let sy = (1.0 - 2.0 * (f64::from(py) + 0.5) / f64::from(camera.height)) * tan;
            let dir = camera.forward + camera.right * sx + camera.up * sy;
            if dir.y >= 0.0 {
                continue;
            }
            let p = camera.eye + dir * (-camera.eye.y / dir.y);
            let (dx, dz) = (p.x - camera.eye.x, p.z - camera.eye.z);
            let d = dx * f.0 + dz * f.1;
            if d > 0.9 * far {
                continue;
            }
            checked += 1;
            let x = dx * r.0 + dz * r.1;
            if d < -s[2] || x.abs() > w[0] + w[1] * (d + s[2]) {
                missed += 1;
            }
        }
    }
    (missed, checked)
}

fn cameras() -> Vec<Camera> {
    let cam = |eye: [f64; 3], at: [f64; 3], fov: f64| {
        Camera::look_at(DVec3::from(eye), DVec3::from(at), fov.to_radians(), 640, 360)
            .expect("camera")
    };
    vec![
        cam([0.0, 5.0, 0.0], [0.0, 5.0, -100.0], 50.0),
        cam([-45.0, 9.0, 125.0], [0.0, 0.0, 45.0], 55.0),
        cam([10.0, 30.0, 0.0], [40.0, 0.0, -20.0], 70.0),
        cam([0.0, 50.0, 0.0], [0.1, 0.0, 0.0], 60.0),
        cam([3.0, 1.5, 2.0], [100.0, 0.5, 30.0], 90.0),
    ]
}

#[test]
fn the_grid_covers_the_sea_in_view() {
    for camera in cameras() {
        let g = block(&camera, 4.0);
        let (missed, checked) = uncovered(&camera, &g);
        assert!(checked > 100, "the view must see the sea: {checked} pixels");
        assert_eq!(missed, 0, "eye {:?}: {missed} of {checked} pixels off the grid", camera.eye);
    }
    // Negative control: a grid half as wide leaves the wide view's edges uncovered.
    let wide = &cameras()[4];
    let mut narrow = block(wide, 4.0);
    narrow.corners[2][1] *= 0.5;
    narrow.corners[2][0] *= 0.5;
    assert!(uncovered(wide, &narrow).0 > 0, "a narrower grid must be caught");
}

#[test]
fn rows_follow_the_seeds_spacing() {
    let camera = &cameras()[0];
    let g = block(camera, 4.0);
    let [step, n, back, _] = g.corners[1].map(f64::from);
    let rows = g.rows as u32;
    assert_eq!(n, f64::from(rows) + 1.0);
    // d_i + back + D/(n − 1) = D/(n − 1)·n/(n − i): its inverse falls linearly with i.
    let inv = |i: u32| 1.0 / (row_distance(&g, i) + back + step);
    let slope = inv(1) - inv(0);
    for i in 1..=rows {
        let d = inv(i) - inv(i - 1);
        assert!((d / slope - 1.0).abs() < 1e-6, "row {i}: {d} vs {slope}");
    }
    // The first row is behind the eye, the last at D, where the plane is within half a pixel
    // of the horizon.
    assert!((row_distance(&g, 0) + back).abs() < 1e-9);
    let far = row_distance(&g, rows);
    let pixel = 2.0 * (0.5 * camera.fov_y).tan() / f64::from(camera.height);
    assert!(camera.eye.y / far <= 0.5 * pixel * 1.0001, "far row {far} m");
}

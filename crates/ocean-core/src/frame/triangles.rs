//! The triangles the object passes draw (`shadow_map`, `reflection_map`, `refraction_map`,
//! `objects`): every object's, camera-relative, and the sea floor's, and the key that tells a
//! back end when a list it keeps is still the one it would make.

use std::sync::OnceLock;

use glam::DVec3;

use super::{ObjectPoses, wet_top_m};
use crate::floating::BoatPose;
use crate::objects::{ObjectKind, ObjectVertex, SPHERE_BANDS, SPHERE_SEGMENTS, hull_triangles};
use crate::scene::{Object, Scene, Shape};
use crate::terrain::terrain_triangles;

/// The unit sphere's points, row-major (band b = 0..=SPHERE_BANDS from +y, segment
/// s = 0..=SPHERE_SEGMENTS): made once, as the tessellation made them at every vertex of every
/// pass (about 18,000 sines and cosines a sphere a pass), with the same expression, so the
/// triangles are bit for bit the ones made before.
fn unit_sphere() -> &'static [DVec3] {
    static POINTS: OnceLock<Vec<DVec3>> = OnceLock::new();
    POINTS.get_or_init(|| {
        (0..=SPHERE_BANDS)
            .flat_map(|b| (0..=SPHERE_SEGMENTS).map(move |s| (b, s)))
            .map(|(b, s)| {
                let theta = std::f64::consts::PI * b as f64 / SPHERE_BANDS as f64;
                let phi = std::f64::consts::TAU * s as f64 / SPHERE_SEGMENTS as f64;
                DVec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin())
            })
            .collect()
    })
}

/// Triangles (three vertices each) of every object, camera-relative, counter-clockwise seen
/// from outside; boats at their entries in `poses` (indexed as `objects`), else at rest.
pub fn object_triangles(
    objects: &[Object],
    poses: &ObjectPoses,
    eye: DVec3,
) -> Vec<[ObjectVertex; 3]> {
    let mut tris = Vec::new();
    for (i, o) in objects.iter().enumerate() {
        push_object_triangles(&mut tris, o, poses.of(i, o), eye);
    }
    tris
}

/// Appends the triangles of one object (a boat at `pose`).
fn push_object_triangles(
    tris: &mut Vec<[ObjectVertex; 3]>,
    o: &Object,
    pose: Option<BoatPose>,
    eye: DVec3,
) {
    let c = DVec3::from_array(o.center);
    let color = o.color.map(|v| v as f32);
    let vertex = |p: DVec3, n: DVec3| ObjectVertex {
        position: (p - eye).as_vec3().to_array(),
        normal: n.as_vec3().to_array(),
        color,
    };
    match (o.shape(), pose) {
        (Some(Shape::Sphere { radius }), _) => {
            let unit = unit_sphere();
            let point = |b: u32, s: u32| unit[(b * (SPHERE_SEGMENTS + 1) + s) as usize];
            for b in 0..SPHERE_BANDS {
                for s in 0..SPHERE_SEGMENTS {
                    let (n00, n01) = (point(b, s), point(b, s + 1));
                    let (n10, n11) = (point(b + 1, s), point(b + 1, s + 1));
                    let v = |n: DVec3| vertex(c + n * radius, n);
                    if b > 0 {
                        tris.push([v(n00), v(n10), v(n01)]);
                    }
                    if b + 1 < SPHERE_BANDS {
                        tris.push([v(n01), v(n10), v(n11)]);
                    }
                }
            }
        }
        (Some(Shape::Box { size }), _) => {
            let h = DVec3::from_array(size) * 0.5;
            // Each face: normal axis and the two in-face axes in counter-clockwise order.
            for (n, u, w) in [
                (DVec3::X, DVec3::NEG_Z, DVec3::Y),
                (DVec3::NEG_X, DVec3::Z, DVec3::Y),
                (DVec3::Y, DVec3::X, DVec3::NEG_Z),
                (DVec3::NEG_Y, DVec3::X, DVec3::Z),
                (DVec3::Z, DVec3::X, DVec3::Y),
                (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y),
            ] {
                let corner = |a: f64, b: f64| c + (n + u * a + w * b) * h;
                let q =
                    [corner(-1.0, -1.0), corner(1.0, -1.0), corner(1.0, 1.0), corner(-1.0, 1.0)];
                tris.push([vertex(q[0], n), vertex(q[1], n), vertex(q[2], n)]);
                tris.push([vertex(q[0], n), vertex(q[2], n), vertex(q[3], n)]);
            }
        }
        (Some(Shape::Boat { size, .. }), Some(pose)) => {
            for (p, n) in hull_triangles(size, &pose) {
                tris.push(p.map(|p| vertex(p, n)));
            }
        }
        (Some(Shape::Boat { .. }), None) | (None, _) => {}
    }
}

/// The triangles an object pass of the plan draws: its objects' (boats at `poses`), then the
/// sea floor's when the pass draws it ([`pass_object_triangles`] then
/// [`pass_floor_triangles`], in one list).
pub fn pass_triangles(
    scene: &Scene,
    poses: &ObjectPoses,
    pass: &crate::plan::PlannedPass,
    eye: DVec3,
) -> Vec<[ObjectVertex; 3]> {
    let mut tris = pass_object_triangles(scene, poses, pass, eye);
    if let Some(floor) = pass_floor_triangles(scene, pass, eye) {
        tris.extend_from_slice(&floor);
    }
    tris
}

/// The triangles of an object pass's objects (boats at `poses`), camera-relative.
pub fn pass_object_triangles(
    scene: &Scene,
    poses: &ObjectPoses,
    pass: &crate::plan::PlannedPass,
    eye: DVec3,
) -> Vec<[ObjectVertex; 3]> {
    let mut tris = Vec::new();
    for &i in &pass.objects {
        let o = &scene.objects[i];
        push_object_triangles(&mut tris, o, poses.of(i, o), eye);
    }
    tris
}

/// The sea floor's triangles when an object pass draws it, camera-relative: one kept list per
/// floor and eye ([`terrain_triangles`]), shared by the frame's passes.
pub fn pass_floor_triangles(
    scene: &Scene,
    pass: &crate::plan::PlannedPass,
    eye: DVec3,
) -> Option<std::sync::Arc<Vec<[ObjectVertex; 3]>>> {
    match (pass.terrain, &scene.terrain) {
        (true, Some(t)) => Some(terrain_triangles(t, eye, wet_top_m(scene))),
        _ => None,
    }
}

/// Everything [`pass_object_triangles`] makes a pass's list from, as bits: each of the pass's
/// objects (kind, centre, radius, size, heading, mass, colour) with its pose, and the eye. Two
/// equal keys give bit-identical lists, so a back end may keep a list, and its upload, while
/// the key holds: a still camera over still objects builds and uploads it once, and the
/// passes of a frame that draw the same objects share one build.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ObjectsKey(Vec<u64>);

impl ObjectsKey {
    /// Makes `self` the key of `pass`'s objects seen from `eye`, in its own allocation (no
    /// allocation once it has held a key as long).
    pub fn set(
        &mut self,
        scene: &Scene,
        poses: &ObjectPoses,
        pass: &crate::plan::PlannedPass,
        eye: DVec3,
    ) {
        let k = &mut self.0;
        k.clear();
        k.push(pass.objects.len() as u64);
        k.extend(eye.to_array().map(f64::to_bits));
        for &i in &pass.objects {
            let o = &scene.objects[i];
            push_object_key(k, o, poses.of(i, o));
        }
    }
}

/// Appends one object's key: an `Option` as a flag and its bits (0 when absent), so no two
/// different objects write the same words.
fn push_object_key(k: &mut Vec<u64>, o: &Object, pose: Option<BoatPose>) {
    let opt = |k: &mut Vec<u64>, v: Option<f64>| {
        k.extend([u64::from(v.is_some()), v.map_or(0, f64::to_bits)])
    };
    k.push(match o.kind {
        ObjectKind::Sphere => 0,
        ObjectKind::Box => 1,
        ObjectKind::Boat => 2,
    });
    k.extend(o.center.map(f64::to_bits));
    opt(k, o.radius);
    k.push(u64::from(o.size.is_some()));
    k.extend(o.size.unwrap_or_default().map(f64::to_bits));
    opt(k, o.heading_deg);
    opt(k, o.mass_kg);
    k.extend(o.color.map(f64::to_bits));
    k.push(u64::from(pose.is_some()));
    let p = pose.map_or([DVec3::ZERO; 4], |p| [p.position, p.forward, p.up, p.starboard]);
    k.extend(p.iter().flat_map(|v| v.to_array()).map(f64::to_bits));
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "a panic in a test is its failure report")]

    use super::*;
    use crate::plan::{FramePlan, OutputKind, Pass, PlannedPass};

    fn object(kind: ObjectKind, center: [f64; 3]) -> Object {
        Object {
            kind,
            center,
            radius: (kind == ObjectKind::Sphere).then_some(2.5),
            size: (kind != ObjectKind::Sphere).then_some([6.0, 1.5, 2.0]),
            heading_deg: (kind == ObjectKind::Boat).then_some(30.0),
            mass_kg: None,
            color: [0.7, 0.2, 0.1],
        }
    }

    /// The built-in scene with a sphere, a box and a boat, and its `objects` pass.
    fn scene() -> (Scene, PlannedPass) {
        let mut s = Scene::builtin();
        s.objects = vec![
            object(ObjectKind::Sphere, [10.0, 1.0, -40.0]),
            object(ObjectKind::Box, [-8.0, 0.5, -30.0]),
            object(ObjectKind::Boat, [0.0, 0.0, -50.0]),
        ];
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        let pass = plan.passes.iter().find(|p| p.name == Pass::Objects).unwrap().clone();
        assert_eq!(pass.objects, [0, 1, 2], "the objects pass draws all three");
        (s, pass)
    }

    #[test]
    fn the_sphere_is_the_directly_evaluated_one_bit_for_bit() {
        let (s, _) = scene();
        let eye = DVec3::new(0.3, 4.0, 7.0);
        let poses = ObjectPoses::default();
        let tris = object_triangles(&s.objects[..1], &poses, eye);
        // Every vertex's sines and cosines evaluated where it is used, as the tessellation
        // was written before its points were kept.
        let (c, r) = (DVec3::from_array(s.objects[0].center), 2.5);
        let point = |b: u32, s: u32| {
            let theta = std::f64::consts::PI * b as f64 / SPHERE_BANDS as f64;
            let phi = std::f64::consts::TAU * s as f64 / SPHERE_SEGMENTS as f64;
            DVec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin())
        };
        let v = |n: DVec3| ((c + n * r - eye).as_vec3().to_array(), n.as_vec3().to_array());
        let mut expected = Vec::new();
        for b in 0..SPHERE_BANDS {
            for sg in 0..SPHERE_SEGMENTS {
                let (n00, n01) = (point(b, sg), point(b, sg + 1));
                let (n10, n11) = (point(b + 1, sg), point(b + 1, sg + 1));
                if b > 0 {
                    expected.push([v(n00), v(n10), v(n01)]);
                }
                if b + 1 < SPHERE_BANDS {
                    expected.push([v(n01), v(n10), v(n11)]);
                }
            }
        }
        assert_eq!(tris.len(), expected.len());
        let bits = |a: [f32; 3]| a.map(f32::to_bits);
        for (t, e) in tris.iter().zip(&expected) {
            for (got, (p, n)) in t.iter().zip(e) {
                assert_eq!(bits(got.position), bits(*p));
                assert_eq!(bits(got.normal), bits(*n));
            }
        }
    }

    #[test]
    fn the_key_holds_exactly_while_the_triangles_would_be_the_same() {
        let (s, pass) = scene();
        let eye = DVec3::new(0.3, 4.0, 7.0);
        let rest = ObjectPoses::default();
        let key = |s: &Scene, poses: &ObjectPoses, pass: &PlannedPass, eye: DVec3| {
            let mut k = ObjectsKey::default();
            k.set(s, poses, pass, eye);
            k
        };
        let base = key(&s, &rest, &pass, eye);
        assert_eq!(base, key(&s, &rest, &pass, eye), "the same inputs, another key");
        let list = pass_object_triangles(&s, &rest, &pass, eye);
        assert_eq!(
            bytemuck::cast_slice::<_, u8>(&list),
            bytemuck::cast_slice::<_, u8>(&pass_object_triangles(&s, &rest, &pass, eye)),
        );

        // Each input that changes the triangles changes the key (its negative controls).
        let tilted =
            crate::floating::BoatPose::from_angles(DVec3::new(0.0, -0.4, -50.0), 0.5, 0.01, 0.0);
        let moved = ObjectPoses::from_poses(vec![None, None, Some(tilted)]);
        assert_ne!(
            bytemuck::cast_slice::<_, u8>(&list),
            bytemuck::cast_slice::<_, u8>(&pass_object_triangles(&s, &moved, &pass, eye)),
            "the boat's pose did not move its hull",
        );
        assert_ne!(base, key(&s, &moved, &pass, eye), "the boat's pose");
        let next = DVec3::new(f64::from_bits(eye.x.to_bits() + 1), eye.y, eye.z);
        assert_ne!(base, key(&s, &rest, &pass, next), "the eye, by one ulp");
        type Edit = (&'static str, fn(&mut Scene));
        let edits: [Edit; 6] = [
            ("a centre", |s| s.objects[1].center[2] += 1e-9),
            ("a radius", |s| s.objects[0].radius = Some(2.6)),
            ("a size", |s| s.objects[1].size = Some([6.0, 1.5, 2.1])),
            ("a colour", |s| s.objects[0].color[1] = 0.21),
            ("a kind", |s| s.objects[1].kind = ObjectKind::Boat),
            ("the order", |s| s.objects.swap(0, 1)),
        ];
        for (what, edit) in edits {
            let mut other = s.clone();
            edit(&mut other);
            assert_ne!(base, key(&other, &rest, &pass, eye), "{what}");
        }
        let mut fewer = pass.clone();
        fewer.objects.pop();
        assert_ne!(base, key(&s, &rest, &fewer, eye), "one object fewer");
    }
}

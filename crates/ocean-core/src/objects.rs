//! The scene's objects (`[[objects]]`): spheres, boxes and floating boats, as the scene file
//! gives them and as a validated scene's typed shapes.

use glam::{DMat4, DVec3};
use serde::{Deserialize, Serialize};

use crate::floating::{BoatParams, BoatPose};
pub use crate::geometry::ObjectVertex;

/// What an object is (`kind = "sphere"`, `"box"` or `"boat"`; meshes may come).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ObjectKind {
    /// A sphere: needs `radius`.
    Sphere,
    /// An axis-aligned box: needs `size`.
    Box,
    /// A boat floating on the waves (`crate::floating`): needs `size` (length, hull depth,
    /// beam), takes `heading_deg` and `mass_kg`.
    Boat,
}

/// An `[[objects]]` entry. A flat table rather than a serde-tagged enum: serde buffers a
/// tagged enum's fields and loses their positions, and a user's error must name the line.
/// [`crate::scene::Scene::validate`] checks that each kind has exactly the keys it needs; [`Object::shape`]
/// gives the typed view.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// What the object is.
    pub kind: ObjectKind,
    /// Centre, m. A boat's is where it starts, (x, z); its y is not used: a boat floats at its
    /// draft below the water there (`crate::frame::ObjectPoses`).
    pub center: [f64; 3],
    /// Radius, m (spheres).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Edge lengths, m (boxes: along x, y, z; boats: length, hull depth keel to deck, beam).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 3]>,
    /// A boat's heading when it starts, degrees from +x towards +z (as the waves' directions):
    /// its bow's direction. Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heading_deg: Option<f64>,
    /// A boat's mass, kg; below its hull's full displacement ρ·L·B·H or it sinks (a refused
    /// scene). Default: the launch's loading, [`crate::floating::LAUNCH_LOADING`] of it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_kg: Option<f64>,
    /// Linear RGB albedo.
    #[serde(default = "default_object_color")]
    pub color: [f64; 3],
}

/// The typed shape of a validated [`Object`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A sphere of this radius, m.
    Sphere {
        /// Radius, m.
        radius: f64,
    },
    /// An axis-aligned box with these edge lengths, m.
    Box {
        /// Edge lengths, m.
        size: [f64; 3],
    },
    /// A boat: its hull and its start.
    Boat {
        /// Length, hull depth (keel to deck) and beam, m.
        size: [f64; 3],
        /// The bow's direction at the start, degrees from +x towards +z.
        heading_deg: f64,
        /// Mass, kg (`None`: the launch's loading).
        mass_kg: Option<f64>,
    },
}

impl Object {
    /// The shape, or `None` if the object lacks its kind's key (a scene that passed
    /// [`crate::scene::Scene::validate`] never does).
    pub fn shape(&self) -> Option<Shape> {
        match self.kind {
            ObjectKind::Sphere => self.radius.map(|radius| Shape::Sphere { radius }),
            ObjectKind::Box => self.size.map(|size| Shape::Box { size }),
            ObjectKind::Boat => self.size.map(|size| Shape::Boat {
                size,
                heading_deg: self.heading_deg.unwrap_or(0.0),
                mass_kg: self.mass_kg,
            }),
        }
    }

    /// A boat's build ([`crate::floating::BoatParams::launch`] of its size and mass), `None`
    /// for the other kinds.
    pub fn boat_params(&self) -> Option<crate::floating::BoatParams> {
        match self.shape()? {
            Shape::Boat { size: [length, depth, beam], mass_kg, .. } => {
                Some(crate::floating::BoatParams::launch(length, depth, beam, mass_kg))
            }
            _ => None,
        }
    }
}

fn default_object_color() -> [f64; 3] {
    [0.5, 0.5, 0.5]
}

/// The bow's share of the hull's length: the last 30 % narrows from the full beam to a
/// point on the centre line.
pub const BOW_SHARE: f64 = 0.3;

/// Triangles of one hull: the deck and the keel (pentagons, 3 each) and five sides (2 each).
pub const HULL_TRIANGLES: u32 = 16;

/// Where a boat starts: its start point's (x, z) and its heading as [`BoatPose`]'s yaw.
pub(crate) fn start(o: &Object) -> Option<(BoatParams, f64, f64, f64)> {
    match o.shape()? {
        Shape::Boat { heading_deg, .. } => {
            // heading_deg turns from +x towards +z, clockwise seen from above; yaw turns the
            // bow to port, anticlockwise: the same angle with the other sign.
            Some((o.boat_params()?, o.center[0], o.center[2], -heading_deg.to_radians()))
        }
        _ => None,
    }
}

/// A boat at rest on still water at y = 0: level, its keel at its draft, at its start point
/// and heading. What the planner, which knows no time, takes for its place (the spray's
/// emitters), and what a boat is drawn at when no pose is given.
pub fn resting_pose(o: &Object) -> Option<BoatPose> {
    let (p, x, z, yaw) = start(o)?;
    Some(BoatPose::from_angles(DVec3::new(x, -p.still_water_draft_m(), z), yaw, 0.0, 0.0))
}

/// The hull's outline seen from above, body frame (x forward, z starboard) on the keel
/// plane: stern port, stern starboard, starboard shoulder, bow, port shoulder.
fn outline(length_m: f64, beam_m: f64) -> [DVec3; 5] {
    let (hl, hb) = (0.5 * length_m, 0.5 * beam_m);
    let shoulder = hl - BOW_SHARE * length_m;
    [
        DVec3::new(-hl, 0.0, -hb),
        DVec3::new(-hl, 0.0, hb),
        DVec3::new(shoulder, 0.0, hb),
        DVec3::new(hl, 0.0, 0.0),
        DVec3::new(shoulder, 0.0, -hb),
    ]
}

/// The hull's faces in the body frame ([`BoatPose`]'s: origin the keel's centre, x forward,
/// y up, z starboard): each a convex polygon counter-clockwise seen from outside, with its
/// outward normal. A prism: the outline (a box with a pointed bow, [`BOW_SHARE`]) extruded
/// from the keel plane y = 0 up to the deck at the hull depth. Its volume is
/// B·H·(L − BOW_SHARE·L/2).
pub fn hull_faces(size: [f64; 3]) -> Vec<(DVec3, Vec<DVec3>)> {
    let [length, depth, beam] = size;
    let keel = outline(length, beam);
    let up = DVec3::new(0.0, depth, 0.0);
    let deck: Vec<DVec3> = keel.iter().map(|&p| p + up).collect();
    let mut faces = vec![(DVec3::Y, deck), (DVec3::NEG_Y, keel.to_vec())];
    for i in 0..keel.len() {
        let (a, b) = (keel[i], keel[(i + 1) % keel.len()]);
        let edge = b - a;
        // The outline's centroid is inside and the polygon convex: the outward normal is the
        // edge's horizontal perpendicular that points away from it.
        let mut n = DVec3::new(edge.z, 0.0, -edge.x).normalize();
        if n.dot(a) < 0.0 {
            n = -n;
        }
        faces.push((n, vec![a, b, b + up, a + up]));
    }
    // Wind each face counter-clockwise seen from outside (Newell's normal along the outward).
    for (n, poly) in &mut faces {
        let newell = (0..poly.len())
            .map(|i| poly[i].cross(poly[(i + 1) % poly.len()]))
            .fold(DVec3::ZERO, |s, c| s + c);
        if newell.dot(*n) < 0.0 {
            poly.reverse();
        }
    }
    faces
}

/// The hull's triangles in the world at `pose`: each face fanned from its first corner, the
/// corners through [`BoatPose::model_matrix`], the normals through its rotation.
pub fn hull_triangles(size: [f64; 3], pose: &BoatPose) -> Vec<([DVec3; 3], DVec3)> {
    let m: DMat4 = pose.model_matrix();
    let mut tris = Vec::new();
    for (n, poly) in hull_faces(size) {
        let n = m.transform_vector3(n);
        let w: Vec<DVec3> = poly.iter().map(|&p| m.transform_point3(p)).collect();
        for i in 1..w.len() - 1 {
            tris.push(([w[0], w[i], w[i + 1]], n));
        }
    }
    tris
}

/// The world box of a hull at `pose` (its ten corners'), m.
pub fn hull_bounds(size: [f64; 3], pose: &BoatPose) -> (DVec3, DVec3) {
    let m = pose.model_matrix();
    let up = DVec3::new(0.0, size[1], 0.0);
    outline(size[0], size[2])
        .iter()
        .flat_map(|&p| [p, p + up])
        .map(|p| m.transform_point3(p))
        .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        })
}

/// Tessellation of a sphere: latitude bands × longitude segments.
pub const SPHERE_BANDS: u32 = 24;

/// Longitude segments of a sphere.
pub const SPHERE_SEGMENTS: u32 = 48;

//! The scene in f64: the tracer's parsed [`tracer::Scene`] with every number converted,
//! and every value the tracer derived in f32 (axes, lengths, plane normals, unit vertex
//! normals, default light intensities) derived again here from the numbers as written.

use crate::primitives::{Axis, Cone, Cylinder, Patch, Planar, Shape, Sphere};
use glam::DVec3;
use tracer::{Rgb, Scene};

/// An NFF `f` material in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    pub color: DVec3,
    pub kd: f64,
    pub ks: f64,
    pub shine: f64,
    pub t: f64,
    pub ior: f64,
}

/// A point light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub position: DVec3,
    /// Intensity per channel (r, g, b).
    pub color: DVec3,
}

/// A primitive with its material.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    pub shape: Shape,
    pub material: Material,
}

/// The NFF view in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub from: DVec3,
    pub at: DVec3,
    pub up: DVec3,
    /// Degrees from the centre of the top sample row to that of the bottom one.
    pub angle_deg: f64,
}

/// A whole scene for the reference renderer.
#[derive(Clone, Debug, PartialEq)]
pub struct RefScene {
    pub view: View,
    /// Colour (r, g, b) of rays that hit nothing.
    pub background: DVec3,
    pub lights: Vec<Light>,
    /// Every primitive, in the tracer's order: spheres, cylinders, cones, polygons,
    /// patches (a tie in distance goes to the first).
    pub objects: Vec<Object>,
}

/// A tracer vector in f64 (exact: every f32 is an f64).
pub fn dvec(v: tracer::Vec3) -> DVec3 {
    DVec3::from_array(v.to_array().map(f64::from))
}

/// A colour as an f64 (r, g, b) vector.
pub fn dcolor(c: Rgb) -> DVec3 {
    DVec3::new(c.r.into(), c.g.into(), c.b.into())
}

impl RefScene {
    /// Converts the tracer's scene.
    pub fn new(scene: &Scene) -> Self {
        let material = |index: u32| {
            // As in the tracer: a missing material index reads as the default material.
            let m = scene
                .materials
                .get(index as usize)
                .copied()
                .unwrap_or_default();
            Material {
                color: dcolor(m.color),
                kd: m.kd.into(),
                ks: m.ks.into(),
                shine: m.shine.into(),
                t: m.t.into(),
                ior: m.ior.into(),
            }
        };
        let outline =
            |vertices: &[tracer::Vec3]| Planar::new(vertices.iter().map(|&v| dvec(v)).collect());
        let mut objects = Vec::with_capacity(scene.primitive_count());
        objects.extend(scene.spheres.iter().map(|s| Object {
            shape: Shape::Sphere(Sphere {
                center: dvec(s.center),
                radius: s.radius.into(),
            }),
            material: material(s.material),
        }));
        objects.extend(scene.cylinders.iter().map(|c| Object {
            shape: Shape::Cylinder(Cylinder {
                axis: Axis::new(dvec(c.base), dvec(c.apex)),
                radius: c.radius.into(),
            }),
            material: material(c.material),
        }));
        objects.extend(scene.cones.iter().map(|c| Object {
            shape: Shape::Cone(Cone {
                axis: Axis::new(dvec(c.base), dvec(c.apex)),
                base_radius: c.base_radius.into(),
                apex_radius: c.apex_radius.into(),
            }),
            material: material(c.material),
        }));
        objects.extend(scene.polygons.iter().map(|p| Object {
            shape: Shape::Polygon(outline(&p.outline.vertices)),
            material: material(p.material),
        }));
        objects.extend(scene.patches.iter().map(|p| {
            let normals: Vec<DVec3> = p.written_normals.iter().map(|&n| dvec(n)).collect();
            Object {
                shape: Shape::Patch(Patch::new(outline(&p.outline.vertices), &normals)),
                material: material(p.material),
            }
        }));
        // The SPD default for lights given without a colour, sqrt(n) / (2n) each.
        let n = scene.lights.len().max(1) as f64;
        let default_intensity = n.sqrt() / (2.0 * n);
        let lights = scene
            .lights
            .iter()
            .map(|l| Light {
                position: dvec(l.position),
                color: if l.color_given {
                    dcolor(l.color)
                } else {
                    DVec3::splat(default_intensity)
                },
            })
            .collect();
        let v = &scene.view;
        Self {
            view: View {
                from: dvec(v.from),
                at: dvec(v.at),
                up: dvec(v.up),
                angle_deg: v.angle_deg.into(),
            },
            background: dcolor(scene.background),
            lights,
            objects,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_primitive_converts_and_derived_values_are_recomputed_in_f64() {
        let scene = tracer::parse_nff(
            "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0\nresolution 4 4\n\
             b 0.1 0.2 0.3\nl 1 2 3\nl 4 5 6 0.5 0.25 1\nf 1 0.5 0 0.8 0.2 10 0.1 1.5\n\
             s 0 0 0 -0.1\nc 0 0 0 0.3 0 0 3 0.3\nc 0 0 0 0.1 0 3 0 0.2\n\
             p 3\n0 0 0\n1 0 0\n0 1 0\npp 3\n0 0 1 0 0 2\n1 0 1 0 0 1\n0 1 1 0 0 1\n",
            "t.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let r = RefScene::new(&scene);
        assert_eq!(r.objects.len(), 5);
        assert!(matches!(&r.objects[0].shape, Shape::Sphere(s) if s.radius == -0.1f32 as f64));
        assert!(matches!(&r.objects[1].shape, Shape::Cylinder(c) if c.axis.length == 3.0));
        assert!(matches!(&r.objects[2].shape, Shape::Cone(c) if c.axis.dir == DVec3::Y));
        assert!(matches!(&r.objects[3].shape, Shape::Polygon(p) if p.normal == DVec3::Z));
        assert!(matches!(&r.objects[4].shape, Shape::Patch(p) if p.normals[0] == DVec3::Z));
        assert_eq!(r.objects[4].material.ior, 1.5);
        // Two lights, the first without a colour: sqrt(2) / 4.
        assert_eq!(r.lights[0].color, DVec3::splat(2f64.sqrt() / 4.0));
        assert_eq!(r.lights[1].color, DVec3::new(0.5, 0.25, 1.0));
        assert_eq!(r.background, dcolor(Rgb::new(0.1, 0.2, 0.3)));
        assert_eq!(r.view.angle_deg, 45.0);
    }
}

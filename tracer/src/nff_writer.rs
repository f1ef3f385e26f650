//! NFF writer: prints a [`Scene`] (or single entities) back to NFF text that
//! [`parse_nff`](crate::parse_nff) reads as the same scene.
//!
//! Numbers are printed with Rust's `Display` for `f32`, the shortest decimal that parses
//! back to the same bits, so a written scene loads exactly. The scene keeps what the
//! file said (sphere and quadric radii with their sign, polygon vertices, patch normals
//! as written), and the writer prints that, not derived data.
//!
//! Layout of [`write_scene`]: `b`, the view block, the lights, then for every material in
//! order its `f` line followed by the primitives that use it (spheres, cylinders, cones,
//! polygons, patches). Parsing numbers materials in `f` order and appends primitives per
//! kind in file order, so a parsed scene is written back with the same material indices
//! and primitive order. Cylinders and cones use the one-line `c` form that the SPD
//! generators write (`c bx by bz br ax ay az ar`).

use crate::color::Rgb;
use crate::primitives::{Cone, Cylinder, Patch, Polygon, Sphere};
use crate::scene::{Light, Material, Scene, View};
use crate::vec3::Vec3;
use std::fmt::Write as _;

/// The whole scene as NFF text.
pub fn scene_to_nff(scene: &Scene) -> String {
    let mut out = String::with_capacity(64 + 48 * scene.primitive_count());
    write_scene(&mut out, scene);
    out
}

/// Appends the whole scene as NFF text to `out`.
///
/// A primitive whose material index has no material in `scene.materials` (possible only
/// in scenes built by hand) is shaded with [`Material::default`], so it is written after
/// an `f` line of that default material.
pub fn write_scene(out: &mut String, scene: &Scene) {
    write_background(out, scene.background);
    write_view(out, &scene.view);
    for light in &scene.lights {
        write_light(out, light);
    }
    // Per kind, primitive indices in material order (stable: file order within one
    // material), walked with one cursor per kind: linear in the scene size.
    let spheres = by_material(scene.spheres.iter().map(|p| p.material));
    let cylinders = by_material(scene.cylinders.iter().map(|p| p.material));
    let cones = by_material(scene.cones.iter().map(|p| p.material));
    let polygons = by_material(scene.polygons.iter().map(|p| p.material));
    let patches = by_material(scene.patches.iter().map(|p| p.material));
    let mut cursors = [0usize; 5];
    // Takes the indices of `order` (from `*cursor` on) whose material is below `end`.
    fn take<'a>(order: &'a [(u32, usize)], cursor: &mut usize, end: u64) -> &'a [(u32, usize)] {
        let start = *cursor;
        while *cursor < order.len() && u64::from(order[*cursor].0) < end {
            *cursor += 1;
        }
        &order[start..*cursor]
    }
    let materials = scene.materials.len() as u64;
    for index in 0..=materials {
        let (material, end) = match scene.materials.get(index as usize) {
            Some(m) => (*m, index + 1),
            None => (Material::default(), u64::MAX),
        };
        let groups = [
            take(&spheres, &mut cursors[0], end),
            take(&cylinders, &mut cursors[1], end),
            take(&cones, &mut cursors[2], end),
            take(&polygons, &mut cursors[3], end),
            take(&patches, &mut cursors[4], end),
        ];
        if index == materials && groups.iter().all(|g| g.is_empty()) {
            break;
        }
        write_material(out, &material);
        for &(_, i) in groups[0] {
            write_sphere(out, &scene.spheres[i]);
        }
        for &(_, i) in groups[1] {
            write_cylinder(out, &scene.cylinders[i]);
        }
        for &(_, i) in groups[2] {
            write_cone(out, &scene.cones[i]);
        }
        for &(_, i) in groups[3] {
            write_polygon(out, &scene.polygons[i]);
        }
        for &(_, i) in groups[4] {
            write_patch(out, &scene.patches[i]);
        }
    }
}

/// `(material, index)` pairs sorted by material, ties in index order.
fn by_material(materials: impl Iterator<Item = u32>) -> Vec<(u32, usize)> {
    let mut order: Vec<(u32, usize)> = materials.zip(0..).collect();
    // Already sorted for parsed scenes (the material index never decreases in a file).
    if !order.is_sorted() {
        order.sort_unstable();
    }
    order
}

/// Appends one line built from `args` and a newline.
fn line(out: &mut String, args: std::fmt::Arguments<'_>) {
    // Writing into a String cannot fail.
    let _ = out.write_fmt(args);
    out.push('\n');
}

/// `x y z`, each the shortest decimal that parses back to the same f32.
struct Xyz(Vec3);

impl std::fmt::Display for Xyz {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [x, y, z] = self.0.to_array();
        write!(f, "{x} {y} {z}")
    }
}

/// `b r g b`.
pub fn write_background(out: &mut String, color: Rgb) {
    line(out, format_args!("b {} {} {}", color.r, color.g, color.b));
}

/// The `v` block: from, at, up, angle, hither, resolution.
pub fn write_view(out: &mut String, view: &View) {
    line(
        out,
        format_args!(
            "v\nfrom {}\nat {}\nup {}\nangle {}\nhither {}\nresolution {} {}",
            Xyz(view.from),
            Xyz(view.at),
            Xyz(view.up),
            view.angle_deg,
            view.hither,
            view.width,
            view.height
        ),
    );
}

/// `l x y z`, with `r g b` when the light's colour was given.
pub fn write_light(out: &mut String, light: &Light) {
    if light.color_given {
        let Rgb { r, g, b } = light.color;
        line(out, format_args!("l {} {r} {g} {b}", Xyz(light.position)));
    } else {
        line(out, format_args!("l {}", Xyz(light.position)));
    }
}

/// `f r g b Kd Ks Shine T index_of_refraction`.
pub fn write_material(out: &mut String, m: &Material) {
    let Rgb { r, g, b } = m.color;
    line(
        out,
        format_args!(
            "f {r} {g} {b} {} {} {} {} {}",
            m.kd, m.ks, m.shine, m.t, m.ior
        ),
    );
}

/// `s x y z radius` from a centre and a radius (sign kept).
pub fn write_sphere_at(out: &mut String, center: Vec3, radius: f32) {
    line(out, format_args!("s {} {radius}", Xyz(center)));
}

/// A sphere as written in its scene.
pub fn write_sphere(out: &mut String, sphere: &Sphere) {
    write_sphere_at(out, sphere.center, sphere.radius);
}

/// One-line `c bx by bz base_radius ax ay az apex_radius` (equal radii: a cylinder).
pub fn write_cone_between(
    out: &mut String,
    base: Vec3,
    base_radius: f32,
    apex: Vec3,
    apex_radius: f32,
) {
    line(
        out,
        format_args!("c {} {base_radius} {} {apex_radius}", Xyz(base), Xyz(apex)),
    );
}

/// A cylinder as a `c` entity with equal radii.
pub fn write_cylinder(out: &mut String, cylinder: &Cylinder) {
    let r = cylinder.radius;
    write_cone_between(out, cylinder.base, r, cylinder.apex, r);
}

/// A cone as a `c` entity.
pub fn write_cone(out: &mut String, cone: &Cone) {
    write_cone_between(
        out,
        cone.base,
        cone.base_radius,
        cone.apex,
        cone.apex_radius,
    );
}

/// `p n` and one `x y z` line per vertex.
pub fn write_polygon_vertices(out: &mut String, vertices: &[Vec3]) {
    line(out, format_args!("p {}", vertices.len()));
    for &v in vertices {
        line(out, format_args!("{}", Xyz(v)));
    }
}

/// A polygon as written in its scene.
pub fn write_polygon(out: &mut String, polygon: &Polygon) {
    write_polygon_vertices(out, &polygon.outline.vertices);
}

/// `pp n` and one `x y z nx ny nz` line per vertex. `normals` must be as long as
/// `vertices`.
pub fn write_patch_vertices(out: &mut String, vertices: &[Vec3], normals: &[Vec3]) {
    line(out, format_args!("pp {}", vertices.len()));
    for (&v, &n) in vertices.iter().zip(normals) {
        line(out, format_args!("{} {}", Xyz(v), Xyz(n)));
    }
}

/// A patch with its vertex normals as written (not the normalized ones it shades with).
pub fn write_patch(out: &mut String, patch: &Patch) {
    write_patch_vertices(out, &patch.outline.vertices, &patch.written_normals);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_nff;

    #[test]
    fn every_entity_is_written_in_its_nff_form() {
        let text = "b 0.1 0.2 0.3\nv\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\n\
                    resolution 32 16\nl 1 2 3\nl 4 5 6 0.5 0.25 1\nf 1 0 0 0.8 0.2 10 0 1\n\
                    s 0 0 0 -1.5\nc 0 0 0 1 0 1 0 1\nc 0 0 0 1 0 1 0 0.5\np 3\n0 0 0\n1 0 0\n0 1 0\n\
                    pp 3\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 0.5 1\n";
        let scene = parse_nff(text, "all.nff").unwrap_or_else(|e| panic!("{e}"));
        // The same text, every kind in its place (one material, so one `f`).
        assert_eq!(scene_to_nff(&scene), text);
    }

    #[test]
    fn primitives_are_grouped_under_their_material() {
        // Primitives before any `f` use the default material, written explicitly; a
        // material no primitive uses is still written (indices stay the same).
        let text = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 4 4\n\
                    s 1 1 1 1\nf 1 0 0 1 0 1 0 1\nf 0 1 0 1 0 1 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n\
                    s 2 2 2 1\n";
        let scene = parse_nff(text, "m.nff").unwrap_or_else(|e| panic!("{e}"));
        let expected = "b 0 0 0\nv\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0\n\
                        resolution 4 4\nf 1 1 1 1 0 1 0 1\ns 1 1 1 1\nf 1 0 0 1 0 1 0 1\n\
                        f 0 1 0 1 0 1 0 1\ns 2 2 2 1\np 3\n0 0 0\n1 0 0\n0 1 0\n";
        assert_eq!(scene_to_nff(&scene), expected);
        let again = parse_nff(expected, "m2.nff").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(again, scene);
    }

    #[test]
    fn hand_built_scene_with_unsorted_and_missing_materials() {
        let mut scene = parse_nff(
            "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 4 4\n",
            "v.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        scene.materials = vec![Material {
            kd: 0.5,
            ..Material::default()
        }];
        scene.spheres = vec![
            Sphere::new(Vec3::new(3.0, 0.0, 0.0), 1.0, 7),
            Sphere::new(Vec3::new(1.0, 0.0, 0.0), 1.0, 0),
        ];
        let text = scene_to_nff(&scene);
        // Material 0 first with its sphere; material 7 does not exist: default material.
        assert!(
            text.ends_with("f 1 1 1 0.5 0 1 0 1\ns 1 0 0 1\nf 1 1 1 1 0 1 0 1\ns 3 0 0 1\n"),
            "{text}"
        );
    }

    #[test]
    fn floats_round_trip_bit_for_bit() {
        for value in [
            0.1f32,
            1.0 / 3.0,
            -0.0,
            1e-7,
            f32::MIN_POSITIVE,
            1e-45,
            f32::MAX,
            -123_456.79,
        ] {
            let mut out = String::new();
            write_sphere_at(&mut out, Vec3::new(value, 0.0, 0.0), 1.0);
            let token = out.split_whitespace().nth(1).unwrap_or("");
            let back: f32 = token.parse().unwrap_or(f32::NAN);
            assert_eq!(back.to_bits(), value.to_bits(), "{token}");
        }
    }
}

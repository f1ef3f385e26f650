//! Tachyon writer: prints a [`Scene`] in Tachyon's own scene language (its `.dat`
//! files, read by `parse.c` of John Stone's Tachyon 0.99), so that Tachyon draws the
//! picture rtprof draws. Tachyon's NFF reader cannot: it ignores the view angle (zoom
//! fixed at 1), draws cones as cylinders of the base radius and fans polygons from
//! their first vertex, which breaks concave outlines such as the gears' faces.
//!
//! What maps to what, and why:
//! - camera (`CAMERA … END_CAMERA`; Tachyon's `camera.c`): Tachyon shoots pixel `x`
//!   (1 … W, left to right) and `y` (1 … H, bottom to top) through
//!   `lowleft + x·psx·right + y·psy·up` on an image plane one unit ahead (focal length
//!   1), where `lowleft` is the frustum's (left, bottom) corner and `psx = (right -
//!   left) / W`, `psy = (top - bottom) / H`. `ZOOM z` alone makes the frustum
//!   `±W/(2Hz)` by `±1/(2z)` (with `ASPECTRATIO 1`): its pitch `1/(Hz)` equals
//!   rtprof's `p = 2 tan(angle/2) / (H - 1)` (the NFF angle spans the centres of the
//!   top and bottom sample rows) when `z = (H - 1) / (2 H tan(angle/2))`, which is the
//!   `ZOOM` written. Two things zoom cannot say, so a `FRUSTUM` (which overrides the
//!   zoom's frustum) follows: Tachyon's samples sit at the frustum's pixel corners
//!   `x = 1 … W`, half a pixel off rtprof's pixel centres; and its right vector is
//!   `up × view`, the mirror of rtprof's `view × up` (NFF is right-handed). The
//!   frustum `left = (W + 1) p / 2`, `right = -(W - 1) p / 2`, `bottom = -(H + 1) p / 2`,
//!   `top = (H - 1) p / 2` (left greater than right mirrors the picture back) puts
//!   Tachyon's sample `(x, y)` on rtprof's pixel `(x - 1, H - y)` exactly. The frustum
//!   holds for one size only: [`scene_to_tachyon_at`] writes it for the size rendered.
//!   `ANTIALIASING 0`, one ray per pixel; `RAYDEPTH` rtprof's [`MAX_DEPTH`] (Tachyon
//!   counts the eye ray too);
//! - lights: `LIGHT … RAD 0 COLOR` point lights, without attenuation, in the colour
//!   rtprof shades with (an NFF light without colour has [`Scene::default_light_intensity`]
//!   already);
//! - materials: one `TEXDEF` per NFF `f`, `AMBIENT 0.1·Kd` (rtprof's ambient
//!   [`AMBIENT`] × Kd; Tachyon multiplies the ambient term by the colour, not by the
//!   diffuse weight), `DIFFUSE Kd`, `SPECULAR Ks` (the reflection weight), `OPACITY 1 - T`,
//!   `PHONG PLASTIC Ks PHONG_SIZE Shine` (a highlight in the light's colour, as rtprof's;
//!   it is rtprof's `(R·V)^Shine` when Tachyon runs with `-shade_phong`, otherwise
//!   Blinn's half-vector form), the colour and `TEXFUNC 0` (plain);
//! - spheres as `SPHERE` (radius without its sign: Tachyon has no inside-only
//!   surfaces), cylinders as `FCYLINDER` (open, as NFF's);
//! - cones: Tachyon has no cone (its scene language has `SPHERE`, `FCYLINDER`,
//!   `CYLINDER`, `RING`, `PLANE`, `BOX`, triangles and height fields, nothing tapered),
//!   so a cone is written as the `FCYLINDER` of its mean radius: the same amount of
//!   work, a silhouette off by half the taper at each end (the SPD's tree, whose every
//!   branch is a cone, is drawn so);
//! - polygons as `TRI`s and patches as `STRI`s with their unit vertex normals, cut by
//!   rtprof's own triangulation (`accel::triangulate`: ear clipping in the projection
//!   rtprof's crossing test uses, vertices lifted onto the plane of the first three), so
//!   that concave outlines such as the gears' faces cover what rtprof's test covers. A
//!   self-intersecting outline, which no triangulation covers as the crossing test's
//!   even-odd rule does, is fanned from its first vertex.
//!
//! What Tachyon cannot draw as rtprof does (the definition's `conventions` says so too):
//! it does not refract (a transmitter passes its `1 - OPACITY` straight through), a
//! transmitter filters shadows instead of blocking them, the reflection ray at the
//! last level shows the background instead of nothing, and it truncates colours to
//! 8 bits where rtprof rounds. Numbers are printed as the shortest decimal of their
//! f32, which Tachyon's `%f` reads back to the same f32.

use crate::accel::triangulate::lift;
use crate::color::Rgb;
use crate::counter::{Counter, NoCount};
use crate::primitives::PlanarOutline;
use crate::scene::{Light, Material, Scene, View};
use crate::shading::{AMBIENT, MAX_DEPTH};
use crate::vec3::Vec3;
use std::fmt::Write as _;

/// The whole scene as a Tachyon scene file, its camera for the NFF's own resolution.
pub fn scene_to_tachyon(scene: &Scene) -> String {
    scene_to_tachyon_at(scene, scene.view.width, scene.view.height)
}

/// The whole scene as a Tachyon scene file whose camera frames a `width` × `height`
/// picture as rtprof renders it at that size (Tachyon run with `-res width height`).
pub fn scene_to_tachyon_at(scene: &Scene, width: u32, height: u32) -> String {
    let vertices: usize = scene
        .polygons
        .iter()
        .map(|p| p.outline.vertices.len())
        .chain(scene.patches.iter().map(|p| p.outline.vertices.len()))
        .sum();
    let mut out = String::with_capacity(1024 + 96 * scene.primitive_count() + 240 * vertices);
    line(
        &mut out,
        format_args!(
            "# Tachyon scene written by rtprof from an NFF scene; the camera frames\n\
             # {width} x {height} pixels as rtprof does (render at that -res).\n\
             BEGIN_SCENE\nRESOLUTION {width} {height}\n"
        ),
    );
    write_camera(&mut out, &scene.view, width, height);
    line(
        &mut out,
        format_args!("BACKGROUND {}\n", Color(scene.background)),
    );
    for light in &scene.lights {
        write_light(&mut out, light);
    }
    out.push('\n');
    for (index, material) in scene.materials.iter().enumerate() {
        write_texture(&mut out, &texture_name(scene, index as u64), material);
    }
    // Primitives of a hand-built scene may name a material the scene lacks: the
    // renderer shades those with the default material, so it is defined for them.
    let materials = scene.materials.len() as u64;
    let missing = |m: u32| u64::from(m) >= materials;
    if scene.spheres.iter().any(|p| missing(p.material))
        || scene.cylinders.iter().any(|p| missing(p.material))
        || scene.cones.iter().any(|p| missing(p.material))
        || scene.polygons.iter().any(|p| missing(p.material))
        || scene.patches.iter().any(|p| missing(p.material))
    {
        write_texture(&mut out, DEFAULT_TEXTURE, &Material::default());
    }
    out.push('\n');
    let name = |m: u32| texture_name(scene, u64::from(m));
    for s in &scene.spheres {
        line(
            &mut out,
            format_args!(
                "SPHERE CENTER {} RAD {} {}",
                Xyz(s.center),
                s.radius.abs(),
                name(s.material)
            ),
        );
    }
    for c in &scene.cylinders {
        write_cylinder(&mut out, c.base, c.apex, c.radius.abs(), &name(c.material));
    }
    for c in &scene.cones {
        let mean = 0.5 * (c.base_radius.abs() + c.apex_radius.abs());
        write_cylinder(&mut out, c.base, c.apex, mean, &name(c.material));
    }
    for p in &scene.polygons {
        let texture = name(p.material);
        let (v, triangles) = triangles(&p.outline);
        for [a, b, c] in triangles {
            line(
                &mut out,
                format_args!(
                    "TRI V0 {} V1 {} V2 {} {texture}",
                    Xyz(v[a]),
                    Xyz(v[b]),
                    Xyz(v[c])
                ),
            );
        }
    }
    for p in &scene.patches {
        let texture = name(p.material);
        let (v, triangles) = triangles(&p.outline);
        for [a, b, c] in triangles {
            // A patch holds one normal per vertex (its constructor checks).
            let (Some(&na), Some(&nb), Some(&nc)) =
                (p.normals.get(a), p.normals.get(b), p.normals.get(c))
            else {
                continue;
            };
            line(
                &mut out,
                format_args!(
                    "STRI V0 {} V1 {} V2 {} N0 {} N1 {} N2 {} {texture}",
                    Xyz(v[a]),
                    Xyz(v[b]),
                    Xyz(v[c]),
                    Xyz(na),
                    Xyz(nb),
                    Xyz(nc)
                ),
            );
        }
    }
    out.push_str("\nEND_SCENE\n");
    out
}

/// The name defined for the default material (primitives whose material is missing).
const DEFAULT_TEXTURE: &str = "mat_default";

/// `mat001` for the scene's first material.
fn texture_name(scene: &Scene, index: u64) -> String {
    if index < scene.materials.len() as u64 {
        format!("mat{:03}", index + 1)
    } else {
        DEFAULT_TEXTURE.to_string()
    }
}

/// Appends one line built from `args` and a newline.
fn line(out: &mut String, args: std::fmt::Arguments<'_>) {
    // Writing into a String cannot fail.
    let _ = out.write_fmt(args);
    out.push('\n');
}

/// `x y z`, each the shortest decimal of its f32.
struct Xyz(Vec3);

impl std::fmt::Display for Xyz {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [x, y, z] = self.0.to_array();
        write!(f, "{x} {y} {z}")
    }
}

/// `r g b`.
struct Color(Rgb);

impl std::fmt::Display for Color {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Rgb { r, g, b } = self.0;
        write!(f, "{r} {g} {b}")
    }
}

/// Tachyon's camera for rtprof's view of a `width` × `height` picture: the zoom whose
/// pitch is rtprof's, and the frustum `[left, right, bottom, top]` that puts each
/// sample on rtprof's pixel centre (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Framing {
    zoom: f64,
    frustum: [f64; 4],
}

/// The [`Framing`] of `view` at `width` × `height`, in f64 from the f32 angle.
fn framing(view: &View, width: u32, height: u32) -> Framing {
    let half_span = (f64::from(view.angle_deg).to_radians() * 0.5).tan();
    // rtprof's pitch: the extreme sample rows at ±tan(angle/2) (one row: as two).
    let rows = f64::from(height.max(2) - 1);
    let pitch = 2.0 * half_span / rows;
    let (w, h) = (f64::from(width), f64::from(height.max(1)));
    Framing {
        zoom: 1.0 / (h * pitch),
        frustum: [
            0.5 * (w + 1.0) * pitch,
            -0.5 * (w - 1.0) * pitch,
            -0.5 * (h + 1.0) * pitch,
            0.5 * (h - 1.0) * pitch,
        ],
    }
}

fn write_camera(out: &mut String, view: &View, width: u32, height: u32) {
    let Framing { zoom, frustum } = framing(view, width, height);
    let [left, right, bottom, top] = frustum.map(|x| x as f32);
    // Writing a file, not the counted render.
    let view_dir = NoCount.sub(view.at, view.from);
    line(
        out,
        format_args!(
            "CAMERA\n  ZOOM {}\n  ASPECTRATIO 1\n  ANTIALIASING 0\n  RAYDEPTH {MAX_DEPTH}\n  \
             CENTER {}\n  VIEWDIR {}\n  UPDIR {}\n  FRUSTUM {left} {right} {bottom} {top}\n\
             END_CAMERA\n",
            zoom as f32,
            Xyz(view.from),
            Xyz(view_dir),
            Xyz(view.up)
        ),
    );
}

fn write_light(out: &mut String, light: &Light) {
    line(
        out,
        format_args!(
            "LIGHT CENTER {} RAD 0 COLOR {}",
            Xyz(light.position),
            Color(light.color)
        ),
    );
}

/// `TEXDEF name AMBIENT … DIFFUSE … SPECULAR … OPACITY … PHONG PLASTIC … PHONG_SIZE …
/// COLOR … TEXFUNC 0` for one NFF material.
fn write_texture(out: &mut String, name: &str, m: &Material) {
    line(
        out,
        format_args!(
            "TEXDEF {name} AMBIENT {} DIFFUSE {} SPECULAR {} OPACITY {}\n  \
             PHONG PLASTIC {} PHONG_SIZE {} COLOR {} TEXFUNC 0",
            AMBIENT * m.kd,
            m.kd,
            m.ks,
            1.0 - m.t,
            m.ks,
            m.shine,
            Color(m.color)
        ),
    );
}

/// `FCYLINDER BASE … APEX … RAD r name`: open, as NFF's cylinders.
fn write_cylinder(out: &mut String, base: Vec3, apex: Vec3, radius: f32, texture: &str) {
    line(
        out,
        format_args!(
            "FCYLINDER BASE {} APEX {} RAD {radius} {texture}",
            Xyz(base),
            Xyz(apex)
        ),
    );
}

/// The vertices and triangles (index triples) a polygon or patch is written as:
/// rtprof's triangulation on the lifted vertices, or for a self-intersecting outline a
/// fan of the vertices as written.
fn triangles(outline: &PlanarOutline) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let lifted = lift(outline);
    match lifted.triangles {
        Some(triangles) => (
            lifted.vertices.into_iter().map(Vec3::from_array).collect(),
            triangles
                .into_iter()
                .map(|t| t.map(|i| i as usize))
                .collect(),
        ),
        None => {
            let n = outline.vertices.len();
            let fan = (1..n.saturating_sub(1)).map(|i| [0, i, i + 1]).collect();
            (outline.vertices.clone(), fan)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_nff;
    use crate::primitives::Sphere;

    fn parse(text: &str) -> Scene {
        parse_nff(text, "tachyon.nff").unwrap_or_else(|e| panic!("{e}"))
    }

    const VIEW: &str = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 90\nhither 1\nresolution 5 3\n";

    #[test]
    fn zoom_and_frustum_of_a_90_degree_view_by_hand() {
        // 90°: tan 45° = 1, so the 3 rows' centres span ±1 and the pitch is 2/(3-1) = 1.
        // Tachyon's frustum from ZOOM z is 1/z high for 3 rows: the pitch 1/(3z) is 1
        // for z = 1/3. The frustum: left (5+1)/2 = 3, right -(5-1)/2 = -2, bottom
        // -(3+1)/2 = -2, top (3-1)/2 = 1; Tachyon's column x = 1 then looks at
        // 3 - 1·1 = 2 along its right (= rtprof's -right): rtprof's column 0, at -2.
        let scene = parse(VIEW);
        let Framing { zoom, frustum } = framing(&scene.view, 5, 3);
        assert!((zoom - 1.0 / 3.0).abs() < 1e-12, "{zoom}");
        for (got, want) in frustum.iter().zip([3.0, -2.0, -2.0, 1.0]) {
            assert!((got - want).abs() < 1e-12, "{frustum:?}");
        }
        // 45°, 512 rows (the SPD's view): z = 511 / (1024 tan 22.5°).
        let spd = parse("v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 512 512\n");
        let zoom = framing(&spd.view, 512, 512).zoom;
        let by_hand = 511.0 / (1024.0 * 0.414_213_562_373_095_03);
        assert!((zoom - by_hand).abs() < 1e-6, "{zoom} vs {by_hand}");
    }

    #[test]
    fn camera_block_in_tachyon_form() {
        let text = scene_to_tachyon(&parse(VIEW));
        let camera = "CAMERA\n  ZOOM 0.33333334\n  ASPECTRATIO 1\n  ANTIALIASING 0\n  \
                      RAYDEPTH 5\n  CENTER 0 0 -5\n  VIEWDIR 0 0 5\n  UPDIR 0 1 0\n  \
                      FRUSTUM 3 -2 -2 1\nEND_CAMERA\n";
        assert!(text.contains(camera), "{text}");
        assert!(text.starts_with("# Tachyon scene"), "{text}");
        assert!(text.contains("\nBEGIN_SCENE\nRESOLUTION 5 3\n"), "{text}");
        assert!(text.ends_with("END_SCENE\n"), "{text}");
        // Written for another size, the frustum follows it: 3 x 3, pitch 1.
        let other = scene_to_tachyon_at(&parse(VIEW), 3, 3);
        assert!(other.contains("RESOLUTION 3 3\n"), "{other}");
        assert!(other.contains("FRUSTUM 2 -1 -2 1\n"), "{other}");
    }

    #[test]
    fn lights_textures_and_primitives_in_tachyon_form() {
        let scene = parse(&format!(
            "b 0.1 0.2 0.3\n{VIEW}l 1 2 3\nl 4 5 6 0.5 0.25 1\n\
             f 1 0.5 0 0.7 0.3 20 0 1\ns 0 0 0 -1.5\nc 0 0 0 1 0 1 0 1\nc 0 0 0 1 0 1 0 0.5\n\
             f 1 1 1 0.5 0 1 0.75 1.5\np 3\n0 0 0\n1 0 0\n0 1 0\n\
             pp 3\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 0.5 1\n"
        ));
        let text = scene_to_tachyon(&scene);
        // Two lights without colour: sqrt(2)/4 each (the SPD default).
        let d = Scene::default_light_intensity(2);
        for expected in [
            "BACKGROUND 0.1 0.2 0.3\n".to_string(),
            format!("LIGHT CENTER 1 2 3 RAD 0 COLOR {d} {d} {d}\n"),
            "LIGHT CENTER 4 5 6 RAD 0 COLOR 0.5 0.25 1\n".to_string(),
            "TEXDEF mat001 AMBIENT 0.07 DIFFUSE 0.7 SPECULAR 0.3 OPACITY 1\n  \
             PHONG PLASTIC 0.3 PHONG_SIZE 20 COLOR 1 0.5 0 TEXFUNC 0\n"
                .to_string(),
            "TEXDEF mat002 AMBIENT 0.05 DIFFUSE 0.5 SPECULAR 0 OPACITY 0.25\n  \
             PHONG PLASTIC 0 PHONG_SIZE 1 COLOR 1 1 1 TEXFUNC 0\n"
                .to_string(),
            "SPHERE CENTER 0 0 0 RAD 1.5 mat001\n".to_string(),
            "FCYLINDER BASE 0 0 0 APEX 0 1 0 RAD 1 mat001\n".to_string(),
            // A cone: the cylinder of its mean radius (Tachyon has no cone).
            "FCYLINDER BASE 0 0 0 APEX 0 1 0 RAD 0.75 mat001\n".to_string(),
            "TRI V0 0 0 0 V1 1 0 0 V2 0 1 0 mat002\n".to_string(),
            // The patch's unit normals, not the written ones.
            "STRI V0 0 0 0 V1 1 0 0 V2 0 1 0 N0 0 0 1 N1 0 0 1 N2 0 0.4472136 0.8944272 \
             mat002\n"
                .to_string(),
        ] {
            assert!(text.contains(&expected), "missing {expected:?} in\n{text}");
        }
        assert!(!text.contains("mat_default"), "{text}");
    }

    #[test]
    fn concave_polygon_is_cut_by_rtprofs_triangulation() {
        // An L of 6 vertices, concave at (1, 1): a fan from vertex 0 would cover the
        // notch; ear clipping gives 4 triangles covering the L's area 3, none folded.
        let scene = parse(&format!(
            "{VIEW}p 6\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n"
        ));
        let text = scene_to_tachyon(&scene);
        let tris: Vec<[[f64; 2]; 3]> = text
            .lines()
            .filter_map(|l| l.strip_prefix("TRI "))
            .map(|l| {
                let n: Vec<f64> = l
                    .split_whitespace()
                    .filter_map(|w| w.parse().ok())
                    .collect();
                [[n[0], n[1]], [n[3], n[4]], [n[6], n[7]]]
            })
            .collect();
        assert_eq!(tris.len(), 4, "{text}");
        let area2 = |[a, b, c]: [[f64; 2]; 3]| {
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        };
        assert!(tris.iter().all(|&t| area2(t) > 0.0), "{tris:?}");
        let total: f64 = tris.iter().map(|&t| area2(t)).sum();
        assert!((total - 6.0).abs() < 1e-9, "{total}");
        // No triangle holds the notch's centre (1.5, 1.5).
        let inside = |[a, b, c]: [[f64; 2]; 3], p: [f64; 2]| {
            [area2([a, b, p]), area2([b, c, p]), area2([c, a, p])]
                .iter()
                .all(|&s| s > 0.0)
        };
        assert!(!tris.iter().any(|&t| inside(t, [1.5, 1.5])), "{tris:?}");
    }

    #[test]
    fn self_intersecting_outline_is_fanned() {
        let scene = parse(&format!("{VIEW}p 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n"));
        let text = scene_to_tachyon(&scene);
        assert!(
            text.contains("TRI V0 0 0 0 V1 1 1 0 V2 1 0 0 mat001\n"),
            "{text}"
        );
        assert!(
            text.contains("TRI V0 0 0 0 V1 1 0 0 V2 0 1 0 mat001\n"),
            "{text}"
        );
    }

    #[test]
    fn missing_material_gets_the_defined_default() {
        let mut scene = parse(VIEW);
        scene.spheres = vec![Sphere::new(Vec3::new(1.0, 0.0, 0.0), 1.0, 3)];
        let text = scene_to_tachyon(&scene);
        assert!(
            text.contains(
                "TEXDEF mat_default AMBIENT 0.1 DIFFUSE 1 SPECULAR 0 OPACITY 1\n  \
                 PHONG PLASTIC 0 PHONG_SIZE 1 COLOR 1 1 1 TEXFUNC 0\n"
            ),
            "{text}"
        );
        assert!(
            text.contains("SPHERE CENTER 1 0 0 RAD 1 mat_default\n"),
            "{text}"
        );
    }
}

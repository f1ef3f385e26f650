//! POV-Ray writer: prints a [`Scene`] as a POV-Ray scene file that draws the picture
//! the SPD's own POV-Ray output draws.
//!
//! It follows Eric Haines's SPD 3.14 library (`lib*.c`, output format
//! `OUTPUT_POVRAY_30`; github.com/erich666/StandardProceduralDatabases), which wrote
//! the POV-Ray files of the seven classic scenes:
//! - camera (`lib_output_viewpoint`): `direction` the unit view vector, `up` the up
//!   vector made perpendicular to it and `right` the view vector × up (POV-Ray is
//!   left-handed), scaled to the frustum `2 tan(angle / 2)` high and `aspect` times as
//!   wide. Like the SPD, the frustum spans the angle edge to edge (NFF: centre row to
//!   centre row, 0.2 % less at 512 rows); the aspect is width / height of the NFF
//!   resolution (square pixels), and `hither` is not written (POV-Ray has none);
//! - lights (`lib_output_light`): point lights; one given without a colour gets
//!   `1 / sqrt(n)` for `n` lights (the SPD's POV-Ray scale, twice the NFF default of
//!   [`Scene::default_light_intensity`]), a given colour is written as it is;
//! - materials (`lib_output_color`): pigment colour with `filter T` for transmitters,
//!   finish `ambient 0`, `diffuse Kd`, `phong Ks phong_size Shine` and `reflection Ks`
//!   when `Ks` is not 0, and for transmitters the `ior` (in `interior`, where POV-Ray
//!   3.x wants it; the SPD's `refraction 1.0 ior` in the finish draws the same but
//!   warns). The NFF carries one `Ks` where the SPD generators had a highlight weight
//!   and a reflection weight, and no ambient: see the note below;
//! - spheres, and cylinders and cones as open `cone`s apex first (`lib_output_sphere`,
//!   `lib_output_cylcone`); radii are written without their sign (POV-Ray has no
//!   inside-only surfaces and draws nothing for a negative sphere radius);
//! - polygons as `triangle`s and patches as `smooth_triangle`s with the normals as
//!   written, split by the SPD's own splitter (`split_polygon` in `libply.c`: cut at
//!   the leftmost vertex), so that concave polygons such as the gears' faces come out
//!   as the SPD's triangles. Not always the very same ones: the SPD cut the
//!   generators' doubles, and where two vertices print the same coordinate its tie
//!   may break otherwise (128 of gears' 9345 faces), into triangles that cover the
//!   same face.
//!
//! The file starts with `#version 3.6;`: POV-Ray 3.7 then renders without gamma
//! correction, as it renders the SPD's files (which declare no version); under
//! `#version 3.7` it would encode the colours for sRGB and draw a brighter picture.
//!
//! What the NFF cannot say: the SPD's POV-Ray files were written from the generators'
//! parameters, not from the NFF. Where a generator gave a highlight weight other than
//! its reflection weight (gears' floor, mount's glass, rings' spheres) or an ambient
//! term (balls' floor), the NFF kept only `Ks` and `Kd`, and this writer, reading the
//! NFF, writes `phong Ks` and `ambient 0`.
//!
//! The scene's numbers are printed with Rust's `Display` for `f32` (the shortest decimal
//! that parses back to the same bits: the NFF's own text). The camera, derived, is
//! computed in f64 from those decimals and printed to six digits, as the SPD computed
//! and printed it, so that POV-Ray shoots the same eye rays from both files.

use crate::color::Rgb;
use crate::scene::{Light, Material, Scene, View};
use crate::vec3::Vec3;
use std::fmt::Write as _;

/// The whole scene as a POV-Ray scene file.
pub fn scene_to_pov(scene: &Scene) -> String {
    let vertices: usize = scene
        .polygons
        .iter()
        .map(|p| p.outline.vertices.len())
        .chain(scene.patches.iter().map(|p| p.outline.vertices.len()))
        .sum();
    let mut out = String::with_capacity(1024 + 64 * scene.primitive_count() + 120 * vertices);
    line(
        &mut out,
        format_args!(
            "// POV-Ray scene written by rtprof from an NFF scene, after the SPD's POV-Ray output.\n\
             // The NFF resolution: render with +W{} +H{} (the camera assumes that aspect).\n\
             #version 3.6; // no gamma correction, as for the SPD's own files\n",
            scene.view.width, scene.view.height
        ),
    );
    write_background(&mut out, scene.background);
    write_camera(&mut out, &scene.view);
    let default_intensity = pov_default_intensity(scene.lights.len());
    for light in &scene.lights {
        write_light(&mut out, light, default_intensity);
    }
    out.push('\n');
    for (index, material) in scene.materials.iter().enumerate() {
        write_material(&mut out, &material_name(scene, index as u64), material);
    }
    // Primitives of a hand-built scene may name a material the scene lacks: the
    // renderer shades those with the default material, so it is declared for them.
    let materials = scene.materials.len() as u64;
    let missing = |m: u32| u64::from(m) >= materials;
    if scene.spheres.iter().any(|p| missing(p.material))
        || scene.cylinders.iter().any(|p| missing(p.material))
        || scene.cones.iter().any(|p| missing(p.material))
        || scene.polygons.iter().any(|p| missing(p.material))
        || scene.patches.iter().any(|p| missing(p.material))
    {
        write_material(&mut out, DEFAULT_MATERIAL, &Material::default());
    }
    let name = |m: u32| material_name(scene, u64::from(m));
    for s in &scene.spheres {
        line(
            &mut out,
            format_args!(
                "sphere {{ {}, {} material {{ {} }} }}",
                Xyz(s.center),
                s.radius.abs(),
                name(s.material)
            ),
        );
    }
    for c in &scene.cylinders {
        let r = c.radius.abs();
        write_cone(&mut out, c.base, r, c.apex, r, &name(c.material));
    }
    for c in &scene.cones {
        let (rb, ra) = (c.base_radius.abs(), c.apex_radius.abs());
        write_cone(&mut out, c.base, rb, c.apex, ra, &name(c.material));
    }
    for p in &scene.polygons {
        let v = &p.outline.vertices;
        let material = name(p.material);
        for [a, b, c] in spd_triangles(v) {
            line(
                &mut out,
                format_args!(
                    "triangle {{ {}, {}, {} material {{ {material} }} }}",
                    Xyz(v[a]),
                    Xyz(v[b]),
                    Xyz(v[c])
                ),
            );
        }
    }
    for p in &scene.patches {
        let (v, n) = (&p.outline.vertices, &p.written_normals);
        let material = name(p.material);
        for [a, b, c] in spd_triangles(v) {
            // A patch holds one normal per vertex (its constructor checks).
            let (Some(&na), Some(&nb), Some(&nc)) = (n.get(a), n.get(b), n.get(c)) else {
                continue;
            };
            line(
                &mut out,
                format_args!(
                    "smooth_triangle {{ {}, {}, {}, {}, {}, {} material {{ {material} }} }}",
                    Xyz(v[a]),
                    Xyz(na),
                    Xyz(v[b]),
                    Xyz(nb),
                    Xyz(v[c]),
                    Xyz(nc)
                ),
            );
        }
    }
    out
}

/// The name declared for the default material (primitives whose material is missing).
const DEFAULT_MATERIAL: &str = "mat_default";

/// `mat001` for the scene's first material (the SPD numbered its `txt001` from 1).
fn material_name(scene: &Scene, index: u64) -> String {
    if index < scene.materials.len() as u64 {
        format!("mat{:03}", index + 1)
    } else {
        DEFAULT_MATERIAL.to_string()
    }
}

/// The intensity the SPD gives each of `n` lights in its POV-Ray files: `1 / sqrt(n)`.
fn pov_default_intensity(light_count: usize) -> f32 {
    let n = light_count.max(1) as f64;
    #[allow(clippy::disallowed_methods)] // writing a file, not the counted render
    let root = n.sqrt();
    (1.0 / root) as f32
}

/// Appends one line built from `args` and a newline.
fn line(out: &mut String, args: std::fmt::Arguments<'_>) {
    // Writing into a String cannot fail.
    let _ = out.write_fmt(args);
    out.push('\n');
}

/// `<x, y, z>`, each the shortest decimal that parses back to the same f32.
struct Xyz(Vec3);

impl std::fmt::Display for Xyz {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [x, y, z] = self.0.to_array();
        write!(f, "<{x}, {y}, {z}>")
    }
}

/// `color red r green g blue b`, the SPD's colour form.
struct Color(Rgb);

impl std::fmt::Display for Color {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Rgb { r, g, b } = self.0;
        write!(f, "color red {r} green {g} blue {b}")
    }
}

fn write_background(out: &mut String, color: Rgb) {
    line(out, format_args!("background {{ {} }}\n", Color(color)));
}

/// The camera vectors of `lib_output_viewpoint`, in f64: `[location, direction, right, up]`.
fn camera_vectors(view: &View) -> [[f64; 3]; 4] {
    let v = |p: Vec3| p.to_array().map(as_written);
    let (from, at) = (v(view.from), v(view.at));
    let up = normalized(v(view.up));
    let direction = normalized([at[0] - from[0], at[1] - from[1], at[2] - from[2]]);
    let right = normalized(cross(up, direction));
    let up = normalized(cross(direction, right));
    let height = 2.0 * (std::f64::consts::PI * f64::from(view.angle_deg) / 360.0).tan();
    // Square pixels: the frustum is as much wider than high as the image.
    let aspect = if view.height > 0 && view.width > 0 {
        f64::from(view.width) / f64::from(view.height)
    } else {
        1.0
    };
    let width = aspect * height;
    // The SPD's right vector is up × direction; POV-Ray, left-handed, wants its negative.
    [
        from,
        direction,
        right.map(|c| -c * width),
        up.map(|c| c * height),
    ]
}

/// The decimal an f32 was read from, as f64 (the shortest decimal that gives these bits,
/// which is the NFF's own text for numbers of up to six digits, as the SPD writes).
fn as_written(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(f64::from(x))
}

/// `x` rounded to six significant digits, what C's `%g` prints.
fn six_digits(x: f64) -> f64 {
    format!("{x:.5e}").parse().unwrap_or(x)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v` scaled to unit length; a zero vector stays zero (as `lib_normalize_vector` does).
fn normalized(v: [f64; 3]) -> [f64; 3] {
    #[allow(clippy::disallowed_methods)] // writing a file, not the counted render
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if length > 0.0 {
        v.map(|c| c / length)
    } else {
        v
    }
}

fn write_camera(out: &mut String, view: &View) {
    // Six digits, as the SPD printed its camera (`%g`): the same eye rays as its file,
    // bit for bit (a camera 1e-7 off moves the edges of balls' 7381 spheres by enough
    // to flip pixels), at 1e-6 of a direction, a thousandth of a pixel at 512 rows.
    let [location, direction, right, up] = camera_vectors(view).map(|[x, y, z]| {
        let [x, y, z] = [x, y, z].map(six_digits);
        format!("<{x}, {y}, {z}>")
    });
    line(
        out,
        format_args!(
            "camera {{\n    location  {location}\n    direction {direction}\n    \
             right     {right}\n    up        {up}\n}}\n"
        ),
    );
}

fn write_light(out: &mut String, light: &Light, default_intensity: f32) {
    let color = if light.color_given {
        light.color
    } else {
        Rgb::new(default_intensity, default_intensity, default_intensity)
    };
    line(
        out,
        format_args!(
            "light_source {{ {} {} }}",
            Xyz(light.position),
            Color(color)
        ),
    );
}

/// `#declare name = material { texture { pigment finish } [interior] }`.
fn write_material(out: &mut String, name: &str, m: &Material) {
    let filter = if m.t > 0.0 {
        format!(" filter {}", m.t)
    } else {
        String::new()
    };
    line(
        out,
        format_args!(
            "#declare {name} = material {{\n    texture {{\n        pigment {{ {}{filter} }}\n        \
             finish {{\n            ambient 0\n            diffuse {}",
            Color(m.color),
            m.kd
        ),
    );
    // Ks is the NFF's highlight and reflection weight both (SPD rule: Phong highlights
    // on reflective surfaces).
    if m.ks != 0.0 {
        line(
            out,
            format_args!(
                "            phong {}  phong_size {}\n            reflection {}",
                m.ks, m.shine, m.ks
            ),
        );
    }
    line(out, format_args!("        }}\n    }}"));
    if m.t > 0.0 {
        line(out, format_args!("    interior {{ ior {} }}", m.ior));
    }
    line(out, format_args!("}}\n"));
}

/// `cone { <apex>, ra, <base>, rb open material { name } }`: the SPD's order, no caps.
fn write_cone(out: &mut String, base: Vec3, rb: f32, apex: Vec3, ra: f32, material: &str) {
    line(
        out,
        format_args!(
            "cone {{ {}, {ra}, {}, {rb} open material {{ {material} }} }}",
            Xyz(apex),
            Xyz(base)
        ),
    );
}

/// The triangles (vertex index triples) into which the SPD's `split_polygon` cuts a
/// polygon of these vertices: repeatedly, at the leftmost vertex (in the projection
/// that drops the largest component of the first three vertices' normal), either its
/// ear or the diagonal to the vertex the ear would contain. `n` vertices give `n - 2`
/// triangles; none for fewer than three. Quadratic in `n`, as the SPD's (each cut scans
/// the rest): the parser's largest polygon, 65,536 vertices, takes tens of seconds.
fn spd_triangles(vertices: &[Vec3]) -> Vec<[usize; 3]> {
    let count = vertices.len();
    if count < 3 {
        return Vec::new();
    }
    let (axis1, axis2) = spd_axes(vertices);
    let points: Vec<[f64; 2]> = vertices
        .iter()
        .map(|v| {
            let c = v.to_array();
            [f64::from(c[axis1]), f64::from(c[axis2])]
        })
        .collect();
    // The SPD's vertex buffer: a stack of polygons, each a run of vertex indices; the
    // top one is last. `ends` holds each run's last position.
    let mut buffer: Vec<usize> = (0..count).collect();
    let mut ends: Vec<usize> = vec![count - 1];
    let mut triangles = Vec::with_capacity(count - 2);
    let mut scratch: Vec<usize> = Vec::with_capacity(count + 2);
    while let Some(&n) = ends.last() {
        let m = match ends.len() {
            0 | 1 => 0,
            len => ends[len - 2] + 1,
        };
        if n < m + 3 {
            // Three vertices (every split leaves runs of at least three).
            if n == m + 2 {
                triangles.push([buffer[m], buffer[m + 1], buffer[m + 2]]);
            }
            ends.pop();
            continue;
        }
        let x = |i: usize| points[buffer[i]][0];
        let y = |i: usize| points[buffer[i]][1];
        // leftmost_vertex: the first of the smallest x.
        let mut l = m;
        for i in m + 1..=n {
            if x(i) < x(l) {
                l = i;
            }
        }
        let la = if l == n { m } else { l + 1 };
        let lb = if l == m { n } else { l - 1 };
        // split_vertex: the leftmost other vertex inside the triangle (lb, l, la), if
        // any (the loop stops before n, as the SPD's does).
        let (yu, yl) = (y(l).max(y(la)).max(y(lb)), y(l).min(y(la)).min(y(lb)));
        let (lpu, lpl) = if y(lb) > y(la) { (lb, la) } else { (la, lb) };
        let mut ls = if x(lb) > x(la) { lb } else { la };
        for k in m..n {
            if k == la || k == l || k == lb || !(y(k) <= yu && y(k) >= yl && x(k) < x(ls)) {
                continue;
            }
            let below_upper = (y(k) - y(l)) * (x(lpu) - x(l)) <= (y(lpu) - y(l)) * (x(k) - x(l));
            let above_lower = (y(k) - y(l)) * (x(lpl) - x(l)) >= (y(lpl) - y(l)) * (x(k) - x(l));
            if below_upper && above_lower {
                ls = k;
            }
        }
        let (m1, n1) = if ls == la || ls == lb {
            (la.min(lb), la.max(lb))
        } else {
            (l.min(ls), l.max(ls))
        };
        // perform_split: the run m1..=n1 becomes a polygon of its own, below the rest
        // (m..=m1 and n1..=n), which is split next.
        scratch.clear();
        scratch.extend_from_slice(&buffer[m1..=n1]);
        scratch.extend_from_slice(&buffer[m..=m1]);
        scratch.extend_from_slice(&buffer[n1..=n]);
        buffer.truncate(m);
        buffer.extend_from_slice(&scratch);
        if let Some(top) = ends.last_mut() {
            *top = m + n1 - m1;
        }
        ends.push(n + 2);
    }
    triangles
}

/// `find_axes`: the two coordinates kept when the largest component of the normal of
/// the first three vertices is dropped.
fn spd_axes(vertices: &[Vec3]) -> (usize, usize) {
    let v = |i: usize| vertices[i].to_array().map(f64::from);
    let (v0, v1, v2) = (v(0), v(1), v(2));
    let p1 = [v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]];
    let p2 = [v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]];
    let [x, y, z] = cross(p1, p2).map(f64::abs);
    if x > y && x > z {
        (1, 2)
    } else if y > x && y > z {
        (0, 2)
    } else {
        (0, 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_nff;
    use crate::primitives::Sphere;

    fn parse(text: &str) -> Scene {
        parse_nff(text, "pov.nff").unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn camera_of_a_view_along_y_by_hand() {
        // From the origin looking along +y, z up, 90 degrees, 200 x 100 pixels: the
        // frustum is 2 tan(45°) = 2 high and twice that wide; right = +x (POV-Ray's
        // left-handed right of a right-handed view along +y with z up).
        let scene =
            parse("v\nfrom 0 0 0\nat 0 5 0\nup 0 0 3\nangle 90\nhither 1\nresolution 200 100\n");
        let [location, direction, right, up] = camera_vectors(&scene.view);
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(p, q)| (p - q).abs() < 1e-12);
        assert!(close(location, [0.0, 0.0, 0.0]));
        assert!(close(direction, [0.0, 1.0, 0.0]), "{direction:?}");
        assert!(close(right, [4.0, 0.0, 0.0]), "{right:?}");
        assert!(close(up, [0.0, 0.0, 2.0]), "{up:?}");
        // The zeros keep the sign of the product that made them (the SPD's have it too).
        let text = scene_to_pov(&scene);
        assert!(
            text.contains(
                "camera {\n    location  <0, 0, 0>\n    direction <0, 1, 0>\n    \
                 right     <4, -0, -0>\n    up        <0, -0, 2>\n}"
            ),
            "{text}"
        );
    }

    #[test]
    fn tilted_up_vector_is_made_perpendicular() {
        // Looking along -x from (1, 0, 0) with up (0, 1, 1), already across the line of
        // sight: up stays (0, 1, 1)/√2 and right = direction × up = (0, 1, -1)/√2 (the
        // right of the picture is +y, as in a right-handed view), both 2 tan(30°) long.
        let scene = parse("v\nfrom 1 0 0\nat 0 0 0\nup 0 1 1\nangle 60\nresolution 8 8\n");
        let [_, direction, right, up] = camera_vectors(&scene.view);
        let h = 2.0 * (30f64).to_radians().tan();
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let expect = [[-1.0, 0.0, 0.0], [0.0, s * h, -s * h], [0.0, s * h, s * h]];
        for (got, want) in [direction, right, up].iter().zip(expect) {
            assert!(
                got.iter().zip(want).all(|(p, q)| (p - q).abs() < 1e-12),
                "{got:?} vs {want:?}"
            );
        }
        // right = direction × up: seen from the eye, right of the picture.
        let c = cross(direction, up);
        assert!(c.iter().zip(right).all(|(p, q)| (p - q).abs() < 1e-12));
    }

    #[test]
    fn lights_materials_and_primitives_in_pov_form() {
        let scene = parse(
            "b 0.1 0.2 0.3\nv\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 4 4\n\
             l 1 2 3\nl 4 5 6 0.5 0.25 1\nl 7 8 9\nl 0 0 0\n\
             f 1 0.5 0 0.7 0.3 20 0 1\ns 0 0 0 -1.5\nc 0 0 0 1 0 1 0 1\nc 0 0 0 1 0 1 0 0.5\n\
             f 1 1 1 0.1 0 1 0.9 1.5\np 3\n0 0 0\n1 0 0\n0 1 0\n\
             pp 3\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0 0 0.5 1\n",
        );
        let text = scene_to_pov(&scene);
        for expected in [
            "#version 3.6;",
            "background { color red 0.1 green 0.2 blue 0.3 }",
            // Four lights, three without colour: 1/√4 each.
            "light_source { <1, 2, 3> color red 0.5 green 0.5 blue 0.5 }",
            "light_source { <4, 5, 6> color red 0.5 green 0.25 blue 1 }",
            "#declare mat001 = material {\n    texture {\n        \
             pigment { color red 1 green 0.5 blue 0 }\n        finish {\n            \
             ambient 0\n            diffuse 0.7\n            phong 0.3  phong_size 20\n            \
             reflection 0.3\n        }\n    }\n}\n",
            "#declare mat002 = material {\n    texture {\n        \
             pigment { color red 1 green 1 blue 1 filter 0.9 }\n        finish {\n            \
             ambient 0\n            diffuse 0.1\n        }\n    }\n    interior { ior 1.5 }\n}\n",
            "sphere { <0, 0, 0>, 1.5 material { mat001 } }",
            "cone { <0, 1, 0>, 1, <0, 0, 0>, 1 open material { mat001 } }",
            "cone { <0, 1, 0>, 0.5, <0, 0, 0>, 1 open material { mat001 } }",
            "triangle { <0, 0, 0>, <1, 0, 0>, <0, 1, 0> material { mat002 } }",
            "smooth_triangle { <0, 0, 0>, <0, 0, 2>, <1, 0, 0>, <0, 0, 1>, <0, 1, 0>, \
             <0, 0.5, 1> material { mat002 } }",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
        assert!(!text.contains("mat_default"), "{text}");
    }

    #[test]
    fn missing_material_gets_the_declared_default() {
        let mut scene = parse("v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 45\nresolution 4 4\n");
        scene.spheres = vec![Sphere::new(Vec3::new(1.0, 0.0, 0.0), 1.0, 3)];
        let text = scene_to_pov(&scene);
        assert!(text.contains("#declare mat_default = material {"), "{text}");
        assert!(text.contains("diffuse 1\n"), "{text}");
        assert!(
            text.contains("sphere { <1, 0, 0>, 1 material { mat_default } }"),
            "{text}"
        );
    }

    /// Twice the signed area of a triangle in the xy plane.
    fn area2(v: &[Vec3], [a, b, c]: [usize; 3]) -> f64 {
        let p = |i: usize| v[i].to_array().map(f64::from);
        let (a, b, c) = (p(a), p(b), p(c));
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    }

    #[test]
    fn square_splits_at_its_leftmost_vertex_as_the_spd_does() {
        // Hand-run of split_polygon on (1,1) (-1,1) (-1,-1) (1,-1): leftmost is vertex 1;
        // its ear (0, 1, 2) holds no other vertex, so the run 0..=2 is cut off and the
        // rest (0, 2, 3) is a triangle; the rest comes out first.
        let v: Vec<Vec3> = [[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]]
            .iter()
            .map(|&[x, y]| Vec3::new(x, y, 0.0))
            .collect();
        assert_eq!(spd_triangles(&v), vec![[0, 2, 3], [0, 1, 2]]);
    }

    #[test]
    fn concave_polygon_is_covered_exactly_and_keeps_its_winding() {
        // A comb: a base 0..6 long with three teeth, counter-clockwise, 12 vertices.
        let outline = [
            [0.0, 0.0],
            [6.0, 0.0],
            [6.0, 3.0],
            [5.0, 3.0],
            [5.0, 1.0],
            [4.0, 1.0],
            [4.0, 3.0],
            [2.0, 3.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        let v: Vec<Vec3> = outline.iter().map(|&[x, y]| Vec3::new(x, y, 0.0)).collect();
        let triangles = spd_triangles(&v);
        assert_eq!(triangles.len(), v.len() - 2);
        // Area of the comb: 6·3 minus two notches of 1×2.
        let total: f64 = triangles.iter().map(|&t| area2(&v, t)).sum();
        assert!((total - 2.0 * 14.0).abs() < 1e-9, "{total}");
        // Every triangle counter-clockwise like the polygon: none folds over another.
        for &t in &triangles {
            assert!(area2(&v, t) > 0.0, "{t:?} of {triangles:?}");
        }
    }

    #[test]
    fn degenerate_outlines_give_no_panic() {
        assert!(spd_triangles(&[]).is_empty());
        assert!(spd_triangles(&[Vec3::new(0.0, 0.0, 0.0); 2]).is_empty());
        // Coincident and non-finite vertices still give n - 2 triangles.
        let same = [Vec3::new(1.0, 1.0, 1.0); 7];
        assert_eq!(spd_triangles(&same).len(), 5);
        let mut odd = vec![Vec3::new(f32::NAN, 0.0, 0.0); 6];
        odd.push(Vec3::new(f32::INFINITY, 1.0, 0.0));
        assert_eq!(spd_triangles(&odd).len(), 5);
    }

    #[test]
    fn default_light_intensity_is_the_spd_povray_one() {
        for (n, expected) in [(1, 1.0f32), (3, 0.57735), (5, 0.447214), (7, 0.377964)] {
            assert!((pov_default_intensity(n) - expected).abs() < 1e-6, "{n}");
        }
        assert_eq!(pov_default_intensity(0), 1.0);
    }
}

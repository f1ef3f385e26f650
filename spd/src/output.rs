//! The NFF side of the SPD output library (`lib_output_*` of `libpr1.c`, `libpr2.c`,
//! `libply.c` for raytracer format 1, curves kept): what each call writes, through
//! [`tracer::nff_writer`].
//!
//! [`Output`] holds what the C keeps in globals: the text, the polygonalization
//! (`gU_resolution`, `gV_resolution`), the transform stack, and counts of the
//! primitives written (for the header comment). The C computes in double and prints
//! with `%g` (6 significant digits); here each number is printed as the shortest
//! decimal of its f32 ([`as_f32`]), which is closer to the double than `%g`.
//! The tessellating outputs (torus, disc, height field) are in
//! [`tessellate`](crate::tessellate).

use crate::transform_stack::TransformStack;
use crate::vector::{
    Coord3, Coord4, EPSILON2, PI, normalize, sub, transform_normal, transform_point,
    transform_vector, xyz,
};
use std::fmt::Write as _;
use tracer::nff_writer;
use tracer::vec3::Vec3;
use tracer::{Light, Material, Rgb, SurfaceTerms, View};

/// `OUTPUT_RESOLUTION` of `lib.h`: the default polygonalization.
const OUTPUT_RESOLUTION: u32 = 3;

/// How many primitives of each NFF kind were written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub spheres: u64,
    /// `c` entities (cylinders and cones).
    pub cones: u64,
    /// `p` entities.
    pub polygons: u64,
    /// `pp` entities.
    pub patches: u64,
}

impl Counts {
    /// All primitives.
    pub fn total(&self) -> u64 {
        self.spheres + self.cones + self.polygons + self.patches
    }

    /// `7381 spheres, 1 polygon`: the non-zero kinds, in NFF keyword order.
    pub fn describe(&self) -> String {
        let kinds = [
            (self.spheres, "sphere", "spheres"),
            (self.cones, "cylinder/cone", "cylinders/cones"),
            (self.polygons, "polygon", "polygons"),
            (self.patches, "polygonal patch", "polygonal patches"),
        ];
        let parts: Vec<String> = kinds
            .iter()
            .filter(|(n, _, _)| *n > 0)
            .map(|&(n, one, many)| format!("{n} {}", if n == 1 { one } else { many }))
            .collect();
        if parts.is_empty() {
            "no primitives".to_string()
        } else {
            parts.join(", ")
        }
    }
}

/// A generated number as the f32 the file holds. Round-off such as 1e-17 (where the C
/// prints `1e-17`) would print as a long run of zeros; it is zero in the geometry. The
/// same rule as `tracer::generators`.
pub fn as_f32(value: f64) -> f32 {
    let value = value as f32;
    if value.abs() < 1e-9 { 0.0 } else { value }
}

fn vec3(v: Coord3) -> Vec3 {
    Vec3::new(as_f32(v[0]), as_f32(v[1]), as_f32(v[2]))
}

fn rgb(c: Coord3) -> Rgb {
    Rgb {
        r: as_f32(c[0]),
        g: as_f32(c[1]),
        b: as_f32(c[2]),
    }
}

/// The library state and the NFF text being written.
#[derive(Debug)]
pub struct Output {
    text: String,
    counts: Counts,
    /// `gU_resolution`, `gV_resolution`.
    u_resolution: u32,
    v_resolution: u32,
    /// `CurrentTx` and its stack.
    pub tx: TransformStack,
    /// Every material's SPD surface terms, in the order of the `f` lines: what the NFF
    /// drops.
    surface_terms: Vec<SurfaceTerms>,
}

impl Output {
    /// An empty output with room for about `bytes` of text.
    pub fn with_capacity(bytes: usize) -> Self {
        Self {
            text: String::with_capacity(bytes),
            counts: Counts::default(),
            u_resolution: OUTPUT_RESOLUTION,
            v_resolution: OUTPUT_RESOLUTION,
            tx: TransformStack::default(),
            surface_terms: Vec::new(),
        }
    }

    /// The text and the primitive counts.
    pub fn finish(self) -> (String, Counts) {
        (self.text, self.counts)
    }

    /// The text, the primitive counts and every material's [`SurfaceTerms`] (which the
    /// text cannot hold), in the order of their `f` lines.
    pub fn finish_with_surface_terms(self) -> (String, Counts, Vec<SurfaceTerms>) {
        (self.text, self.counts, self.surface_terms)
    }

    /// `gU_resolution`, `gV_resolution`.
    pub fn resolution(&self) -> (u32, u32) {
        (self.u_resolution, self.v_resolution)
    }

    /// `lib_set_polygonalization`: ignored unless both are positive, as in the C.
    pub fn set_polygonalization(&mut self, u_steps: u32, v_steps: u32) {
        if u_steps > 0 && v_steps > 0 {
            self.u_resolution = u_steps;
            self.v_resolution = v_steps;
        }
    }

    /// `lib_output_comment`: `# comment`.
    pub fn comment(&mut self, comment: &str) {
        // Writing into a String cannot fail.
        let _ = writeln!(self.text, "# {comment}");
    }

    /// `lib_output_background_color`: `b r g b`.
    pub fn background(&mut self, color: Coord3) {
        nff_writer::write_background(&mut self.text, rgb(color));
    }

    /// `lib_output_viewpoint`: the `v` block. The aspect ratio is not part of NFF.
    #[allow(clippy::too_many_arguments)]
    pub fn viewpoint(
        &mut self,
        from: Coord3,
        at: Coord3,
        up: Coord3,
        fov_angle: f64,
        _aspect_ratio: f64,
        hither: f64,
        resx: u32,
        resy: u32,
    ) {
        let view = View {
            from: vec3(from),
            at: vec3(at),
            up: vec3(up),
            angle_deg: as_f32(fov_angle),
            hither: as_f32(hither),
            width: resx,
            height: resy,
        };
        nff_writer::write_view(&mut self.text, &view);
    }

    /// `lib_output_light`: `l x y z`. The w (intensity scale) is not written for NFF.
    /// Under a transform the C moves the light with `lib_transform_vector` (no
    /// translation); kept as is.
    pub fn light(&mut self, center: Coord4) {
        let mut position = xyz(center);
        if self.tx.active() {
            position = transform_vector(position, self.tx.current());
        }
        let light = Light {
            position: vec3(position),
            color: Rgb::WHITE,
            color_given: false,
        };
        nff_writer::write_light(&mut self.text, &light);
    }

    /// `lib_output_color`: `f r g b Kd Ks Shine T ior`, the Phong exponent made from
    /// the half angle `ang` (degrees) at which the highlight falls to 50 %. `ka` and
    /// `ks_spec` have no place in NFF: they are kept as the material's [`SurfaceTerms`]
    /// (see [`finish_with_surface_terms`](Self::finish_with_surface_terms)), which the
    /// SPD's POV-Ray output writes as `ambient ka` and `phong ks_spec`.
    #[allow(clippy::too_many_arguments)]
    pub fn color(
        &mut self,
        color: Coord3,
        ka: f64,
        kd: f64,
        ks: f64,
        ks_spec: f64,
        ang: f64,
        kt: f64,
        ior: f64,
    ) {
        let ang_radians = PI * ang / 180.0;
        let phong_pow = if ang_radians <= 0.0 {
            // Essentially invisible, very very sharp.
            100_000.0
        } else if ang_radians >= PI / 2.0 {
            1.0
        } else {
            0.5f64.ln() / ang_radians.cos().ln()
        };
        let material = Material {
            color: rgb(color),
            kd: as_f32(kd),
            ks: as_f32(ks),
            shine: as_f32(phong_pow),
            t: as_f32(kt),
            ior: as_f32(ior),
        };
        nff_writer::write_material(&mut self.text, &material);
        self.surface_terms.push(SurfaceTerms {
            ambient: as_f32(ka),
            highlight: as_f32(ks_spec),
        });
    }

    /// `lib_output_sphere` (curves): `s x y z r`. Under a transform the centre goes
    /// through it and the radius is scaled by its X scale.
    pub fn sphere(&mut self, center: Coord4) {
        let mut c = xyz(center);
        let mut radius = center[3];
        if self.tx.active() {
            c = transform_point(c, self.tx.current());
            radius *= self.tx.scale_x().abs();
        }
        nff_writer::write_sphere_at(&mut self.text, vec3(c), as_f32(radius));
        self.counts.spheres += 1;
    }

    /// `lib_output_cylcone` (curves): `c base r apex r`, transformed like a sphere.
    pub fn cylcone(&mut self, base: Coord4, apex: Coord4) {
        let (mut b, mut a) = (xyz(base), xyz(apex));
        let (mut base_radius, mut apex_radius) = (base[3], apex[3]);
        if self.tx.active() {
            let scale = self.tx.scale_x().abs();
            b = transform_point(b, self.tx.current());
            base_radius *= scale;
            a = transform_point(a, self.tx.current());
            apex_radius *= scale;
        }
        nff_writer::write_cone_between(
            &mut self.text,
            vec3(b),
            as_f32(base_radius),
            vec3(a),
            as_f32(apex_radius),
        );
        self.counts.cones += 1;
    }

    /// `lib_output_polygon`: `p n` and the vertices. As in the C, a vertex closer than
    /// `EPSILON2` to the next one (cyclically) is dropped first, and what is left is
    /// not written if under 3 vertices. (The C also rewrites the caller's array; no SPD
    /// program reads it back after a collapse or under a transform.)
    pub fn polygon(&mut self, vertices: &[Coord3]) {
        let mut vert: Vec<Coord3> = vertices.to_vec();
        let mut i = 0;
        while i < vert.len() {
            let mut edge = sub(vert[i], vert[(i + 1) % vert.len()]);
            if normalize(&mut edge) < EPSILON2 {
                vert.remove(i);
            } else {
                i += 1;
            }
        }
        if vert.len() < 3 {
            return;
        }
        if self.tx.active() {
            for v in &mut vert {
                *v = transform_point(*v, self.tx.current());
            }
        }
        let points: Vec<Vec3> = vert.iter().map(|&v| vec3(v)).collect();
        nff_writer::write_polygon_vertices(&mut self.text, &points);
        self.counts.polygons += 1;
    }

    /// `lib_output_polypatch` for a triangle: `pp 3` and vertex-normal lines. The C
    /// splits every patch into triangles first (`split_polygon`); a triangle comes out
    /// of the splitter as it went in, and the SPD programs only pass triangles. Under
    /// a transform, vertices go through it and normals through its inverse transpose.
    pub fn patch_triangle(&mut self, vertices: &[Coord3; 3], normals: &[Coord3; 3]) {
        let (mut vert, mut norm) = (*vertices, *normals);
        if self.tx.active() {
            let inverse = crate::vector::invert(self.tx.current());
            for (v, n) in vert.iter_mut().zip(&mut norm) {
                *v = transform_point(*v, self.tx.current());
                *n = transform_normal(*n, &inverse);
            }
        }
        let points = vert.map(vec3);
        let normals = norm.map(vec3);
        nff_writer::write_patch_vertices(&mut self.text, &points, &normals);
        self.counts.patches += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_collapses_repeated_vertices() {
        let mut out = Output::with_capacity(0);
        // The disc's centre twice: one triangle.
        out.polygon(&[
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
        ]);
        // Two distinct vertices only: nothing.
        out.polygon(&[[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        let (text, counts) = out.finish();
        assert_eq!(text, "p 3\n1 0 0\n0 1 0\n0 0 0\n");
        assert_eq!(counts.polygons, 1);
    }

    #[test]
    fn phong_exponent_from_half_angle() {
        let mut out = Output::with_capacity(0);
        out.color([1.0, 0.9, 0.7], 0.0, 0.5, 0.5, 0.5, 37.0, 0.0, 1.0);
        out.color([1.0, 1.0, 1.0], 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        out.color([1.0, 1.0, 1.0], 0.0, 1.0, 0.0, 0.0, 95.0, 0.0, 0.0);
        let (text, _) = out.finish();
        let lines: Vec<&str> = text.lines().collect();
        assert!(
            lines[0].starts_with("f 1 0.9 0.7 0.5 0.5 3.0827"),
            "{}",
            lines[0]
        );
        assert_eq!(lines[1], "f 1 1 1 1 0 100000 0 0");
        assert_eq!(lines[2], "f 1 1 1 1 0 1 0 0");
    }

    #[test]
    fn transformed_sphere_and_cone() {
        let mut out = Output::with_capacity(0);
        out.tx.translate([1.0, 2.0, 3.0]);
        out.tx.scale([0.5, 0.5, 0.5]);
        out.sphere([2.0, 0.0, 0.0, 1.0]);
        out.cylcone([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 2.0, 0.5]);
        let (text, counts) = out.finish();
        assert_eq!(text, "s 2 2 3 0.5\nc 1 2 3 0.5 1 2 4 0.25\n");
        assert_eq!((counts.spheres, counts.cones, counts.total()), (1, 1, 2));
        assert_eq!(counts.describe(), "1 sphere, 1 cylinder/cone");
    }

    #[test]
    fn tiny_round_off_prints_as_zero() {
        assert_eq!(as_f32(-1.11022e-16), 0.0);
        assert_eq!(as_f32(-0.0).to_string(), "0");
        assert_eq!(as_f32(0.25), 0.25);
    }
}

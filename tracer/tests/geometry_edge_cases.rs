//! Degenerate geometry and cameras: every case either fails to parse with an error
//! naming its line, or renders a tiny image whose every pixel is finite (and, where it
//! can be worked out, the expected colour), with each intersection structure.

// Test rays are built outside the counting layer.
#![allow(clippy::disallowed_methods)]

use tracer::primitives::{Cylinder, Sphere};
use tracer::{
    BruteForce, Bvh, Frame, NoCount, Ray, RenderError, RenderOptions, Rgb, Sampling, Scene,
    ShadingMode, Simd, Vec3, parse_nff,
};

fn parse(text: &str) -> Scene {
    parse_nff(text, "edge.nff").unwrap_or_else(|e| panic!("{e}"))
}

/// The view block used by most cases: eye at z = -5 looking at the origin, 7 x 5 pixels
/// (odd sizes put the middle pixel's ray exactly on the view axis), lines 1 to 7.
const VIEW: &str = "v\nfrom 0 0 -5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 7 5\n";

/// The frame rendered with brute force, SIMD and the BVH; all must be finite, and the
/// three must agree (they run the same tests in different orders).
fn render_all(scene: &Scene) -> Frame {
    let options = RenderOptions::for_scene(scene);
    let brute = tracer::render::<NoCount, _>(
        scene,
        &BruteForce::new(scene),
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .frame;
    let simd = tracer::render::<NoCount, _>(
        scene,
        &Simd::new(scene),
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .frame;
    let bvh = tracer::render::<NoCount, _>(
        scene,
        &Bvh::build(scene),
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .frame;
    for (name, frame) in [("brute force", &brute), ("simd", &simd), ("bvh", &bvh)] {
        assert!(frame.is_finite(), "{name}: {:?}", frame.pixels);
    }
    assert_eq!(brute.to_rgb8(), simd.to_rgb8(), "simd differs");
    assert_eq!(brute.to_rgb8(), bvh.to_rgb8(), "bvh differs");
    brute
}

/// Unit rays from 64 origins around `target`, aimed at it.
fn rays_through(target: Vec3) -> Vec<Ray> {
    let [tx, ty, tz] = target.to_array();
    (0..64)
        .map(|i| {
            let (i, a) = (i as f32, i as f32 * 0.7);
            let origin = [
                tx + 5.0 * a.cos(),
                ty + 3.0 * (a * 1.3).sin(),
                tz - 4.0 - 0.1 * i,
            ];
            let d = [tx - origin[0], ty - origin[1], tz - origin[2]];
            let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            Ray {
                origin: Vec3::from_array(origin),
                dir: Vec3::from_array(d.map(|v| v / length)),
            }
        })
        .collect()
}

fn parse_error(text: &str) -> (usize, String) {
    match parse_nff(text, "edge.nff") {
        Ok(_) => panic!("expected an error for {text:?}"),
        Err(e) => (e.line, e.message),
    }
}

const BACKGROUND: Rgb = Rgb::new(0.25, 0.5, 0.75);

fn all_background(frame: &Frame) -> bool {
    frame.pixels.iter().all(|&p| p == BACKGROUND)
}

#[test]
fn zero_radius_sphere_is_invisible() {
    // The middle ray passes exactly through the centre of the zero-radius sphere at the
    // origin and the other one at (0, 0, 2): nothing has an area to show.
    let scene = parse(&format!(
        "b 0.25 0.5 0.75\n{VIEW}l 0 5 -5\nf 1 0 0 1 0.5 10 0 1\ns 0 0 0 0\ns 0 0 2 -0\n"
    ));
    assert!(all_background(&render_all(&scene)));
    // Rays from many places aimed at the point: rounding makes some discriminants
    // slightly positive, which must still not count as a hit.
    let point = Sphere::new(Vec3::new(0.3, -0.7, 1.1), 0.0, 0);
    for ray in rays_through(point.center) {
        assert_eq!(
            point.intersect(&ray, 0.0, f32::INFINITY, &mut NoCount),
            None
        );
    }
    // A radius whose square underflows to zero is the same point.
    let underflow = Sphere::new(point.center, 1e-30, 0);
    for ray in rays_through(underflow.center) {
        assert_eq!(
            underflow.intersect(&ray, 0.0, f32::INFINITY, &mut NoCount),
            None
        );
    }
}

#[test]
fn zero_radius_cylinder_and_cone_with_both_radii_zero_are_invisible() {
    // A vertical segment through the view axis, and one along it (the middle ray runs
    // inside it); both radii 0 (also written 0 and -0) make a cylinder of radius 0.
    let scene = parse(&format!(
        "b 0.25 0.5 0.75\n{VIEW}l 0 5 -5\nc 0 -1 0 0 0 1 0 0\nc\n0 0 1 0\n0 0 3 -0\n"
    ));
    assert_eq!((scene.cylinders.len(), scene.cones.len()), (2, 0));
    assert!(all_background(&render_all(&scene)));
    let (base, apex) = (Vec3::new(0.1, -0.3, 0.2), Vec3::new(0.7, 1.3, -0.4));
    let segment = Cylinder::new(base, apex, 0.0, 0).unwrap_or_else(|e| panic!("{e}"));
    for k in 1..10 {
        // A point a k-th of the way along the segment.
        let f = k as f32 / 10.0;
        let [bx, by, bz] = base.to_array();
        let [ax, ay, az] = apex.to_array();
        let on_axis = Vec3::new(bx + f * (ax - bx), by + f * (ay - by), bz + f * (az - bz));
        for ray in rays_through(on_axis) {
            assert_eq!(segment.intersect(&ray, 0.0, 100.0, &mut NoCount), None);
        }
    }
}

#[test]
fn coincident_cone_ends_are_a_parse_error_on_the_c_line() {
    for body in [
        "c 1 1 1 0.5 1 1 1 0.2\n",
        "c 1 1 1 0.5 1 1 1 0.5\n",
        "c\n1 1 1 0\n1 1 1 0\n",
    ] {
        let (line, message) = parse_error(&format!("{VIEW}{body}"));
        assert_eq!(line, 8, "{body:?}: {message}");
        assert!(message.contains("zero-length axis"), "{message}");
    }
}

#[test]
fn pointed_cone_seen_along_its_axis_has_a_finite_tip() {
    // Base radius 1 at z = 0, apex radius 0 at z = -1, pointing at the eye: the middle
    // ray runs along the axis into the tip.
    let scene = parse(&format!(
        "b 0.25 0.5 0.75\n{VIEW}l 0 0 -5\nf 1 1 1 1 0.5 10 0 1\nc 0 0 0 1 0 0 -1 0\n"
    ));
    let frame = render_all(&scene);
    // The middle ray touches the tip (a double root: tangent, no hit) and runs inside
    // the open cone along its axis: background.
    assert_eq!(frame.pixels[2 * 7 + 3], BACKGROUND);
    // The next column looks 2 tan 20° / 4 = 0.182 to the side and meets the outer wall
    // facing the eye and the light near z = -0.11: lit.
    let beside = frame.pixels[2 * 7 + 4];
    assert!(beside.r > 0.1 && beside != BACKGROUND, "{beside:?}");
}

#[test]
fn collinear_polygon_vertices_are_a_parse_error_on_the_p_line() {
    let cases = [
        "p 3\n0 0 0\n1 1 1\n2 2 2\n",
        "p 4\n0 0 0\n0 0 0\n1 0 0\n0 1 0\n",
        "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n2 0 0 0 0 1\n",
    ];
    for body in cases {
        let (line, message) = parse_error(&format!("{VIEW}l 0 0 -5\n{body}"));
        assert_eq!(line, 9, "{body:?}: {message}");
        assert!(message.contains("collinear"), "{message}");
    }
}

/// A floor polygon (y = 0, 200 units wide) under an eye at height `eye_y` looking
/// horizontally, 8 x 7 pixels so that the middle row (row 3) is horizontal: parallel to
/// the floor.
fn floor_scene(eye_y: &str) -> Scene {
    parse(&format!(
        "b 0.25 0.5 0.75\nv\nfrom 0 {eye_y} 0\nat 0 {eye_y} 10\nup 0 1 0\nangle 40\nhither 0\n\
         resolution 8 7\nl 0 10 5\nf 1 1 1 1 0 1 0 1\n\
         p 4\n-100 0 -100\n-100 0 100\n100 0 100\n100 0 -100\n"
    ))
}

#[test]
fn rays_parallel_to_a_plane_miss_it() {
    let frame = render_all(&floor_scene("1"));
    for row in 0..7 {
        for column in 0..8 {
            let p = frame.pixels[row * 8 + column];
            if row <= 3 {
                // Above the horizon and on it (parallel rays): background.
                assert_eq!(p, BACKGROUND, "row {row} column {column}");
            } else {
                // Row 4 looks down by one pitch (2 tan 20° / 6 = 0.121 per unit ahead)
                // and meets the floor about 8 units ahead, well inside it: lit floor.
                assert!(p != BACKGROUND && p.r > 0.1, "row {row}: {p:?}");
            }
        }
    }
    // With the eye in the floor's plane every ray starts on the plane: t = 0 is not a
    // hit, so the floor is seen edge-on and nothing is drawn.
    assert!(all_background(&render_all(&floor_scene("0"))));
}

#[test]
fn tangent_rays_do_not_hit() {
    // Exact tangents: the discriminant is exactly 0 (no area to see, no normal trouble).
    let unit = Sphere::new(Vec3::ZERO, 1.0, 0);
    let tangent: Ray = Ray {
        origin: Vec3::new(-5.0, 1.0, 0.0),
        dir: Vec3::new(1.0, 0.0, 0.0),
    };
    assert_eq!(unit.intersect(&tangent, 0.0, 100.0, &mut NoCount), None);
    let cylinder = Cylinder::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0), 1.0, 0)
        .unwrap_or_else(|e| panic!("{e}"));
    let along_x: Ray = Ray {
        origin: Vec3::new(-5.0, 1.0, 1.0),
        dir: Vec3::new(1.0, 0.0, 0.0),
    };
    assert_eq!(cylinder.intersect(&along_x, 0.0, 100.0, &mut NoCount), None);
    // Along the wall, parallel to the axis: a = 0.
    let along_wall: Ray = Ray {
        origin: Vec3::new(1.0, 0.0, -5.0),
        dir: Vec3::new(0.0, 0.0, 1.0),
    };
    assert_eq!(
        cylinder.intersect(&along_wall, 0.0, 100.0, &mut NoCount),
        None
    );
}

#[test]
fn grazing_rays_render_finite_silhouettes() {
    // 90° view from the origin: the top and bottom rows leave at 45°, the rows spaced
    // tan 45° / 3 apart. A sphere at distance 3 sqrt 2 along z with radius 3 has
    // silhouette rays at exactly 45° (sin = 3 / (3 sqrt 2)): the outer rows graze it,
    // and the cylinder along x at the same place is grazed by the same rows.
    for body in [
        "s 0 0 4.2426405 3\n",
        "c -10 0 4.2426405 3 10 0 4.2426405 3\n",
        "c -10 0 4.2426405 -3 10 0 4.2426405 -3\n",
        "c -10 0 4.2426405 3 10 0 4.2426405 1\n",
    ] {
        let scene = parse(&format!(
            "b 0.25 0.5 0.75\nv\nfrom 0 0 0\nat 0 0 1\nup 0 1 0\nangle 90\nhither 0\n\
             resolution 7 7\nl 0 0 -1\nl 5 5 0 0.5 0.5 0.5\nf 1 1 1 0.6 0.4 8 0 1\n{body}"
        ));
        let frame = render_all(&scene);
        // The middle pixel looks straight at the surface: never background.
        assert!(frame.pixels[3 * 7 + 3] != BACKGROUND, "{body}");
    }
}

#[test]
fn up_parallel_to_the_view_and_from_equal_to_at_are_errors_naming_the_view() {
    let cases = [
        ("from 0 0 -5\nat 0 0 0\nup 0 0 1\n", "parallel"),
        ("from 0 0 -5\nat 0 0 0\nup 0 0 -3\n", "parallel"),
        ("from 0 0 -5\nat 0 0 0\nup 0 0 0\n", "parallel"),
        // sin² of the angle 1e-12, below the 1e-10 threshold.
        ("from 0 0 -5\nat 0 0 0\nup 0.000001 0 1\n", "parallel"),
        ("from 1 2 3\nat 1 2 3\nup 0 1 0\n", "same point"),
    ];
    for (vectors, needle) in cases {
        let text = format!("b 0 0 0\nv\n{vectors}angle 40\nresolution 8 6\ns 0 0 0 1\n");
        let (line, message) = parse_error(&text);
        // The `v` line (line 2) starts the block holding the from, at and up entries.
        assert_eq!(line, 2, "{vectors:?}: {message}");
        assert!(message.contains(needle), "{message}");
    }
    // A tilted but valid up (sin² = 1e-8, above the threshold) renders.
    let scene = parse(
        "v\nfrom 0 0 -5\nat 0 0 0\nup 0.0001 0 1\nangle 40\nresolution 8 6\nl 0 5 -5\ns 0 0 0 1\n",
    );
    assert!(render_all(&scene).is_finite());
    // A view built by hand is checked by the renderer too.
    let mut bad = scene.clone();
    bad.view.up = Vec3::new(0.0, 0.0, 2.0);
    let options = RenderOptions::new(8, 6, Sampling::PixelCenters, ShadingMode::Color);
    let result = tracer::render::<NoCount, _>(
        &bad,
        &BruteForce::new(&bad),
        &options,
        &tracer::RenderMethod::default(),
        &|_| {},
    );
    assert!(matches!(result, Err(RenderError::Camera(m)) if m.contains("parallel")));
}

#[test]
fn light_inside_a_sphere_leaves_the_outside_dark() {
    // The light at the centre of an opaque sphere: every outside point faces away from
    // it, so no shadow ray is cast and the sphere shows its ambient term alone,
    // 0.1 x Kd x colour = 0.1 x 0.8 x (1, 0.5, 0) = (0.08, 0.04, 0).
    let scene = parse(&format!(
        "b 0.25 0.5 0.75\n{VIEW}l 0 0 0\nf 1 0.5 0 0.8 0 1 0 1\ns 0 0 0 1\n\
         c 0 -3 0 0.5 0 -3 3 0.5\nl 0 -3 1.5\n"
    ));
    let frame = render_all(&scene);
    let middle = frame.pixels[2 * 7 + 3];
    for (got, want) in [(middle.r, 0.08), (middle.g, 0.04), (middle.b, 0.0)] {
        assert!((got - want).abs() < 1e-6, "{middle:?}");
    }
    assert!(frame.pixels.contains(&BACKGROUND));
}

#[test]
fn zero_length_patch_normals_are_a_parse_error_naming_the_vertex() {
    let text = format!("{VIEW}l 0 0 -5\npp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n");
    let (line, message) = parse_error(&text);
    assert_eq!(line, 9, "{message}");
    assert!(
        message.contains("normal of vertex 2") && message.contains("zero length"),
        "{message}"
    );
}

#[test]
fn tiny_patch_normals_are_normalized_and_huge_ones_refused() {
    // |n|² underflows (1e-25² = 1e-50) in f32; the normal is still a direction and
    // shades like a unit one. Components beyond the coordinate range (±1e9, where
    // products start to overflow) are refused on their line.
    let patch = |n: &str| {
        format!("b 0.25 0.5 0.75\n{VIEW}l 0 0 -5\npp 3\n-2 -2 0 {n}\n2 -2 0 {n}\n0 2 0 {n}\n")
    };
    let unit = render_all(&parse(&patch("0 0 -1")));
    let huge = tracer::parse_nff(&patch("0 0 -1e25"), "edge.nff")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        huge.starts_with("edge.nff:11:") && huge.contains("coordinate range"),
        "{huge}"
    );
    // Scaled by their largest component first: exactly (0, 0, -1) again.
    for n in ["0 0 -1e-25", "0 0 -1e-20"] {
        let scene = parse(&patch(n));
        let normal = scene.patches[0].normals[0].to_array();
        assert!((normal[2] + 1.0).abs() < 1e-6, "{n}: {normal:?}");
        assert_eq!(render_all(&scene).pixels, unit.pixels, "{n}");
    }
    let tilted = parse(&patch("1e-30 0 -1e-25"));
    let [x, y, z] = tilted.patches[0].normals[0].to_array();
    assert!((x - 1e-5).abs() < 1e-9 && y == 0.0 && (z + 1.0).abs() < 1e-6);
    assert!(render_all(&tilted).is_finite());
}

#[test]
fn tiny_radius_hits_have_finite_normals() {
    // Radii whose squares are subnormal: rounding decides hit or miss, but a reported
    // hit must have a usable normal.
    for radius in [1e-20f32, 1e-19, 1e-10] {
        let sphere = Sphere::new(Vec3::new(0.3, -0.7, 1.1), radius, 0);
        for ray in rays_through(sphere.center) {
            if let Some(t) = sphere.intersect(&ray, 0.0, f32::INFINITY, &mut NoCount) {
                let [ox, oy, oz] = ray.origin.to_array();
                let [dx, dy, dz] = ray.dir.to_array();
                let p = Vec3::new(ox + t * dx, oy + t * dy, oz + t * dz);
                assert!(sphere.normal(p, &mut NoCount).is_finite(), "r = {radius}");
            }
        }
        let scene = parse(&format!(
            "b 0.25 0.5 0.75\n{VIEW}l 0 5 -5\nf 1 1 1 1 0.5 10 0 1\ns 0 0 0 {radius}\n\
             c 0 -1 0 {radius} 0 1 0 {radius}\nc 0 0 1 {radius} 0 0 3 0\n"
        ));
        render_all(&scene);
    }
}

//! Property tests of the NFF parser and writer.
//!
//! - Random valid scenes (view, background, lights, materials, spheres, cylinders,
//!   cones, planar convex polygons, patches with normals) built from independent entity
//!   descriptions: parsing the written scene gives the scene back, and writing it again
//!   gives the same text.
//! - The same entities written in varied NFF styles (spacing, tabs, CRLF, comments, the
//!   two-line `c` form) parse to the same scene.
//! - Random byte mutations of valid files (the project's `scenes/*.nff` and generated
//!   ones) never panic: the parser returns a scene, which round-trips through the
//!   writer, or an error whose line is inside the file.
//!
//! Case counts are modest so the suite runs in seconds at opt-level 1.

use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::FileFailurePersistence;
use tracer::nff::check_view_basis;
use tracer::nff_writer::scene_to_nff;
use tracer::primitives::{Cone, Cylinder, Patch, Polygon, Sphere};
use tracer::{Light, Material, Rgb, Scene, Vec3, View, parse_nff};

/// `cases` cases; a failing case is saved beside this file
/// (`proptest_nff.proptest-regressions`) and replayed first on later runs.
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..ProptestConfig::default()
    }
}

/// One NFF entity after the view block, as the strategies generate it.
#[derive(Clone, Debug)]
enum Entity {
    Light {
        position: [f32; 3],
        color: Option<[f32; 3]>,
    },
    Material([f32; 8]),
    Sphere {
        center: [f32; 3],
        radius: f32,
    },
    /// Equal radii: a cylinder.
    Cone {
        base: [f32; 3],
        base_radius: f32,
        apex: [f32; 3],
        apex_radius: f32,
    },
    Polygon(Vec<[f32; 3]>),
    Patch(Vec<[f32; 3]>, Vec<[f32; 3]>),
}

/// A coordinate: arbitrary floats, whole numbers and two-decimal numbers.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        -1000.0f32..1000.0,
        (-100i32..100).prop_map(|i| i as f32),
        (-100_000i32..100_000).prop_map(|i| i as f32 / 100.0),
    ]
}

fn point() -> impl Strategy<Value = [f32; 3]> {
    [coordinate(), coordinate(), coordinate()]
}

fn unit_interval() -> impl Strategy<Value = f32> {
    prop_oneof![0.0f32..=1.0, Just(0.0), Just(1.0)]
}

/// A direction of length 0.5 to 20 (in f64, for building geometry).
fn direction() -> impl Strategy<Value = [f64; 3]> {
    [-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0].prop_filter("length 0.5 to 20", |d| {
        (0.25..400.0).contains(&(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]))
    })
}

fn radius() -> impl Strategy<Value = f32> {
    prop_oneof![0.01f32..100.0, -100.0f32..-0.01]
}

fn cone_radius() -> impl Strategy<Value = f32> {
    prop_oneof![Just(0.0f32), 0.01f32..10.0, -10.0f32..-0.01]
}

fn add(p: [f32; 3], d: [f64; 3]) -> [f32; 3] {
    [0, 1, 2].map(|i| (f64::from(p[i]) + d[i]) as f32)
}

/// A planar convex polygon: `n` points on a circle around `center` in the plane
/// spanned by two perpendicular unit vectors built from `normal`.
fn circle_points(
    center: [f32; 3],
    normal: [f64; 3],
    radius: f64,
    n: usize,
    turn: f64,
) -> Vec<[f32; 3]> {
    let length = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
    let w = normal.map(|v| v / length);
    // Any vector not parallel to w, then Gram-Schmidt.
    let helper = if w[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let u = cross(w, helper);
    let u_length = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let u = u.map(|v| v / u_length);
    let v = cross(w, u);
    (0..n)
        .map(|i| {
            let angle = turn + std::f64::consts::TAU * i as f64 / n as f64;
            let (s, c) = angle.sin_cos();
            add(center, [0, 1, 2].map(|k| radius * (c * u[k] + s * v[k])))
        })
        .collect()
}

fn polygon_points() -> impl Strategy<Value = Vec<[f32; 3]>> {
    (point(), direction(), 0.5f64..50.0, 3usize..9, 0.0f64..6.3)
        .prop_map(|(c, n, r, count, turn)| circle_points(c, n, r, count, turn))
}

fn entity() -> impl Strategy<Value = Entity> {
    let light = (
        point(),
        proptest::option::of([unit_interval(), unit_interval(), unit_interval()]),
    )
        .prop_map(|(position, color)| Entity::Light { position, color });
    let material = (
        [unit_interval(), unit_interval(), unit_interval()],
        unit_interval(),
        unit_interval(),
        prop_oneof![0.0f32..200.0, (0u8..100).prop_map(f32::from)],
        prop_oneof![Just(0.0f32), 0.01f32..1.0],
        0.1f32..3.0,
    )
        .prop_map(|([r, g, b], kd, ks, shine, t, ior)| {
            Entity::Material([r, g, b, kd, ks, shine, t, ior])
        });
    let sphere = (point(), radius()).prop_map(|(center, radius)| Entity::Sphere { center, radius });
    let radii = prop_oneof![
        cone_radius().prop_map(|r| (r, r)),
        (cone_radius(), cone_radius()).prop_filter("distinct radii", |(a, b)| a != b),
    ];
    let cone = (point(), direction(), radii).prop_map(|(base, d, (base_radius, apex_radius))| {
        Entity::Cone {
            base,
            base_radius,
            apex: add(base, d),
            apex_radius,
        }
    });
    let polygon = polygon_points().prop_map(Entity::Polygon);
    let patch = polygon_points()
        .prop_flat_map(|points| {
            let n = points.len();
            let normals = proptest::collection::vec(direction(), n).prop_map(|ds| {
                ds.into_iter()
                    .map(|d| d.map(|v| v as f32))
                    .collect::<Vec<_>>()
            });
            (Just(points), normals)
        })
        .prop_map(|(points, normals)| Entity::Patch(points, normals));
    prop_oneof![
        2 => light,
        2 => material,
        3 => sphere,
        3 => cone,
        2 => polygon,
        2 => patch,
    ]
}

fn view() -> impl Strategy<Value = View> {
    (
        point(),
        direction(),
        direction(),
        prop_oneof![0.5f32..179.5, (1u8..180).prop_map(f32::from)],
        prop_oneof![Just(0.0f32), 0.0f32..1.0],
        1u32..=64,
        1u32..=64,
    )
        .prop_map(|(from, look, up, angle_deg, hither, width, height)| View {
            from: Vec3::from_array(from),
            at: Vec3::from_array(add(from, look)),
            up: Vec3::from_array(up.map(|v| v as f32)),
            angle_deg,
            hither,
            width,
            height,
        })
        .prop_filter("a camera basis", |v| check_view_basis(v).is_ok())
}

fn rgb(c: [f32; 3]) -> Rgb {
    Rgb::new(c[0], c[1], c[2])
}

/// The scene the entities describe, built directly (NFF semantics: primitives use the
/// last material, or a default one before any `f`; uncoloured lights share the SPD
/// default intensity).
fn model(view: &View, background: [f32; 3], entities: &[Entity]) -> Scene {
    let mut scene = Scene::new(view.clone());
    scene.background = rgb(background);
    let material = |materials: &mut Vec<Material>| {
        if materials.is_empty() {
            materials.push(Material::default());
        }
        (materials.len() - 1) as u32
    };
    let v = Vec3::from_array;
    for entity in entities {
        match entity {
            Entity::Light { position, color } => scene.lights.push(Light {
                position: v(*position),
                color: color.map(rgb).unwrap_or(Rgb::WHITE),
                color_given: color.is_some(),
            }),
            &Entity::Material([r, g, b, kd, ks, shine, t, ior]) => scene.materials.push(Material {
                color: Rgb::new(r, g, b),
                kd,
                ks,
                shine,
                t,
                ior,
            }),
            Entity::Sphere { center, radius } => {
                let m = material(&mut scene.materials);
                scene.spheres.push(Sphere::new(v(*center), *radius, m));
            }
            Entity::Cone {
                base,
                base_radius,
                apex,
                apex_radius,
            } => {
                let m = material(&mut scene.materials);
                if base_radius == apex_radius {
                    let c = Cylinder::new(v(*base), v(*apex), *base_radius, m);
                    scene
                        .cylinders
                        .push(c.unwrap_or_else(|e| panic!("strategy: {e}")));
                } else {
                    let c = Cone::new(v(*base), *base_radius, v(*apex), *apex_radius, m);
                    scene
                        .cones
                        .push(c.unwrap_or_else(|e| panic!("strategy: {e}")));
                }
            }
            Entity::Polygon(points) => {
                let m = material(&mut scene.materials);
                let p = Polygon::new(points.iter().map(|&p| v(p)).collect(), m);
                scene
                    .polygons
                    .push(p.unwrap_or_else(|e| panic!("strategy: {e}")));
            }
            Entity::Patch(points, normals) => {
                let m = material(&mut scene.materials);
                let p = Patch::new(
                    points.iter().map(|&p| v(p)).collect(),
                    normals.iter().map(|&n| v(n)).collect(),
                    m,
                );
                scene
                    .patches
                    .push(p.unwrap_or_else(|e| panic!("strategy: {e}")));
            }
        }
    }
    let intensity = Scene::default_light_intensity(scene.lights.len());
    for light in scene.lights.iter_mut().filter(|l| !l.color_given) {
        light.color = Rgb::gray(intensity);
    }
    scene
}

/// How [`styled_nff`] lays out the text.
#[derive(Clone, Debug)]
struct Style {
    /// Separator between numbers (a space, several, a tab).
    separator: &'static str,
    line_end: &'static str,
    /// Whether to append a comment to every line.
    comments: bool,
    /// Whether to write `c` entities in the two-line form.
    two_line_cones: bool,
}

fn style() -> impl Strategy<Value = Style> {
    (
        prop::sample::select(vec![" ", "  ", "\t", " \t "]),
        prop::sample::select(vec!["\n", "\r\n"]),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(|(separator, line_end, comments, two_line_cones)| Style {
            separator,
            line_end,
            comments,
            two_line_cones,
        })
}

/// The entities as NFF text in the given style (the view block lines in reverse order:
/// any order is allowed).
fn styled_nff(view: &View, background: [f32; 3], entities: &[Entity], style: &Style) -> String {
    let mut out = String::from("# generated by proptest_nff");
    out.push_str(style.line_end);
    let mut line = |words: Vec<String>| {
        out.push_str(&words.join(style.separator));
        if style.comments {
            out.push_str(" # comment 1 2 3");
        }
        out.push_str(style.line_end);
    };
    let nums = |values: &[f32]| values.iter().map(f32::to_string).collect::<Vec<_>>();
    let with = |keyword: &str, values: &[f32]| {
        let mut words = vec![keyword.to_string()];
        words.extend(nums(values));
        words
    };
    line(vec!["v".into()]);
    line(vec![
        "resolution".into(),
        view.width.to_string(),
        view.height.to_string(),
    ]);
    line(with("hither", &[view.hither]));
    line(with("angle", &[view.angle_deg]));
    line(with("up", &view.up.to_array()));
    line(with("at", &view.at.to_array()));
    line(with("from", &view.from.to_array()));
    line(with("b", &background));
    for entity in entities {
        match entity {
            Entity::Light { position, color } => {
                let mut values = position.to_vec();
                values.extend(color.iter().flatten());
                line(with("l", &values));
            }
            Entity::Material(values) => line(with("f", values)),
            Entity::Sphere { center, radius } => {
                line(with("s", &[center[0], center[1], center[2], *radius]))
            }
            Entity::Cone {
                base,
                base_radius,
                apex,
                apex_radius,
            } => {
                let b = [base[0], base[1], base[2], *base_radius];
                let a = [apex[0], apex[1], apex[2], *apex_radius];
                if style.two_line_cones {
                    line(vec!["c".into()]);
                    line(nums(&b));
                    line(nums(&a));
                } else {
                    line(with("c", &[b, a].concat()));
                }
            }
            Entity::Polygon(points) => {
                line(vec!["p".into(), points.len().to_string()]);
                for p in points {
                    line(nums(p));
                }
            }
            Entity::Patch(points, normals) => {
                line(vec!["pp".into(), points.len().to_string()]);
                for (p, n) in points.iter().zip(normals) {
                    line(nums(&[*p, *n].concat()));
                }
            }
        }
    }
    out
}

fn background() -> impl Strategy<Value = [f32; 3]> {
    [unit_interval(), unit_interval(), unit_interval()]
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn written_scenes_parse_back_to_the_same_scene_and_text(
        view in view(),
        background in background(),
        entities in proptest::collection::vec(entity(), 0..24),
    ) {
        let scene = model(&view, background, &entities);
        let text = scene_to_nff(&scene);
        let parsed = parse_nff(&text, "written.nff");
        prop_assert!(parsed.is_ok(), "{:?}\n{}", parsed.err(), text);
        let parsed = parsed.unwrap_or_else(|_| scene.clone());
        prop_assert_eq!(&parsed, &scene);
        prop_assert_eq!(scene_to_nff(&parsed), text);
    }

    #[test]
    fn styled_nff_parses_to_the_described_scene(
        view in view(),
        background in background(),
        entities in proptest::collection::vec(entity(), 0..16),
        style in style(),
    ) {
        let text = styled_nff(&view, background, &entities, &style);
        let parsed = parse_nff(&text, "styled.nff");
        prop_assert!(parsed.is_ok(), "{:?}\n{}", parsed.err(), text);
        let parsed = parsed.unwrap_or_else(|_| Scene::new(view.clone()));
        prop_assert_eq!(parsed, model(&view, background, &entities));
    }
}

/// The valid files mutated below: the project's scenes and small generated ones.
fn corpus() -> Vec<(String, Vec<u8>)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(Result::ok)
        .map(|entry| entry.path())
        .filter(|path| path.extension().is_some_and(|e| e == "nff"))
        .map(|path| {
            let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
            (path.display().to_string(), bytes)
        })
        .collect();
    files.sort();
    assert!(files.len() >= 20, "scenes/ holds the test bench and more");
    let generated = [
        ("sphereflake:1", tracer::generators::sphereflake(1)),
        ("lattice:2", tracer::generators::lattice(2)),
    ];
    for (name, text) in generated {
        let text = text.unwrap_or_else(|e| panic!("{e}"));
        files.push((name.to_string(), text.into_bytes()));
    }
    for (name, bytes) in &files {
        let text = String::from_utf8_lossy(bytes);
        assert!(parse_nff(&text, name).is_ok(), "{name} must be valid");
    }
    files
}

#[derive(Clone, Debug)]
enum Mutation {
    FlipBit(Index, u8),
    Insert(Index, u8),
    Delete(Index),
    Replace(Index, u8),
    Truncate(Index),
    DuplicateLine(Index),
    DeleteLine(Index),
}

fn byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        any::<u8>(),
        prop::sample::select(b"0123456789-+.eE \t\r\n#vpcslfbx".to_vec()),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<Index>(), 0u8..8).prop_map(|(i, b)| Mutation::FlipBit(i, b)),
        (any::<Index>(), byte()).prop_map(|(i, b)| Mutation::Insert(i, b)),
        any::<Index>().prop_map(Mutation::Delete),
        (any::<Index>(), byte()).prop_map(|(i, b)| Mutation::Replace(i, b)),
        any::<Index>().prop_map(Mutation::Truncate),
        any::<Index>().prop_map(Mutation::DuplicateLine),
        any::<Index>().prop_map(Mutation::DeleteLine),
    ]
}

/// Byte range `[start, end)` of the line holding byte `at` (with its `\n`).
fn line_around(bytes: &[u8], at: usize) -> (usize, usize) {
    let start = bytes[..at]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let end = bytes[at..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |i| at + i + 1);
    (start, end)
}

fn apply(bytes: &mut Vec<u8>, mutation: &Mutation) {
    if bytes.is_empty() {
        if let Mutation::Insert(_, b) = mutation {
            bytes.push(*b);
        }
        return;
    }
    match *mutation {
        Mutation::FlipBit(ref i, bit) => {
            let at = i.index(bytes.len());
            bytes[at] ^= 1 << bit;
        }
        Mutation::Insert(ref i, b) => {
            let at = i.index(bytes.len() + 1);
            bytes.insert(at, b);
        }
        Mutation::Delete(ref i) => {
            bytes.remove(i.index(bytes.len()));
        }
        Mutation::Replace(ref i, b) => {
            let at = i.index(bytes.len());
            bytes[at] = b;
        }
        Mutation::Truncate(ref i) => bytes.truncate(i.index(bytes.len())),
        Mutation::DuplicateLine(ref i) => {
            let (start, end) = line_around(bytes, i.index(bytes.len()));
            let line = bytes[start..end].to_vec();
            bytes.splice(end..end, line);
        }
        Mutation::DeleteLine(ref i) => {
            let (start, end) = line_around(bytes, i.index(bytes.len()));
            bytes.drain(start..end);
        }
    }
}

proptest! {
    #![proptest_config(config(2048))]

    #[test]
    fn mutated_files_never_panic_and_errors_point_into_the_file(
        file in any::<Index>(),
        mutations in proptest::collection::vec(mutation(), 1..6),
    ) {
        thread_local! {
            static CORPUS: Vec<(String, Vec<u8>)> = corpus();
        }
        let (name, mut bytes) = CORPUS.with(|c| c[file.index(c.len())].clone());
        for m in &mutations {
            apply(&mut bytes, m);
        }
        let text = String::from_utf8_lossy(&bytes);
        let lines = text.lines().count();
        match parse_nff(&text, &name) {
            Ok(scene) => {
                // Whatever parses also survives the writer.
                let written = scene_to_nff(&scene);
                let again = parse_nff(&written, "rewritten.nff");
                prop_assert!(again.is_ok(), "{:?}", again.err());
                prop_assert_eq!(again.ok(), Some(scene));
            }
            Err(e) => {
                prop_assert!(e.line >= 1 && e.line <= lines + 1, "{} ({} lines)", e, lines);
                prop_assert!(!e.message.is_empty());
                let prefix = format!("{}:{}: ", name, e.line);
                prop_assert!(e.to_string().starts_with(&prefix), "{}", e);
            }
        }
    }
}

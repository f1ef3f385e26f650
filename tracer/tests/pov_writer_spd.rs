//! `tracer::scene_to_pov` on the seven classic SPD scenes against the SPD's own POV-Ray
//! output of them (`../shared/peers/povray/*.pov.gz`, written by the SPD 3.14 library
//! from the generators): the same camera, lights, background, primitives (kind by kind,
//! in order; each polygon and patch cut into n - 2 triangles of its own corners that
//! cover it, the SPD's very triangles but where its doubles broke a tie otherwise) and
//! texture values.
//!
//! The one difference allowed is what the NFF cannot carry: the generators gave the SPD's
//! POV-Ray writer an ambient term and a highlight weight apart from the reflection
//! weight, and the NFF `f` line keeps neither (`Ks` is both weights, no ambient). Those
//! differences are listed per scene below, so that any other one fails.

mod common;

use common::load_spd;
use common::pov::{PovScene, Primitive, Texture, parse_pov, spd_pov_text};
use tracer::{Scene, Vec3};

const SCENES: [&str; 7] = [
    "balls", "gears", "mount", "rings", "teapot", "tetra", "tree",
];

fn length(v: [f64; 3]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs()).max(1.0)
}

/// `(SPD's ambient, SPD's phong) -> (rtprof's ambient, rtprof's phong)` of the textures
/// whose SPD values the NFF does not carry.
fn nff_losses(name: &str) -> Vec<((f64, f64), (f64, f64))> {
    match name {
        // The floor: ambient 0.2 diffuse 0.8 in balls.c; the NFF has Kd 0.8 only.
        "balls" => vec![((0.2, 0.0), (0.0, 0.0))],
        // The floor: highlight 0.3, reflection 0.6 in gears.c; the NFF has Ks 0.6.
        "gears" => vec![((0.0, 0.3), (0.0, 0.6))],
        // The glass spheres: highlight 0.4, reflection 0.1 in mount.c; Ks 0.1.
        "mount" => vec![((0.0, 0.4), (0.0, 0.1))],
        // The rings' spheres and cylinders: highlight 0.3, reflection 0.2; Ks 0.2.
        "rings" => vec![((0.0, 0.3), (0.0, 0.2))],
        _ => Vec::new(),
    }
}

fn compare_textures(
    name: &str,
    what: &str,
    spd: &Texture,
    ours: &Texture,
) -> Option<((f64, f64), (f64, f64))> {
    let same = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => close(a, b, 1e-6),
        (None, None) => true,
        _ => false,
    };
    let context = format!("{name}: {what}: SPD {spd:?}, rtprof {ours:?}");
    for c in 0..3 {
        assert!(close(spd.color[c], ours.color[c], 1e-6), "{context}");
    }
    assert!(same(spd.filter, ours.filter), "filter: {context}");
    assert!(same(spd.diffuse, ours.diffuse), "diffuse: {context}");
    assert!(
        same(spd.reflection, ours.reflection),
        "reflection: {context}"
    );
    assert!(
        same(spd.phong_size, ours.phong_size),
        "phong_size: {context}"
    );
    assert!(same(spd.ior, ours.ior), "ior: {context}");
    // rtprof writes ambient 0 and the highlight weight Ks (the reflection weight).
    assert_eq!(ours.ambient, Some(0.0), "{context}");
    assert_eq!(ours.phong.is_some(), spd.phong.is_some(), "{context}");
    assert!(same(ours.phong, ours.reflection), "{context}");
    let spd_pair = (spd.ambient.unwrap_or(0.1), spd.phong.unwrap_or(0.0));
    let our_pair = (0.0, ours.phong.unwrap_or(0.0));
    let differs = !close(spd_pair.0, our_pair.0, 1e-6) || !close(spd_pair.1, our_pair.1, 1e-6);
    differs.then_some((spd_pair, our_pair))
}

/// Each NFF polygon (or patch) as its vertices, each followed by its normal for patches.
type Outline = Vec<Vec<f64>>;

fn outlines(scene: &Scene, kind: &str) -> Vec<Outline> {
    let flat = |v: Vec3| v.to_array().map(f64::from).to_vec();
    match kind {
        "triangle" => scene
            .polygons
            .iter()
            .map(|p| p.outline.vertices.iter().map(|&v| flat(v)).collect())
            .collect(),
        _ => scene
            .patches
            .iter()
            .map(|p| {
                p.outline
                    .vertices
                    .iter()
                    .zip(&p.written_normals)
                    .map(|(&v, &n)| [flat(v), flat(n)].concat())
                    .collect()
            })
            .collect(),
    }
}

/// Twice the area of the triangle of the first three numbers of each corner.
fn area2(corners: &[&[f64]]) -> f64 {
    let d = |i: usize, c: usize| corners[i][c] - corners[0][c];
    let cross = [
        d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1),
        d(1, 2) * d(2, 0) - d(1, 0) * d(2, 2),
        d(1, 0) * d(2, 1) - d(1, 1) * d(2, 0),
    ];
    length(cross)
}

/// The triangles that come from one outline: each corner (vertex, and normal for
/// patches) is one of the outline's, and together they cover the outline's area (any
/// two cuts of a polygon into n - 2 triangles from its own vertices that do not
/// overlap have the same total). Returns whether they are the very same triangles.
fn check_cut(context: &str, outline: &Outline, spd: &[&Primitive], ours: &[&Primitive]) -> bool {
    let stride = outline[0].len();
    let corners = |p: &'_ Primitive| -> Vec<Vec<f64>> {
        p.numbers.chunks(stride).map(<[f64]>::to_vec).collect()
    };
    let mut areas = [0.0f64; 2];
    for (side, triangles) in [spd, ours].iter().enumerate() {
        for t in triangles.iter() {
            let c = corners(t);
            assert_eq!(c.len(), 3, "{context}: {t:?}");
            for corner in &c {
                assert!(
                    outline
                        .iter()
                        .any(|v| v.iter().zip(corner).all(|(a, b)| close(*a, *b, 1e-6))),
                    "{context}: corner {corner:?} is none of the outline's"
                );
            }
            let refs: Vec<&[f64]> = c.iter().map(Vec::as_slice).collect();
            areas[side] += area2(&refs);
        }
    }
    assert!(
        close(areas[0], areas[1], 1e-5),
        "{context}: triangles cover {} (SPD) and {} (rtprof)",
        areas[0],
        areas[1]
    );
    spd.iter().zip(ours).all(|(p, q)| {
        p.numbers
            .iter()
            .zip(&q.numbers)
            .all(|(a, b)| close(*a, *b, 1e-6))
    })
}

fn check_primitives(
    name: &str,
    kind: &str,
    scene: &Scene,
    spd: &PovScene,
    ours: &PovScene,
) -> Vec<((f64, f64), (f64, f64))> {
    let a: Vec<&Primitive> = spd.of_kind(kind).collect();
    let b: Vec<&Primitive> = ours.of_kind(kind).collect();
    assert_eq!(a.len(), b.len(), "{name}: number of {kind}s");
    if kind.ends_with("triangle") {
        // The SPD cut each polygon in its file order, n - 2 triangles each, as rtprof
        // does. Its cut ran on the generator's doubles: where two vertices print the same
        // coordinate (gears' teeth), its leftmost vertex may be another than rtprof's,
        // which sees the printed decimals, and the cut differs (the picture does not).
        let mut start = 0;
        let mut different = 0;
        for (i, outline) in outlines(scene, kind).iter().enumerate() {
            let end = start + outline.len() - 2;
            let context = format!("{name}: {kind}s of outline {i}");
            if !check_cut(&context, outline, &a[start..end], &b[start..end]) {
                different += 1;
            }
            start = end;
        }
        assert_eq!(start, a.len(), "{name}: {kind}s");
        if different > 0 {
            eprintln!("{name}: {different} {kind} outlines cut otherwise than by the SPD");
        }
        let expected = if (name, kind) == ("gears", "triangle") {
            1..usize::MAX
        } else {
            0..1
        };
        assert!(
            expected.contains(&different),
            "{name}: {different} {kind} outlines cut otherwise than by the SPD"
        );
    }
    let mut losses = Vec::new();
    for (i, (p, q)) in a.iter().zip(&b).enumerate() {
        assert_eq!(p.numbers.len(), q.numbers.len(), "{name}: {kind} {i}");
        if !kind.ends_with("triangle") {
            for (x, y) in p.numbers.iter().zip(&q.numbers) {
                // Both are the same %g decimals of the generator's doubles.
                assert!(
                    close(*x, *y, 1e-6),
                    "{name}: {kind} {i}: SPD {:?} vs rtprof {:?}",
                    p.numbers,
                    q.numbers
                );
            }
        }
        assert_eq!(p.open, q.open, "{name}: {kind} {i}: open");
        let what = format!("{kind} {i}");
        if let Some(loss) = compare_textures(name, &what, &p.texture, &q.texture)
            && !losses.contains(&loss)
        {
            losses.push(loss);
        }
    }
    losses
}

#[test]
fn seven_spd_scenes_match_the_spds_own_povray_files() {
    for name in SCENES {
        let scene = load_spd(name);
        let ours = parse_pov(&tracer::scene_to_pov(&scene));
        let spd = parse_pov(&spd_pov_text(name));

        for (slot, what) in ["location", "direction", "right", "up"].iter().enumerate() {
            let (a, b) = (spd.camera[slot], ours.camera[slot]);
            let diff = length([a[0] - b[0], a[1] - b[1], a[2] - b[2]]);
            assert!(
                diff <= 1e-4 * length(a).max(1e-3),
                "{name}: camera {what}: SPD {a:?} vs rtprof {b:?}"
            );
        }
        for c in 0..3 {
            assert!(
                close(spd.background[c], ours.background[c], 1e-6),
                "{name}: background"
            );
        }
        assert_eq!(spd.lights.len(), ours.lights.len(), "{name}: lights");
        for ((p, c), (q, d)) in spd.lights.iter().zip(&ours.lights) {
            for i in 0..3 {
                assert!(close(p[i], q[i], 1e-6), "{name}: light at {p:?} vs {q:?}");
                // The SPD prints 1/sqrt(n) to six digits.
                assert!(
                    close(c[i], d[i], 1e-5),
                    "{name}: light colour {c:?} vs {d:?}"
                );
            }
        }
        assert_eq!(
            spd.textures.len(),
            ours.textures.len(),
            "{name}: one declared texture per NFF material"
        );
        assert_eq!(ours.textures.len(), scene.materials.len(), "{name}");
        let mut losses = Vec::new();
        for kind in ["sphere", "cone", "triangle", "smooth_triangle"] {
            for loss in check_primitives(name, kind, &scene, &spd, &ours) {
                if !losses.contains(&loss) {
                    losses.push(loss);
                }
            }
        }
        assert_eq!(
            losses,
            nff_losses(name),
            "{name}: texture values the NFF lacks"
        );
        assert_eq!(spd.primitives.len(), ours.primitives.len(), "{name}");
    }
}

#[test]
fn counts_follow_the_nff_primitives() {
    // Independent of the SPD's files: spheres, cylinders and cones one each, polygons
    // and patches cut into n - 2 triangles.
    for name in SCENES {
        let scene = load_spd(name);
        let pov = parse_pov(&tracer::scene_to_pov(&scene));
        let count = |kind: &str| pov.of_kind(kind).count();
        let triangles =
            |outlines: &mut dyn Iterator<Item = usize>| -> usize { outlines.map(|n| n - 2).sum() };
        assert_eq!(count("sphere"), scene.spheres.len(), "{name}");
        assert_eq!(
            count("cone"),
            scene.cylinders.len() + scene.cones.len(),
            "{name}"
        );
        assert_eq!(
            count("triangle"),
            triangles(&mut scene.polygons.iter().map(|p| p.outline.vertices.len())),
            "{name}"
        );
        assert_eq!(
            count("smooth_triangle"),
            triangles(&mut scene.patches.iter().map(|p| p.outline.vertices.len())),
            "{name}"
        );
        assert_eq!(pov.lights.len(), scene.lights.len(), "{name}");
    }
}

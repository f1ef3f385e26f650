//! The sample's profile of `rings` (baseline and `bvh`): flat rows, Amdahl figures.

use super::scene_spec::variant_name;
use results::{AmdahlFigures, AmdahlRow, FlatRow, Profile, ProfileView, SceneResult};

/// Flat-profile functions of `rings` (baseline): name, % time, inclusive %, count key.
pub(super) const BASELINE_FLAT: [(&str, f64, f64, Option<&str>); 13] = [
    (
        "tracer::primitives::cylinder::Cylinder::intersect",
        31.2,
        38.9,
        Some("tests.cylinder.tests"),
    ),
    (
        "tracer::primitives::sphere::Sphere::intersect",
        22.4,
        28.6,
        Some("tests.sphere.tests"),
    ),
    ("tracer::vec3::dot", 14.8, 14.8, Some("ops.dot")),
    ("tracer::vec3::Vec3::sub", 8.1, 8.1, Some("ops.sub")),
    (
        "tracer::scene::Scene::intersect",
        7.5,
        82.1,
        Some("calls.intersect"),
    ),
    ("tracer::render::trace", 3.2, 97.4, Some("calls.trace")),
    ("tracer::shading::shade", 2.6, 14.2, Some("calls.shade")),
    (
        "tracer::fast_sqrt::WithSqrt::sqrt",
        1.9,
        1.9,
        Some("ops.sqrt"),
    ),
    (
        "tracer::vec3::Vec3::normalize",
        1.1,
        2.0,
        Some("ops.normalize"),
    ),
    (
        "tracer::camera::Camera::primary_ray",
        0.6,
        1.3,
        Some("rays.primary"),
    ),
    (
        "tracer::shading::color_contribution",
        0.5,
        3.1,
        Some("calls.color_contribution"),
    ),
    (
        "tracer::primitives::polygon::Polygon::intersect",
        0.4,
        0.5,
        Some("tests.polygon.tests"),
    ),
    ("tracer::render::render::{{closure}}", 0.2, 99.6, None),
];

/// The same for `rings` with `bvh`.
pub(super) const BVH_FLAT: [(&str, f64, f64, Option<&str>); 9] = [
    (
        "tracer::accel::bvh::Bvh::intersect",
        27.5,
        71.0,
        Some("calls.intersect"),
    ),
    (
        "tracer::accel::aabb::Aabb::hit",
        21.8,
        21.8,
        Some("accel.nodes_visited"),
    ),
    (
        "tracer::primitives::cylinder::Cylinder::intersect",
        14.1,
        16.9,
        Some("tests.cylinder.tests"),
    ),
    (
        "tracer::primitives::sphere::Sphere::intersect",
        11.7,
        13.2,
        Some("tests.sphere.tests"),
    ),
    ("tracer::shading::shade", 7.9, 24.5, Some("calls.shade")),
    ("tracer::accel::bvh::Bvh::occluded", 6.2, 15.4, None),
    ("tracer::vec3::dot", 4.4, 4.4, Some("ops.dot")),
    ("tracer::render::trace", 3.6, 97.9, Some("calls.trace")),
    (
        "tracer::vec3::Vec3::normalize",
        1.8,
        2.6,
        Some("ops.normalize"),
    ),
];

fn amdahl_figures(fraction: f64) -> AmdahlFigures {
    let speedup = |factor: f64| 1.0 / ((1.0 - fraction) + fraction / factor);
    AmdahlFigures {
        fraction,
        speedup_2x: speedup(2.0),
        speedup_10x: speedup(10.0),
        speedup_limit: if fraction < 1.0 {
            1.0 / (1.0 - fraction)
        } else {
            f64::INFINITY
        },
    }
}

fn amdahl_row(name: &str, fraction: f64, inclusive: f64) -> AmdahlRow {
    let own = amdahl_figures(fraction);
    AmdahlRow {
        name: name.to_string(),
        fraction,
        speedup_2x: own.speedup_2x,
        speedup_10x: own.speedup_10x,
        speedup_limit: own.speedup_limit,
        inclusive: Some(amdahl_figures(inclusive)),
    }
}

pub(super) fn sample_profile(
    scene: &SceneResult,
    variant: &str,
    rows: &[(&str, f64, f64, Option<&str>)],
) -> Profile {
    let total = scene
        .variants
        .iter()
        .find(|v| v.variant == variant)
        .map_or(1.0, |v| v.time.median);
    let counts = scene
        .variants
        .iter()
        .find(|v| v.variant == variant)
        .map(|v| v.counts.clone())
        .unwrap_or_default();
    let seconds_per_sample = 0.001;
    let flat: Vec<FlatRow> = rows
        .iter()
        .map(|(name, percent, inclusive, key)| FlatRow {
            name: (*name).to_string(),
            percent: *percent,
            self_seconds: total * percent / 100.0,
            total_seconds: total * inclusive / 100.0,
            calls: key.and_then(|k| counts.get(k).copied()),
            inclusive_percent: Some(*inclusive),
            self_interval: None,
            inclusive_interval: None,
            noise: false,
            root: false,
        })
        .collect();
    let amdahl = flat
        .iter()
        .take(6)
        .map(|r| {
            let inclusive = r.inclusive_percent.unwrap_or(r.percent);
            amdahl_row(&r.name, r.percent / 100.0, inclusive / 100.0)
        })
        .collect();
    let stem = format!("profile/{}-{variant}", scene.name);
    Profile {
        variant: variant_name(variant),
        samples: (total / seconds_per_sample).round() as u64,
        seconds_per_sample,
        flat,
        flat_text: format!("{stem}-flat.txt"),
        callgraph_text: format!("{stem}-callgraph.txt"),
        flame_svg: format!("{stem}-flame.svg"),
        amdahl,
        renders: Some(1),
        samples_asked: Some((total / seconds_per_sample).round() as u64),
        timer: Some(results::Timer::PerfCpuClock),
        cpu_seconds: Some(total),
        counts,
        view: ProfileView::Native,
        second_view: None,
        exports: Vec::new(),
    }
}

//! Every SPD scene in ../shared/spd parses, renders without NaN or infinity, and obeys
//! the ray-count identities of the SPD procedure and of brute force.

mod common;

use common::{load_spd, options, render_counted, spd_dir};
use tracer::{Sampling, Scene};

fn spd_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(spd_dir())
        .unwrap_or_else(|e| panic!("{e}"))
        .filter_map(|entry| {
            let path = entry.ok()?.path();
            let stem = path.file_stem()?.to_string_lossy().into_owned();
            (path.extension()? == "nff").then_some(stem)
        })
        .collect();
    names.sort();
    names
}

#[test]
fn all_twelve_spd_scenes_render_finite_images_with_consistent_counts() {
    let names = spd_names();
    assert_eq!(names.len(), 12, "{names:?}");
    for name in &names {
        let scene = load_spd(name);
        let out = render_counted(&scene, &options(12, 12, Sampling::SpdCorners), 2);
        assert!(
            out.frame.is_finite(),
            "{name}: NaN or infinity in the framebuffer"
        );
        assert_eq!(out.frame.pixels.len(), 144);
        let c = out
            .counts()
            .unwrap_or_else(|| panic!("counted render gave no counts"));
        let r = c.rays;
        assert_eq!(
            r.primary,
            13 * 13,
            "{name}: (W+1)(H+1) eye rays in SPD mode"
        );
        assert!(
            r.primary_hit <= r.primary && r.shadow_blocked <= r.shadow,
            "{name}: {r:?}"
        );
        // Every traced ray is an eye, reflection or refraction ray; every query is a
        // traced ray or a shadow ray.
        assert_eq!(
            c.calls.trace,
            r.primary + r.reflection + r.refraction,
            "{name}"
        );
        assert_eq!(c.calls.intersect, c.calls.trace + r.shadow, "{name}");
        // Every hit is shaded once: eye hits plus the secondary rays that hit.
        assert!(c.calls.shade >= r.primary_hit, "{name}");
        assert!(
            c.calls.shade - r.primary_hit <= r.reflection + r.refraction,
            "{name}"
        );
        assert!(
            r.refraction <= r.reflection,
            "{name}: every refraction comes with a reflection"
        );
        for (kind, th) in [
            ("sphere", c.tests.sphere),
            ("cylinder", c.tests.cylinder),
            ("cone", c.tests.cone),
            ("polygon", c.tests.polygon),
            ("patch", c.tests.patch),
            ("plane", c.tests.plane),
        ] {
            assert!(
                th.hits <= th.tests,
                "{name}: {kind} hits {} > tests {}",
                th.hits,
                th.tests
            );
        }
        // Brute force: every closest-hit query tests every primitive.
        let closest = c.calls.trace;
        assert!(
            c.tests.sphere.tests >= scene.spheres.len() as u64 * closest,
            "{name}"
        );
        assert!(
            c.tests.cylinder.tests >= scene.cylinders.len() as u64 * closest,
            "{name}"
        );
        assert!(
            c.tests.cone.tests >= scene.cones.len() as u64 * closest,
            "{name}"
        );
        assert!(
            c.tests.polygon.tests >= scene.polygons.len() as u64 * closest,
            "{name}"
        );
        assert!(
            c.tests.patch.tests >= scene.patches.len() as u64 * closest,
            "{name}"
        );
        assert_eq!(
            c.tests.plane.tests,
            c.tests.polygon.tests + c.tests.patch.tests,
            "{name}"
        );
        assert_eq!(
            c.accel.nodes_visited, 0,
            "{name}: brute force visits no nodes"
        );
    }
}

#[test]
fn mount_glass_spheres_refract() {
    let scene = load_spd("mount");
    let out = render_counted(&scene, &options(10, 10, Sampling::PixelCenters), 2);
    let c = out.counts().unwrap_or_default();
    assert!(
        c.rays.refraction > 0,
        "mount's glass spheres refract: {:?}",
        c.rays
    );
}

#[test]
fn rings_brute_force_tests_every_primitive_per_closest_hit_query() {
    let scene: Scene = load_spd("rings");
    assert_eq!(
        (
            scene.spheres.len(),
            scene.cylinders.len(),
            scene.polygons.len()
        ),
        (4200, 4200, 1)
    );
    let out = render_counted(&scene, &options(8, 6, Sampling::PixelCenters), 2);
    let c = out.counts().unwrap_or_default();
    let r = c.rays;
    let closest_queries = r.primary + r.reflection + r.refraction;
    assert_eq!(r.primary, 48);
    assert!(r.reflection > 0, "rings has reflective materials");
    assert!(c.tests.sphere.tests >= 4200 * closest_queries);
    assert!(c.tests.cylinder.tests >= 4200 * closest_queries);
    assert!(c.tests.polygon.tests >= closest_queries);
    // Shadow queries stop at the first blocker, so they add between 0 and 4200 each.
    assert!(c.tests.sphere.tests <= 4200 * (closest_queries + r.shadow));
    assert!(
        c.tests.sphere.hits <= c.tests.sphere.tests
            && c.tests.cylinder.hits <= c.tests.cylinder.tests
    );
}

#[test]
fn project_scenes_parse_and_render() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut rendered = 0;
    for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.map(|e| e.path()).unwrap_or_default();
        if path.extension().is_some_and(|e| e == "nff") {
            let scene = tracer::load_nff(&path).unwrap_or_else(|e| panic!("{e}"));
            let out = render_counted(&scene, &options(16, 12, Sampling::PixelCenters), 1);
            assert!(out.frame.is_finite(), "{}", path.display());
            assert!(
                out.rays.primary_hit > 0,
                "{}: the camera sees nothing",
                path.display()
            );
            rendered += 1;
        }
    }
    assert!(rendered >= 2);
}

#[test]
fn every_spd_scene_round_trips_through_the_writer() {
    for name in spd_names() {
        let scene = load_spd(&name);
        let text = tracer::scene_to_nff(&scene);
        let again = tracer::parse_nff(&text, &format!("{name} (written)"))
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(
            again == scene,
            "{name}: the written scene parses differently"
        );
        assert_eq!(tracer::scene_to_nff(&again), text, "{name}");
    }
}

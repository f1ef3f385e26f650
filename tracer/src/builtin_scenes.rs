//! The project's own NFF scenes (`scenes/*.nff`), compiled into the binary.
//!
//! [`TEST_BENCH`] is the thesis's annex-1 test bench as this project writes it: 1 to 7
//! spheres (`balls1`…`balls7`), 1 to 7 open cylinders (`cylinder1`…`cylinder7`) and 1 to
//! 7 primitives mixing both (`both1`…`both7`), each with one light and diffuse materials,
//! the workload of the hardware model. [`MISC`] holds the other scenes. Embedding them
//! lets the suite and the tests run from the binary alone, without a checkout.

use crate::nff::{NffError, parse_nff};
use crate::scene::Scene;

/// One embedded scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BuiltinScene {
    /// File stem in `scenes/`, e.g. `balls3`.
    pub name: &'static str,
    /// `"balls"`, `"cylinder"`, `"both"` (the test bench) or `"misc"`.
    pub family: &'static str,
    /// Number of primitives of every kind in the scene.
    pub primitives: usize,
    /// The NFF text.
    pub text: &'static str,
}

impl BuiltinScene {
    /// Parses the embedded text; errors name the file as `builtin:NAME`.
    pub fn parse(&self) -> Result<Scene, NffError> {
        parse_nff(self.text, &format!("builtin:{}", self.name))
    }
}

/// Keeps the name, the family and the embedded file in one place.
macro_rules! builtin {
    ($name:literal, $family:literal, $primitives:expr) => {
        BuiltinScene {
            name: $name,
            family: $family,
            primitives: $primitives,
            text: include_str!(concat!("../../scenes/", $name, ".nff")),
        }
    };
}

/// The 21 test-bench scenes, in order `balls1..7`, `cylinder1..7`, `both1..7`.
pub const TEST_BENCH: &[BuiltinScene] = &[
    builtin!("balls1", "balls", 1),
    builtin!("balls2", "balls", 2),
    builtin!("balls3", "balls", 3),
    builtin!("balls4", "balls", 4),
    builtin!("balls5", "balls", 5),
    builtin!("balls6", "balls", 6),
    builtin!("balls7", "balls", 7),
    builtin!("cylinder1", "cylinder", 1),
    builtin!("cylinder2", "cylinder", 2),
    builtin!("cylinder3", "cylinder", 3),
    builtin!("cylinder4", "cylinder", 4),
    builtin!("cylinder5", "cylinder", 5),
    builtin!("cylinder6", "cylinder", 6),
    builtin!("cylinder7", "cylinder", 7),
    builtin!("both1", "both", 1),
    builtin!("both2", "both", 2),
    builtin!("both3", "both", 3),
    builtin!("both4", "both", 4),
    builtin!("both5", "both", 5),
    builtin!("both6", "both", 6),
    builtin!("both7", "both", 7),
];

/// The project's other scenes.
pub const MISC: &[BuiltinScene] = &[
    builtin!("one-sphere", "misc", 1),
    // A polygon, two spheres, a cylinder, a cone and a patch.
    builtin!("primitives", "misc", 6),
];

/// Every embedded scene: the test bench, then [`MISC`].
pub fn all() -> impl Iterator<Item = &'static BuiltinScene> {
    TEST_BENCH.iter().chain(MISC)
}

/// One line per built-in scene: name, family, primitives (`rtprof scene list`).
pub fn list_text() -> String {
    all()
        .map(|s| {
            format!(
                "{:<12} {:<9} {:>3} primitives\n",
                s.name, s.family, s.primitives
            )
        })
        .collect()
}

/// The embedded scene called `name` (`balls3`; a trailing `.nff` is accepted too).
pub fn find(name: &str) -> Option<&'static BuiltinScene> {
    let stem = name.strip_suffix(".nff").unwrap_or(name);
    all().find(|scene| scene.name == stem)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_or_panic(scene: &BuiltinScene) -> Scene {
        scene.parse().unwrap_or_else(|e| panic!("{e}"))
    }

    /// The number at the end of a test-bench name: `cylinder4` -> 4.
    fn suffix_number(name: &str) -> usize {
        let digits = name.trim_start_matches(|c: char| !c.is_ascii_digit());
        digits
            .parse()
            .unwrap_or_else(|_| panic!("{name} has no number suffix"))
    }

    type V = [f64; 3];

    fn v64(v: crate::Vec3) -> V {
        v.to_array().map(f64::from)
    }
    fn sub(a: V, b: V) -> V {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn dot(a: V, b: V) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    fn cross(a: V, b: V) -> V {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    fn unit(a: V) -> V {
        let len = dot(a, a).sqrt();
        [a[0] / len, a[1] / len, a[2] / len]
    }

    /// Camera frame: (forward, right, up), right = forward × up as the NFF format defines it.
    fn camera_frame(scene: &Scene) -> (V, V, V, V) {
        let eye = v64(scene.view.from);
        let forward = unit(sub(v64(scene.view.at), eye));
        let right = unit(cross(forward, v64(scene.view.up)));
        let up = cross(right, forward);
        (eye, forward, right, up)
    }

    /// Whether `p` projects inside the image (aspect from the resolution, square pixels).
    fn projects_inside(scene: &Scene, p: V) -> bool {
        let (eye, forward, right, up) = camera_frame(scene);
        let d = sub(p, eye);
        let depth = dot(d, forward);
        let half_tan = (f64::from(scene.view.angle_deg) / 2.0).to_radians().tan();
        let aspect = f64::from(scene.view.width) / f64::from(scene.view.height);
        depth > 0.0
            && (dot(d, right) / depth).abs() < half_tan * aspect
            && (dot(d, up) / depth).abs() < half_tan
    }

    /// Distance from `p` to the segment `a`-`b`.
    fn distance_to_segment(p: V, a: V, b: V) -> f64 {
        let ab = sub(b, a);
        let s = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
        let closest = [a[0] + s * ab[0], a[1] + s * ab[1], a[2] + s * ab[2]];
        let d = sub(p, closest);
        dot(d, d).sqrt()
    }

    #[test]
    fn test_bench_is_21_scenes_in_family_order() {
        let mut expected = Vec::new();
        for family in ["balls", "cylinder", "both"] {
            for n in 1..=7 {
                expected.push(format!("{family}{n}"));
            }
        }
        let names: Vec<&str> = TEST_BENCH.iter().map(|s| s.name).collect();
        assert_eq!(names, expected);
        for scene in TEST_BENCH {
            assert!(scene.name.starts_with(scene.family), "{}", scene.name);
        }
    }

    #[test]
    fn every_test_bench_scene_parses_with_one_light_and_only_spheres_and_cylinders() {
        for builtin in TEST_BENCH {
            let scene = parse_or_panic(builtin);
            let name = builtin.name;
            assert_eq!(scene.lights.len(), 1, "{name}: lights");
            assert!(!scene.lights[0].color_given, "{name}: plain `l x y z`");
            assert_eq!(
                scene.cones.len() + scene.polygons.len() + scene.patches.len(),
                0,
                "{name}: only spheres and cylinders"
            );
            let n = suffix_number(name);
            assert_eq!(builtin.primitives, n, "{name}: primitives field vs suffix");
            assert_eq!(
                scene.spheres.len() + scene.cylinders.len(),
                n,
                "{name}: parsed spheres + cylinders"
            );
            assert_eq!(scene.primitive_count(), n, "{name}");
            let expected_kinds = match builtin.family {
                "balls" => (n, 0),
                "cylinder" => (0, n),
                _ => (scene.spheres.len(), scene.cylinders.len()),
            };
            assert_eq!((scene.spheres.len(), scene.cylinders.len()), expected_kinds);
            if builtin.family == "both" && n >= 2 {
                assert!(!scene.spheres.is_empty(), "{name}: needs a sphere");
                assert!(!scene.cylinders.is_empty(), "{name}: needs a cylinder");
            }
            // Open cylinders only: the parser makes a cone when the radii differ, and
            // none is allowed above; a negative radius would show the inside.
            assert!(scene.cylinders.iter().all(|c| c.radius > 0.0), "{name}");
            assert!(scene.spheres.iter().all(|s| s.radius > 0.0), "{name}");
        }
    }

    #[test]
    fn test_bench_scenes_follow_the_bench_conventions() {
        for builtin in TEST_BENCH {
            let scene = parse_or_panic(builtin);
            let name = builtin.name;
            assert_eq!((scene.view.width, scene.view.height), (640, 480), "{name}");
            assert!((40.0..=45.0).contains(&scene.view.angle_deg), "{name}");
            let bg = scene.background;
            assert!(bg.r > 0.0 && bg.r < 0.4, "{name}: dark gray background");
            assert!(
                (bg.r - bg.g).abs() < 0.1 && (bg.r - bg.b).abs() < 0.1,
                "{name}"
            );
            // One diffuse, non-reflective, opaque material per object.
            assert_eq!(scene.materials.len(), builtin.primitives, "{name}");
            for m in &scene.materials {
                assert!((0.7..=0.8).contains(&m.kd), "{name}: kd {}", m.kd);
                assert_eq!((m.ks, m.t, m.ior), (0.0, 0.0, 1.0), "{name}");
            }
        }
    }

    #[test]
    fn test_bench_objects_are_in_view_and_the_light_outside_them() {
        for builtin in TEST_BENCH {
            let scene = parse_or_panic(builtin);
            let name = builtin.name;
            let (eye, forward, _, _) = camera_frame(&scene);
            let light = v64(scene.lights[0].position);
            for s in &scene.spheres {
                let c = v64(s.center);
                let r = f64::from(s.radius);
                assert!(
                    dot(sub(c, eye), forward) > r,
                    "{name}: sphere behind the eye"
                );
                assert!(
                    projects_inside(&scene, c),
                    "{name}: sphere centre off screen"
                );
                let to_light = sub(light, c);
                assert!(
                    dot(to_light, to_light).sqrt() > r,
                    "{name}: light in a sphere"
                );
                // Lit from the front: the light is on the camera's side of the sphere.
                assert!(
                    dot(to_light, forward) < 0.0,
                    "{name}: sphere lit from behind"
                );
            }
            for cyl in &scene.cylinders {
                let (b, a) = (v64(cyl.base), v64(cyl.apex));
                let r = f64::from(cyl.radius);
                for end in [b, a] {
                    assert!(dot(sub(end, eye), forward) > r, "{name}: cylinder behind");
                    assert!(
                        projects_inside(&scene, end),
                        "{name}: cylinder end off screen"
                    );
                }
                assert!(
                    distance_to_segment(light, b, a) > r,
                    "{name}: light in a cylinder"
                );
            }
        }
    }

    #[test]
    fn find_knows_the_bench_and_the_misc_scenes() {
        let found = find("balls3").map(|s| (s.name, s.family, s.primitives));
        assert_eq!(found, Some(("balls3", "balls", 3)));
        assert_eq!(find("cylinder7.nff").map(|s| s.name), Some("cylinder7"));
        assert_eq!(find("both1").map(|s| s.family), Some("both"));
        assert_eq!(find("one-sphere").map(|s| s.family), Some("misc"));
        assert_eq!(find("primitives").map(|s| s.family), Some("misc"));
        assert_eq!(find("balls8"), None);
        assert_eq!(find(""), None);
        assert_eq!(find("../scenes/balls1"), None);
        assert_eq!(all().count(), 23);
    }

    #[test]
    fn misc_scenes_parse_with_their_primitive_counts() {
        for builtin in MISC {
            let scene = parse_or_panic(builtin);
            assert_eq!(
                scene.primitive_count(),
                builtin.primitives,
                "{}",
                builtin.name
            );
        }
        let primitives = parse_or_panic(&MISC[1]);
        let kinds = (
            primitives.spheres.len(),
            primitives.cylinders.len(),
            primitives.cones.len(),
            primitives.polygons.len(),
            primitives.patches.len(),
        );
        assert_eq!(kinds, (2, 1, 1, 1, 1));
    }

    #[test]
    fn parse_errors_name_the_builtin() {
        let broken = BuiltinScene {
            name: "broken",
            family: "misc",
            primitives: 0,
            text: "s 0 0 0 1\n",
        };
        let e = broken.parse().err().map(|e| e.file);
        assert_eq!(e.as_deref(), Some("builtin:broken"));
    }
}

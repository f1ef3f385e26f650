//! Tests of the binary BVH: its build, its bounds and its traversal.

use super::*;
use crate::accel::BruteForce;
use crate::counter::NoCount;
use crate::nff::parse_nff;

pub(super) fn mixed_scene() -> Scene {
    let mut text = String::from(
        "v\nfrom 0 -12 3\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0\nresolution 16 16\n\
         l 4 -6 8\nf 1 0.5 0.2 0.7 0.3 8 0 1\n",
    );
    // A grid of spheres, cylinders, cones and polygons, including a flat one on the
    // z = 0 plane (a zero-thickness box).
    for i in 0..6 {
        for j in 0..6 {
            let (x, y) = (i as f32 * 1.5 - 4.0, j as f32 * 1.5 - 4.0);
            match (i + j) % 4 {
                0 => text += &format!("s {x} {y} 0.5 0.6\n"),
                1 => text += &format!("c\n{x} {y} 0 0.3\n{x} {y} 1.2 0.3\n"),
                2 => text += &format!("c\n{x} {y} 0 0.5\n{} {y} 1 0.1\n", x + 0.2),
                _ => text += &format!("p 3\n{x} {y} 0\n{} {y} 0\n{x} {} 0\n", x + 1.0, y + 1.0),
            }
        }
    }
    parse_nff(&text, "mixed.nff").unwrap_or_else(|e| panic!("{e}"))
}

/// The wide tree of `scene` this CPU runs, and its portable twin (no AVX2).
pub(super) fn both_paths(scene: &Scene) -> [super::WideBvh<'_>; 2] {
    let wide = super::WideBvh::build_with(scene, super::BvhBuilder::BinnedSah);
    let mut portable = wide.clone();
    portable.avx2 = false;
    [wide, portable]
}

/// A ray's traversal work: nodes visited, lanes issued and active, leaves visited,
/// sphere tests, intersect calls.
pub(super) fn traversal_work(c: &crate::counter::Count) -> [u64; 6] {
    use crate::counter::Stat;
    [
        Stat::NodesVisited,
        Stat::LanesIssued,
        Stat::LanesActive,
        Stat::LeavesVisited,
        Stat::SphereTest,
        Stat::Intersect,
    ]
    .map(|s| c.get(s))
}

pub(super) fn rays() -> Vec<Ray> {
    let mut out = Vec::new();
    let mut state = 12345u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        (state as f32 / u32::MAX as f32) * 2.0 - 1.0
    };
    for _ in 0..4000 {
        let origin = Vec3::new(next() * 8.0, next() * 8.0 - 10.0, next() * 4.0 + 1.0);
        let d = Vec3::new(next(), next() + 1.2, next() * 0.8 - 0.3);
        let dir = NoCount.normalize(d);
        out.push(Ray { origin, dir });
    }
    // Axis-parallel rays exercise infinite slab distances.
    out.push(Ray {
        origin: Vec3::new(-4.0, -20.0, 0.5),
        dir: Vec3::new(0.0, 1.0, 0.0),
    });
    out.push(Ray {
        origin: Vec3::new(-4.0, -4.0, 5.0),
        dir: Vec3::new(0.0, 0.0, -1.0),
    });
    out
}

#[test]
fn bvh_finds_the_same_closest_hits_and_blockers_as_brute_force() {
    let scene = mixed_scene();
    let brute = BruteForce::new(&scene);
    let bvh = Bvh::build(&scene);
    assert!(bvh.stats().leaves > 1 && bvh.stats().max_leaf_size <= MAX_LEAF);
    let mut hits = 0;
    for ray in rays() {
        let a = brute.closest_hit(&ray, 0.0, &mut NoCount);
        let b = bvh.closest_hit(&ray, 0.0, &mut NoCount);
        assert_eq!(a.map(|h| h.prim), b.map(|h| h.prim), "{ray:?}");
        assert_eq!(a.map(|h| h.t), b.map(|h| h.t));
        hits += usize::from(a.is_some());
        for limit in [1.0, 5.0, f32::INFINITY] {
            assert_eq!(
                brute.occluded(&ray, 0.0, limit, &mut NoCount),
                bvh.occluded(&ray, 0.0, limit, &mut NoCount)
            );
        }
    }
    assert!(hits > 300, "the test rays must hit something: {hits}");
}

#[test]
fn traversal_counts_nodes_and_tests_fewer_primitives() {
    let scene = mixed_scene();
    let bvh = Bvh::build(&scene);
    let ray: Ray = Ray {
        origin: Vec3::new(0.0, -12.0, 3.0),
        dir: NoCount.normalize(Vec3::new(0.0, 12.0, -3.0)),
    };
    let mut c = crate::counter::Count::default();
    bvh.closest_hit(&ray, 0.0, &mut c);
    let tests = c.get(Stat::SphereTest)
        + c.get(Stat::CylinderTest)
        + c.get(Stat::ConeTest)
        + c.get(Stat::PolygonTest);
    assert!(c.get(Stat::NodesVisited) >= 1);
    assert!(c.get(Stat::LeavesVisited) >= 1);
    assert!(tests < scene.primitive_count() as u64 / 2, "{tests}");
}

#[test]
fn sah_cost_of_a_two_leaf_tree_is_the_hand_computed_one() {
    // Two unit spheres 10 apart: a root over both and one leaf per sphere.
    // Leaf boxes 2x2x2: area 24 each. Root box 12x2x2: area 2(24 + 4 + 24) = 104.
    // SAH = 0.5 * 104/104 + 1 * 24/104 + 1 * 24/104 = 0.5 + 48/104.
    let scene = parse_nff(
        "v\nfrom 0 -20 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 4 4\n\
         f 1 1 1 1 0 1 0 1\ns -5 0 0 1\ns 5 0 0 1\n",
        "two.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let stats = Bvh::build(&scene).stats();
    assert_eq!((stats.nodes, stats.leaves), (3, 2));
    // The boxes are padded by 1e-5 of their size against rounding.
    let close = |a: f64, b: f64| (a - b).abs() < 1e-3 * b;
    assert!(close(stats.sah_cost, 0.5 + 48.0 / 104.0), "{stats:?}");
    assert!(close(stats.predicted_nodes_per_ray, 3.0), "{stats:?}");
    assert!(close(stats.predicted_leaves_per_ray, 48.0 / 104.0));
    assert!(close(stats.predicted_tests_per_ray, 48.0 / 104.0));
    // A shadow ray along the x axis through both spheres tests the 3 boxes the
    // model counts for a line that enters the root, and stops at the first leaf.
    let ray: Ray = Ray {
        origin: Vec3::new(-20.0, 0.0, 0.0),
        dir: Vec3::new(1.0, 0.0, 0.0),
    };
    let mut c = crate::counter::Count::default();
    assert!(Bvh::build(&scene).occluded(&ray, 0.0, f32::INFINITY, &mut c));
    assert_eq!(c.get(Stat::NodesVisited), 3);
    assert_eq!(c.get(Stat::LeavesVisited), 1);
}

#[test]
fn empty_scene_has_no_hits() {
    let scene = parse_nff(
        "v\nfrom 0 0 -4\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 4 4\n",
        "empty.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let bvh = Bvh::build(&scene);
    let ray: Ray = Ray {
        origin: Vec3::ZERO,
        dir: Vec3::new(0.0, 0.0, 1.0),
    };
    assert!(bvh.closest_hit(&ray, 0.0, &mut NoCount).is_none());
    assert!(!bvh.occluded(&ray, 0.0, 1.0, &mut NoCount));
}

//! The wide BVH against brute force, and its counts by hand.

use super::super::ray_lanes::RayLanes;
use super::super::tests::{mixed_scene, rays};
use super::*;
use crate::accel::BruteForce;
use crate::counter::{Count, NoCount};
use crate::nff::parse_nff;
use crate::vec3::Vec3;

/// Both code paths of a tree: the one this CPU runs and the portable one.
fn both_paths(scene: &Scene) -> [WideBvh<'_>; 2] {
    let wide = WideBvh::build_with(scene, BvhBuilder::BinnedSah);
    let mut portable = wide.clone();
    portable.avx2 = false;
    [wide, portable]
}

/// A cluster of overlapping spheres (leaves of several spheres: packs) around
/// cylinders and polygons.
fn cluster_scene() -> Scene {
    let mut text = String::from(
        "v\nfrom 0 -12 3\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0\nresolution 8 8\n\
         l 4 -6 8\nf 1 1 1 1 0 1 0 1\ns 0 0 0 -20\n",
    );
    let mut state = 99u32;
    let mut next = || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
    };
    for _ in 0..300 {
        let (x, y, z) = (next() * 5.0, next() * 5.0, next() * 2.0);
        text += &format!("s {x} {y} {z} {}\n", 0.2 + 0.3 * next().abs());
    }
    for i in 0..12 {
        let x = i as f32 - 6.0;
        text += &format!(
            "c\n{x} 3 -1 0.2\n{x} 3.5 1 0.2\np 3\n{x} -3 -1\n{} -3 -1\n{x} -3 0\n",
            x + 0.8
        );
    }
    parse_nff(&text, "cluster.nff").unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn wide_tree_finds_the_same_hits_and_blockers_as_brute_force_bit_for_bit() {
    for scene in [mixed_scene(), cluster_scene()] {
        let brute = BruteForce::new(&scene);
        let mut hits = 0;
        for wide in both_paths(&scene) {
            for ray in rays() {
                let a = brute.closest_hit(&ray, 0.0, &mut NoCount);
                let b = wide.closest_hit(&ray, 0.0, &mut NoCount);
                assert_eq!(
                    a.map(|h| (h.prim, h.t, h.aux)),
                    b.map(|h| (h.prim, h.t, h.aux)),
                    "{ray:?}"
                );
                hits += usize::from(a.is_some());
                for limit in [1.0, 5.0, f32::INFINITY] {
                    assert_eq!(
                        brute.occluded(&ray, 0.0, limit, &mut NoCount),
                        wide.occluded(&ray, 0.0, limit, &mut NoCount),
                        "{ray:?} {limit}"
                    );
                }
            }
        }
        assert!(hits > 600, "the test rays must hit something: {hits}");
    }
}

#[test]
fn every_primitive_is_in_exactly_one_leaf_and_nodes_are_wide() {
    let scene = cluster_scene();
    let wide = WideBvh::build_with(&scene, BvhBuilder::BinnedSah);
    let mut seen: Vec<PrimRef> = wide.others.clone();
    for leaf in &wide.leaves {
        if leaf.spheres > 0 {
            let pack = &wide.packs[leaf.pack as usize];
            seen.extend(
                pack.index[..leaf.spheres as usize]
                    .iter()
                    .map(|&index| PrimRef {
                        kind: PrimKind::Sphere,
                        index,
                    }),
            );
            // Unused lanes are never hit.
            assert!(
                pack.radius_sq[leaf.spheres as usize..]
                    .iter()
                    .all(|r| *r == f32::NEG_INFINITY)
            );
        }
    }
    for pack in &wide.triangle_packs {
        seen.extend(&pack.owner[..pack.live as usize]);
    }
    // The cluster's polygons are triangles: one piece each.
    assert_eq!(seen.len(), scene.primitive_count());
    let mut keys: Vec<(u8, u32)> = seen.iter().map(|p| (p.kind as u8, p.index)).collect();
    keys.sort_unstable();
    keys.dedup();
    assert_eq!(keys.len(), scene.primitive_count());
    let stats = wide.stats();
    // The leaves are those of the binary tree built over the wide tree's items; with
    // a pack of lanes costing about one test, they hold more items than the leaves of
    // the `bvh` variant's tree, which costs every item a test.
    let own = Bvh::build_over(&scene, BvhBuilder::BinnedSah, triangles::items(&scene).0);
    assert_eq!(stats.leaves, own.stats().leaves);
    let binary = Bvh::build(&scene).stats();
    assert!(stats.leaves < binary.leaves, "{stats:?} {binary:?}");
    // Collapsing removes interior nodes: n binary interior nodes in about n / 7 wide ones.
    assert!(
        stats.nodes * 3 < binary.nodes - binary.leaves,
        "{stats:?} {binary:?}"
    );
    assert!(stats.mean_children > 4.0, "{stats:?}");
    assert!(!wide.packs.is_empty());
}

#[test]
fn counts_of_a_two_leaf_tree_are_the_hand_computed_ones() {
    // Two unit spheres 10 apart: one wide node with two leaf children (one sphere
    // each, tested by the scalar test: a pack needs two).
    let scene = parse_nff(
        "v\nfrom 0 -20 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 4 4\n\
         f 1 1 1 1 0 1 0 1\ns -5 0 0 1\ns 5 0 0 1\n",
        "two.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let wide = WideBvh::build_with(&scene, BvhBuilder::BinnedSah);
    assert_eq!((wide.stats().nodes, wide.stats().leaves), (1, 2));
    let ray: Ray = Ray {
        origin: Vec3::new(-20.0, 0.0, 0.0),
        dir: Vec3::new(1.0, 0.0, 0.0),
    };
    // Closest hit: both boxes tested (2 of 8 lanes), the near leaf entered and hit at
    // t = 14, the far one dropped (it starts at 24 > 14).
    let mut c = Count::default();
    let hit = wide.closest_hit(&ray, 0.0, &mut c);
    assert_eq!(hit.map(|h| (h.prim.index, h.t)), Some((0, 14.0)));
    assert_eq!(c.get(Stat::NodesVisited), 2);
    assert_eq!(c.get(Stat::LeavesVisited), 1);
    assert_eq!((c.get(Stat::LanesIssued), c.get(Stat::LanesActive)), (8, 2));
    assert_eq!((c.get(Stat::SphereTest), c.get(Stat::Intersect)), (1, 1));
    // A shadow ray stops at the first leaf too.
    let mut c = Count::default();
    assert!(wide.occluded(&ray, 0.0, f32::INFINITY, &mut c));
    assert_eq!(
        (c.get(Stat::NodesVisited), c.get(Stat::LeavesVisited)),
        (2, 1)
    );
    // Between the spheres, looking at neither: boxes tested, nothing entered.
    let up: Ray = Ray {
        origin: Vec3::ZERO,
        dir: Vec3::new(0.0, 0.0, 1.0),
    };
    let mut c = Count::default();
    assert!(wide.closest_hit(&up, 0.0, &mut c).is_none());
    assert_eq!(
        (c.get(Stat::NodesVisited), c.get(Stat::LeavesVisited)),
        (2, 0)
    );
}

#[test]
fn sphere_packs_count_their_live_lanes() {
    // Three nearly coincident spheres: splitting them cannot pay, so one leaf and one
    // pack of 3.
    let scene = parse_nff(
        "v\nfrom 0 -20 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 4 4\n\
         f 1 1 1 1 0 1 0 1\ns 0 0 0 1\ns 0.01 0 0 1\ns 0 0 0.01 1\n",
        "three.nff",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let wide = WideBvh::build_with(&scene, BvhBuilder::BinnedSah);
    assert_eq!((wide.stats().leaves, wide.packs.len()), (1, 1));
    let ray: Ray = Ray {
        origin: Vec3::new(0.0, -20.0, 0.0),
        dir: Vec3::new(0.0, 1.0, 0.0),
    };
    let mut c = Count::default();
    let hit = wide.closest_hit(&ray, 0.0, &mut c);
    let brute = BruteForce::new(&scene).closest_hit(&ray, 0.0, &mut NoCount);
    assert_eq!(hit, brute);
    // One node lane (the leaf) and one pack of 3 live lanes.
    assert_eq!(
        (c.get(Stat::LanesIssued), c.get(Stat::LanesActive)),
        (16, 4)
    );
    // Each sphere meets the ray but is small as seen from 20 away (the first
    // stage's discriminant b² - (|Voc|² - r²) ≈ 1 is below |Voc|²/2⁸ ≈ 1.56), so each
    // runs both stages of the test: `sub` and two `dot`, then `scale`, `sub`, `dot`.
    assert_eq!(
        (
            c.get(Stat::SphereTest),
            c.get(Stat::Sub),
            c.get(Stat::Dot),
            c.get(Stat::Scale)
        ),
        (3, 6, 9, 3)
    );
    // Every sphere meets the ray (disc > 0): three square roots.
    assert_eq!(c.get(Stat::Sqrt), 3);
}

#[test]
fn a_packets_slabs_are_each_rays_own_bit_for_bit() {
    // Directions with zero, negative and tiny components (infinite and huge
    // reciprocals), in packets of every length.
    let mut all = rays();
    for dir in [
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(-0.0, 1.0, 0.0),
        Vec3::new(1e-30, -3.0, 7.0),
    ] {
        all.push(Ray {
            origin: Vec3::new(1.0, -2.0, 3.0),
            dir,
        });
    }
    let bits = |s: &Slab| (s.origin.map(f32::to_bits), s.inv_dir.map(f32::to_bits));
    // Packets of eight rays, as the packet traversal takes them, given 1 to 8, on
    // both code paths.
    for n in 1..=8 {
        for group in all.chunks(n) {
            let mut paths = vec![RayLanes::of::<false, false>(group)];
            if crate::accel::cpu_has_avx2_fma() {
                paths.push(RayLanes::of::<false, true>(group));
            }
            for lanes in paths {
                // Every lane, the unused ones repeating the first ray; the directions too.
                for lane in 0..WIDTH {
                    let ray = group.get(lane).unwrap_or(&group[0]);
                    assert_eq!(bits(&lanes.slab(lane)), bits(&Slab::new(ray)), "{ray:?}");
                    let dir = [0, 1, 2].map(|axis| lanes.dir[axis][lane].to_bits());
                    assert_eq!(dir, ray.dir.to_array().map(f32::to_bits), "{ray:?}");
                }
            }
        }
    }
}

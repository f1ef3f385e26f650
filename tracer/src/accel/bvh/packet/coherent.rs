//! Coherent packets through the wide BVH (eye rays of the variant `packets`), as
//! Embree traces coherent packets: the packet walks the tree by its bounds
//! ([`Frustum`]), one box step per node for all its rays, instead of one per ray. Only
//! at the last level are the rays told apart: a leaf child the bounds reach is tested
//! against each ray's own box test, and the leaf's triangles are tested one triangle
//! at a time against all the rays that enter it, a ray per lane.
//!
//! Every ray still gets the closest hit it gets alone: the bounds never drop a child
//! some ray enters, a leaf's rays are the ones whose own box test enters it, and each
//! ray-triangle pair is the same arithmetic as in a triangle pack (only the lane
//! differs), with the same tie rule ([`HitBound`]). So the picture is the wide BVH's,
//! bit for bit; the work differs.
//!
//! Counting (the work as done, ray by ray): a bounds step is one node step of [`WIDTH`]
//! lanes, as many active as the node has children, added to one ray of the packet in
//! turn; each leaf child tested by the rays adds one `accel.nodes_visited` and one lane
//! to each ray tested (the step's idle lanes to the ray in turn); a triangle tested
//! against the rays adds a `tests.triangle.tests` with its operations and one lane to
//! each ray tested, as a pack's lane does.

use super::super::frustum::Frustum;
use super::super::node::LEAF;
use super::super::ray_lanes::RayLanes;
use super::super::triangles::{TrianglePack, triangle_pack};
use super::super::wide::{
    Leaf, STACK, WideBvh, closest_lane, descend, search_leaf_parts, visit_order,
};
use super::{PACKET, Pending, next_waiting};
use crate::accel::BVH_WIDTH as WIDTH;
use crate::counter::{Counter, Phase, Stat};
use crate::ray::{Hit, HitBound, Ray};
use std::mem::MaybeUninit;

/// The search state of a packet's rays: each ray's reach, its closest hit so far, the
/// rays still searching, and the ray the next shared step is counted on.
struct Rays<'a, C, const FROM_EYE: bool> {
    rays: &'a [Ray<FROM_EYE>],
    lanes: &'a RayLanes,
    /// The query's reach per ray (a hit must come nearer).
    reach: [f32; PACKET],
    /// The reach left per ray: its closest hit's distance, or -inf once a shadow ray
    /// is blocked.
    t_max: [f32; PACKET],
    hits: &'a mut [Option<Hit>],
    counters: &'a mut [C],
    searching: u32,
    turn: u32,
}

impl<C: Counter, const FROM_EYE: bool> Rays<'_, C, FROM_EYE> {
    /// The counter a step shared by `rays` is added to: each ray of the set in turn,
    /// so that per-pixel counts stay even across the packet.
    fn shared(&mut self, rays: u32) -> &mut C {
        let k = self.turn % rays.count_ones();
        self.turn = self.turn.wrapping_add(1);
        let mut bits = rays;
        for _ in 0..k {
            bits &= bits - 1;
        }
        &mut self.counters[bits.trailing_zeros() as usize]
    }

    /// Ray `r` found `hit` (which beats its bound): with `ANY` it is blocked and leaves
    /// the search.
    #[inline(always)]
    fn found<const ANY: bool>(&mut self, r: usize, hit: Hit) {
        self.hits[r] = Some(hit);
        if ANY {
            self.t_max[r] = f32::NEG_INFINITY;
            self.searching &= !(1 << r);
        } else {
            self.t_max[r] = hit.t;
        }
    }

    /// Ray `r`'s bound: its closest hit so far, or its reach.
    #[inline(always)]
    fn bound(&self, r: usize) -> HitBound {
        self.hits[r].map_or(HitBound::reach(self.t_max[r]), |h| HitBound::of(&h))
    }
}

/// The traversal (phase `traversal`) of at most [`PACKET`] rays sharing `frustum`, ray
/// `i` within `(t_min, reach[i])`: each ray's closest hit, or with `ANY` the first
/// found.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn coherent_search<
    C: Counter,
    const FROM_EYE: bool,
    const ANY: bool,
    const AVX2: bool,
>(
    bvh: &WideBvh,
    rays: &[Ray<FROM_EYE>],
    lanes: &RayLanes,
    frustum: &Frustum,
    t_min: f32,
    reach: &[f32; PACKET],
    hits: &mut [Option<Hit>],
    counters: &mut [C],
) {
    let n = rays.len();
    let mut state = Rays {
        rays,
        lanes,
        reach: *reach,
        t_max: *reach,
        hits,
        counters,
        searching: (1u32 << n) - 1,
        turn: 0,
    };
    // Uninitialised as the per-ray packet's stack: only entries below `top` are read.
    let mut stack = [const { MaybeUninit::<Pending>::uninit() }; STACK];
    let mut top = 0usize;
    let mut current = Pending {
        child: 0,
        rays: state.searching,
        t: t_min,
    };
    loop {
        if current.rays & (current.rays - 1) == 0 {
            // One ray left: the single-ray loop.
            let r = current.rays.trailing_zeros() as usize;
            let found = descend::<C, FROM_EYE, ANY, AVX2>(
                bvh,
                &rays[r],
                &lanes.slab(r),
                current.child,
                t_min,
                state.reach[r],
                state.hits[r],
                &mut state.counters[r],
            );
            if let Some(hit) = found {
                state.found::<ANY>(r, hit);
            }
        } else if current.child & LEAF != 0 {
            let leaf = &bvh.leaves[(current.child & !LEAF) as usize];
            search_leaf_rays::<C, FROM_EYE, ANY, AVX2>(bvh, leaf, current.rays, t_min, &mut state);
        } else {
            let node = &bvh.nodes[current.child as usize];
            let active = current.rays;
            let far = farthest(&state.t_max, active);
            let (candidates, near) = frustum.children::<AVX2>(node, t_min, far);
            let mut step = [Pending {
                child: 0,
                rays: 0,
                t: 0.0,
            }; WIDTH];
            let mut entered = 0u32;
            let mut bits = candidates;
            while bits != 0 {
                let lane = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let child = node.child[lane];
                let (set, t) = if child & LEAF != 0 {
                    // The last level: each ray's own box test.
                    Frustum::rays_entering::<AVX2>(lanes, node, lane, active, t_min, &state.t_max)
                } else {
                    (active, near[lane])
                };
                if set != 0 {
                    entered |= 1 << lane;
                    step[lane] = Pending {
                        child,
                        rays: set,
                        t,
                    };
                }
            }
            if C::ENABLED {
                count_node_step(&mut state, node.used, candidates, active, node.child);
            }
            let entry = |lane: u32| step[lane as usize];
            if let Some(next) = visit_order::<_, ANY>(entered, entry, &mut stack, &mut top) {
                current = next;
                continue;
            }
        }
        if ANY && state.searching == 0 {
            return;
        }
        // The nearest waiting entry with a ray that can still reach it (the bounds'
        // entry is no later than any ray's).
        match next_waiting(&stack, &mut top, &state.t_max) {
            Some(next) => current = next,
            None => return,
        }
    }
}

/// The farthest reach left among `rays` (bit per ray).
#[inline(always)]
fn farthest(t_max: &[f32; PACKET], rays: u32) -> f32 {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{
            _mm_and_ps, _mm_andnot_ps, _mm_castsi128_ps, _mm_cmpeq_epi32, _mm_cvtss_f32,
            _mm_loadu_ps, _mm_max_ps, _mm_movehl_ps, _mm_or_ps, _mm_set_epi32, _mm_set1_epi32,
            _mm_set1_ps, _mm_shuffle_ps,
        };
        const _: () = assert!(PACKET == 8, "two SSE halves");
        // SAFETY: SSE2 is part of x86-64; the loads read the 8 floats of `t_max`.
        // Lanes outside `rays` become -inf; `maxps` of the rest is their largest (a
        // reach is never NaN).
        unsafe {
            let bits = _mm_set1_epi32(rays as i32);
            let low_bits = _mm_set_epi32(8, 4, 2, 1);
            let high_bits = _mm_set_epi32(128, 64, 32, 16);
            let select = |v, lane_bits| {
                let on = _mm_castsi128_ps(_mm_cmpeq_epi32(
                    std::arch::x86_64::_mm_and_si128(bits, lane_bits),
                    lane_bits,
                ));
                _mm_or_ps(
                    _mm_and_ps(on, v),
                    _mm_andnot_ps(on, _mm_set1_ps(f32::NEG_INFINITY)),
                )
            };
            let low = select(_mm_loadu_ps(t_max.as_ptr()), low_bits);
            let high = select(_mm_loadu_ps(t_max.as_ptr().add(4)), high_bits);
            let m = _mm_max_ps(low, high);
            let m = _mm_max_ps(m, _mm_movehl_ps(m, m));
            let m = _mm_max_ps(m, _mm_shuffle_ps::<0b01>(m, m));
            _mm_cvtss_f32(m)
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    farthest_portable(t_max, rays)
}

/// [`farthest`] lane by lane.
#[cfg_attr(target_arch = "x86_64", allow(dead_code))]
#[inline(always)]
fn farthest_portable(t_max: &[f32; PACKET], rays: u32) -> f32 {
    let mut far = f32::NEG_INFINITY;
    for (r, &t) in t_max.iter().enumerate() {
        let t = if rays & (1 << r) != 0 {
            t
        } else {
            f32::NEG_INFINITY
        };
        far = if t > far { t } else { far };
    }
    far
}

/// Counts one node step as the module says: the bounds step on one ray in turn, each
/// leaf child the rays were tested against on every ray tested.
fn count_node_step<C: Counter, const FROM_EYE: bool>(
    state: &mut Rays<'_, C, FROM_EYE>,
    used: u32,
    candidates: u32,
    active: u32,
    child: [u32; WIDTH],
) {
    let live = u64::from(used.count_ones());
    let mut leaf_children = 0u64;
    let mut bits = candidates;
    while bits != 0 {
        let lane = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        leaf_children += u64::from(child[lane] & LEAF != 0);
    }
    let idle = (PACKET as u64 - u64::from(active.count_ones())) * leaf_children;
    let c = state.shared(active);
    c.tally_n(Stat::NodesVisited, live);
    c.tally_n(Stat::LanesIssued, WIDTH as u64 + idle);
    c.tally_n(Stat::LanesActive, live);
    if leaf_children > 0 {
        let mut bits = active;
        while bits != 0 {
            let c = &mut state.counters[bits.trailing_zeros() as usize];
            bits &= bits - 1;
            c.tally_n(Stat::NodesVisited, leaf_children);
            c.tally_n(Stat::LanesIssued, leaf_children);
            c.tally_n(Stat::LanesActive, leaf_children);
        }
    }
}

/// A leaf for the rays in `rays`: its triangle packs a triangle at a time against all
/// those rays (or a pack per ray when the rays are fewer than its triangles), then its
/// spheres and other primitives ray by ray.
#[inline(always)]
fn search_leaf_rays<C: Counter, const FROM_EYE: bool, const ANY: bool, const AVX2: bool>(
    bvh: &WideBvh,
    leaf: &Leaf,
    mut rays: u32,
    t_min: f32,
    state: &mut Rays<'_, C, FROM_EYE>,
) {
    if C::ENABLED {
        let mut bits = rays;
        while bits != 0 {
            let c = &mut state.counters[bits.trailing_zeros() as usize];
            bits &= bits - 1;
            c.tally(Stat::LeavesVisited);
        }
    }
    let packs = leaf.first_triangle_pack as usize;
    for pack in &bvh.triangle_packs[packs..packs + leaf.triangle_packs as usize] {
        if rays.count_ones() <= pack.live {
            pack_per_ray::<C, FROM_EYE, ANY>(bvh, pack, rays, t_min, state);
        } else {
            pack_in_ray_lanes::<C, FROM_EYE, ANY, AVX2>(pack, rays, t_min, state);
        }
        rays &= state.searching;
        if rays == 0 {
            return;
        }
    }
    if leaf.spheres > 0 || leaf.others > 0 {
        let mut bits = rays;
        while bits != 0 {
            let r = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let bound = state.bound(r);
            let found = search_leaf_parts::<C, FROM_EYE, ANY, false>(
                bvh,
                leaf,
                &state.rays[r],
                t_min,
                state.reach[r],
                bound,
                &mut state.counters[r],
            );
            if let Some(hit) = found {
                state.found::<ANY>(r, hit);
            }
        }
    }
}

/// A triangle pack against each ray of `rays` in turn (its lanes the triangles).
#[inline(always)]
fn pack_per_ray<C: Counter, const FROM_EYE: bool, const ANY: bool>(
    bvh: &WideBvh,
    pack: &TrianglePack,
    rays: u32,
    t_min: f32,
    state: &mut Rays<'_, C, FROM_EYE>,
) {
    let mut bits = rays;
    while bits != 0 {
        let r = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        let ray = &state.rays[r];
        let lanes = triangle_pack(
            pack,
            ray,
            t_min,
            state.reach[r],
            bvh.avx2,
            &mut state.counters[r],
        );
        let prim = |lane: usize| pack.owner[lane];
        if let Some((t, lane)) = lanes.and_then(|t| closest_lane(&t, prim, state.bound(r), ANY)) {
            state.found::<ANY>(
                r,
                Hit {
                    t,
                    prim: prim(lane),
                    aux: 0.0,
                },
            );
        }
    }
}

/// A triangle pack a triangle at a time against all the rays of `rays` (a ray per
/// lane); each ray keeps the hits that beat its bound.
#[inline(always)]
fn pack_in_ray_lanes<C: Counter, const FROM_EYE: bool, const ANY: bool, const AVX2: bool>(
    pack: &TrianglePack,
    mut rays: u32,
    t_min: f32,
    state: &mut Rays<'_, C, FROM_EYE>,
) {
    let _phase = C::enter_phase(Phase::TriangleTest);
    for i in 0..pack.live as usize {
        // Each ray's distance, and the rays whose hit is at or within their reach left
        // (ties are decided by `admits`).
        let (t, ranged, inside, within) =
            triangle_lanes::<AVX2>(pack, i, state.lanes, t_min, &state.reach, &state.t_max);
        if C::ENABLED {
            count_triangle::<C, FROM_EYE>(state, rays, ranged, inside);
        }
        let mut near = within & rays;
        while near != 0 {
            let r = near.trailing_zeros() as usize;
            near &= near - 1;
            let prim = pack.owner[i];
            if state.bound(r).admits(t[r], prim) {
                state.found::<ANY>(
                    r,
                    Hit {
                        t: t[r],
                        prim,
                        aux: 0.0,
                    },
                );
            }
        }
        if ANY {
            rays &= state.searching;
            if rays == 0 {
                return;
            }
        }
    }
}

/// [`triangle_rays`](super::super::triangles::triangle_rays) on the code path `AVX2` names,
/// and the rays that hit at or within their `t_max` (bits per ray).
#[inline(always)]
fn triangle_lanes<const AVX2: bool>(
    pack: &TrianglePack,
    i: usize,
    lanes: &RayLanes,
    t_min: f32,
    reach: &[f32; PACKET],
    t_max: &[f32; PACKET],
) -> ([f32; PACKET], u32, u32, u32) {
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: `AVX2` is set only on CPUs with AVX2 (see `packet_search_avx2`).
        return unsafe {
            super::super::triangles::triangle_rays_avx2(pack, i, lanes, t_min, reach, t_max)
        };
    }
    let (t, ranged, inside) = super::super::triangles::triangle_rays(pack, i, lanes, t_min, reach);
    let mut within = 0u32;
    for r in 0..PACKET {
        within |= u32::from(t[r] <= t_max[r]) << r;
    }
    (t, ranged, inside, inside & within)
}

/// Counts one triangle tested against `rays` as a pack's lane counts it, on each ray.
fn count_triangle<C: Counter, const FROM_EYE: bool>(
    state: &mut Rays<'_, C, FROM_EYE>,
    rays: u32,
    ranged: u32,
    inside: u32,
) {
    let idle = PACKET as u64 - u64::from(rays.count_ones());
    state.shared(rays).tally_n(Stat::LanesIssued, idle);
    let mut bits = rays;
    while bits != 0 {
        let r = bits.trailing_zeros();
        bits &= bits - 1;
        let c = &mut state.counters[r as usize];
        c.tally(Stat::LanesIssued);
        c.tally(Stat::LanesActive);
        c.tally(Stat::TriangleTest);
        if !FROM_EYE {
            c.tally(Stat::Sub);
        }
        c.tally_n(Stat::Dot, 2);
        if ranged & (1 << r) != 0 {
            c.tally(Stat::Scale);
            c.tally(Stat::Add);
            c.tally_n(Stat::Dot, 3);
        }
        if inside & (1 << r) != 0 {
            c.tally(Stat::TriangleHit);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::tests::{both_paths, mixed_scene, traversal_work as get};
    use super::*;
    use crate::accel::Intersector;
    use crate::counter::{Count, NoCount};
    use crate::nff::parse_nff;
    use crate::vec3::Vec3;

    /// Rays from one origin through a grid of points: eye rays of a pinhole.
    fn eye_rays(origin: Vec3, columns: usize, rows: usize) -> Vec<Ray> {
        let mut out = Vec::new();
        for j in 0..rows {
            for i in 0..columns {
                let at = Vec3::new(
                    -6.0 + 12.0 * (i as f32 + 0.37) / columns as f32,
                    0.5,
                    -2.0 + 5.0 * (j as f32 + 0.61) / rows as f32,
                );
                let d = NoCount.sub(at, origin);
                out.push(Ray {
                    origin,
                    dir: NoCount.normalize(d),
                });
            }
        }
        out
    }

    /// The mixed grid with layers of overlapping triangles behind it: a ray crosses
    /// several triangles of one leaf, so the nearest must win in the ray lanes.
    fn layered_scene() -> crate::scene::Scene {
        let mut text = String::from(
            "v\nfrom 0 -12 3\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0\nresolution 16 16\n\
             f 1 1 1 1 0 1 0 1\n",
        );
        for layer in 0..12 {
            let y = 0.5 + 0.25 * layer as f32;
            let shift = 0.3 * (layer % 5) as f32;
            for k in 0..4 {
                let x = -6.0 + 3.0 * k as f32 + shift;
                text += &format!(
                    "p 3\n{x} {y} -2\n{} {} 3\n{} {y} 3.5\n",
                    x + 4.0,
                    y + 0.2,
                    x - 1.0
                );
            }
        }
        parse_nff(&text, "layers.nff").unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn coherent_packets_find_each_rays_own_closest_hit_bit_for_bit() {
        let (mut coherent, mut hits, mut traced) = (0, 0, 0);
        for scene in [mixed_scene(), layered_scene()] {
            for wide in both_paths(&scene) {
                // From in front of the grid, and from above it (rays meeting flat boxes).
                for origin in [Vec3::new(0.3, -12.0, 3.0), Vec3::new(-0.2, -3.0, 9.0)] {
                    let rays = eye_rays(origin, 64, 24);
                    for size in [2, 3, 8] {
                        for group in rays.chunks(size) {
                            let lanes = RayLanes::of::<false, false>(group);
                            coherent +=
                                usize::from(Frustum::of_one_origin::<false>(&lanes).is_some());
                            let mut found = vec![None; group.len()];
                            let mut counters = vec![NoCount; group.len()];
                            wide.closest_hits(group, &mut found, &mut counters);
                            for (ray, hit) in group.iter().zip(&found) {
                                let alone = wide.closest_hit(ray, 0.0, &mut NoCount);
                                assert_eq!(
                                    hit.map(|h| (h.prim, h.t, h.aux)),
                                    alone.map(|h| (h.prim, h.t, h.aux)),
                                    "packet of {size}: {ray:?}"
                                );
                                hits += usize::from(alone.is_some());
                                traced += 1;
                            }
                        }
                    }
                }
            }
        }
        // Nearly every packet took the coherent path (those across the grid's middle
        // column mix octants), and both hits and misses were compared in numbers.
        assert!(coherent > 2 * 2 * 1000, "{coherent}");
        assert!(
            hits > traced / 5 && traced - hits > traced / 5,
            "{hits} of {traced}"
        );
    }

    #[test]
    fn a_coherent_packet_counts_its_work_hand_computed() {
        // Two unit spheres at z = 1, 10 apart along x: one wide node, two leaves.
        let scene = parse_nff(
            "v\nfrom 0 -20 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 4 4\n\
             f 1 1 1 1 0 1 0 1\ns 2 0 1 1\ns 12 0 1 1\n",
            "two.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let origin = Vec3::new(0.0, -20.0, 0.0);
        let toward = |x: f32| Ray {
            origin,
            dir: NoCount.normalize(Vec3::new(x, 20.0, 1.0)),
        };
        for wide in both_paths(&scene) {
            let packet = [toward(2.0), toward(12.0)];
            let lanes = RayLanes::of::<false, false>(&packet);
            assert!(Frustum::of_one_origin::<false>(&lanes).is_some());
            let mut found = [None; 2];
            let mut counters = [Count::default(), Count::default()];
            wide.closest_hits(&packet, &mut found, &mut counters);
            for (ray, hit) in packet.iter().zip(&found) {
                let alone = wide.closest_hit(ray, 0.0, &mut NoCount);
                assert_eq!(hit.map(|h| (h.prim, h.t)), alone.map(|h| (h.prim, h.t)));
                assert!(hit.is_some());
            }
            // The bounds step of the root (2 live children of 8 lanes) on the first ray
            // (the first in turn), with the idle lanes of its two leaf-child steps
            // (6 rays absent, 2 children: 12); then each ray tests both leaf children
            // (2 nodes, 2 lanes issued and active), enters its own sphere's leaf alone
            // and tests that sphere.
            assert_eq!(
                counters.map(|c| get(&c)),
                [[2 + 2, 8 + 12 + 2, 2 + 2, 1, 1, 1], [2, 2, 2, 1, 1, 1]]
            );
        }
    }
}

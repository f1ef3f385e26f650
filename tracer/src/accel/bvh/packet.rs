//! Packets of rays through the wide BVH (variant `packets`, with `bvh` + `simd`).
//!
//! Eye rays of a pinhole camera (one origin, one octant) take the coherent traversal
//! of [`coherent`]: one box step per node for the whole packet, by its bounds.
//! Other packets (reflections, refractions, shadow rays) take the steps below.
//!
//! Neighbouring rays meet the same boxes, so up to [`PACKET`] of them walk the tree
//! together: at each node every ray still in the packet tests the node's child boxes
//! (one lane step per ray, with its own reach), the children any ray enters are visited
//! nearest first by the packet's nearest entry, and each child carries the set of rays
//! that entered it. A leaf tests only those rays, each with its own closest hit so far.
//! One traversal decision, one stack and one fetch of each node serve the whole packet.
//! A subtree that only one ray of the packet enters is handed to the single-ray loop
//! (the same steps in the same order, without the packet's bookkeeping).
//!
//! Every ray gets the closest hit it gets alone (the same leaves' tests, each with the
//! ray's own distance limit), so the picture is the wide BVH's. The work differs a
//! little from one ray alone: a ray may still test a node the packet reaches before the
//! ray's own nearer hit is found. Counting follows the work, ray by ray: each ray's box
//! steps (`accel.nodes_visited` per live child, [`WIDTH`] `accel.lanes_issued`), leaves
//! and primitive tests are added to that ray's own counter.

use super::frustum::Frustum;
use super::node::{LEAF, Slab, WideNode};
use super::ray_lanes::RayLanes;
use super::wide::{STACK, WideBvh, descend, search_leaf, visit_order};
use crate::accel::BVH_WIDTH as WIDTH;
use crate::counter::{Counter, Phase, Stat};
use crate::ray::{Hit, HitBound, Ray};
use coherent::coherent_search;
use std::mem::MaybeUninit;

mod coherent;

/// Rays traced together: one bit each in a `u32` ray set.
pub const PACKET: usize = 8;

/// A node or leaf waiting to be visited by the rays in `rays` (bit per ray), with the
/// nearest distance at which one of them enters it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Pending {
    pub(super) child: u32,
    pub(super) rays: u32,
    pub(super) t: f32,
}

impl super::wide::Waiting for Pending {
    #[inline(always)]
    fn entered_at(&self) -> f32 {
        self.t
    }
}

/// The children of one node step: which children any ray enters (bit per lane), the
/// rays that enter each, and the nearest entry distance per child.
struct Step {
    entered: u32,
    rays: [u32; WIDTH],
    t: [f32; WIDTH],
}

impl WideBvh<'_> {
    /// The closest hits of `rays` in `(t_min, ∞)`, [`PACKET`] at a time; `hits` and
    /// `counters` are as long as `rays`.
    pub(super) fn packet_closest<C: Counter, const FROM_EYE: bool>(
        &self,
        rays: &[Ray<FROM_EYE>],
        t_min: f32,
        hits: &mut [Option<Hit>],
        counters: &mut [C],
    ) {
        let reach = [f32::INFINITY; PACKET];
        for ((rays, hits), counters) in rays
            .chunks(PACKET)
            .zip(hits.chunks_mut(PACKET))
            .zip(counters.chunks_mut(PACKET))
        {
            self.packet::<C, FROM_EYE, false>(rays, t_min, &reach, hits, counters);
        }
    }

    /// Whether anything lies in `(t_min, t_max[i])` along `rays[i]` (shadow rays),
    /// [`PACKET`] at a time; each ray stops at its first blocker.
    pub(super) fn packet_occluded<C: Counter>(
        &self,
        rays: &[Ray],
        t_min: f32,
        t_max: &[f32],
        blocked: &mut [bool],
        counters: &mut [C],
    ) {
        let mut hits = [None; PACKET];
        for (((rays, t_max), blocked), counters) in rays
            .chunks(PACKET)
            .zip(t_max.chunks(PACKET))
            .zip(blocked.chunks_mut(PACKET))
            .zip(counters.chunks_mut(PACKET))
        {
            // Lane by lane: a slice copy of at most 8 floats was a `memcpy` call.
            let reach: [f32; PACKET] =
                std::array::from_fn(|i| t_max.get(i).copied().unwrap_or(f32::INFINITY));
            let n = rays.len();
            self.packet::<C, false, true>(rays, t_min, &reach, &mut hits[..n], counters);
            for (b, hit) in blocked.iter_mut().zip(&hits) {
                *b = hit.is_some();
            }
        }
    }

    /// One packet of at most [`PACKET`] rays, on the code path this CPU runs.
    fn packet<C: Counter, const FROM_EYE: bool, const ANY: bool>(
        &self,
        rays: &[Ray<FROM_EYE>],
        t_min: f32,
        t_max: &[f32; PACKET],
        hits: &mut [Option<Hit>],
        counters: &mut [C],
    ) {
        for c in counters.iter_mut() {
            c.tally(Stat::Intersect);
        }
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is true only when the CPU reported AVX2 and FMA.
            unsafe {
                packet_search_avx2::<C, FROM_EYE, ANY>(self, rays, t_min, t_max, hits, counters)
            };
            return;
        }
        packet_search::<C, FROM_EYE, ANY, false>(self, rays, t_min, t_max, hits, counters);
    }
}

/// [`packet_search`] compiled with AVX2 + FMA (the caller checks the CPU has them).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn packet_search_avx2<C: Counter, const FROM_EYE: bool, const ANY: bool>(
    bvh: &WideBvh,
    rays: &[Ray<FROM_EYE>],
    t_min: f32,
    t_max: &[f32; PACKET],
    hits: &mut [Option<Hit>],
    counters: &mut [C],
) {
    packet_search::<C, FROM_EYE, ANY, true>(bvh, rays, t_min, t_max, hits, counters);
}

/// The packet's nearest-first traversal (phase `traversal`) of at most [`PACKET`]
/// rays, ray `i` within `(t_min, t_max[i])`: each ray's closest hit, or with `ANY` the
/// first found (a shadow ray, which then leaves the packet).
#[inline(always)]
fn packet_search<C: Counter, const FROM_EYE: bool, const ANY: bool, const AVX2: bool>(
    bvh: &WideBvh,
    rays: &[Ray<FROM_EYE>],
    t_min: f32,
    t_max: &[f32; PACKET],
    hits: &mut [Option<Hit>],
    counters: &mut [C],
) {
    let _phase = C::enter_phase(Phase::Traversal);
    let n = rays.len().min(PACKET).min(hits.len()).min(counters.len());
    hits.iter_mut().for_each(|h| *h = None);
    if bvh.nodes.is_empty() || n == 0 {
        return;
    }
    if n == 1 {
        // One ray (a packet's lone reflection, or its only point facing a light): the
        // single-ray loop, as the packet would hand it over, without the lanes' set-up.
        hits[0] = descend::<C, FROM_EYE, ANY, AVX2>(
            bvh,
            &rays[0],
            &Slab::new(&rays[0]),
            0,
            t_min,
            t_max[0],
            None,
            &mut counters[0],
        );
        return;
    }
    let slabs: [Slab; PACKET] = if ANY {
        // Shadow rays leave from different points: straight to each ray's slab
        // constants (unused lanes repeat the first ray, as in the lanes).
        std::array::from_fn(|r| Slab::new(&rays[if r < n { r } else { 0 }]))
    } else {
        let lanes = RayLanes::of::<FROM_EYE, AVX2>(&rays[..n]);
        // Eye rays of a pinhole sharing an octant: the packet walks by its bounds. (Not
        // shadow rays: a packet's leave from different points, and the bounds of those
        // rays turned round from the light did not pay; see docs/benchmarks.md.)
        if let Some(frustum) = Frustum::of_one_origin::<AVX2>(&lanes) {
            coherent_search::<C, FROM_EYE, ANY, AVX2>(
                bvh,
                &rays[..n],
                &lanes,
                &frustum,
                t_min,
                t_max,
                hits,
                counters,
            );
            return;
        }
        std::array::from_fn(|r| lanes.slab(r))
    };
    let reach = *t_max;
    let mut t_max = *t_max;
    let mut searching = (1u32 << n) - 1;
    // Uninitialised for the same reason as the single-ray stack: only entries below
    // `top` are read, and each was written first.
    let mut stack = [const { MaybeUninit::<Pending>::uninit() }; STACK];
    let mut top = 0usize;
    let mut current = Pending {
        child: 0,
        rays: searching,
        t: t_min,
    };
    loop {
        if current.rays & (current.rays - 1) == 0 {
            // One ray left in this subtree: the single-ray loop does the same steps
            // without the packet's bookkeeping.
            let r = current.rays.trailing_zeros() as usize;
            let found = descend::<C, FROM_EYE, ANY, AVX2>(
                bvh,
                &rays[r],
                &slabs[r],
                current.child,
                t_min,
                reach[r],
                hits[r],
                &mut counters[r],
            );
            if let Some(hit) = found {
                hits[r] = Some(hit);
                if ANY {
                    t_max[r] = f32::NEG_INFINITY;
                    searching &= !(1 << r);
                    if searching == 0 {
                        return;
                    }
                } else {
                    t_max[r] = hit.t;
                }
            }
        } else if current.child & LEAF != 0 {
            let leaf = &bvh.leaves[(current.child & !LEAF) as usize];
            let mut bits = current.rays;
            while bits != 0 {
                let r = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let c = &mut counters[r];
                c.tally(Stat::LeavesVisited);
                let bound = hits[r].map_or(HitBound::reach(t_max[r]), |h| HitBound::of(&h));
                if let Some(hit) =
                    search_leaf::<C, FROM_EYE, ANY>(bvh, leaf, &rays[r], t_min, reach[r], bound, c)
                {
                    hits[r] = Some(hit);
                    if ANY {
                        // Blocked: out of the packet (no box is entered below -inf).
                        t_max[r] = f32::NEG_INFINITY;
                        searching &= !(1 << r);
                        if searching == 0 {
                            return;
                        }
                    } else {
                        t_max[r] = hit.t;
                    }
                }
            }
        } else {
            let node = &bvh.nodes[current.child as usize];
            #[cfg(target_arch = "x86_64")]
            let step = if AVX2 {
                // SAFETY: `AVX2` is set only inside `packet_search_avx2`, which runs
                // only on CPUs with AVX2 and FMA.
                unsafe { step_avx2(node, &slabs, current.rays, t_min, &t_max) }
            } else {
                step(node, &slabs, current.rays, t_min, &t_max)
            };
            #[cfg(not(target_arch = "x86_64"))]
            let step = step(node, &slabs, current.rays, t_min, &t_max);
            if C::ENABLED {
                let live = u64::from(node.used.count_ones());
                let mut bits = current.rays;
                while bits != 0 {
                    let c = &mut counters[bits.trailing_zeros() as usize];
                    bits &= bits - 1;
                    c.tally_n(Stat::NodesVisited, live);
                    c.tally_n(Stat::LanesIssued, WIDTH as u64);
                    c.tally_n(Stat::LanesActive, live);
                }
            }
            let entry = |lane: u32| Pending {
                child: node.child[lane as usize],
                rays: step.rays[lane as usize],
                t: step.t[lane as usize],
            };
            if let Some(next) = visit_order::<_, ANY>(step.entered, entry, &mut stack, &mut top) {
                current = next;
                continue;
            }
        }
        match next_waiting(&stack, &mut top, &t_max) {
            Some(next) => current = next,
            None => return,
        }
    }
}

/// The nearest waiting entry (the stack's top first) with a ray that can still reach
/// it, its rays cut to those; `None` when the stack runs out. Entries below `top` must
/// have been written.
#[inline(always)]
pub(super) fn next_waiting(
    stack: &[MaybeUninit<Pending>],
    top: &mut usize,
    t_max: &[f32; PACKET],
) -> Option<Pending> {
    while *top > 0 {
        *top -= 1;
        // SAFETY: entries below `top` were written (the caller's promise).
        let waiting = unsafe { stack[*top].assume_init() };
        // Every ray's test at once (no branch per ray), then the entry's rays.
        let reach = rays_reaching(waiting.t, t_max) & waiting.rays;
        if reach != 0 {
            return Some(Pending {
                rays: reach,
                ..waiting
            });
        }
    }
    None
}

/// The rays (bit per ray) whose reach `t_max` is at least `t`.
#[inline(always)]
pub(super) fn rays_reaching(t: f32, t_max: &[f32; PACKET]) -> u32 {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_cmple_ps, _mm_loadu_ps, _mm_movemask_ps, _mm_set1_ps};
        const _: () = assert!(PACKET == 8, "two SSE halves");
        // SAFETY: SSE2 is part of x86-64; the loads read the 8 floats of `t_max`. The
        // compare is the scalar `<=` (false on NaN).
        unsafe {
            let t = _mm_set1_ps(t);
            let low = _mm_movemask_ps(_mm_cmple_ps(t, _mm_loadu_ps(t_max.as_ptr()))) as u32;
            let high = _mm_movemask_ps(_mm_cmple_ps(t, _mm_loadu_ps(t_max.as_ptr().add(4))));
            low | (high as u32) << 4
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let mut reach = 0;
        for (r, &t_max) in t_max.iter().enumerate() {
            reach |= u32::from(t <= t_max) << r;
        }
        reach
    }
}

/// One node step of the packet, lane by lane: each ray in `rays` runs the single-ray
/// slab test with its own reach.
#[inline(always)]
fn step(
    node: &WideNode,
    slabs: &[Slab; PACKET],
    rays: u32,
    t_min: f32,
    t_max: &[f32; PACKET],
) -> Step {
    let mut out = Step {
        entered: 0,
        rays: [0; WIDTH],
        t: [f32::INFINITY; WIDTH],
    };
    let mut bits = rays;
    while bits != 0 {
        let r = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        let (mask, near) = slabs[r].test(node, t_min, t_max[r]);
        for (lane, (set, t)) in out.rays.iter_mut().zip(&mut out.t).enumerate() {
            if mask & (1 << lane) != 0 {
                *set |= 1 << r;
                *t = t.min(near[lane]);
            }
        }
        out.entered |= mask;
    }
    out
}

/// [`step`] in AVX2 instructions: the rays' sets and nearest distances are gathered in
/// lanes, without a branch per child.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn step_avx2(
    node: &WideNode,
    slabs: &[Slab; PACKET],
    rays: u32,
    t_min: f32,
    t_max: &[f32; PACKET],
) -> Step {
    use std::arch::x86_64::{
        _mm256_and_si256, _mm256_blendv_ps, _mm256_castps_si256, _mm256_castsi256_ps,
        _mm256_cmpeq_epi32, _mm256_min_ps, _mm256_movemask_ps, _mm256_or_si256, _mm256_set1_epi32,
        _mm256_set1_ps, _mm256_setzero_si256, _mm256_storeu_ps, _mm256_storeu_si256,
    };
    // SAFETY: the caller guarantees AVX2; the stores write 8 lanes into 8-lane arrays.
    unsafe {
        let mut sets = _mm256_setzero_si256();
        let far = _mm256_set1_ps(f32::INFINITY);
        let mut nearest = far;
        let mut bits = rays;
        while bits != 0 {
            let r = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let (near, inside) = slabs[r].near_inside_avx2(node, t_min, t_max[r]);
            let bit = _mm256_set1_epi32(1 << r);
            sets = _mm256_or_si256(sets, _mm256_and_si256(_mm256_castps_si256(inside), bit));
            nearest = _mm256_min_ps(nearest, _mm256_blendv_ps(far, near, inside));
        }
        let none = _mm256_cmpeq_epi32(sets, _mm256_setzero_si256());
        let entered = !(_mm256_movemask_ps(_mm256_castsi256_ps(none)) as u32) & 0xFF;
        let mut out = Step {
            entered: entered & node.used,
            rays: [0; WIDTH],
            t: [0.0; WIDTH],
        };
        _mm256_storeu_si256(out.rays.as_mut_ptr().cast(), sets);
        _mm256_storeu_ps(out.t.as_mut_ptr(), nearest);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{both_paths, mixed_scene, rays, traversal_work as get};
    use super::*;
    use crate::accel::Intersector;
    use crate::counter::{Count, NoCount};
    use crate::nff::parse_nff;
    use crate::ray::Ray;
    use crate::vec3::Vec3;

    #[test]
    fn packets_find_each_rays_own_closest_hit_bit_for_bit() {
        let scene = mixed_scene();
        let rays = rays();
        for wide in both_paths(&scene) {
            // Packets of every size, and a slice longer than one packet.
            for size in [1, 2, 3, 5, 8, 11] {
                for group in rays.chunks(size) {
                    let mut hits = vec![None; group.len()];
                    let mut counters = vec![NoCount; group.len()];
                    wide.closest_hits(group, &mut hits, &mut counters);
                    for (ray, hit) in group.iter().zip(&hits) {
                        let alone = wide.closest_hit(ray, 0.0, &mut NoCount);
                        assert_eq!(
                            hit.map(|h| (h.prim, h.t, h.aux)),
                            alone.map(|h| (h.prim, h.t, h.aux)),
                            "packet of {size}: {ray:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn shadow_packets_find_the_same_blockers_as_rays_alone() {
        let scene = mixed_scene();
        let rays = rays();
        for wide in both_paths(&scene) {
            for size in [1, 3, 8, 13] {
                for (g, group) in rays.chunks(size).enumerate() {
                    // Reaches from short to unbounded, so some rays stop before a blocker.
                    let reach: Vec<f32> = (0..group.len())
                        .map(|i| [2.0, 6.0, 15.0, f32::INFINITY][(g + i) % 4])
                        .collect();
                    let mut blocked = vec![false; group.len()];
                    let mut counters = vec![NoCount; group.len()];
                    wide.occluded_packet(group, &reach, &mut blocked, &mut counters);
                    for ((ray, &reach), &blocked) in group.iter().zip(&reach).zip(&blocked) {
                        let alone = wide.occluded(ray, 0.0, reach, &mut NoCount);
                        assert_eq!(blocked, alone, "packet of {size}: {ray:?} to {reach}");
                    }
                }
            }
            // A packet of one shadow ray does exactly the work of the ray alone.
            for ray in rays.iter().take(50) {
                let mut alone = Count::default();
                wide.occluded(ray, 0.0, 10.0, &mut alone);
                let mut counters = [Count::default()];
                wide.occluded_packet(&[*ray], &[10.0], &mut [false], &mut counters);
                assert_eq!(counters[0], alone, "{ray:?}");
            }
        }
    }

    /// The twelve SPD scenes at small size: packets of eye rays along rows (as the
    /// renderer makes them) and of their shadow rays find what each ray finds alone.
    #[test]
    fn packets_on_the_spd_scenes_find_each_rays_own_hits_and_blockers() {
        use crate::camera::{Camera, Sampling};
        use crate::counter::Counter as _;
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/spd");
        // Eye rays that hit, shadow rays blocked and not: every outcome is compared.
        let (mut hit_rays, mut blocked_rays, mut lit_rays) = (0, 0, 0);
        for name in [
            "balls", "gears", "jacks", "lattice", "mount", "rings", "sample", "shells", "sombrero",
            "teapot", "tetra", "tree",
        ] {
            let path = dir.join(format!("{name}.nff"));
            let scene = crate::nff::load_nff(&path).unwrap_or_else(|e| panic!("{e}"));
            let (w, h) = (40, 24);
            let camera =
                Camera::perspective(&scene.view, w, h, Sampling::PixelCenters, &mut NoCount)
                    .unwrap_or_else(|e| panic!("{e}"));
            for wide in both_paths(&scene) {
                for row in 0..h {
                    // Rows in packets of 8 neighbouring eye rays, as the renderer traces them.
                    let eye: Vec<Ray> = (0..w)
                        .map(|col| camera.ray(col, row, &mut NoCount))
                        .collect();
                    for group in eye.chunks(PACKET) {
                        let mut hits = vec![None; group.len()];
                        let mut counters = vec![NoCount; group.len()];
                        wide.closest_hits(group, &mut hits, &mut counters);
                        // Shadow rays from the hits toward the first light, as a packet.
                        let mut shadow = Vec::new();
                        let mut reach = Vec::new();
                        for (ray, hit) in group.iter().zip(&hits) {
                            let alone = wide.closest_hit(ray, 0.0, &mut NoCount);
                            assert_eq!(
                                hit.map(|h| (h.prim, h.t, h.aux)),
                                alone.map(|h| (h.prim, h.t, h.aux)),
                                "{name}: {ray:?}"
                            );
                            if let (Some(hit), Some(light)) = (hit, scene.lights.first()) {
                                let c = &mut NoCount;
                                let along = c.scale(ray.dir, hit.t);
                                let point = c.add(ray.origin, along);
                                let to_light = c.sub(light.position, point);
                                let dir = c.normalize(to_light);
                                let offset = c.scale(dir, 1e-3);
                                let origin = c.add(point, offset);
                                shadow.push(Ray { origin, dir });
                                reach.push(c.dot(to_light, dir));
                            }
                        }
                        let mut blocked = vec![false; shadow.len()];
                        let mut counters = vec![NoCount; shadow.len()];
                        wide.occluded_packet(&shadow, &reach, &mut blocked, &mut counters);
                        for ((ray, &reach), &blocked) in shadow.iter().zip(&reach).zip(&blocked) {
                            let alone = wide.occluded(ray, 0.0, reach, &mut NoCount);
                            assert_eq!(blocked, alone, "{name}: {ray:?} to {reach}");
                            blocked_rays += usize::from(blocked);
                            lit_rays += usize::from(!blocked);
                        }
                        hit_rays += shadow.len();
                    }
                }
            }
        }
        assert!(hit_rays > 10_000 && blocked_rays > 1000 && lit_rays > 1000);
    }

    #[test]
    fn a_packet_of_one_ray_does_the_work_of_the_ray_alone() {
        let scene = mixed_scene();
        for wide in both_paths(&scene) {
            for ray in rays() {
                let mut alone = Count::default();
                wide.closest_hit(&ray, 0.0, &mut alone);
                let mut counters = [Count::default()];
                wide.closest_hits(&[ray], &mut [None], &mut counters);
                assert_eq!(counters[0], alone, "{ray:?}");
            }
        }
    }

    #[test]
    fn each_ray_of_a_packet_counts_its_own_work_hand_computed() {
        // Two unit spheres 10 apart: one wide node with two one-sphere leaves.
        let scene = parse_nff(
            "v\nfrom 0 -20 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 4 4\n\
             f 1 1 1 1 0 1 0 1\ns -5 0 0 1\ns 5 0 0 1\n",
            "two.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let along_x = |x: f32, dir: f32| Ray {
            origin: Vec3::new(x, 0.0, 0.0),
            dir: Vec3::new(dir, 0.0, 0.0),
        };
        let along_y = |x: f32| Ray {
            origin: Vec3::new(x, -20.0, 0.0),
            dir: Vec3::new(0.0, 1.0, 0.0),
        };
        for wide in both_paths(&scene) {
            // Each ray's hit (primitive, distance) and counts, traced as one packet.
            let trace = |packet: &[Ray; 2]| {
                let mut hits = [None; 2];
                let mut counters = [Count::default(), Count::default()];
                wide.closest_hits(packet, &mut hits, &mut counters);
                (
                    hits.map(|h| h.map(|h| (h.prim.index, h.t))),
                    counters.map(|c| get(&c)),
                )
            };
            // Rays parallel to y, one through each sphere: each enters one box of the
            // two it tests (2 of 8 lanes) and tests one sphere, at t = 19.
            let (hits, counts) = trace(&[along_y(-5.0), along_y(5.0)]);
            assert_eq!(hits, [Some((0, 19.0)), Some((1, 19.0))]);
            assert_eq!(counts, [[2, 8, 2, 1, 1, 1]; 2]);
            // Rays along x from either side: each enters both boxes, the near one at
            // t = 14 and the far one at 24. Alone, a ray drops its far box (24 > 14);
            // in the packet, the other ray's near box is entered at 14, so both rays
            // test both leaves (2 leaves, 2 sphere tests each), and still hit their
            // own near sphere at t = 14.
            let packet = [along_x(-20.0, 1.0), along_x(20.0, -1.0)];
            let (hits, counts) = trace(&packet);
            assert_eq!(hits, [Some((0, 14.0)), Some((1, 14.0))]);
            assert_eq!(counts, [[2, 8, 2, 2, 2, 1]; 2]);
            let mut alone = Count::default();
            wide.closest_hit(&packet[0], 0.0, &mut alone);
            assert_eq!(get(&alone), [2, 8, 2, 1, 1, 1]);
        }
    }
}

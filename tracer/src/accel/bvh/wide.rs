//! The wide BVH (variants `bvh` + `simd`): the thesis's parallel intersection units
//! (8.3.3) inside the hierarchy. The binned-SAH binary tree is collapsed into nodes of
//! up to [`WIDTH`] children whose boxes sit in structure-of-arrays lanes, so one step
//! tests all the children's boxes at once; the children hit are visited nearest first,
//! and a shadow ray stops at its first blocker (visiting them in lane order, unsorted).
//!
//! The binary tree is built over the scene's primitives with polygons and patches
//! replaced by the triangles of their outlines ([`triangles`]), its leaves chosen with a
//! pack of lanes costing about as much as one test alone ([`Lane`](super::Lane)). Leaves are the binary
//! tree's leaves. Their spheres are packed into lanes too (a leaf's spheres are tested
//! together, the thesis's units on one leaf), and so are their triangles; cylinders,
//! cones and the outlines kept whole are tested one by one with the same tests as
//! brute force. Spheres and quadrics give the baseline's picture bit for bit;
//! triangles the polygon's distance, with their edges differing by rounding only.
//!
//! The box and sphere lanes are compiled twice: for the build's target (SSE2 on any
//! x86-64) and with AVX2 + FMA, chosen at run time when the CPU has them. Neither path
//! fuses multiplies and adds that the scalar tests keep apart, so both give the same
//! distances bit for bit.
//!
//! Counting: every child box tested adds one `accel.nodes_visited` (the root has no box
//! of its own: its children's cover it), every leaf entered one `accel.leaves_visited`; each node step issues
//! [`WIDTH`] lanes (`accel.lanes_issued`), as many active as the node has children, and
//! each sphere or triangle pack as many as it holds. The primitive tests count
//! themselves with the operations of the scalar test.

use super::node::{EMPTY, LEAF, Slab, WIDTH, WideNode};
use super::triangles::{self, Piece, Triangle, TrianglePack, triangle_pack};
use super::{Bvh, BvhBuilder, Node};
use crate::accel::{Intersector, cpu_has_avx2_fma, intersect_primitive};
use crate::counter::{Counter, Phase, Stat};
use crate::huge_pages;
use crate::primitives::{first_stage_suffices, sphere_first_disc, sphere_may_hit};
use crate::ray::{Hit, HitBound, PrimKind, PrimRef, Ray};
use crate::scene::Scene;
use std::mem::MaybeUninit;

/// A leaf: its spheres packed in lanes (at most one pack: binary leaves hold at most 8
/// primitives) and its other primitives as references.
#[derive(Clone, Copy, Debug)]
pub(super) struct Leaf {
    /// Index into `packs`, or [`EMPTY`] when the leaf has no sphere.
    pack: u32,
    /// Spheres in the pack.
    pub(super) spheres: u32,
    /// The leaf's triangles: `triangle_packs` packs from `first_triangle_pack`.
    pub(super) first_triangle_pack: u32,
    pub(super) triangle_packs: u32,
    /// The leaf's other primitives: `others` entries from `first`.
    first: u32,
    pub(super) others: u32,
}

/// A leaf's spheres in structure-of-arrays form (unused lanes: radius² -inf, never hit).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
struct SpherePack {
    cx: [f32; WIDTH],
    cy: [f32; WIDTH],
    cz: [f32; WIDTH],
    radius_sq: [f32; WIDTH],
    /// 1.0 where only the inside is visible.
    inside: [f32; WIDTH],
    /// The spheres' indices in the scene.
    index: [u32; WIDTH],
}

/// Figures about a built wide tree.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WideBvhStats {
    /// The binary tree's builder.
    pub builder: BvhBuilder,
    pub nodes: usize,
    pub leaves: usize,
    /// Children per node over all nodes (at most [`WIDTH`]).
    pub mean_children: f64,
    pub max_depth: usize,
    /// Bytes of the nodes, leaves, sphere packs and primitive references.
    pub bytes: usize,
}

/// A wide BVH over a scene.
#[derive(Clone, Debug)]
pub struct WideBvh<'s> {
    scene: &'s Scene,
    pub(super) nodes: Vec<WideNode>,
    pub(super) leaves: Vec<Leaf>,
    packs: Vec<SpherePack>,
    pub(super) triangle_packs: Vec<TrianglePack>,
    others: Vec<PrimRef>,
    stats: WideBvhStats,
    pub(super) avx2: bool,
}

/// Entries a traversal stack can hold: each node step pops one entry and pushes at most
/// [`WIDTH`], and a wide tree is no deeper than its binary tree.
pub(super) const STACK: usize = (WIDTH - 1) * (super::MAX_DEPTH + 20) + 1;

/// A node or leaf waiting to be visited (a child reference: [`LEAF`] set for leaves),
/// with the distance at which the ray enters it.
#[derive(Clone, Copy, Debug)]
struct Entry {
    child: u32,
    t: f32,
}

impl<'s> WideBvh<'s> {
    /// Builds the binary tree with `builder` over the scene's items (polygons and
    /// patches as their triangles, `triangles::items`) and collapses it.
    pub fn build_with(scene: &'s Scene, builder: BvhBuilder) -> Self {
        let (items, pieces) = triangles::items(scene);
        Self::collapse(&Bvh::build_over(scene, builder, items), &pieces)
    }

    /// Collapses a binary tree built over `triangles::items` (whose polygon
    /// references index `pieces`): each wide node takes the two children of a binary
    /// node and keeps opening its largest interior child (by surface area) until it has
    /// [`WIDTH`] children or only leaves.
    fn collapse(binary: &Bvh<'s>, pieces: &[Piece]) -> Self {
        let mut wide = Self {
            scene: binary.scene,
            nodes: huge_pages::vec_with_capacity(binary.nodes.len().max(1)),
            leaves: Vec::with_capacity(binary.stats.leaves),
            packs: Vec::new(),
            triangle_packs: Vec::new(),
            others: Vec::with_capacity(binary.prims.len()),
            stats: WideBvhStats {
                builder: binary.stats.builder,
                ..WideBvhStats::default()
            },
            avx2: cpu_has_avx2_fma(),
        };
        if !binary.prims.is_empty() {
            let root = binary.nodes[0].0[0];
            wide.nodes.push(WideNode::UNUSED);
            if root.count > 0 {
                // A one-leaf tree: a root node with that leaf as its only child.
                let leaf = wide.push_leaf(binary, pieces, &root);
                wide.nodes[0].set(0, root.bounds(), leaf, true);
            } else {
                wide.fill(binary, pieces, 0, &root, 1);
            }
        }
        wide.nodes.shrink_to_fit();
        let children: usize = wide.nodes.iter().map(WideNode::children).sum();
        wide.stats.nodes = wide.nodes.len();
        wide.stats.leaves = wide.leaves.len();
        wide.stats.mean_children = children as f64 / wide.nodes.len().max(1) as f64;
        wide.stats.bytes = wide.nodes.capacity() * size_of::<WideNode>()
            + wide.leaves.capacity() * size_of::<Leaf>()
            + wide.packs.capacity() * size_of::<SpherePack>()
            + wide.triangle_packs.capacity() * size_of::<TrianglePack>()
            + wide.others.capacity() * size_of::<PrimRef>();
        wide
    }

    /// Fills wide node `at` with the collapsed children of binary interior node `node`.
    fn fill(&mut self, binary: &Bvh, pieces: &[Piece], at: usize, node: &Node, depth: usize) {
        self.stats.max_depth = self.stats.max_depth.max(depth);
        let mut open: Vec<Node> = binary.nodes[node.offset as usize].0.to_vec();
        while open.len() < WIDTH {
            let largest = open
                .iter()
                .enumerate()
                .filter(|(_, n)| n.count == 0)
                .max_by(|a, b| {
                    let area = |n: &Node| n.bounds().surface_area();
                    area(a.1).total_cmp(&area(b.1))
                })
                .map(|(i, _)| i);
            let Some(i) = largest else { break };
            let opened = open.remove(i);
            let [a, b] = binary.nodes[opened.offset as usize].0;
            // Keep the children where the parent was: the lane order stays spatial.
            open.insert(i, b);
            open.insert(i, a);
        }
        for (lane, child) in open.iter().enumerate() {
            if child.count > 0 {
                let leaf = self.push_leaf(binary, pieces, child);
                self.nodes[at].set(lane, child.bounds(), leaf, true);
            } else {
                let index = self.nodes.len();
                self.nodes.push(WideNode::UNUSED);
                self.nodes[at].set(lane, child.bounds(), index as u32, false);
                self.fill(binary, pieces, index, child, depth + 1);
            }
        }
    }

    /// Stores a binary leaf: its spheres in a pack, its triangles in packs, the rest as
    /// references (polygon references of the binary tree are pieces).
    fn push_leaf(&mut self, binary: &Bvh, pieces: &[Piece], node: &Node) -> u32 {
        let first = node.offset as usize;
        let items = &binary.prims[first..first + node.count as usize];
        let mut leaf_triangles: Vec<Triangle> = Vec::new();
        let mut prims: Vec<PrimRef> = Vec::with_capacity(items.len());
        for item in items {
            match (item.kind, pieces.get(item.index as usize)) {
                (PrimKind::Polygon, Some(Piece::Triangle(t))) => leaf_triangles.push(*t),
                (PrimKind::Polygon, Some(Piece::Whole(prim))) => prims.push(*prim),
                _ => prims.push(*item),
            }
        }
        let first_triangle_pack = self.triangle_packs.len() as u32;
        for group in leaf_triangles.chunks(WIDTH) {
            self.triangle_packs.push(TrianglePack::new(group));
        }
        let spheres: Vec<u32> = prims
            .iter()
            .filter(|p| p.kind == PrimKind::Sphere)
            .map(|p| p.index)
            .collect();
        let mut leaf = Leaf {
            pack: EMPTY,
            spheres: 0,
            first_triangle_pack,
            triangle_packs: self.triangle_packs.len() as u32 - first_triangle_pack,
            first: self.others.len() as u32,
            others: 0,
        };
        // Binary leaves hold at most 8 primitives unless they could not be split (many
        // coincident centroids); spheres beyond one pack are tested one by one.
        let packed = if spheres.len() > 1 {
            spheres.len().min(WIDTH)
        } else {
            0
        };
        if packed > 0 {
            let mut pack = SpherePack {
                cx: [0.0; WIDTH],
                cy: [0.0; WIDTH],
                cz: [0.0; WIDTH],
                radius_sq: [f32::NEG_INFINITY; WIDTH],
                inside: [0.0; WIDTH],
                index: [EMPTY; WIDTH],
            };
            for (lane, &index) in spheres[..packed].iter().enumerate() {
                let s = &self.scene.spheres[index as usize];
                let [x, y, z] = s.center.to_array();
                (pack.cx[lane], pack.cy[lane], pack.cz[lane]) = (x, y, z);
                pack.radius_sq[lane] = s.radius_sq();
                pack.inside[lane] = f32::from(u8::from(s.inside_visible()));
                pack.index[lane] = index;
            }
            leaf.pack = self.packs.len() as u32;
            leaf.spheres = packed as u32;
            self.packs.push(pack);
        }
        let in_pack =
            |p: &PrimRef| p.kind == PrimKind::Sphere && spheres[..packed].contains(&p.index);
        for p in prims.iter().filter(|p| !in_pack(p)) {
            self.others.push(*p);
            leaf.others += 1;
        }
        self.leaves.push(leaf);
        (self.leaves.len() - 1) as u32
    }

    /// Figures about the tree.
    pub fn stats(&self) -> WideBvhStats {
        self.stats
    }

    /// Whether the AVX2 + FMA code path runs on this CPU.
    pub fn uses_avx2(&self) -> bool {
        self.avx2
    }

    #[inline(always)]
    fn closest<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        c: &mut C,
    ) -> Option<Hit> {
        c.tally(Stat::Intersect);
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is true only when the CPU reported AVX2 and FMA.
            return unsafe {
                search_avx2::<C, FROM_EYE, false>(self, ray, t_min, f32::INFINITY, c)
            };
        }
        search::<C, FROM_EYE, false, false>(self, ray, t_min, f32::INFINITY, c)
    }
}

/// [`search`] compiled with AVX2 + FMA (the caller checks the CPU has them).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn search_avx2<C: Counter, const FROM_EYE: bool, const ANY: bool>(
    bvh: &WideBvh,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    t_max: f32,
    c: &mut C,
) -> Option<Hit> {
    search::<C, FROM_EYE, ANY, true>(bvh, ray, t_min, t_max, c)
}

/// Nearest-first traversal (phase `traversal`, the leaves' tests inside it): the
/// closest hit in `(t_min, t_max)`, or with `ANY` the first found (a shadow ray). The
/// interval shrinks as hits are found, so waiting entries beyond it are dropped when
/// they come up. `AVX2`: the box test uses AVX instructions (only inside
/// [`search_avx2`]).
#[inline(always)]
fn search<C: Counter, const FROM_EYE: bool, const ANY: bool, const AVX2: bool>(
    bvh: &WideBvh,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    t_max: f32,
    c: &mut C,
) -> Option<Hit> {
    let _phase = C::enter_phase(Phase::Traversal);
    if bvh.nodes.is_empty() {
        return None;
    }
    descend::<C, FROM_EYE, ANY, AVX2>(bvh, ray, &Slab::new(ray), 0, t_min, t_max, None, c)
}

/// [`search`] below one child (`start`, a child reference), for a ray whose closest
/// hit so far is `best` (then the query's interval ends at it) within the query's
/// `reach`: the closest hit, `best` if nothing beats it, or with `ANY` the first
/// found. The packet traversal hands a subtree that only one of its rays enters to
/// this loop: the same steps in the same order as in the packet.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn descend<C: Counter, const FROM_EYE: bool, const ANY: bool, const AVX2: bool>(
    bvh: &WideBvh,
    ray: &Ray<FROM_EYE>,
    slab: &Slab,
    start: u32,
    t_min: f32,
    reach: f32,
    mut best: Option<Hit>,
    c: &mut C,
) -> Option<Hit> {
    let mut t_max = best.map_or(reach, |b| b.t);
    // Uninitialised: a node step may push up to 7 entries, so the bound is large (kB),
    // and clearing it would cost more than a short query. Only entries below `top` are
    // read, and each was written first.
    let mut stack = [const { MaybeUninit::<Entry>::uninit() }; STACK];
    let mut top = 0usize;
    let mut current = Entry {
        child: start,
        t: 0.0,
    };
    loop {
        if current.child & LEAF != 0 {
            c.tally(Stat::LeavesVisited);
            let leaf = &bvh.leaves[(current.child & !LEAF) as usize];
            let bound = best.map_or(HitBound::reach(t_max), |b| HitBound::of(&b));
            if let Some(hit) =
                search_leaf::<C, FROM_EYE, ANY>(bvh, leaf, ray, t_min, reach, bound, c)
            {
                if ANY {
                    return Some(hit);
                }
                t_max = hit.t;
                best = Some(hit);
            }
        } else {
            let node = &bvh.nodes[current.child as usize];
            #[cfg(target_arch = "x86_64")]
            let (mask, t_near) = if AVX2 {
                // SAFETY: `AVX2` is set only inside `search_avx2`, which runs only on
                // CPUs with AVX2 and FMA.
                unsafe { slab.test_avx2(node, t_min, t_max) }
            } else {
                slab.test(node, t_min, t_max)
            };
            #[cfg(not(target_arch = "x86_64"))]
            let (mask, t_near) = slab.test(node, t_min, t_max);
            if C::ENABLED {
                let live = u64::from(node.used.count_ones());
                c.tally_n(Stat::NodesVisited, live);
                c.tally_n(Stat::LanesIssued, WIDTH as u64);
                c.tally_n(Stat::LanesActive, live);
            }
            let entry = |lane: u32| Entry {
                child: node.child[lane as usize],
                t: t_near[lane as usize],
            };
            if let Some(next) = visit_order::<_, ANY>(mask, entry, &mut stack, &mut top) {
                current = next;
                continue;
            }
        }
        // The nearest waiting entry still in reach.
        loop {
            if top == 0 {
                return best;
            }
            top -= 1;
            // SAFETY: entries below `top` were written (see above).
            let waiting = unsafe { stack[top].assume_init() };
            if waiting.t <= t_max {
                current = waiting;
                break;
            }
        }
    }
}

/// A child waiting on a traversal stack, with the distance at which it is entered.
pub(super) trait Waiting: Copy {
    fn entered_at(&self) -> f32;
}

impl Waiting for Entry {
    #[inline(always)]
    fn entered_at(&self) -> f32 {
        self.t
    }
}

/// The order in which a node step's entered children (bit per lane in `mask`, made
/// by `entry`) are visited, nearest first: with one, straight into it (returned); with
/// two, the far one waits on the stack and the near one is returned; with more, all
/// wait, sorted with the farthest at the bottom, and `None` says to take the nearest
/// from the stack (as with none).
///
/// With `ANY` (a shadow ray, which stops at any blocker) the order matters less than
/// its cost: the first child is entered and the others wait in lane order, unsorted,
/// as Embree's any-hit traversal does.
#[inline(always)]
pub(super) fn visit_order<E: Waiting, const ANY: bool>(
    mask: u32,
    entry: impl Fn(u32) -> E,
    stack: &mut [MaybeUninit<E>],
    top: &mut usize,
) -> Option<E> {
    if mask == 0 {
        return None;
    }
    let a = entry(mask.trailing_zeros());
    let rest = mask & (mask - 1);
    if rest == 0 {
        // One child entered (the common case).
        return Some(a);
    }
    if ANY {
        let mut bits = rest;
        while bits != 0 {
            stack[*top].write(entry(bits.trailing_zeros()));
            *top += 1;
            bits &= bits - 1;
        }
        return Some(a);
    }
    let b = entry(rest.trailing_zeros());
    if rest & (rest - 1) == 0 {
        let (near, far) = if b.entered_at() < a.entered_at() {
            (b, a)
        } else {
            (a, b)
        };
        stack[*top].write(far);
        *top += 1;
        return Some(near);
    }
    let first = *top;
    let mut bits = mask;
    while bits != 0 {
        let new = entry(bits.trailing_zeros());
        bits &= bits - 1;
        let mut at = *top;
        // SAFETY: `first <= at - 1 < top`: a written entry.
        while at > first && unsafe { stack[at - 1].assume_init() }.entered_at() < new.entered_at() {
            stack[at] = stack[at - 1];
            at -= 1;
        }
        stack[at].write(new);
        *top += 1;
    }
    None
}

/// The closest hit in a leaf that beats `bound` (with `ANY`: the first): its sphere
/// pack, its triangle packs, then its other primitives one by one.
#[inline(always)]
pub(super) fn search_leaf<C: Counter, const FROM_EYE: bool, const ANY: bool>(
    bvh: &WideBvh,
    leaf: &Leaf,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    reach: f32,
    bound: HitBound,
    c: &mut C,
) -> Option<Hit> {
    search_leaf_parts::<C, FROM_EYE, ANY, true>(bvh, leaf, ray, t_min, reach, bound, c)
}

/// [`search_leaf`], its triangle packs only with `TRIANGLES` (the coherent packets
/// test those a triangle at a time against all their rays).
#[inline(always)]
pub(super) fn search_leaf_parts<
    C: Counter,
    const FROM_EYE: bool,
    const ANY: bool,
    const TRIANGLES: bool,
>(
    bvh: &WideBvh,
    leaf: &Leaf,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    reach: f32,
    mut bound: HitBound,
    c: &mut C,
) -> Option<Hit> {
    let mut best = None;
    if leaf.spheres > 0 {
        let pack = &bvh.packs[leaf.pack as usize];
        let lanes = sphere_pack(pack, leaf.spheres, ray, t_min, reach, c);
        let prim = |lane: usize| PrimRef {
            kind: PrimKind::Sphere,
            index: pack.index[lane],
        };
        if let Some((t, lane)) = lanes.and_then(|t| closest_lane(&t, prim, bound, ANY)) {
            let hit = Hit {
                t,
                prim: prim(lane),
                aux: 0.0,
            };
            if ANY {
                return Some(hit);
            }
            bound = HitBound::of(&hit);
            best = Some(hit);
        }
    }
    let packs = leaf.first_triangle_pack as usize;
    let triangle_packs = if TRIANGLES { leaf.triangle_packs } else { 0 };
    for pack in &bvh.triangle_packs[packs..packs + triangle_packs as usize] {
        let lanes = triangle_pack(pack, ray, t_min, reach, bvh.avx2, c);
        let prim = |lane: usize| pack.owner[lane];
        if let Some((t, lane)) = lanes.and_then(|t| closest_lane(&t, prim, bound, ANY)) {
            let hit = Hit {
                t,
                prim: prim(lane),
                aux: 0.0,
            };
            if ANY {
                return Some(hit);
            }
            bound = HitBound::of(&hit);
            best = Some(hit);
        }
    }
    let first = leaf.first as usize;
    for &prim in &bvh.others[first..first + leaf.others as usize] {
        if let Some((t, aux)) = intersect_primitive(bvh.scene, prim, ray, t_min, reach, c)
            && bound.admits(t, prim)
        {
            let hit = Hit { t, prim, aux };
            if ANY {
                return Some(hit);
            }
            bound = HitBound::of(&hit);
            best = Some(hit);
        }
    }
    best
}

/// The lanes of `t` below `bound` or, with `ties`, equal to it (bit per lane).
#[inline(always)]
fn lanes_within(t: &[f32; WIDTH], bound: f32, ties: bool) -> u32 {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{
            _mm_and_ps, _mm_castsi128_ps, _mm_cmpeq_ps, _mm_cmplt_ps, _mm_loadu_ps,
            _mm_movemask_ps, _mm_or_ps, _mm_set1_epi32, _mm_set1_ps,
        };
        const _: () = assert!(WIDTH == 8, "two SSE halves");
        // SAFETY: SSE2 is part of x86-64; the loads read the 8 floats of `t`. The
        // compares are the scalar ones (`<` and `==`, false on NaN).
        unsafe {
            let b = _mm_set1_ps(bound);
            let tie = _mm_castsi128_ps(_mm_set1_epi32(-i32::from(ties)));
            let half = |v| _mm_or_ps(_mm_cmplt_ps(v, b), _mm_and_ps(tie, _mm_cmpeq_ps(v, b)));
            let low = _mm_movemask_ps(half(_mm_loadu_ps(t.as_ptr()))) as u32;
            let high = _mm_movemask_ps(half(_mm_loadu_ps(t.as_ptr().add(4)))) as u32;
            low | high << 4
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let mut near = 0u32;
        for (lane, &tl) in t.iter().enumerate() {
            near |= u32::from((tl < bound) | (ties & (tl == bound))) << lane;
        }
        near
    }
}

/// The lane of a pack's distances (infinite where a lane misses) that beats `bound`,
/// as `(t, lane)`: the nearest, on equal distances the first primitive in scene order
/// (see [`HitBound`]); with `any`, the first lane that beats it.
#[inline(always)]
pub(super) fn closest_lane(
    t: &[f32; WIDTH],
    prim: impl Fn(usize) -> PrimRef,
    mut bound: HitBound,
    any: bool,
) -> Option<(f32, usize)> {
    // The lanes at or within the bound first, without a branch per lane (most packs
    // have none or one): only those are looked at in turn.
    // A bound at an infinite reach has no primitive, so a missing lane never ties.
    let mut near = lanes_within(t, bound.t, bound.prim.is_some());
    let mut best = None;
    while near != 0 {
        let lane = near.trailing_zeros() as usize;
        near &= near - 1;
        let tl = t[lane];
        if bound.admits(tl, prim(lane)) {
            if any {
                return Some((tl, lane));
            }
            bound = HitBound {
                t: tl,
                prim: Some(prim(lane)),
            };
            best = Some((tl, lane));
        }
    }
    best
}

/// Each lane's hit distance in a pack of spheres (infinite where it misses), testing
/// `live` lanes against the query's reach `(t_min, reach)`; `None` when no lane passes
/// the first stage. The arithmetic is the scalar sphere test's (both stages and the
/// choice between them) in the same order, so the distances are the same bit for bit.
#[inline(always)]
fn sphere_pack<C: Counter, const FROM_EYE: bool>(
    pack: &SpherePack,
    live: u32,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    reach: f32,
    c: &mut C,
) -> Option<[f32; WIDTH]> {
    let _phase = C::enter_phase(Phase::SphereTest);
    let [ox, oy, oz] = ray.origin.to_array();
    let [dx, dy, dz] = ray.dir.to_array();
    // The first stage (the thesis's discriminant, trusted for certain misses).
    let mut half_b = [0.0f32; WIDTH];
    let mut passed = [false; WIDTH];
    // The first stage's discriminant, and whether it is kept (see the scalar test).
    let mut disc = [0.0f32; WIDTH];
    let mut second = [false; WIDTH];
    let (mut any_passed, mut any_second) = (false, false);
    for i in 0..WIDTH {
        let (vx, vy, vz) = (ox - pack.cx[i], oy - pack.cy[i], oz - pack.cz[i]);
        half_b[i] = dx * vx + dy * vy + dz * vz;
        let oo = vx * vx + vy * vy + vz * vz;
        disc[i] = sphere_first_disc(half_b[i], oo, pack.radius_sq[i]);
        passed[i] = sphere_may_hit(disc[i], oo);
        second[i] = passed[i] && !first_stage_suffices(disc[i], 1.0, oo);
        any_passed |= passed[i];
        any_second |= second[i];
    }
    let n = u64::from(live);
    let live = live as usize;
    if C::ENABLED {
        c.tally_n(Stat::LanesIssued, WIDTH as u64);
        c.tally_n(Stat::LanesActive, n);
        c.tally_n(Stat::SphereTest, n);
        if !FROM_EYE {
            // Eye rays of the `bounded` variant use the precomputed offsets instead.
            c.tally_n(Stat::Sub, n);
        }
        c.tally_n(Stat::Dot, 2 * n);
    }
    if !any_passed {
        return None;
    }
    // The second stage where the first was not kept: the centre's offset across the
    // ray (skipped when no lane needs it).
    if any_second {
        for i in 0..WIDTH {
            let (vx, vy, vz) = (ox - pack.cx[i], oy - pack.cy[i], oz - pack.cz[i]);
            let (ax, ay, az) = (
                vx - dx * half_b[i],
                vy - dy * half_b[i],
                vz - dz * half_b[i],
            );
            let exact = pack.radius_sq[i] - (ax * ax + ay * ay + az * az);
            disc[i] = if second[i] { exact } else { disc[i] };
        }
    }
    // The roots and the query's reach.
    let mut t = [f32::INFINITY; WIDTH];
    let mut disc_positive = [false; WIDTH];
    for i in 0..WIDTH {
        let disc = disc[i];
        disc_positive[i] = passed[i] && disc > 0.0;
        let root = C::sqrt_kernel(disc.max(0.0));
        let near = -half_b[i] - root;
        let far = -half_b[i] + root;
        let near_ok = pack.inside[i] == 0.0 && near > t_min && near < reach;
        let far_ok = far > t_min && far < reach;
        let chosen = if near_ok { near } else { far };
        t[i] = if disc_positive[i] && (near_ok || far_ok) {
            chosen
        } else {
            f32::INFINITY
        };
    }
    if C::ENABLED {
        let second = second[..live].iter().filter(|&&p| p).count() as u64;
        c.tally_n(Stat::Scale, second);
        c.tally_n(Stat::Sub, second);
        c.tally_n(Stat::Dot, second);
        c.tally_n(
            Stat::Sqrt,
            disc_positive[..live].iter().filter(|&&p| p).count() as u64,
        );
        let hits = t[..live].iter().filter(|x| x.is_finite()).count();
        c.tally_n(Stat::SphereHit, hits as u64);
    }
    Some(t)
}

impl Intersector for WideBvh<'_> {
    const PACKETS: bool = true;

    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit> {
        self.closest(ray, t_min, c)
    }

    fn closest_hit_from_eye<C: Counter>(&self, ray: &Ray<true>, c: &mut C) -> Option<Hit> {
        self.closest(ray, 0.0, c)
    }

    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool {
        c.tally(Stat::Intersect);
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is true only when the CPU reported AVX2 and FMA.
            return unsafe { search_avx2::<C, false, true>(self, ray, t_min, t_max, c) }.is_some();
        }
        search::<C, false, true, false>(self, ray, t_min, t_max, c).is_some()
    }

    fn closest_hits<C: Counter>(&self, rays: &[Ray], hits: &mut [Option<Hit>], counters: &mut [C]) {
        self.packet_closest(rays, 0.0, hits, counters);
    }

    fn occluded_packet<C: Counter>(
        &self,
        rays: &[Ray],
        t_max: &[f32],
        blocked: &mut [bool],
        counters: &mut [C],
    ) {
        self.packet_occluded(rays, 0.0, t_max, blocked, counters);
    }

    fn closest_hits_from_eye<C: Counter>(
        &self,
        rays: &[Ray<true>],
        hits: &mut [Option<Hit>],
        counters: &mut [C],
    ) {
        self.packet_closest(rays, 0.0, hits, counters);
    }
}

#[cfg(test)]
mod tests;

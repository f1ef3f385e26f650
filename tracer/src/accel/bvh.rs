//! Bounding volume hierarchy (variant `bvh`): axis-aligned boxes over every primitive
//! kind, built once with the surface area heuristic (binned, as pbrt does; or, for
//! comparing how the quality metrics predict the cost, at the spatial middle:
//! [`BvhBuilder`]), traversed front to back for closest hits and stopped at the first
//! blocker for shadow rays. Its quality metrics (SAH cost, end-point overlap, shape) are
//! in [`quality`].
//!
//! Counting: every node whose box is tested adds one `accel.nodes_visited`, every
//! leaf whose primitives are tested one `accel.leaves_visited`; the primitive tests
//! count themselves as in brute force. Box tests are not vector operations of the
//! thesis's table (they use no dot product), so they add nothing to `ops.*`. With a
//! BVH the bottleneck moves from the primitive tests to this traversal: compare
//! `tests.*` and `accel.*` between `baseline` and `bvh`.

mod frustum;
mod node;
mod packet;
mod quality;
mod ray_lanes;
mod triangles;
mod wide;

pub use node::WIDTH;
pub use packet::PACKET;
pub use quality::BvhShape;
pub use wide::{WideBvh, WideBvhStats};

use super::{Intersector, intersect_primitive};
use crate::counter::{Counter, Phase, Stat};
use crate::huge_pages;
use crate::ray::{Hit, HitBound, PrimKind, PrimRef, Ray};
use crate::scene::Scene;
use crate::vec3::Vec3;
use glam::Vec3A;

/// Bins per axis in the SAH sweep.
const BINS: usize = 16;
/// Leaves never hold more than this many primitives (unless they cannot be split).
const MAX_LEAF: usize = 8;
/// Cost of one traversal step relative to one primitive test, for the SAH.
const TRAVERSAL_COST: f32 = 0.5;
/// Cost of one pack of [`WIDTH`] lanes against one test alone, for the leaf decision
/// (measured on SPD gears and teapot: 1.0 and 1.5 were slower on gears).
const PACK_COST: f32 = 2.0;
/// Traversal stack depth; the build stops splitting before the tree gets deeper.
const MAX_DEPTH: usize = 48;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Aabb {
    min: Vec3A,
    max: Vec3A,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    fn grow(self, p: Vec3A) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    fn surface_area(self) -> f32 {
        let d = (self.max - self.min).max(Vec3A::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    fn centroid(self) -> Vec3A {
        (self.min + self.max) * 0.5
    }

    /// The box grown by a relative margin so that rounding in the primitive tests can
    /// never report a hit outside it.
    fn padded(self) -> Aabb {
        let pad = (self.max - self.min)
            .max_element()
            .max(self.max.abs().max_element())
            * 1e-5
            + f32::MIN_POSITIVE;
        Aabb {
            min: self.min - Vec3A::splat(pad),
            max: self.max + Vec3A::splat(pad),
        }
    }
}

/// Half-extents of a disk of radius `r` around unit axis `a`: `r sqrt(1 - a_i²)`.
fn disk_extent(axis: Vec3, r: f32) -> Vec3A {
    let a = axis.0;
    let one_minus = (Vec3A::ONE - a * a).max(Vec3A::ZERO);
    #[allow(clippy::disallowed_methods)] // build time, not the counted render
    let root = Vec3A::new(one_minus.x.sqrt(), one_minus.y.sqrt(), one_minus.z.sqrt());
    root * r.abs()
}

fn disk_box(center: Vec3, axis: Vec3, r: f32) -> Aabb {
    let e = disk_extent(axis, r);
    Aabb {
        min: center.0 - e,
        max: center.0 + e,
    }
}

/// The bounds of one primitive.
fn bounds_of(scene: &Scene, prim: PrimRef) -> Aabb {
    let i = prim.index as usize;
    let outline = |vertices: &[Vec3]| vertices.iter().fold(Aabb::EMPTY, |b, v| b.grow(v.0));
    let b = match prim.kind {
        PrimKind::Sphere => {
            let s = &scene.spheres[i];
            let r = Vec3A::splat(s.radius.abs());
            Aabb {
                min: s.center.0 - r,
                max: s.center.0 + r,
            }
        }
        PrimKind::Cylinder => {
            let cy = &scene.cylinders[i];
            disk_box(cy.base, cy.axis, cy.radius).union(disk_box(cy.apex, cy.axis, cy.radius))
        }
        PrimKind::Cone => {
            let co = &scene.cones[i];
            disk_box(co.base, co.axis, co.base_radius).union(disk_box(
                co.apex,
                co.axis,
                co.apex_radius,
            ))
        }
        PrimKind::Polygon => outline(&scene.polygons[i].outline.vertices),
        PrimKind::Patch => outline(&scene.patches[i].outline.vertices),
    };
    b.padded()
}

/// One node of the flattened tree: its box and either its children (interior nodes:
/// the pair at `offset`) or its primitives (leaves: `count` of them from `offset`).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
struct Node {
    min: [f32; 3],
    offset: u32,
    max: [f32; 3],
    /// Primitives in the leaf; 0 for interior nodes.
    count: u16,
    /// Split axis of an interior node (the children's front-to-back order).
    axis: u16,
}

impl Node {
    const UNUSED: Node = Node {
        min: [f32::INFINITY; 3],
        offset: 0,
        max: [f32::NEG_INFINITY; 3],
        count: 0,
        axis: 0,
    };

    fn new(bounds: Aabb, offset: u32, count: u16, axis: u16) -> Self {
        Node {
            min: bounds.min.to_array(),
            offset,
            max: bounds.max.to_array(),
            count,
            axis,
        }
    }

    fn bounds(&self) -> Aabb {
        Aabb {
            min: Vec3A::from_array(self.min),
            max: Vec3A::from_array(self.max),
        }
    }
}

/// The two children of an interior node, side by side in one 64-byte cache line: the
/// traversal tests both boxes from one memory access. On scenes of a million
/// primitives the tree outgrows the caches and the lines fetched per level set the
/// time per ray; with the children apart (depth-first order) a level costs up to two.
/// Pair 0 holds the root (and an unused slot).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct NodePair([Node; 2]);

/// How the tree chooses its splits.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum BvhBuilder {
    /// The surface area heuristic over 16 bins of each centroid axis (the cheapest
    /// split of the three); a leaf when splitting would cost more than testing (at
    /// most 8 primitives). The `bvh` variant's tree.
    #[default]
    BinnedSah,
    /// The middle of the widest centroid axis (pbrt's `SplitMethod::Middle`): blind to
    /// the primitives' sizes; a leaf per primitive (unless centroids coincide).
    Midpoint,
}

impl BvhBuilder {
    pub const ALL: [BvhBuilder; 2] = [BvhBuilder::BinnedSah, BvhBuilder::Midpoint];

    /// The name in results and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            BvhBuilder::BinnedSah => "binned_sah",
            BvhBuilder::Midpoint => "midpoint",
        }
    }

    /// The builder called `name`, if any.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|b| b.name() == name)
    }
}

impl std::str::FromStr for BvhBuilder {
    type Err = String;

    /// A builder by name (`--bvh-builder`); the error lists the names.
    fn from_str(name: &str) -> Result<Self, String> {
        Self::parse(name).ok_or_else(|| {
            let names: Vec<&str> = Self::ALL.iter().map(|b| b.name()).collect();
            format!(
                "unknown builder '{name}'; choose one of {}",
                names.join(", ")
            )
        })
    }
}

impl std::fmt::Display for BvhBuilder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// Figures about a built tree (reported as preprocessing).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BvhStats {
    /// The strategy that built it.
    #[serde(default)]
    pub builder: BvhBuilder,
    pub nodes: usize,
    pub leaves: usize,
    pub max_depth: usize,
    pub max_leaf_size: usize,
    /// Bytes of the nodes and the primitive references (what the tree adds to the
    /// scene).
    #[serde(default)]
    pub bytes: usize,
    /// The tree's surface area heuristic cost: the expected cost of a ray that enters
    /// the root box, for random lines (a box is entered with probability its area over
    /// the root's), each interior node costing `TRAVERSAL_COST` and each primitive
    /// test 1: `Σ_interior 0.5 A(n)/A(root) + Σ_leaves N(l) A(l)/A(root)`.
    #[serde(default)]
    pub sah_cost: f64,
    /// What the same model predicts per ray that enters the root box, searching the
    /// whole line (no early exit): boxes tested (the root and both children of every
    /// interior node entered), leaves entered and primitive tests.
    #[serde(default)]
    pub predicted_nodes_per_ray: f64,
    #[serde(default)]
    pub predicted_leaves_per_ray: f64,
    #[serde(default)]
    pub predicted_tests_per_ray: f64,
}

/// A SAH bounding volume hierarchy over a scene.
#[derive(Clone, Debug)]
pub struct Bvh<'s> {
    scene: &'s Scene,
    nodes: Vec<NodePair>,
    prims: Vec<PrimRef>,
    stats: BvhStats,
    /// Leaves per depth and per primitive count, filled by the build.
    shape: BvhShape,
}

struct BuildItem {
    bounds: Aabb,
    centroid: Vec3A,
    prim: PrimRef,
    lane: Lane,
}

/// How a leaf tests an item: alone, or in a pack of [`WIDTH`] lanes with its kind (the
/// wide BVH's spheres and triangles), which costs about the same for one item or eight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Lane {
    Alone,
    Sphere,
    Triangle,
}

impl<'s> Bvh<'s> {
    /// Builds the tree over every primitive of `scene` with the binned SAH.
    pub fn build(scene: &'s Scene) -> Self {
        Self::build_with(scene, BvhBuilder::BinnedSah)
    }

    /// Builds the tree over every primitive of `scene` with `builder`.
    pub fn build_with(scene: &'s Scene, builder: BvhBuilder) -> Self {
        let kinds = [
            (PrimKind::Sphere, scene.spheres.len()),
            (PrimKind::Cylinder, scene.cylinders.len()),
            (PrimKind::Cone, scene.cones.len()),
            (PrimKind::Polygon, scene.polygons.len()),
            (PrimKind::Patch, scene.patches.len()),
        ];
        let mut items = Vec::with_capacity(scene.primitive_count());
        for (kind, n) in kinds {
            for index in 0..n {
                let prim = PrimRef {
                    kind,
                    index: index as u32,
                };
                items.push((prim, bounds_of(scene, prim), Lane::Alone));
            }
        }
        Self::build_over(scene, builder, items)
    }

    /// Builds the tree over `items`, each a reference and its box. The wide BVH builds
    /// its binary tree over its own items (triangles in place of polygons), whose
    /// references then index its tables rather than `scene`: such a tree is only
    /// collapsed, never queried.
    fn build_over(
        scene: &'s Scene,
        builder: BvhBuilder,
        items: Vec<(PrimRef, Aabb, Lane)>,
    ) -> Self {
        let mut items: Vec<BuildItem> = items
            .into_iter()
            .map(|(prim, bounds, lane)| BuildItem {
                bounds,
                centroid: bounds.centroid(),
                prim,
                lane,
            })
            .collect();
        let mut bvh = Self {
            scene,
            // Pairs: one per interior node (at most n - 1) and the root's.
            nodes: huge_pages::vec_with_capacity(items.len().max(1)),
            prims: huge_pages::vec_with_capacity(items.len()),
            stats: BvhStats {
                builder,
                ..BvhStats::default()
            },
            shape: BvhShape::default(),
        };
        bvh.nodes.push(NodePair([Node::UNUSED; 2]));
        if !items.is_empty() {
            bvh.nodes[0].0[0] = bvh.build_node(&mut items, 1);
            // The root, and two children for each pair after the root's.
            bvh.stats.nodes = 2 * bvh.nodes.len() - 1;
        }
        // Interior nodes are fewer than n - 1 when leaves hold several primitives.
        bvh.nodes.shrink_to_fit();
        bvh.surface_area_metrics();
        bvh.stats.bytes = bvh.nodes.capacity() * std::mem::size_of::<NodePair>()
            + bvh.prims.capacity() * std::mem::size_of::<PrimRef>();
        bvh
    }

    /// Fills the SAH cost and the predictions of [`BvhStats`] from the built tree.
    fn surface_area_metrics(&mut self) {
        if self.prims.is_empty() {
            return;
        }
        let root = f64::from(self.nodes[0].0[0].bounds().surface_area());
        if !(root > 0.0) {
            return;
        }
        let (mut interior, mut leaves, mut tests) = (0.0, 0.0, 0.0);
        let every_node = std::iter::once(&self.nodes[0].0[0])
            .chain(self.nodes[1..].iter().flat_map(|pair| pair.0.iter()));
        for node in every_node {
            let p = f64::from(node.bounds().surface_area()) / root;
            if node.count == 0 {
                interior += p;
            } else {
                leaves += p;
                tests += p * f64::from(node.count);
            }
        }
        let stats = &mut self.stats;
        stats.sah_cost = f64::from(TRAVERSAL_COST) * interior + tests;
        stats.predicted_nodes_per_ray = 1.0 + 2.0 * interior;
        stats.predicted_leaves_per_ray = leaves;
        stats.predicted_tests_per_ray = tests;
    }

    /// Figures about the tree.
    pub fn stats(&self) -> BvhStats {
        self.stats
    }

    /// The tree's shape: leaves per depth and per size.
    pub fn shape(&self) -> &BvhShape {
        &self.shape
    }

    fn push_leaf(&mut self, bounds: Aabb, items: &[BuildItem], depth: usize) -> Node {
        let leaf = Node::new(bounds, self.prims.len() as u32, items.len() as u16, 0);
        self.prims.extend(items.iter().map(|it| it.prim));
        self.stats.leaves += 1;
        self.stats.max_leaf_size = self.stats.max_leaf_size.max(items.len());
        self.shape.add_leaf(depth, items.len());
        leaf
    }

    /// Builds the subtree over `items` and returns its root node (not yet stored).
    fn build_node(&mut self, items: &mut [BuildItem], depth: usize) -> Node {
        self.stats.max_depth = self.stats.max_depth.max(depth);
        let bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
        let centroids = items.iter().fold(Aabb::EMPTY, |b, it| b.grow(it.centroid));
        let n = items.len();
        let extent = centroids.max - centroids.min;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let fits_leaf = n <= u16::MAX as usize;
        if n == 1 || (fits_leaf && (!(extent[axis] > 0.0) || depth >= MAX_DEPTH)) {
            return self.push_leaf(bounds, items, depth);
        }
        if !(extent[axis] > 0.0) {
            // Too many primitives with one centroid for a leaf: split by count.
            return self.push_interior(bounds, axis, items, n / 2, depth);
        }
        if self.stats.builder == BvhBuilder::Midpoint {
            // The extremes' centroids fall on either side: both halves hold some.
            let middle = centroids.min[axis] + 0.5 * extent[axis];
            let mut mid = partition(items, |it| it.centroid[axis] < middle);
            if mid == 0 || mid == n {
                // The middle rounded onto an extreme: halve by count instead.
                items.sort_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
                mid = n / 2;
            }
            return self.push_interior(bounds, axis, items, mid, depth);
        }

        // Binned SAH along every axis the centroids spread over (the widest first:
        // it wins ties).
        let mut best = (f32::INFINITY, axis, 0usize);
        for a in [axis, (axis + 1) % 3, (axis + 2) % 3] {
            if extent[a] > 0.0 {
                let (cost, split) = sah_split(items, centroids, a);
                if cost < best.0 {
                    best = (cost, a, split);
                }
            }
        }
        let (best_cost, axis, best_split) = best;
        if best_split == 0 {
            items.sort_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
            return self.push_interior(bounds, axis, items, n / 2, depth);
        }
        let area = bounds.surface_area().max(f32::MIN_POSITIVE);
        if n <= MAX_LEAF {
            let left = |it: &BuildItem| bin_of(centroids, axis, it.centroid) < best_split;
            let split_cost = if items.iter().all(|it| it.lane == Lane::Alone) {
                best_cost
            } else {
                let side = |on_left: bool| {
                    let side: Vec<&BuildItem> =
                        items.iter().filter(|it| left(it) == on_left).collect();
                    let bounds = side.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
                    bounds.surface_area() * leaf_cost(side.into_iter())
                };
                side(true) + side(false)
            };
            if TRAVERSAL_COST + split_cost / area >= leaf_cost(items.iter()) {
                return self.push_leaf(bounds, items, depth);
            }
        }
        let mid = partition(items, |it| {
            bin_of(centroids, axis, it.centroid) < best_split
        });
        self.push_interior(bounds, axis, items, mid, depth)
    }

    /// An interior node over `items` split at `mid`: its children's pair is stored
    /// before their subtrees, so that a pair precedes the pairs below it.
    fn push_interior(
        &mut self,
        bounds: Aabb,
        axis: usize,
        items: &mut [BuildItem],
        mid: usize,
        depth: usize,
    ) -> Node {
        let at = self.nodes.len();
        self.nodes.push(NodePair([Node::UNUSED; 2]));
        let (left, right) = items.split_at_mut(mid);
        let left = self.build_node(left, depth + 1);
        let right = self.build_node(right, depth + 1);
        self.nodes[at] = NodePair([left, right]);
        Node::new(bounds, at as u32, 0, axis as u16)
    }

    /// Front-to-back traversal (phase `traversal`, the leaves' tests inside it);
    /// `visit` tests a leaf's primitives and returns whether the search is over (a
    /// shadow ray found a blocker). `t_max` shrinks as hits are found, so farther boxes,
    /// including those already waiting on the stack, are skipped.
    ///
    /// An interior node's two children are tested together (one cache line); the
    /// near one (along the split axis) is entered, the far one waits with its entry
    /// distance.
    #[inline(always)]
    fn traverse<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        t_max: &mut f32,
        c: &mut C,
        mut visit: impl FnMut(&[PrimRef], &mut f32, &mut C) -> bool,
    ) {
        let _phase = C::enter_phase(Phase::Traversal);
        if self.prims.is_empty() {
            return;
        }
        let origin = ray.origin.0;
        let inv_dir = Vec3A::ONE / ray.dir.0;
        let negative = [inv_dir.x < 0.0, inv_dir.y < 0.0, inv_dir.z < 0.0];
        let root = &self.nodes[0].0[0];
        c.tally(Stat::NodesVisited);
        if slab_entry(root, origin, inv_dir, t_min, *t_max).is_none() {
            return;
        }
        // Past MAX_DEPTH only count splits of > 65535 coincident centroids remain (< 17 levels).
        let mut stack = [(root, 0.0f32); MAX_DEPTH + 20];
        let mut top = 0usize;
        let mut node = root;
        loop {
            if node.count > 0 {
                c.tally(Stat::LeavesVisited);
                let first = node.offset as usize;
                let leaf = &self.prims[first..first + node.count as usize];
                if visit(leaf, t_max, c) {
                    return;
                }
            } else {
                let [a, b] = &self.nodes[node.offset as usize].0;
                self.prefetch(a);
                self.prefetch(b);
                c.tally(Stat::NodesVisited);
                c.tally(Stat::NodesVisited);
                match (
                    slab_entry(a, origin, inv_dir, t_min, *t_max),
                    slab_entry(b, origin, inv_dir, t_min, *t_max),
                ) {
                    (Some(ta), Some(tb)) => {
                        // Front to back along the split axis.
                        let (near, far, t_far) = if negative[node.axis as usize] {
                            (b, a, ta)
                        } else {
                            (a, b, tb)
                        };
                        stack[top] = (far, t_far);
                        top += 1;
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // The nearest waiting node that is still in reach.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (waiting, t_entry) = stack[top];
                if t_entry <= *t_max {
                    node = waiting;
                    break;
                }
            }
        }
    }

    /// Asks the memory system for what `node` will need when it is taken from the
    /// stack (its children's pair or its primitive references), so that the fetch
    /// overlaps the near subtree's work.
    #[inline(always)]
    fn prefetch(&self, node: &Node) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            let line: *const i8 = if node.count == 0 {
                std::ptr::from_ref(&self.nodes[node.offset as usize]).cast()
            } else {
                std::ptr::from_ref(&self.prims[node.offset as usize]).cast()
            };
            // SAFETY: a prefetch is a hint that never faults, and `line` points into
            // this tree's own arrays.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(line) };
        }
    }

    #[inline(always)]
    fn closest<C: Counter, const FROM_EYE: bool>(
        &self,
        ray: &Ray<FROM_EYE>,
        t_min: f32,
        c: &mut C,
    ) -> Option<Hit> {
        c.tally(Stat::Intersect);
        let mut best: Option<Hit> = None;
        let mut t_max = f32::INFINITY;
        let scene = self.scene;
        self.traverse(ray, t_min, &mut t_max, c, |leaf, t_max, c| {
            for &prim in leaf {
                // Tested against the query's reach (the hit counts whatever was found
                // before), kept when it beats the closest so far (ties: scene order).
                if let Some((t, aux)) =
                    intersect_primitive(scene, prim, ray, t_min, f32::INFINITY, c)
                    && best
                        .map_or(HitBound::reach(*t_max), |b| HitBound::of(&b))
                        .admits(t, prim)
                {
                    *t_max = t;
                    best = Some(Hit { t, prim, aux });
                }
            }
            false
        });
        best
    }
}

/// What testing `items` as one leaf costs, in primitive tests: one per item tested
/// alone, [`PACK_COST`] per pack of lanes.
fn leaf_cost<'a>(items: impl Iterator<Item = &'a BuildItem>) -> f32 {
    let (mut alone, mut spheres, mut triangles) = (0usize, 0usize, 0usize);
    for it in items {
        match it.lane {
            Lane::Alone => alone += 1,
            Lane::Sphere => spheres += 1,
            Lane::Triangle => triangles += 1,
        }
    }
    let packs = spheres.div_ceil(WIDTH) + triangles.div_ceil(WIDTH);
    alone as f32 + PACK_COST * packs as f32
}

/// The bin of a centroid along `axis` of the centroids' box (whose extent there is
/// positive).
#[inline]
fn bin_of(centroids: Aabb, axis: usize, c: Vec3A) -> usize {
    let (lo, span) = (
        centroids.min[axis],
        centroids.max[axis] - centroids.min[axis],
    );
    (((c[axis] - lo) / span * BINS as f32) as usize).min(BINS - 1)
}

/// The cheapest binned SAH split of `items` along `axis`: its cost (area times count
/// summed over both sides) and the first bin of its right side (0: no split puts
/// items on both sides).
fn sah_split(items: &[BuildItem], centroids: Aabb, axis: usize) -> (f32, usize) {
    let mut bin_bounds = [Aabb::EMPTY; BINS];
    let mut bin_counts = [0usize; BINS];
    for it in items {
        let b = bin_of(centroids, axis, it.centroid);
        bin_bounds[b] = bin_bounds[b].union(it.bounds);
        bin_counts[b] += 1;
    }
    let mut right_area = [0.0f32; BINS];
    let mut right_count = [0usize; BINS];
    let (mut acc, mut count) = (Aabb::EMPTY, 0);
    for b in (1..BINS).rev() {
        acc = acc.union(bin_bounds[b]);
        count += bin_counts[b];
        right_area[b] = acc.surface_area();
        right_count[b] = count;
    }
    let (mut best_cost, mut best_split) = (f32::INFINITY, 0);
    let (mut acc, mut count) = (Aabb::EMPTY, 0);
    for split in 1..BINS {
        acc = acc.union(bin_bounds[split - 1]);
        count += bin_counts[split - 1];
        if count == 0 || right_count[split] == 0 {
            continue;
        }
        let cost =
            acc.surface_area() * count as f32 + right_area[split] * right_count[split] as f32;
        if cost < best_cost {
            best_cost = cost;
            best_split = split;
        }
    }
    (best_cost, best_split)
}

/// Moves the items for which `left` holds to the front; returns how many there are.
fn partition(items: &mut [BuildItem], left: impl Fn(&BuildItem) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..items.len() {
        if left(&items[i]) {
            items.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

/// The slab test: where the ray enters the box inside `(t_min, t_max)`, or `None` if
/// it misses it there. A direction component of zero gives infinite slab distances,
/// which `min`/`max` order correctly; a NaN (origin exactly on a slab of a flat box) is
/// dropped by `min`/`max`.
#[inline(always)]
fn slab_entry(node: &Node, origin: Vec3A, inv_dir: Vec3A, t_min: f32, t_max: f32) -> Option<f32> {
    let b = node.bounds();
    let t0 = (b.min - origin) * inv_dir;
    let t1 = (b.max - origin) * inv_dir;
    let near = t0.min(t1).max_element().max(t_min);
    let far = t0.max(t1).min_element().min(t_max);
    (near <= far).then_some(near)
}

impl Intersector for Bvh<'_> {
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit> {
        self.closest(ray, t_min, c)
    }

    fn closest_hit_from_eye<C: Counter>(&self, ray: &Ray<true>, c: &mut C) -> Option<Hit> {
        self.closest(ray, 0.0, c)
    }

    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool {
        c.tally(Stat::Intersect);
        let scene = self.scene;
        let mut blocked = false;
        let mut limit = t_max;
        self.traverse(ray, t_min, &mut limit, c, |leaf, t_max, c| {
            blocked = leaf
                .iter()
                .any(|&p| intersect_primitive(scene, p, ray, t_min, *t_max, c).is_some());
            blocked
        });
        blocked
    }
}

/// Checks, for tests, that every primitive's box contains sample points of its
/// surface hits: brute force and BVH agree on closest hits of many rays.
#[cfg(test)]
mod tests;

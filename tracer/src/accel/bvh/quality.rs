//! How good a built tree is, beyond its SAH cost ([`BvhStats`](super::BvhStats)):
//! its shape (leaves per depth and per size, [`BvhShape`]) and its end-point overlap
//! ([`Bvh::end_point_overlap`]).
//!
//! End-point overlap (EPO; Aila, Karras and Laine, "On Quality Metrics of Bounding
//! Volume Hierarchies", HPG 2013) measures what the SAH misses: a ray that starts or
//! ends on a surface must visit every node whose box holds that point, also the nodes
//! whose subtree does not contain the surface. For each node `n`, the area of the
//! scene's surfaces inside `n`'s box but outside `n`'s subtree, weighted by the node's
//! cost (interior 0.5, leaf 1 per primitive, the SAH's weights), over the whole
//! surface area:
//!
//! `EPO = Σ_n C(n) Σ_{t ∉ subtree(n)} A(t ∩ box(n)) / Σ_t A(t)`.
//!
//! Polygons and patches are clipped against the boxes exactly; curved surfaces are
//! first cut into planar facets (spheres 8 × 16, cylinder and cone sides 16 quads,
//! about 97 % of the true area), consistently in both sums. The cost grows with the
//! overlaps, so it is computed on request, not at build.

use super::{Aabb, Bvh, Node, TRAVERSAL_COST, bounds_of};
use crate::ray::{PrimKind, PrimRef};
use crate::scene::Scene;
use crate::vec3::Vec3;
use glam::Vec3A;

/// Latitude bands and longitude segments of a sphere's facets.
const SPHERE_BANDS: usize = 8;
const SPHERE_SEGMENTS: usize = 16;
/// Quads around a cylinder's or a cone's side.
const SIDE_SEGMENTS: usize = 16;

/// Leaves by depth (index 0: a root that is a leaf) and by primitive count.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BvhShape {
    pub depth_histogram: Vec<u64>,
    pub leaf_size_histogram: Vec<u64>,
}

impl BvhShape {
    /// Records a leaf of `size` primitives at `depth` (the root's depth is 1).
    pub(super) fn add_leaf(&mut self, depth: usize, size: usize) {
        bump(&mut self.depth_histogram, depth.saturating_sub(1));
        bump(&mut self.leaf_size_histogram, size);
    }
}

fn bump(histogram: &mut Vec<u64>, at: usize) {
    if histogram.len() <= at {
        histogram.resize(at + 1, 0);
    }
    histogram[at] += 1;
}

impl Bvh<'_> {
    /// The tree's end-point overlap (module doc); 0 for an empty scene or one without
    /// surface area.
    pub fn end_point_overlap(&self) -> f64 {
        if self.prims.is_empty() {
            return 0.0;
        }
        let ranges = self.subtree_ranges();
        let root = self.nodes[0].0[0];
        let mut facets = Vec::new();
        let mut clipped = (Vec::new(), Vec::new());
        let (mut overlap, mut total) = (0.0f64, 0.0f64);
        let mut stack: Vec<(Node, (u32, u32))> = Vec::new();
        for (position, &prim) in self.prims.iter().enumerate() {
            let position = position as u32;
            facets.clear();
            facets_of(self.scene, prim, &mut facets);
            let area: f64 = facets.iter().map(|f| polygon_area(f)).sum();
            total += area;
            let bounds = bounds_of(self.scene, prim);
            stack.clear();
            stack.push((root, ranges.root));
            while let Some((node, (lo, hi))) = stack.pop() {
                let b = node.bounds();
                if !overlaps(b, bounds) {
                    continue;
                }
                if !(lo..hi).contains(&position) {
                    let inside = if contains(b, bounds) {
                        area
                    } else {
                        facets.iter().map(|f| area_inside(f, b, &mut clipped)).sum()
                    };
                    overlap += node_cost(&node) * inside;
                }
                if node.count == 0 {
                    let pair = node.offset as usize;
                    for (slot, child) in self.nodes[pair].0.iter().enumerate() {
                        stack.push((*child, ranges.pairs[pair][slot]));
                    }
                }
            }
        }
        if total > 0.0 { overlap / total } else { 0.0 }
    }

    /// The primitive positions (in `prims`) under every node: the build stores a
    /// subtree's primitives contiguously, left subtree first.
    fn subtree_ranges(&self) -> SubtreeRanges {
        let mut pairs = vec![[(0u32, 0u32); 2]; self.nodes.len()];
        let range = |node: &Node, pairs: &[[(u32, u32); 2]]| {
            if node.count > 0 {
                (node.offset, node.offset + u32::from(node.count))
            } else {
                let children = pairs[node.offset as usize];
                (children[0].0, children[1].1)
            }
        };
        // A pair precedes the pairs below it, so from the back every child's range is
        // known before its parent's.
        for i in (1..self.nodes.len()).rev() {
            for slot in 0..2 {
                pairs[i][slot] = range(&self.nodes[i].0[slot], &pairs);
            }
        }
        SubtreeRanges {
            root: range(&self.nodes[0].0[0], &pairs),
            pairs,
        }
    }
}

struct SubtreeRanges {
    root: (u32, u32),
    /// Per node pair, its two children's ranges (pair 0 unused).
    pairs: Vec<[(u32, u32); 2]>,
}

/// The cost weight of a node in the EPO sum (the SAH's).
fn node_cost(node: &Node) -> f64 {
    if node.count == 0 {
        f64::from(TRAVERSAL_COST)
    } else {
        f64::from(node.count)
    }
}

fn overlaps(a: Aabb, b: Aabb) -> bool {
    a.min.cmple(b.max).all() && b.min.cmple(a.max).all()
}

fn contains(outer: Aabb, inner: Aabb) -> bool {
    outer.min.cmple(inner.min).all() && inner.max.cmple(outer.max).all()
}

/// Area of the planar polygon `facet` inside `b` (clipped by its six planes).
fn area_inside(facet: &[Vec3A], b: Aabb, work: &mut (Vec<Vec3A>, Vec<Vec3A>)) -> f64 {
    let bounds = facet.iter().fold(Aabb::EMPTY, |acc, v| acc.grow(*v));
    if contains(b, bounds) {
        return polygon_area(facet);
    }
    if !overlaps(b, bounds) {
        return 0.0;
    }
    let (current, next) = work;
    current.clear();
    current.extend_from_slice(facet);
    for axis in 0..3 {
        for (limit, keep_below) in [(b.min[axis], false), (b.max[axis], true)] {
            clip_by_plane(current, next, axis, limit, keep_below);
            std::mem::swap(current, next);
            if current.len() < 3 {
                return 0.0;
            }
        }
    }
    polygon_area(current)
}

/// Sutherland–Hodgman: the part of `input` with `v[axis] <= limit` (`keep_below`) or
/// `>= limit`, into `output`. A concave polygon stays correct in area (the cut may leave
/// zero-width bridges, which add nothing).
fn clip_by_plane(
    input: &[Vec3A],
    output: &mut Vec<Vec3A>,
    axis: usize,
    limit: f32,
    keep_below: bool,
) {
    output.clear();
    let inside = |v: Vec3A| {
        if keep_below {
            v[axis] <= limit
        } else {
            v[axis] >= limit
        }
    };
    for (i, &a) in input.iter().enumerate() {
        let b = input[(i + 1) % input.len()];
        let (a_in, b_in) = (inside(a), inside(b));
        if a_in {
            output.push(a);
        }
        if a_in != b_in {
            let t = (limit - a[axis]) / (b[axis] - a[axis]);
            let mut crossing = a + (b - a) * t;
            crossing[axis] = limit;
            output.push(crossing);
        }
    }
}

/// Area of a planar polygon: half the length of the sum of its edges' cross products.
fn polygon_area(vertices: &[Vec3A]) -> f64 {
    let mut sum = glam::DVec3::ZERO;
    for (i, a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        sum += a.as_dvec3().cross(b.as_dvec3());
    }
    0.5 * sum.length()
}

/// The planar facets of one primitive's surface.
fn facets_of(scene: &Scene, prim: PrimRef, out: &mut Vec<Vec<Vec3A>>) {
    let i = prim.index as usize;
    let outline = |vertices: &[Vec3]| vertices.iter().map(|v| v.0).collect::<Vec<_>>();
    match prim.kind {
        PrimKind::Sphere => {
            let s = &scene.spheres[i];
            sphere_facets(s.center.0, s.radius.abs(), out);
        }
        PrimKind::Cylinder => {
            let c = &scene.cylinders[i];
            side_facets(c.base.0, c.apex.0, c.axis.0, c.radius, c.radius, out);
        }
        PrimKind::Cone => {
            let c = &scene.cones[i];
            side_facets(
                c.base.0,
                c.apex.0,
                c.axis.0,
                c.base_radius,
                c.apex_radius,
                out,
            );
        }
        PrimKind::Polygon => out.push(outline(&scene.polygons[i].outline.vertices)),
        PrimKind::Patch => out.push(outline(&scene.patches[i].outline.vertices)),
    }
}

fn sphere_facets(center: Vec3A, r: f32, out: &mut Vec<Vec<Vec3A>>) {
    use std::f32::consts::{PI, TAU};
    let point = |band: usize, segment: usize| {
        let theta = PI * band as f32 / SPHERE_BANDS as f32;
        let phi = TAU * segment as f32 / SPHERE_SEGMENTS as f32;
        center
            + r * Vec3A::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            )
    };
    for band in 0..SPHERE_BANDS {
        for segment in 0..SPHERE_SEGMENTS {
            out.push(vec![
                point(band, segment),
                point(band + 1, segment),
                point(band + 1, segment + 1),
                point(band, segment + 1),
            ]);
        }
    }
}

/// The side of a (possibly truncated) cone from `base` (radius `r0`) to `apex`
/// (radius `r1`) around unit `axis`.
fn side_facets(base: Vec3A, apex: Vec3A, axis: Vec3A, r0: f32, r1: f32, out: &mut Vec<Vec<Vec3A>>) {
    use std::f32::consts::TAU;
    let u = axis.any_orthonormal_vector();
    #[allow(clippy::disallowed_methods)] // a metric of the tree, not the counted render
    let v = axis.cross(u);
    let rim = |centre: Vec3A, r: f32, k: usize| {
        let phi = TAU * k as f32 / SIDE_SEGMENTS as f32;
        centre + r.abs() * (phi.cos() * u + phi.sin() * v)
    };
    for k in 0..SIDE_SEGMENTS {
        out.push(vec![
            rim(base, r0, k),
            rim(base, r0, k + 1),
            rim(apex, r1, k + 1),
            rim(apex, r1, k),
        ]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::bvh::BvhBuilder;
    use crate::nff::parse_nff;

    const VIEW: &str = "v\nfrom 0 0 -10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\n\
                        resolution 4 4\nf 1 1 1 1 0 1 0 1\n";

    #[test]
    fn epo_and_sah_of_two_overlapping_squares_are_the_hand_computed_ones() {
        // Two 2 × 2 squares on z = 0, A over x in [0, 2] and B over [1, 3]. Both
        // builders make a root over both and one leaf per square (the centroids 1 and
        // 2 straddle both the SAH's best bin and the middle 1.5).
        // EPO: half of B (area 2) lies in A's leaf box, half of A in B's; the root
        // holds both in its subtree. Leaves cost 1 per primitive:
        // (1 · 2 + 1 · 2) / (4 + 4) = 0.5.
        // SAH: flat boxes, area 2 · (w · h): leaves 8 each, root 2 · (3 · 2) = 12:
        // 0.5 + (8 + 8) / 12.
        let text =
            format!("{VIEW}p 4\n0 0 0\n2 0 0\n2 2 0\n0 2 0\np 4\n1 0 0\n3 0 0\n3 2 0\n1 2 0\n");
        let scene = parse_nff(&text, "squares.nff").unwrap_or_else(|e| panic!("{e}"));
        for builder in BvhBuilder::ALL {
            let bvh = Bvh::build_with(&scene, builder);
            let stats = bvh.stats();
            assert_eq!((stats.nodes, stats.leaves), (3, 2), "{builder}");
            // The boxes are padded by 1e-5 of their size against rounding.
            let close = |a: f64, b: f64| (a - b).abs() < 1e-3 * b;
            assert!(
                close(bvh.end_point_overlap(), 0.5),
                "{builder}: {}",
                bvh.end_point_overlap()
            );
            assert!(
                close(stats.sah_cost, 0.5 + 16.0 / 12.0),
                "{builder}: {stats:?}"
            );
            assert_eq!(bvh.shape().depth_histogram, vec![0, 2]);
            assert_eq!(bvh.shape().leaf_size_histogram, vec![0, 2]);
        }
    }

    #[test]
    fn apart_primitives_have_no_end_point_overlap() {
        let text = format!("{VIEW}s -5 0 0 1\ns 5 0 0 1\n");
        let scene = parse_nff(&text, "two.nff").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(Bvh::build(&scene).end_point_overlap(), 0.0);
    }

    #[test]
    fn a_sphere_inside_another_sphere_s_leaf_box_overlaps_by_its_whole_area() {
        // A small sphere (r = 0.5) inside a big one's box (r = 4) and a third far
        // away: the midpoint builder splits the centroids 0, 0.1 and 20 at 10, then
        // at 0.05, a leaf each.
        // The small sphere lies wholly in the big one's leaf box: its whole area
        // (cost 1) counts. The small one's box lies inside the big sphere, which has
        // no surface there; the far sphere overlaps no other box; the interior node
        // above big and small holds both. So EPO = small / (big + small + far).
        let text = format!("{VIEW}s 0 0 0 4\ns 0.1 0 0 0.5\ns 20 0 0 1\n");
        let scene = parse_nff(&text, "nested.nff").unwrap_or_else(|e| panic!("{e}"));
        let bvh = Bvh::build_with(&scene, BvhBuilder::Midpoint);
        let mut facets = Vec::new();
        let area = |prim: usize, facets: &mut Vec<Vec<Vec3A>>| {
            facets.clear();
            let p = PrimRef {
                kind: PrimKind::Sphere,
                index: prim as u32,
            };
            facets_of(&scene, p, facets);
            facets.iter().map(|f| polygon_area(f)).sum::<f64>()
        };
        let (big, small, far) = (
            area(0, &mut facets),
            area(1, &mut facets),
            area(2, &mut facets),
        );
        // The tessellated sphere is within 5 % of 4πr².
        let true_area = 4.0 * std::f64::consts::PI * 16.0;
        assert!((big / true_area - 1.0).abs() < 0.05, "{big} vs {true_area}");
        let epo = bvh.end_point_overlap();
        let expected = small / (big + small + far);
        assert!((epo / expected - 1.0).abs() < 1e-9, "{epo} vs {expected}");
    }
}

//! A bounding volume hierarchy of f64 boxes over the reference's primitives, written
//! here (it shares nothing with the tracer's BVH). It only culls: a box is tested before
//! the primitives inside it, every primitive a ray could hit is still tested with its
//! own exact test, and the closest hit is the least (distance, scene order) pair, the
//! same one the brute-force walk keeps (ties go to the first primitive in scene
//! order). So the picture is the brute-force walk's, bit for bit (tested), at a cost
//! that lets the suite render the reference at the SPD's full frame.
//!
//! Boxes are padded by `1e-9 × (1 + largest |coordinate|)`, far beyond the f64 rounding
//! of the slab test and of the primitives' own distances, so that no hit a primitive's
//! test returns lies outside its box.

use crate::primitives::Shape;
use crate::ray::{Hit, Ray};
use crate::scene::Object;
use glam::DVec3;

/// Primitives per leaf at most.
const LEAF_SIZE: usize = 4;

/// Relative padding of every box (see the module doc).
const PAD: f64 = 1e-9;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bounds {
    lo: DVec3,
    hi: DVec3,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        lo: DVec3::INFINITY,
        hi: DVec3::NEG_INFINITY,
    };

    fn around(points: impl IntoIterator<Item = (DVec3, f64)>) -> Bounds {
        points.into_iter().fold(Bounds::EMPTY, |b, (p, r)| {
            let r = r.abs();
            b.union(Bounds {
                lo: p - DVec3::splat(r),
                hi: p + DVec3::splat(r),
            })
        })
    }

    fn union(self, o: Bounds) -> Bounds {
        Bounds {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    fn padded(self) -> Bounds {
        let pad = PAD * (1.0 + self.lo.abs().max(self.hi.abs()).max_element());
        Bounds {
            lo: self.lo - DVec3::splat(pad),
            hi: self.hi + DVec3::splat(pad),
        }
    }

    fn centre(self) -> DVec3 {
        (self.lo + self.hi) * 0.5
    }

    /// Whether `ray` passes through the box at some `0 ≤ t ≤ reach` (slabs; an axis the
    /// ray runs parallel to is an interval test on the origin, so no 0 × ∞).
    fn meets(&self, ray: &Ray, reach: f64) -> bool {
        let (mut near, mut far) = (0.0f64, reach);
        for axis in 0..3 {
            let (o, d) = (ray.origin[axis], ray.dir[axis]);
            let (lo, hi) = (self.lo[axis], self.hi[axis]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return false;
                }
                continue;
            }
            let (a, b) = ((lo - o) / d, (hi - o) / d);
            near = near.max(a.min(b));
            far = far.min(a.max(b));
            if !(near <= far) {
                return false;
            }
        }
        true
    }
}

/// The box around one primitive: a sphere's centre ± radius; a cylinder's or cone's two
/// end discs, each inside its centre ± radius; an outline's vertices.
fn shape_bounds(shape: &Shape) -> Bounds {
    match shape {
        Shape::Sphere(s) => Bounds::around([(s.center, s.radius)]),
        Shape::Cylinder(c) => Bounds::around([
            (c.axis.base, c.radius),
            (c.axis.base + c.axis.dir * c.axis.length, c.radius),
        ]),
        Shape::Cone(c) => Bounds::around([
            (c.axis.base, c.base_radius),
            (c.axis.base + c.axis.dir * c.axis.length, c.apex_radius),
        ]),
        Shape::Polygon(p) => Bounds::around(p.vertices.iter().map(|&v| (v, 0.0))),
        Shape::Patch(p) => Bounds::around(p.outline.vertices.iter().map(|&v| (v, 0.0))),
    }
    .padded()
}

/// A node: a leaf holds `count` primitives from `first` of the order; an inner node's
/// children are the next node and `first`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Bounds,
    first: u32,
    count: u32,
}

/// The hierarchy over a scene's objects.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Object indices, leaf by leaf.
    order: Vec<u32>,
}

impl Bvh {
    /// Builds the hierarchy by median splits along the widest axis of the centres.
    pub fn build(objects: &[Object]) -> Bvh {
        let boxes: Vec<Bounds> = objects.iter().map(|o| shape_bounds(&o.shape)).collect();
        let mut order: Vec<u32> = (0..objects.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * objects.len() / LEAF_SIZE + 1);
        if !objects.is_empty() {
            split(&boxes, &mut order, 0, &mut nodes);
        }
        Bvh { nodes, order }
    }

    /// Walks the leaves whose boxes `ray` meets within `reach()` (asked again before
    /// each node, as a closest-hit query shortens it), handing each leaf's object
    /// indices to `leaf`; stops when `leaf` says so.
    fn walk(&self, ray: &Ray, reach: impl Fn() -> f64, mut leaf: impl FnMut(&[u32]) -> bool) {
        let mut stack: Vec<usize> = Vec::with_capacity(64);
        if !self.nodes.is_empty() {
            stack.push(0);
        }
        while let Some(at) = stack.pop() {
            let node = self.nodes[at];
            if !node.bounds.meets(ray, reach()) {
                continue;
            }
            if node.count == 0 {
                stack.push(node.first as usize);
                stack.push(at + 1);
                continue;
            }
            let first = node.first as usize;
            if leaf(&self.order[first..first + node.count as usize]) {
                return;
            }
        }
    }

    /// The closest hit at `0 < t` (ties: the first object in scene order), as the
    /// brute-force walk finds it.
    pub fn closest<'o>(&self, objects: &'o [Object], ray: &Ray) -> Option<(&'o Object, Hit)> {
        let best: std::cell::Cell<Option<(usize, Hit)>> = std::cell::Cell::new(None);
        let reach = || best.get().map_or(f64::INFINITY, |(_, h)| h.t);
        self.walk(ray, reach, |indices| {
            for &index in indices {
                let index = index as usize;
                let (reach, tie_wins) = match best.get() {
                    None => (f64::INFINITY, false),
                    Some((b, h)) => (h.t, index < b),
                };
                // A test accepts t < reach; an earlier object at exactly `reach` wins
                // the tie, as it would have come first in the brute-force walk.
                let limit = if tie_wins { reach.next_up() } else { reach };
                if let Some(hit) = objects[index].shape.intersect(ray, 0.0, limit) {
                    best.set(Some((index, hit)));
                }
            }
            false
        });
        best.get().map(|(i, h)| (&objects[i], h))
    }

    /// Whether any object lies on `ray` at `0 < t < reach`.
    pub fn occluded(&self, objects: &[Object], ray: &Ray, reach: f64) -> bool {
        let mut found = false;
        self.walk(
            ray,
            || reach,
            |indices| {
                found = indices.iter().any(|&i| {
                    objects[i as usize]
                        .shape
                        .intersect(ray, 0.0, reach)
                        .is_some()
                });
                found
            },
        );
        found
    }
}

/// Appends the subtree over `order` (whose first element sits at `offset` of the whole
/// order) and returns nothing: its root is the node pushed first.
fn split(boxes: &[Bounds], order: &mut [u32], offset: usize, nodes: &mut Vec<Node>) {
    let bounds = order
        .iter()
        .fold(Bounds::EMPTY, |b, &i| b.union(boxes[i as usize]));
    let centres = order.iter().fold(Bounds::EMPTY, |b, &i| {
        let c = boxes[i as usize].centre();
        b.union(Bounds { lo: c, hi: c })
    });
    let extent = centres.hi - centres.lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    // NaN-free extents only (a box of infinities splits nowhere useful).
    if order.len() <= LEAF_SIZE || !(extent[axis] > 0.0) {
        nodes.push(Node {
            bounds,
            first: offset as u32,
            count: order.len() as u32,
        });
        return;
    }
    let at = nodes.len();
    nodes.push(Node {
        bounds,
        first: 0,
        count: 0,
    });
    let half = order.len() / 2;
    order.select_nth_unstable_by(half, |&a, &b| {
        let (ca, cb) = (boxes[a as usize].centre(), boxes[b as usize].centre());
        ca[axis].total_cmp(&cb[axis]).then(a.cmp(&b))
    });
    let (left, right) = order.split_at_mut(half);
    split(boxes, left, offset, nodes);
    nodes[at].first = nodes.len() as u32;
    split(boxes, right, offset + half, nodes);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_is_met_only_within_reach_and_parallel_rays_test_the_origin() {
        let b = Bounds {
            lo: DVec3::splat(-1.0),
            hi: DVec3::splat(1.0),
        };
        let ray = Ray {
            origin: DVec3::new(0.0, 0.0, -5.0),
            dir: DVec3::Z,
        };
        assert!(b.meets(&ray, f64::INFINITY));
        // The box starts at t = 4.
        assert!(b.meets(&ray, 4.0));
        assert!(!b.meets(&ray, 3.999));
        // Parallel to x and y, outside in y.
        let beside = Ray {
            origin: DVec3::new(0.0, 2.0, -5.0),
            dir: DVec3::Z,
        };
        assert!(!b.meets(&beside, f64::INFINITY));
        // Behind the origin.
        let away = Ray {
            origin: DVec3::new(0.0, 0.0, -5.0),
            dir: -DVec3::Z,
        };
        assert!(!b.meets(&away, f64::INFINITY));
    }
}

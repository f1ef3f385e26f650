//! The boxes Embree culls user primitives with (build time only): axis-aligned boxes,
//! the disk box of a cylinder's or cone's end, and the slack that widens a quadric's
//! box by the rounding of rtprof's tests in [`EmbreeMode::Exact`].

use super::EmbreeMode;
use super::ffi::RTCBounds;
use crate::counter::{Counter, NoCount};
use crate::scene::Scene;
use crate::vec3::Vec3;

/// An axis-aligned box (build time only).
#[derive(Clone, Copy, Debug)]
pub(super) struct Aabb {
    min: [f32; 3],
    max: [f32; 3],
}

impl Aabb {
    pub(super) const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    pub(super) fn grow(self, p: Vec3) -> Aabb {
        let p = p.to_array();
        Aabb {
            min: std::array::from_fn(|i| self.min[i].min(p[i])),
            max: std::array::from_fn(|i| self.max[i].max(p[i])),
        }
    }

    /// The box widened by `e` on each side.
    pub(super) fn grow_by(self, e: [f32; 3]) -> Aabb {
        Aabb {
            min: std::array::from_fn(|i| self.min[i] - e[i]),
            max: std::array::from_fn(|i| self.max[i] + e[i]),
        }
    }

    pub(super) fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: std::array::from_fn(|i| self.min[i].min(o.min[i])),
            max: std::array::from_fn(|i| self.max[i].max(o.max[i])),
        }
    }

    /// Grown by a relative margin (as the BVH's boxes) so that rounding in the exact
    /// tests never reports a hit outside the box Embree culls with.
    pub(super) fn padded(self) -> Aabb {
        let extent = (0..3).fold(0.0f32, |m, i| {
            m.max(self.max[i] - self.min[i])
                .max(self.max[i].abs())
                .max(self.min[i].abs())
        });
        let pad = extent * 1e-5 + f32::MIN_POSITIVE;
        self.grow_by([pad; 3])
    }
}

impl From<Aabb> for RTCBounds {
    fn from(b: Aabb) -> Self {
        RTCBounds {
            lower_x: b.min[0],
            lower_y: b.min[1],
            lower_z: b.min[2],
            align0: 0.0,
            upper_x: b.max[0],
            upper_y: b.max[1],
            upper_z: b.max[2],
            align1: 0.0,
        }
    }
}

/// How far from its surface rtprof's quadric tests (sphere, cylinder, cone) can
/// report a hit, as a wider radius for the boxes Embree culls user primitives with
/// in [`EmbreeMode::Exact`].
///
/// The tests' first stage computes `b² - c` from terms of size `|O - C|²` and assumes
/// `|dir| = 1`; a hit is decided by the second stage, which has no such error, or by
/// the first where its discriminant is far above that error (so the ray certainly
/// crosses the true quadric and its box), so this bound (of the first stage's error)
/// is conservative.
/// Their discriminant is off by up to about `γ |O - C|²` with `γ = 8 ε`: in units of
/// the rounding `u = ε/2`, 7 from `(R·Voc)²`, 4 from `Voc·Voc - r²`, 4 from
/// `|dir|² - 1` of a normalized f32 vector. A hit can then be reported up to
/// `sqrt(r² + γ |O - C|²)` from the centre or axis: more than `r` for small far
/// quadrics (`tree`'s leaves, radius 0.0012, are hit 1.5 radii off). Boxes of the
/// true radius would cull those hits, as rtprof's own BVH does (its `tree` differs
/// from the baseline's by RMS 0.77 at 32x32). Every ray starts at the eye or on a
/// primitive, so the farthest corner of the box of the eye and all primitives
/// bounds `|O - C|`.
#[derive(Clone, Copy, Debug)]
pub(super) struct QuadricSlack {
    /// The box of every possible ray origin; `None` for tight boxes.
    origins: Option<Aabb>,
}

impl QuadricSlack {
    const GAMMA: f32 = 8.0 * f32::EPSILON;

    pub(super) fn new(scene: &Scene, mode: EmbreeMode) -> Self {
        if mode != EmbreeMode::Exact {
            return Self { origins: None };
        }
        let mut b = Aabb::EMPTY.grow(scene.view.from);
        for s in &scene.spheres {
            let r = s.radius.abs();
            b = b.union(Aabb::EMPTY.grow(s.center).grow_by([r; 3]));
        }
        for c in &scene.cylinders {
            let r = c.radius.abs();
            b = b.union(Aabb::EMPTY.grow(c.base).grow(c.apex).grow_by([r; 3]));
        }
        for c in &scene.cones {
            let r = c.base_radius.abs().max(c.apex_radius.abs());
            b = b.union(Aabb::EMPTY.grow(c.base).grow(c.apex).grow_by([r; 3]));
        }
        let outlines = scene.polygons.iter().map(|p| &p.outline);
        for o in outlines.chain(scene.patches.iter().map(|p| &p.outline)) {
            b = o.vertices.iter().fold(b, |b, v| b.grow(*v));
        }
        Self { origins: Some(b) }
    }

    /// The box radius for a quadric of radius `r` (either sign) around `center` (a
    /// sphere's centre, or an end of a cylinder or cone, whose distance to the
    /// other end's origins the other end's radius covers).
    pub(super) fn radius(self, r: f32, center: Vec3) -> f32 {
        let Some(b) = self.origins else {
            return r.abs();
        };
        let c = center.to_array();
        let reach_sq: f32 = (0..3)
            .map(|i| {
                let d = (c[i] - b.min[i]).abs().max((b.max[i] - c[i]).abs());
                d * d
            })
            .sum();
        NoCount.sqrt(r * r + Self::GAMMA * reach_sq)
    }
}

/// The box of a disk of radius `r` around unit `axis` at `center`: half-extents
/// `|r| sqrt(1 - axis_i²)`.
pub(super) fn disk_box(center: Vec3, axis: Vec3, r: f32) -> Aabb {
    let a = axis.to_array();
    let e = a.map(|ai| NoCount.sqrt((1.0 - ai * ai).max(0.0)) * r.abs());
    Aabb::EMPTY.grow(center).grow_by(e)
}

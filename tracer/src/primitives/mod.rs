//! Ray-primitive intersection tests, one primitive per file.
//!
//! Each test counts itself (`tests.<kind>.tests` on entry, `.hits` when it reports an
//! intersection inside the ray's interval) next to the code it counts. A test returns
//! only the distance (and, for quadrics, the axial coordinate); the surface normal is
//! computed afterwards for the closest hit alone (the thesis's "hit body").

mod cone;
mod cylinder;
mod edge_slabs;
mod patch;
mod plane;
mod polygon;
mod sphere;

pub use cone::Cone;
pub use cylinder::Cylinder;
pub use patch::Patch;
pub use plane::PlanarOutline;
pub use polygon::Polygon;
pub use sphere::Sphere;

/// Why a primitive could not be built from its description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    #[error("a polygon needs at least 3 vertices, found {0}")]
    TooFewVertices(usize),
    #[error("the first three polygon vertices are collinear or coincident (no plane normal)")]
    DegeneratePolygon,
    #[error("the cone/cylinder base and apex coincide (zero-length axis)")]
    ZeroLengthAxis,
    /// The 1-based vertex whose normal is the zero vector.
    #[error("the normal of vertex {0} has zero length")]
    ZeroNormal(usize),
    #[error("patch has {vertices} vertices but {normals} normals")]
    NormalCountMismatch { vertices: usize, normals: usize },
}

/// The squared radius a quadric test uses: `radius²`, or -inf when that is zero (a zero
/// radius, or one whose square underflows). A point or a line has no area to see, but
/// rounding can make its discriminant slightly positive and report a hit whose normal
/// is undefined; -inf makes every discriminant -inf (or NaN), never a hit, with no
/// extra test in the intersection loop.
pub(crate) fn test_radius_sq(radius: f32) -> f32 {
    let sq = radius * radius;
    if sq > 0.0 { sq } else { f32::NEG_INFINITY }
}

/// `2⁻¹⁶`: see [`quick_miss_margin`].
const QUICK_MISS_FRACTION: f32 = 1.0 / 65536.0;

/// The margin below which a quadric test's first-stage (the thesis's) discriminant
/// certainly means a miss, for `scale` bounding the terms that cancel in it (`|Voc|²` for
/// the sphere and the cylinder, weighted by the slope for the cone). Those terms carry
/// rounding errors of a few ulps of `scale` (about 10 ε·scale for the sphere's products
/// and sums, ε = 2⁻²⁴); the margin is 2⁻¹⁶·scale = 256 ε·scale, well above any of them,
/// so no hit is ever rejected, and a power of two, so the product is exact. Tests that
/// pass this stage (hits and near misses) compute the discriminant again without
/// cancellation.
#[inline(always)]
pub(crate) fn quick_miss_margin(scale: f32) -> f32 {
    scale * QUICK_MISS_FRACTION
}

/// The sphere test's first stage: whether the thesis's discriminant
/// `b² - (|Voc|² - r²)` (`b = R·Voc`) may show a hit, i.e. lies above
/// `-`[`quick_miss_margin`]`(|Voc|²)`. Rearranged as `b² + r² ≥ (1 - 2⁻¹⁶) |Voc|²`, it
/// takes as many operations as the thesis's test of the discriminant's sign, so a
/// certain miss costs what it did. `1 - 2⁻¹⁶` is exact in f32, and either arrangement's
/// rounding (a few ulps of `|Voc|²`) is far inside the margin. A zero radius
/// (`r² = -inf`) and a NaN say no. Every path (scalar, lanes, packs) calls this one
/// function, so their decisions agree bit for bit.
#[inline(always)]
pub(crate) fn sphere_may_hit(half_b: f32, oo: f32, radius_sq: f32) -> bool {
    half_b * half_b + radius_sq >= oo * (1.0 - QUICK_MISS_FRACTION)
}

/// The two roots of `a t² + 2 half_b t + c = 0` in ascending order, given the square
/// root of the discriminant `half_b² - a c`. `a` must not be zero.
#[inline(always)]
pub(crate) fn ordered_roots(a: f32, half_b: f32, root: f32) -> [f32; 2] {
    let t1 = (-half_b - root) / a;
    let t2 = (-half_b + root) / a;
    if t1 <= t2 { [t1, t2] } else { [t2, t1] }
}

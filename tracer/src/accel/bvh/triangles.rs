//! Polygons and patches as triangles in SIMD lanes (the wide BVH, variants `bvh` +
//! `simd`).
//!
//! The thesis's polygon test (a plane test, then a crossing test over every edge of
//! the outline) runs one polygon at a time. Here each outline is ear-clipped into
//! triangles ([`triangulate`](crate::accel::triangulate)), each triangle becomes an item
//! of the tree, and a leaf's triangles are tested [`WIDTH`] at a time:
//!
//! - the **plane test** is the polygon's own, with the same arithmetic (`Voc = O - V0`,
//!   `t = -(Voc·N) / (R·N)`, the hit point `O + R t`), so a triangle's distance is the
//!   polygon's bit for bit;
//! - then **three edge functions** of the hit point in the projection the crossing test
//!   uses (the normal's largest component dropped): `A u + B v + C ≥ 0` on every edge.
//!   An edge shared by two triangles of one outline (a diagonal of the ear clipping)
//!   has one set of coefficients, rounded once from f64 and negated for the second
//!   triangle, so the two tests are exact complements: no ray slips between them.
//!
//! The region is the crossing test's (the outline lifted onto its plane); only points
//! within rounding of an outer edge can fall differently, so the picture differs from
//! the baseline's at silhouette pixels at most. Outlines that ear clipping cannot
//! reproduce (self-intersecting ones, whose crossing test is even-odd) and outlines of
//! many vertices ([`MAX_TRIANGULATED_VERTICES`]) keep the polygon test whole.
//!
//! Counting: each live lane is one `tests.triangle.tests`, with the plane test's `sub`
//! and two `dot`; each lane whose plane hit lies in the query's range adds the hit
//! point (`scale`, `add`) and three `dot` (the edge functions); a lane inside its
//! triangle is a `tests.triangle.hits`. A pack issues [`WIDTH`] lanes.

use super::ray_lanes::RayLanes;
use super::{Aabb, Lane};
use crate::accel::BVH_WIDTH as WIDTH;
use crate::accel::triangulate;
use crate::counter::{Counter, Phase, Stat};
use crate::primitives::PlanarOutline;
use crate::ray::{PrimKind, PrimRef, Ray};
use crate::scene::Scene;
use glam::Vec3A;

/// Outlines of more vertices stay whole (the crossing test with `EdgeSlabs` walks only
/// the edges near the point), so that ear clipping, quadratic in the vertices, stays
/// cheap. The gears' 144-gon faces are triangulated: ear clipping that takes the
/// shortest diagonal first cuts them into nested triangles whose boxes the tree
/// separates well (the earlier sweep round the outline gave slivers, and the faces
/// then stayed whole). Measured on SPD gears at 1024x1024, 1 thread, CPU time: diffuse
/// 197 -> 158 ms, Whitted 2.00 -> 1.52 s (with this file's and the tree's other
/// changes of that step).
const MAX_TRIANGULATED_VERTICES: usize = 1024;

/// One triangle of an outline, ready for a lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Triangle {
    /// The polygon or patch it belongs to (what a hit names).
    pub owner: PrimRef,
    /// The outline's unit normal and first written vertex: its plane test.
    normal: [f32; 3],
    v0: [f32; 3],
    /// Per edge `[m_x, m_y, m_z, k]`: inside where `m·p + k ≥ 0` (the dropped axis's
    /// `m` is zero, so this is the 2D edge function of the projection).
    edges: [[f32; 4]; 3],
}

/// A tree item that stands for part of a polygon or patch: one of its triangles, or
/// the whole outline when ear clipping cannot reproduce it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Piece {
    Triangle(Triangle),
    Whole(PrimRef),
}

/// The wide BVH's items: every sphere, cylinder and cone as itself, every polygon and
/// patch as its pieces. An item's reference is the primitive's for the first three
/// kinds; for a piece it is [`PrimKind::Polygon`] with the piece's index in the
/// returned table (the binary tree built over these items is only collapsed, never
/// queried).
pub(super) fn items(scene: &Scene) -> (Vec<(PrimRef, Aabb, Lane)>, Vec<Piece>) {
    let mut items = Vec::with_capacity(scene.primitive_count());
    for (kind, n) in [
        (PrimKind::Sphere, scene.spheres.len()),
        (PrimKind::Cylinder, scene.cylinders.len()),
        (PrimKind::Cone, scene.cones.len()),
    ] {
        for index in 0..n as u32 {
            let prim = PrimRef { kind, index };
            let lane = if kind == PrimKind::Sphere {
                Lane::Sphere
            } else {
                Lane::Alone
            };
            items.push((prim, super::bounds_of(scene, prim), lane));
        }
    }
    let mut pieces = Vec::new();
    let outlines = scene
        .polygons
        .iter()
        .map(|p| (PrimKind::Polygon, &p.outline))
        .chain(scene.patches.iter().map(|p| (PrimKind::Patch, &p.outline)));
    let mut counters = [0u32; 2];
    for (kind, outline) in outlines {
        let slot = usize::from(kind == PrimKind::Patch);
        let owner = PrimRef {
            kind,
            index: counters[slot],
        };
        counters[slot] += 1;
        let mut push = |piece: Piece, bounds: Aabb| {
            let lane = match piece {
                Piece::Triangle(_) => Lane::Triangle,
                _ => Lane::Alone,
            };
            let index = pieces.len() as u32;
            pieces.push(piece);
            let prim = PrimRef {
                kind: PrimKind::Polygon,
                index,
            };
            items.push((prim, bounds, lane));
        };
        if outline.vertices.len() > MAX_TRIANGULATED_VERTICES {
            push(Piece::Whole(owner), super::bounds_of(scene, owner));
            continue;
        }
        let lifted = triangulate::lift(outline);
        match &lifted.triangles {
            Some(triangles) => {
                for &corners in triangles {
                    let triangle = Triangle::new(owner, outline, &lifted, corners);
                    // The lifted corners hold the region; the written ones are what the
                    // binary tree boxes: the union holds either rounding.
                    let bounds = corners.iter().fold(Aabb::EMPTY, |b, &i| {
                        let i = i as usize;
                        b.grow(Vec3A::from_array(lifted.vertices[i]))
                            .grow(outline.vertices[i].0)
                    });
                    push(Piece::Triangle(triangle), bounds);
                }
            }
            None => push(Piece::Whole(owner), super::bounds_of(scene, owner)),
        }
    }
    (items, pieces)
}

impl Triangle {
    /// The triangle `corners` (indices into the outline's vertices, turning as the
    /// outline) of `owner`'s outline.
    fn new(
        owner: PrimRef,
        outline: &PlanarOutline,
        lifted: &triangulate::Lifted,
        corners: [u32; 3],
    ) -> Self {
        let p = |i: u32| lifted.projected[i as usize];
        let [a, b, c] = corners.map(p);
        let area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let orientation = if area2 < 0.0 { -1.0f32 } else { 1.0 };
        let mut edges = [[0.0f32; 4]; 3];
        for (edge, (from, to)) in edges.iter_mut().zip([
            (corners[0], corners[1]),
            (corners[1], corners[2]),
            (corners[2], corners[0]),
        ]) {
            // The edge's function taken from its lower vertex index to its higher one,
            // whichever triangle asks: the same rounded coefficients for both
            // triangles beside a diagonal, one of them negated (exactly).
            let (lo, hi) = (from.min(to), from.max(to));
            let (l, h) = (p(lo), p(hi));
            let coeff_a = -(h[1] - l[1]);
            let coeff_b = h[0] - l[0];
            let coeff_c = -(coeff_a * l[0] + coeff_b * l[1]);
            let rounded = [coeff_a as f32, coeff_b as f32, coeff_c as f32];
            let sign = if from == lo {
                orientation
            } else {
                -orientation
            };
            let mut m = [0.0f32; 3];
            m[lifted.axes[0]] = sign * rounded[0];
            m[lifted.axes[1]] = sign * rounded[1];
            *edge = [m[0], m[1], m[2], sign * rounded[2]];
        }
        Triangle {
            owner,
            normal: outline.normal.to_array(),
            v0: outline.vertices[0].to_array(),
            edges,
        }
    }
}

/// Up to [`WIDTH`] triangles in structure-of-arrays lanes. Unused lanes have a zero
/// normal: their plane test divides 0 by 0 and is never in range.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(super) struct TrianglePack {
    normal: [[f32; WIDTH]; 3],
    v0: [[f32; WIDTH]; 3],
    /// Edge `e`'s `m_x, m_y, m_z, k`.
    edges: [[[f32; WIDTH]; 4]; 3],
    /// The polygon or patch each lane belongs to.
    pub owner: [PrimRef; WIDTH],
    /// Lanes in use (the first `live`).
    pub live: u32,
}

impl TrianglePack {
    /// Packs up to [`WIDTH`] triangles.
    pub(super) fn new(triangles: &[Triangle]) -> Self {
        let mut pack = TrianglePack {
            normal: [[0.0; WIDTH]; 3],
            v0: [[0.0; WIDTH]; 3],
            edges: [[[0.0; WIDTH]; 4]; 3],
            owner: [PrimRef {
                kind: PrimKind::Polygon,
                index: u32::MAX,
            }; WIDTH],
            live: triangles.len().min(WIDTH) as u32,
        };
        for (lane, t) in triangles.iter().take(WIDTH).enumerate() {
            for axis in 0..3 {
                pack.normal[axis][lane] = t.normal[axis];
                pack.v0[axis][lane] = t.v0[axis];
            }
            for (e, edge) in t.edges.iter().enumerate() {
                for (j, &x) in edge.iter().enumerate() {
                    pack.edges[e][j][lane] = x;
                }
            }
            pack.owner[lane] = t.owner;
        }
        pack
    }
}

/// Each lane's hit distance in a pack of triangles (infinite where it misses), testing
/// the pack's live lanes against the query's reach `(t_min, reach)`; `None` when no
/// lane hits. `avx2`: the CPU has AVX2 (the wide BVH's flag).
#[inline(always)]
pub(super) fn triangle_pack<C: Counter, const FROM_EYE: bool>(
    pack: &TrianglePack,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    reach: f32,
    avx2: bool,
    c: &mut C,
) -> Option<[f32; WIDTH]> {
    let _phase = C::enter_phase(Phase::TriangleTest);
    #[cfg(target_arch = "x86_64")]
    let (hit, ranged, inside) = if avx2 {
        // SAFETY: `avx2` is the wide BVH's flag, set only when the CPU has AVX2.
        unsafe { lanes_avx2(pack, ray, t_min, reach) }
    } else {
        lanes(pack, ray, t_min, reach)
    };
    #[cfg(not(target_arch = "x86_64"))]
    let (hit, ranged, inside) = {
        let _ = avx2;
        lanes(pack, ray, t_min, reach)
    };
    if C::ENABLED {
        let n = u64::from(pack.live);
        c.tally_n(Stat::LanesIssued, WIDTH as u64);
        c.tally_n(Stat::LanesActive, n);
        c.tally_n(Stat::TriangleTest, n);
        if !FROM_EYE {
            c.tally_n(Stat::Sub, n);
        }
        c.tally_n(Stat::Dot, 2 * n);
        let ranged = u64::from(ranged.count_ones());
        c.tally_n(Stat::Scale, ranged);
        c.tally_n(Stat::Add, ranged);
        c.tally_n(Stat::Dot, 3 * ranged);
        c.tally_n(Stat::TriangleHit, u64::from(inside.count_ones()));
    }
    (inside != 0).then_some(hit)
}

/// Each lane's hit distance (infinite where it misses), the lanes whose plane hit
/// lies in `(t_min, reach)` and the lanes that hit (bits per lane; unused lanes never
/// do). The polygon's plane test in its order of operations, then the hit point and the
/// edge functions.
#[inline(always)]
fn lanes<const FROM_EYE: bool>(
    pack: &TrianglePack,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    reach: f32,
) -> ([f32; WIDTH], u32, u32) {
    let [ox, oy, oz] = ray.origin.to_array();
    let [dx, dy, dz] = ray.dir.to_array();
    let [nx, ny, nz] = &pack.normal;
    let [vx, vy, vz] = &pack.v0;
    let [e0, e1, e2] = &pack.edges;
    let mut hit = [f32::INFINITY; WIDTH];
    let (mut ranged, mut hits) = (0u32, 0u32);
    for i in 0..WIDTH {
        let (wx, wy, wz) = (ox - vx[i], oy - vy[i], oz - vz[i]);
        let along = dx * nx[i] + dy * ny[i] + dz * nz[i];
        let offset = wx * nx[i] + wy * ny[i] + wz * nz[i];
        let t = -offset / along;
        let in_range = t > t_min && t < reach;
        let (px, py, pz) = (ox + dx * t, oy + dy * t, oz + dz * t);
        let edge = |e: &[[f32; WIDTH]; 4]| e[0][i] * px + e[1][i] * py + e[2][i] * pz + e[3][i];
        let inside = edge(e0) >= 0.0 && edge(e1) >= 0.0 && edge(e2) >= 0.0;
        ranged |= u32::from(in_range) << i;
        if in_range && inside {
            hit[i] = t;
            hits |= 1 << i;
        }
    }
    (hit, ranged, hits)
}

/// [`lanes`] in AVX instructions, the same operations in the same order (no fused
/// multiply-add), so the same floats.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn lanes_avx2<const FROM_EYE: bool>(
    pack: &TrianglePack,
    ray: &Ray<FROM_EYE>,
    t_min: f32,
    reach: f32,
) -> ([f32; WIDTH], u32, u32) {
    use std::arch::x86_64::{
        __m256, _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LT_OQ, _mm256_add_ps, _mm256_and_ps, _mm256_blendv_ps,
        _mm256_cmp_ps, _mm256_div_ps, _mm256_load_ps, _mm256_movemask_ps, _mm256_mul_ps,
        _mm256_set1_ps, _mm256_setzero_ps, _mm256_storeu_ps, _mm256_sub_ps, _mm256_xor_ps,
    };
    // SAFETY: the caller guarantees AVX2; every row is 8 floats at a 32-byte aligned
    // offset of a 32-byte aligned pack.
    unsafe {
        let o = ray.origin.to_array().map(|x| _mm256_set1_ps(x));
        let d = ray.dir.to_array().map(|x| _mm256_set1_ps(x));
        let load = |row: &[f32; WIDTH]| _mm256_load_ps(row.as_ptr());
        let dot3 = |a: [__m256; 3], b: [__m256; 3]| {
            _mm256_add_ps(
                _mm256_add_ps(_mm256_mul_ps(a[0], b[0]), _mm256_mul_ps(a[1], b[1])),
                _mm256_mul_ps(a[2], b[2]),
            )
        };
        let n = pack.normal.each_ref().map(load);
        let w = [0, 1, 2].map(|a| _mm256_sub_ps(o[a], load(&pack.v0[a])));
        let along = dot3(d, n);
        let offset = dot3(w, n);
        let negated = _mm256_xor_ps(offset, _mm256_set1_ps(-0.0));
        let t = _mm256_div_ps(negated, along);
        let in_range = _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GT_OQ>(t, _mm256_set1_ps(t_min)),
            _mm256_cmp_ps::<_CMP_LT_OQ>(t, _mm256_set1_ps(reach)),
        );
        let ranged = _mm256_movemask_ps(in_range) as u32;
        let mut hit = [f32::INFINITY; WIDTH];
        if ranged == 0 {
            return (hit, 0, 0);
        }
        let p = [0, 1, 2].map(|a| _mm256_add_ps(o[a], _mm256_mul_ps(d[a], t)));
        let zero = _mm256_setzero_ps();
        let mut inside = in_range;
        for e in &pack.edges {
            let m = [load(&e[0]), load(&e[1]), load(&e[2])];
            let value = _mm256_add_ps(dot3(m, p), load(&e[3]));
            inside = _mm256_and_ps(inside, _mm256_cmp_ps::<_CMP_GE_OQ>(value, zero));
        }
        let t = _mm256_blendv_ps(_mm256_set1_ps(f32::INFINITY), t, inside);
        _mm256_storeu_ps(hit.as_mut_ptr(), t);
        (hit, ranged, _mm256_movemask_ps(inside) as u32)
    }
}

/// Triangle `i` of `pack` against every ray of `rays` (a ray per lane), ray `r`
/// within `(t_min, reach[r])`: each ray's hit distance (infinite where it misses), the
/// rays whose plane hit is in range and the rays that hit (bits per ray). The same
/// operations in the same order as [`lanes`], with the ray in the lane instead of the
/// triangle, so each pair's distance is the one [`triangle_pack`] gives, bit for bit.
#[inline(always)]
pub(super) fn triangle_rays(
    pack: &TrianglePack,
    i: usize,
    rays: &RayLanes,
    t_min: f32,
    reach: &[f32; WIDTH],
) -> ([f32; WIDTH], u32, u32) {
    let [nx, ny, nz] = pack.normal.map(|row| row[i]);
    let [vx, vy, vz] = pack.v0.map(|row| row[i]);
    let e = pack.edges.map(|edge| edge.map(|row| row[i]));
    let mut hit = [f32::INFINITY; WIDTH];
    let (mut ranged, mut hits) = (0u32, 0u32);
    for r in 0..WIDTH {
        let [ox, oy, oz] = [rays.origin[0][r], rays.origin[1][r], rays.origin[2][r]];
        let [dx, dy, dz] = [rays.dir[0][r], rays.dir[1][r], rays.dir[2][r]];
        let (wx, wy, wz) = (ox - vx, oy - vy, oz - vz);
        let along = dx * nx + dy * ny + dz * nz;
        let offset = wx * nx + wy * ny + wz * nz;
        let t = -offset / along;
        let in_range = t > t_min && t < reach[r];
        let (px, py, pz) = (ox + dx * t, oy + dy * t, oz + dz * t);
        let edge = |e: &[f32; 4]| e[0] * px + e[1] * py + e[2] * pz + e[3];
        let inside = edge(&e[0]) >= 0.0 && edge(&e[1]) >= 0.0 && edge(&e[2]) >= 0.0;
        ranged |= u32::from(in_range) << r;
        if in_range && inside {
            hit[r] = t;
            hits |= 1 << r;
        }
    }
    (hit, ranged, hits)
}

/// [`triangle_rays`] in AVX instructions, the same operations in the same order (no
/// fused multiply-add), so the same floats; also the rays that hit at or within their
/// `t_max` (bits per ray), and the distances are stored only when there are any. Written
/// without closures: a closure would not inherit the caller's AVX and would call each
/// intrinsic.
///
/// # Safety
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(super) unsafe fn triangle_rays_avx2(
    pack: &TrianglePack,
    i: usize,
    rays: &RayLanes,
    t_min: f32,
    reach: &[f32; WIDTH],
    t_max: &[f32; WIDTH],
) -> ([f32; WIDTH], u32, u32, u32) {
    use std::arch::x86_64::{
        _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm256_add_ps, _mm256_and_ps,
        _mm256_blendv_ps, _mm256_cmp_ps, _mm256_div_ps, _mm256_load_ps, _mm256_loadu_ps,
        _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm256_storeu_ps,
        _mm256_sub_ps, _mm256_xor_ps,
    };
    // SAFETY: the caller guarantees AVX2; the ray rows are 32-byte aligned rows of 8
    // floats, `reach` is 8 floats, and `i < WIDTH` indexes the pack's rows.
    unsafe {
        let ox = _mm256_load_ps(rays.origin[0].as_ptr());
        let oy = _mm256_load_ps(rays.origin[1].as_ptr());
        let oz = _mm256_load_ps(rays.origin[2].as_ptr());
        let dx = _mm256_load_ps(rays.dir[0].as_ptr());
        let dy = _mm256_load_ps(rays.dir[1].as_ptr());
        let dz = _mm256_load_ps(rays.dir[2].as_ptr());
        let nx = _mm256_set1_ps(pack.normal[0][i]);
        let ny = _mm256_set1_ps(pack.normal[1][i]);
        let nz = _mm256_set1_ps(pack.normal[2][i]);
        let wx = _mm256_sub_ps(ox, _mm256_set1_ps(pack.v0[0][i]));
        let wy = _mm256_sub_ps(oy, _mm256_set1_ps(pack.v0[1][i]));
        let wz = _mm256_sub_ps(oz, _mm256_set1_ps(pack.v0[2][i]));
        let along = _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(dx, nx), _mm256_mul_ps(dy, ny)),
            _mm256_mul_ps(dz, nz),
        );
        let offset = _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(wx, nx), _mm256_mul_ps(wy, ny)),
            _mm256_mul_ps(wz, nz),
        );
        let negated = _mm256_xor_ps(offset, _mm256_set1_ps(-0.0));
        let t = _mm256_div_ps(negated, along);
        let in_range = _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GT_OQ>(t, _mm256_set1_ps(t_min)),
            _mm256_cmp_ps::<_CMP_LT_OQ>(t, _mm256_loadu_ps(reach.as_ptr())),
        );
        let ranged = _mm256_movemask_ps(in_range) as u32;
        let mut hit = [f32::INFINITY; WIDTH];
        if ranged == 0 {
            return (hit, 0, 0, 0);
        }
        let far = _mm256_set1_ps(f32::INFINITY);
        let px = _mm256_add_ps(ox, _mm256_mul_ps(dx, t));
        let py = _mm256_add_ps(oy, _mm256_mul_ps(dy, t));
        let pz = _mm256_add_ps(oz, _mm256_mul_ps(dz, t));
        let zero = _mm256_setzero_ps();
        let mut inside = in_range;
        for e in &pack.edges {
            let value = _mm256_add_ps(
                _mm256_add_ps(
                    _mm256_add_ps(
                        _mm256_mul_ps(_mm256_set1_ps(e[0][i]), px),
                        _mm256_mul_ps(_mm256_set1_ps(e[1][i]), py),
                    ),
                    _mm256_mul_ps(_mm256_set1_ps(e[2][i]), pz),
                ),
                _mm256_set1_ps(e[3][i]),
            );
            inside = _mm256_and_ps(inside, _mm256_cmp_ps::<_CMP_GE_OQ>(value, zero));
        }
        let hits = _mm256_movemask_ps(inside) as u32;
        let within = _mm256_cmp_ps::<_CMP_LE_OQ>(t, _mm256_loadu_ps(t_max.as_ptr()));
        let near = _mm256_movemask_ps(_mm256_and_ps(inside, within)) as u32;
        if near != 0 {
            _mm256_storeu_ps(hit.as_mut_ptr(), _mm256_blendv_ps(far, t, inside));
        }
        (hit, ranged, hits, near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{Count, NoCount};
    use crate::nff::parse_nff;
    use crate::vec3::Vec3;

    fn scene(body: &str) -> Scene {
        let text = format!(
            "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 4 4\n\
             f 1 1 1 1 0 1 0 1\n{body}"
        );
        parse_nff(&text, "t.nff").unwrap_or_else(|e| panic!("{e}"))
    }

    fn pack_of(scene: &Scene) -> (TrianglePack, u32) {
        let (_, pieces) = items(scene);
        let triangles: Vec<Triangle> = pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Triangle(t) => Some(*t),
                Piece::Whole(_) => None,
            })
            .collect();
        (TrianglePack::new(&triangles), triangles.len() as u32)
    }

    /// The nearest lane that hits (the first of equal ones), as `(t, lane)`.
    fn nearest(lanes: Option<[f32; WIDTH]>) -> Option<(f32, usize)> {
        let lanes = lanes?;
        let (lane, &t) = lanes
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1).then(a.0.cmp(&b.0)))?;
        t.is_finite().then_some((t, lane))
    }

    /// The pack's closest hit on the portable path, checked equal to the AVX2 path's
    /// where the CPU has it.
    fn both(pack: &TrianglePack, ray: &Ray) -> Option<(f32, usize)> {
        let test = |avx2| {
            nearest(triangle_pack(
                pack,
                ray,
                0.0,
                f32::INFINITY,
                avx2,
                &mut NoCount,
            ))
        };
        let portable = test(false);
        if crate::accel::cpu_has_avx2_fma() {
            assert_eq!(test(true), portable, "{ray:?}");
        }
        portable
    }

    fn down(x: f32, y: f32) -> Ray {
        Ray {
            origin: Vec3::new(x, y, 10.0),
            dir: Vec3::new(0.0, 0.0, -1.0),
        }
    }

    #[test]
    fn a_concave_u_is_hit_exactly_where_the_crossing_test_hits_it() {
        // The U of `triangulate`'s test, at z = 1: 6 triangles.
        let s = scene("p 8\n0 0 1\n3 0 1\n3 3 1\n2 3 1\n2 1 1\n1 1 1\n1 3 1\n0 3 1\n");
        let (pack, live) = pack_of(&s);
        assert_eq!(live, 6);
        let polygon = &s.polygons[0];
        let mut grid_hits = 0;
        // A grid over the U and around it, offset from every vertex and diagonal.
        for i in 0..40 {
            for j in 0..40 {
                let (x, y) = (-0.5 + 0.1 * i as f32 + 0.013, -0.5 + 0.1 * j as f32 + 0.007);
                let ray = down(x, y);
                let lanes = both(&pack, &ray);
                let whole = polygon.intersect(&ray, 0.0, f32::INFINITY, &mut NoCount);
                assert_eq!(lanes.map(|(t, _)| t), whole, "({x}, {y})");
                grid_hits += usize::from(whole.is_some());
            }
        }
        // 7 of the 16 square units around it: about 7 / 0.01 grid points.
        assert!((690..=710).contains(&grid_hits), "{grid_hits}");
    }

    #[test]
    fn rays_through_a_diagonal_never_slip_between_its_triangles() {
        // A skewed quad; rays straight down the diagonal from (0,0) to (2,3), many
        // points along it: each hits one triangle or both, never neither.
        let s = scene("p 4\n0 0 0\n4 0.5 0\n2 3 0\n-1 2 0\n");
        let (pack, live) = pack_of(&s);
        assert_eq!(live, 2);
        for k in 1..1000 {
            let f = k as f32 / 1000.0;
            let ray = down(2.0 * f, 3.0 * f);
            let hit = both(&pack, &ray);
            assert_eq!(hit.map(|(t, _)| t), Some(10.0), "{f}");
        }
    }

    #[test]
    fn a_pack_counts_its_live_lanes_and_the_plane_hits_hand_computed() {
        // Two triangles at z = 0 and one facing sideways (its plane parallel to the ray).
        let s =
            scene("p 3\n0 0 0\n1 0 0\n0 1 0\np 3\n2 0 0\n3 0 0\n2 1 0\np 3\n5 0 0\n5 1 0\n5 0 1\n");
        let (pack, live) = pack_of(&s);
        assert_eq!(live, 3);
        let mut c = Count::default();
        let hit = nearest(triangle_pack(
            &pack,
            &down(0.25, 0.25),
            0.0,
            f32::INFINITY,
            crate::accel::cpu_has_avx2_fma(),
            &mut c,
        ));
        assert_eq!(hit, Some((10.0, 0)));
        // 3 live lanes: 3 tests, 3 `sub`, 6 `dot`; 2 planes in range (the third is
        // parallel): 2 `scale`, 2 `add`, 6 more `dot`; 1 triangle holds the point.
        assert_eq!(
            [
                Stat::TriangleTest,
                Stat::Sub,
                Stat::Dot,
                Stat::Scale,
                Stat::Add,
                Stat::TriangleHit,
                Stat::LanesIssued,
                Stat::LanesActive
            ]
            .map(|s| c.get(s)),
            [3, 3, 12, 2, 2, 1, 8, 3]
        );
    }

    #[test]
    fn a_triangle_against_rays_in_lanes_gives_each_pairs_distance_bit_for_bit() {
        // The U's 6 triangles (z = 1) and rays of one origin and of many, some out of
        // reach: each ray-triangle pair as in the pack's lanes, on both code paths.
        let s = scene("p 8\n0 0 1\n3 0 1\n3 3 1\n2 3 1\n2 1 1\n1 1 1\n1 3 1\n0 3 1\n");
        let (pack, live) = pack_of(&s);
        let mut compared = [0u32; 2];
        for k in 0..40 {
            let rays: Vec<Ray> = (0..WIDTH)
                .map(|r| {
                    let (x, y) = (
                        -0.4 + 0.1 * (k + 3 * r) as f32,
                        0.05 + 0.13 * (k % 23) as f32,
                    );
                    let origin = if k % 2 == 0 {
                        Vec3::new(1.5, 1.5, 9.0)
                    } else {
                        Vec3::new(x, y, 10.0 - r as f32)
                    };
                    let d = NoCount.sub(Vec3::new(x, y, 1.0), origin);
                    Ray {
                        origin,
                        dir: NoCount.normalize(d),
                    }
                })
                .collect();
            let in_lanes = RayLanes::of::<false, false>(&rays);
            let reach: [f32; WIDTH] = std::array::from_fn(|r| [f32::INFINITY, 8.5, 3.0][r % 3]);
            let t_max: [f32; WIDTH] = std::array::from_fn(|r| reach[r] - 0.5 * (r % 2) as f32);
            for i in 0..live as usize {
                let (t, ranged, inside) = triangle_rays(&pack, i, &in_lanes, 0.0, &reach);
                for (r, ray) in rays.iter().enumerate() {
                    let (pack_t, pack_ranged, pack_inside) = lanes(&pack, ray, 0.0, reach[r]);
                    assert_eq!(t[r].to_bits(), pack_t[i].to_bits(), "{k} {i} {r}");
                    assert_eq!(ranged >> r & 1, pack_ranged >> i & 1, "{k} {i} {r}");
                    assert_eq!(inside >> r & 1, pack_inside >> i & 1, "{k} {i} {r}");
                    compared[usize::from(inside >> r & 1 == 1)] += 1;
                }
                #[cfg(target_arch = "x86_64")]
                if crate::accel::cpu_has_avx2_fma() {
                    // SAFETY: the CPU has AVX2.
                    let (wide_t, wide_ranged, wide_inside, near) =
                        unsafe { triangle_rays_avx2(&pack, i, &in_lanes, 0.0, &reach, &t_max) };
                    assert_eq!((wide_ranged, wide_inside), (ranged, inside));
                    let mut expected = 0;
                    for r in 0..WIDTH {
                        expected |= u32::from(inside >> r & 1 == 1 && t[r] <= t_max[r]) << r;
                        if near != 0 {
                            assert_eq!(wide_t[r].to_bits(), t[r].to_bits());
                        }
                    }
                    assert_eq!(near, expected);
                }
            }
        }
        // Hits and misses both compared in numbers.
        assert!(compared[0] > 1000 && compared[1] > 100, "{compared:?}");
    }

    #[test]
    fn a_self_intersecting_outline_stays_whole() {
        let s = scene("p 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n");
        let (_, pieces) = items(&s);
        assert_eq!(
            pieces,
            vec![Piece::Whole(PrimRef {
                kind: PrimKind::Polygon,
                index: 0
            })]
        );
    }
}

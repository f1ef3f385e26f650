//! A packet's bounds (Embree's coherent packet traversal): one box test of a node's
//! children against bounds that hold every ray of the packet, instead of one per ray.
//! The coherent traversal of eye-ray packets ([`super::packet`]) walks the tree with it;
//! only a leaf's rays are then told apart ([`Frustum::rays_entering`]: the packet's
//! rays against one box, a ray per lane).
//!
//! Why the bounds hold every ray: with each axis turned so that the packet's directions
//! point up it (all rays share the octant, or the packet has no frustum), a ray's
//! entry on an axis is `(lo - o) × r` with `r = 1/d > 0`. Over the packet's origins
//! `o ≤ o_max` and reciprocals `r_min ≤ r ≤ r_max`, `(lo - o_max) × (r_min if lo -
//! o_max ≥ 0 else r_max)` is no larger, and rounding keeps the order (a rounded
//! difference or product is monotone in each operand); the exit likewise is no
//! smaller. A ray that enters a box has entry ≤ exit, so the bounds' entry ≤ exit too,
//! and the bounds' entry is no later than any ray's: a child the bounds miss is missed
//! by every ray, and a child waiting at the bounds' entry can be dropped for a ray
//! whose reach ends before it.

use super::node::{WIDTH, WideNode};
use super::ray_lanes::RayLanes;

/// Rays in one packet step: one per lane.
pub(super) const LANES: usize = 8;

/// The bounds of a packet's origins and reciprocal directions, each axis turned so that
/// the directions point up it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frustum {
    /// Per axis: whether the packet's directions point down it (the axis is turned).
    down: [bool; 3],
    /// Per axis, turned: the largest and smallest origin, the smallest and largest
    /// reciprocal direction.
    origin_max: [f32; 3],
    origin_min: [f32; 3],
    inv_min: [f32; 3],
    inv_max: [f32; 3],
}

impl Frustum {
    /// The frustum of `rays` when they start at one point (eye rays of a pinhole) and
    /// share one octant; `None` otherwise, or when a direction has a zero component (an
    /// infinite reciprocal): then the bounds could not be formed. Unused lanes repeat
    /// the first ray, so the bounds may be taken over all lanes. On the code path
    /// `AVX2` names.
    #[inline(always)]
    pub(super) fn of_one_origin<const AVX2: bool>(rays: &RayLanes) -> Option<Frustum> {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            // SAFETY: `AVX2` is set only on CPUs with AVX2 (see `packet_search_avx2`).
            return unsafe { Self::of_one_origin_avx2(rays) };
        }
        if !rays.one_origin() {
            return None;
        }
        let mut f = Frustum {
            down: [false; 3],
            origin_max: [0.0; 3],
            origin_min: [0.0; 3],
            inv_min: [0.0; 3],
            inv_max: [0.0; 3],
        };
        for axis in 0..3 {
            let down = rays.inv_dir[axis][0] < 0.0;
            let sign = if down { -1.0 } else { 1.0 };
            // Turned: -o and -r are exact, so the turned products are the rays' own
            // with their sign flipped.
            let mut o = [0.0f32; LANES];
            let mut r = [0.0f32; LANES];
            let mut usable = true;
            for lane in 0..LANES {
                o[lane] = sign * rays.origin[axis][lane];
                r[lane] = sign * rays.inv_dir[axis][lane];
                usable &= (r[lane] > 0.0) & (r[lane] < f32::INFINITY);
            }
            if !usable {
                return None;
            }
            f.down[axis] = down;
            (f.origin_min[axis], f.origin_max[axis]) = extent(&o);
            (f.inv_min[axis], f.inv_max[axis]) = extent(&r);
        }
        Some(f)
    }

    /// [`Frustum::of_one_origin`] in AVX instructions (the same compares, turned values
    /// and extents: `vminps`/`vmaxps` of finite positive values are the scalar ones).
    /// The origins are one point, so its turned coordinates are both their least and
    /// greatest.
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn of_one_origin_avx2(rays: &RayLanes) -> Option<Frustum> {
        use std::arch::x86_64::{
            __m256, _CMP_EQ_OQ, _CMP_GT_OQ, _CMP_LT_OQ, _mm_cvtss_f32, _mm_max_ps, _mm_min_ps,
            _mm_movehdup_ps, _mm_movehl_ps, _mm256_and_ps, _mm256_castps256_ps128, _mm256_cmp_ps,
            _mm256_extractf128_ps, _mm256_load_ps, _mm256_movemask_ps, _mm256_mul_ps,
            _mm256_set1_ps, _mm256_setzero_ps,
        };
        // SAFETY: the caller guarantees AVX; the rows are 32-byte aligned, 8 floats.
        unsafe {
            let mut f = Frustum {
                down: [false; 3],
                origin_max: [0.0; 3],
                origin_min: [0.0; 3],
                inv_min: [0.0; 3],
                inv_max: [0.0; 3],
            };
            // Macros, not closures: a closure would not inherit the caller's AVX.
            macro_rules! reduce {
                ($v:expr, $op:ident) => {{
                    let v: __m256 = $v;
                    let half = $op(_mm256_castps256_ps128(v), _mm256_extractf128_ps::<1>(v));
                    let quarter = $op(half, _mm_movehl_ps(half, half));
                    _mm_cvtss_f32($op(quarter, _mm_movehdup_ps(quarter)))
                }};
            }
            let mut same = true;
            for axis in 0..3 {
                let first = rays.origin[axis][0];
                let o = _mm256_load_ps(rays.origin[axis].as_ptr());
                same &= _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(o, _mm256_set1_ps(first)))
                    == 0xFF;
                let down = rays.inv_dir[axis][0] < 0.0;
                let sign = if down { -1.0 } else { 1.0 };
                let r = _mm256_mul_ps(
                    _mm256_set1_ps(sign),
                    _mm256_load_ps(rays.inv_dir[axis].as_ptr()),
                );
                let usable = _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GT_OQ>(r, _mm256_setzero_ps()),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(r, _mm256_set1_ps(f32::INFINITY)),
                );
                if _mm256_movemask_ps(usable) != 0xFF {
                    return None;
                }
                f.down[axis] = down;
                (f.origin_min[axis], f.origin_max[axis]) = (sign * first, sign * first);
                (f.inv_min[axis], f.inv_max[axis]) =
                    (reduce!(r, _mm_min_ps), reduce!(r, _mm_max_ps));
            }
            same.then_some(f)
        }
    }

    /// The children the bounds may enter within `(t_min, reach)` (bit per child) and
    /// the bounds' entry distance into each (no later than any ray's), on the code
    /// path `AVX2` names.
    #[inline(always)]
    pub(super) fn children<const AVX2: bool>(
        &self,
        node: &WideNode,
        t_min: f32,
        reach: f32,
    ) -> (u32, [f32; WIDTH]) {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            // SAFETY: `AVX2` is set only on CPUs with AVX2 (see `packet_search_avx2`).
            return unsafe { self.bounds_step_avx2(node, t_min, reach) };
        }
        self.bounds_step(node, t_min, reach)
    }

    /// The rays in `rays` that enter child `child`'s box within their own reach (bit
    /// per ray) and the nearest entry among them, on the code path `AVX2` names: the
    /// single-ray slab test's arithmetic, so the same rays as each ray's own test.
    #[inline(always)]
    pub(super) fn rays_entering<const AVX2: bool>(
        rays_lanes: &RayLanes,
        node: &WideNode,
        child: usize,
        rays: u32,
        t_min: f32,
        t_max: &[f32; LANES],
    ) -> (u32, f32) {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            // SAFETY: as in `children`.
            return unsafe { Self::rays_step_avx2(rays_lanes, node, child, rays, t_min, t_max) };
        }
        Self::rays_step(rays_lanes, node, child, rays, t_min, t_max)
    }

    /// The children the bounds may enter within `(t_min, reach)` (bit per child).
    #[inline(always)]
    fn bounds_step(&self, node: &WideNode, t_min: f32, reach: f32) -> (u32, [f32; WIDTH]) {
        let mut near = [t_min; WIDTH];
        let mut far = [reach; WIDTH];
        for axis in 0..3 {
            let (lo, hi) = if self.down[axis] {
                (&node.bounds[3 + axis], &node.bounds[axis])
            } else {
                (&node.bounds[axis], &node.bounds[3 + axis])
            };
            let sign = if self.down[axis] { -1.0 } else { 1.0 };
            let (o_max, o_min) = (self.origin_max[axis], self.origin_min[axis]);
            let (r_min, r_max) = (self.inv_min[axis], self.inv_max[axis]);
            for i in 0..WIDTH {
                let (lo, hi) = (sign * lo[i], sign * hi[i]);
                let enter = lo - o_max;
                let leave = hi - o_min;
                let t0 = enter * if enter >= 0.0 { r_min } else { r_max };
                let t1 = leave * if leave >= 0.0 { r_max } else { r_min };
                near[i] = if t0 > near[i] { t0 } else { near[i] };
                far[i] = if t1 < far[i] { t1 } else { far[i] };
            }
        }
        let mut mask = 0u32;
        for i in 0..WIDTH {
            mask |= u32::from(near[i] <= far[i]) << i;
        }
        (mask & node.used, near)
    }

    /// The rays in `rays` that enter child `child`'s box (bit per ray) and the nearest
    /// entry among them: [`Slab::test`](super::node::Slab::test)'s arithmetic, a ray per
    /// lane.
    #[inline(always)]
    fn rays_step(
        lanes: &RayLanes,
        node: &WideNode,
        child: usize,
        rays: u32,
        t_min: f32,
        t_max: &[f32; LANES],
    ) -> (u32, f32) {
        let mut near = [t_min; LANES];
        let mut far = *t_max;
        for axis in 0..3 {
            let (lo, hi) = (node.bounds[axis][child], node.bounds[3 + axis][child]);
            let (o, inv) = (&lanes.origin[axis], &lanes.inv_dir[axis]);
            for r in 0..LANES {
                let t0 = (lo - o[r]) * inv[r];
                let t1 = (hi - o[r]) * inv[r];
                // `max(min(t0, t1), near)` and `min(max(t0, t1), far)` with the x86
                // rule (a NaN first operand gives the second), as `Slab::test`.
                let small = if t0 < t1 { t0 } else { t1 };
                let large = if t0 > t1 { t0 } else { t1 };
                near[r] = if small > near[r] { small } else { near[r] };
                far[r] = if large < far[r] { large } else { far[r] };
            }
        }
        let mut set = 0u32;
        let mut nearest = f32::INFINITY;
        for r in 0..LANES {
            let inside = near[r] <= far[r] && rays & (1 << r) != 0;
            set |= u32::from(inside) << r;
            let t = if inside { near[r] } else { f32::INFINITY };
            nearest = if t < nearest { t } else { nearest };
        }
        (set, nearest)
    }

    /// [`Frustum::bounds_step`] in AVX instructions (`vmaxps`/`vminps` keep the
    /// scalar code's choice, so both find the same children).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn bounds_step_avx2(
        &self,
        node: &WideNode,
        t_min: f32,
        reach: f32,
    ) -> (u32, [f32; WIDTH]) {
        use std::arch::x86_64::{
            _CMP_GE_OQ, _CMP_LE_OQ, _mm256_blendv_ps, _mm256_cmp_ps, _mm256_load_ps, _mm256_max_ps,
            _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setzero_ps,
            _mm256_storeu_ps, _mm256_sub_ps,
        };
        // SAFETY: the caller guarantees AVX; the node's rows are 32-byte aligned.
        unsafe {
            let zero = _mm256_setzero_ps();
            let mut near = _mm256_set1_ps(t_min);
            let mut far = _mm256_set1_ps(reach);
            for axis in 0..3 {
                let (lo, hi) = if self.down[axis] {
                    let neg = _mm256_set1_ps(-1.0);
                    (
                        _mm256_mul_ps(neg, _mm256_load_ps(node.bounds[3 + axis].as_ptr())),
                        _mm256_mul_ps(neg, _mm256_load_ps(node.bounds[axis].as_ptr())),
                    )
                } else {
                    (
                        _mm256_load_ps(node.bounds[axis].as_ptr()),
                        _mm256_load_ps(node.bounds[3 + axis].as_ptr()),
                    )
                };
                let enter = _mm256_sub_ps(lo, _mm256_set1_ps(self.origin_max[axis]));
                let leave = _mm256_sub_ps(hi, _mm256_set1_ps(self.origin_min[axis]));
                let (r_min, r_max) = (
                    _mm256_set1_ps(self.inv_min[axis]),
                    _mm256_set1_ps(self.inv_max[axis]),
                );
                let r_enter =
                    _mm256_blendv_ps(r_max, r_min, _mm256_cmp_ps::<_CMP_GE_OQ>(enter, zero));
                let r_leave =
                    _mm256_blendv_ps(r_min, r_max, _mm256_cmp_ps::<_CMP_GE_OQ>(leave, zero));
                near = _mm256_max_ps(_mm256_mul_ps(enter, r_enter), near);
                far = _mm256_min_ps(_mm256_mul_ps(leave, r_leave), far);
            }
            let inside = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
            let mut t = [0.0f32; WIDTH];
            _mm256_storeu_ps(t.as_mut_ptr(), near);
            (inside & node.used, t)
        }
    }

    /// [`Frustum::rays_step`] in AVX instructions, the same arithmetic as
    /// `Slab::near_inside_avx2` with a ray per lane.
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn rays_step_avx2(
        lanes: &RayLanes,
        node: &WideNode,
        child: usize,
        rays: u32,
        t_min: f32,
        t_max: &[f32; LANES],
    ) -> (u32, f32) {
        use std::arch::x86_64::{
            _CMP_LE_OQ, _mm_cvtss_f32, _mm_min_ps, _mm_min_ss, _mm_movehdup_ps, _mm_movehl_ps,
            _mm256_blendv_ps, _mm256_castps256_ps128, _mm256_cmp_ps, _mm256_extractf128_ps,
            _mm256_load_ps, _mm256_loadu_ps, _mm256_max_ps, _mm256_min_ps, _mm256_movemask_ps,
            _mm256_mul_ps, _mm256_set1_ps, _mm256_sub_ps,
        };
        // SAFETY: the caller guarantees AVX; the frustum's rows are 32-byte aligned and
        // `t_max` is 8 floats long.
        unsafe {
            let mut near = _mm256_set1_ps(t_min);
            let mut far = _mm256_loadu_ps(t_max.as_ptr());
            for axis in 0..3 {
                let lo = _mm256_set1_ps(node.bounds[axis][child]);
                let hi = _mm256_set1_ps(node.bounds[3 + axis][child]);
                let o = _mm256_load_ps(lanes.origin[axis].as_ptr());
                let inv = _mm256_load_ps(lanes.inv_dir[axis].as_ptr());
                let t0 = _mm256_mul_ps(_mm256_sub_ps(lo, o), inv);
                let t1 = _mm256_mul_ps(_mm256_sub_ps(hi, o), inv);
                near = _mm256_max_ps(_mm256_min_ps(t0, t1), near);
                far = _mm256_min_ps(_mm256_max_ps(t0, t1), far);
            }
            let inside = _mm256_cmp_ps::<_CMP_LE_OQ>(near, far);
            let set = _mm256_movemask_ps(inside) as u32 & rays;
            if set == 0 {
                return (0, f32::INFINITY);
            }
            // The nearest entry of the rays in `set` (others +inf).
            let in_set = _mm256_load_ps(LANE_MASKS[set as usize].0.as_ptr());
            let t = _mm256_blendv_ps(_mm256_set1_ps(f32::INFINITY), near, in_set);
            let half = _mm_min_ps(_mm256_castps256_ps128(t), _mm256_extractf128_ps::<1>(t));
            let quarter = _mm_min_ps(half, _mm_movehl_ps(half, half));
            let one = _mm_min_ss(quarter, _mm_movehdup_ps(quarter));
            (set, _mm_cvtss_f32(one))
        }
    }
}

/// The least and greatest of `lanes`, in halving steps (which compile to lane
/// operations; a running minimum would be a chain of scalar compares).
#[inline(always)]
fn extent(lanes: &[f32; LANES]) -> (f32, f32) {
    let min = |a: f32, b: f32| if a < b { a } else { b };
    let max = |a: f32, b: f32| if a > b { a } else { b };
    let (mut lo, mut hi) = (*lanes, *lanes);
    let mut width = LANES / 2;
    while width > 0 {
        for i in 0..width {
            lo[i] = min(lo[i], lo[i + width]);
            hi[i] = max(hi[i], hi[i + width]);
        }
        width /= 2;
    }
    (lo[0], hi[0])
}

/// For each set of rays (bit per lane), lanes with all bits set where the ray is in it.
#[cfg(target_arch = "x86_64")]
static LANE_MASKS: [AlignedLanes; 256] = {
    let mut masks = [AlignedLanes([0.0; LANES]); 256];
    let mut set = 0;
    while set < 256 {
        let mut lane = 0;
        while lane < LANES {
            if set & (1 << lane) != 0 {
                masks[set].0[lane] = f32::from_bits(u32::MAX);
            }
            lane += 1;
        }
        set += 1;
    }
    masks
};

/// Eight lanes, 32-byte aligned for an aligned load.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
#[repr(C, align(32))]
struct AlignedLanes([f32; LANES]);

#[cfg(test)]
mod tests {
    use super::super::tests::rays;
    use super::*;
    use crate::ray::Ray;
    use crate::vec3::Vec3;

    /// The frustum's fields, bit for bit (`None` when it has none).
    fn bits(f: Option<Frustum>) -> Option<([bool; 3], [[u32; 3]; 4])> {
        f.map(|f| {
            let b = |v: [f32; 3]| v.map(f32::to_bits);
            (
                f.down,
                [b(f.origin_min), b(f.origin_max), b(f.inv_min), b(f.inv_max)],
            )
        })
    }

    #[test]
    fn a_frustum_is_formed_for_one_origin_and_octant_the_same_on_both_code_paths() {
        // The shared test rays (mixed origins and octants, zero components) as they
        // are, and again from one origin; packets of every length.
        let mixed = rays();
        let one_origin: Vec<Ray> = mixed
            .iter()
            .map(|r| Ray {
                origin: Vec3::new(0.5, -7.0, 2.0),
                dir: r.dir,
            })
            .collect();
        let avx2 = crate::accel::cpu_has_avx2_fma();
        let (mut formed, mut refused) = (0, 0);
        for all in [&mixed, &one_origin] {
            for n in 1..=LANES {
                for start in 0..all.len().saturating_sub(n) {
                    let group = &all[start..start + n];
                    let lanes = RayLanes::of::<false, false>(group);
                    let scalar = Frustum::of_one_origin::<false>(&lanes);
                    // Formed exactly when the rays share the first one's origin and the
                    // signs of its direction, with no zero component.
                    let first = group[0];
                    let expected = group.iter().all(|r| {
                        r.origin == first.origin
                            && (0..3).all(|a| {
                                let (d, d0) = (r.dir.to_array()[a], first.dir.to_array()[a]);
                                d != 0.0 && (d < 0.0) == (d0 < 0.0)
                            })
                    });
                    assert_eq!(scalar.is_some(), expected, "{group:?}");
                    if avx2 {
                        // SAFETY: the CPU has AVX2 (checked above).
                        let avx = unsafe { Frustum::of_one_origin_avx2(&lanes) };
                        assert_eq!(bits(avx), bits(scalar), "{group:?}");
                    }
                    formed += usize::from(scalar.is_some());
                    refused += usize::from(scalar.is_none());
                }
            }
        }
        // Both answers were compared in numbers.
        assert!(
            formed > 50 && refused > 50,
            "{formed} formed, {refused} refused"
        );
    }
}

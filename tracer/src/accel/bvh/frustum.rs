//! A packet's bound and its rays in lanes (variant `packets`): the node step of a
//! coherent packet, SIMD across rays.
//!
//! Where every ray of a packet goes the same way along each axis (finite inverse
//! directions of one sign), the packet is bounded per axis by the interval of its
//! origins and that of its inverse directions (the interval traversal of Benthin et al.
//! 2012, the frustum test of Embree's coherent packets). One lane step tests a node's
//! children against that bound: a child no ray of the packet can enter is culled for
//! all of them at once. Each child that survives is then tested against the packet's
//! rays, one ray per lane, with the single ray's slab arithmetic, so the rays that enter
//! it and where are the same bit for bit as with one step per ray.
//!
//! The bound never culls a child a ray enters: float subtraction and multiplication
//! round monotonically, so the bound's corner products (no NaN: all finite but the
//! boxes' infinities) bracket every ray's slab distances as computed.

use super::packet::PACKET;
use super::wide::{Slab, WideNode, max_or_second, min_or_second};
use crate::accel::BVH_WIDTH as WIDTH;

/// A coherent packet's rays in lanes (structure of arrays) and its bound per axis.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(super) struct Frustum {
    /// Each ray's origin and inverse direction per axis, one lane per ray (lanes past
    /// the packet repeat its first ray; the ray sets mask them out).
    origin: [[f32; PACKET]; 3],
    inv_dir: [[f32; PACKET]; 3],
    /// Per axis, the row of a node's bounds the rays enter by (the minimum for a
    /// positive direction, the maximum for a negative one), and the origin bound that
    /// gives the earliest entry (the farthest origin along the direction).
    near_row: [usize; 3],
    near_origin: [f32; 3],
    /// Per axis, the row the rays leave by and the origin bound of the latest exit.
    far_row: [usize; 3],
    far_origin: [f32; 3],
    /// Per axis, the smallest and largest inverse direction.
    inv_lo: [f32; 3],
    inv_hi: [f32; 3],
}

impl Frustum {
    /// The bound of the rays with these slab constants (at most [`PACKET`], at least
    /// one), or `None` when along some axis a ray is parallel to it (an infinite inverse
    /// direction) or the rays go both ways.
    #[inline(always)]
    pub(super) fn of(slabs: &[Slab]) -> Option<Frustum> {
        let first = slabs.first()?;
        let mut origin = [[0.0; PACKET]; 3];
        let mut inv_dir = [[0.0; PACKET]; 3];
        for lane in 0..PACKET {
            let slab = if lane < slabs.len() {
                &slabs[lane]
            } else {
                first
            };
            for axis in 0..3 {
                origin[axis][lane] = slab.origin[axis];
                inv_dir[axis][lane] = slab.inv_dir[axis];
            }
        }
        let mut f = Frustum {
            origin,
            inv_dir,
            near_row: [0; 3],
            near_origin: [0.0; 3],
            far_row: [0; 3],
            far_origin: [0.0; 3],
            inv_lo: [0.0; 3],
            inv_hi: [0.0; 3],
        };
        for axis in 0..3 {
            let (o, inv) = (&f.origin[axis], &f.inv_dir[axis]);
            let (mut o_lo, mut o_hi) = (o[0], o[0]);
            let (mut i_lo, mut i_hi) = (inv[0], inv[0]);
            // Plain comparisons: a NaN or an infinity fails the check below.
            let mut finite = true;
            for lane in 0..PACKET {
                o_lo = if o[lane] < o_lo { o[lane] } else { o_lo };
                o_hi = if o[lane] > o_hi { o[lane] } else { o_hi };
                i_lo = if inv[lane] < i_lo { inv[lane] } else { i_lo };
                i_hi = if inv[lane] > i_hi { inv[lane] } else { i_hi };
                finite &= (o[lane] - o[lane] == 0.0) & (inv[lane] - inv[lane] == 0.0);
            }
            // One sign per axis: both ends of the interval on the same side of 0.
            if !finite || !((i_lo > 0.0) | (i_hi < 0.0)) {
                return None;
            }
            let negative = i_hi < 0.0;
            // Entry at (near plane - origin) / dir: earliest from the origin nearest
            // that plane; exit latest from the origin farthest from the far plane.
            (f.near_row[axis], f.near_origin[axis]) = if negative {
                (3 + axis, o_lo)
            } else {
                (axis, o_hi)
            };
            (f.far_row[axis], f.far_origin[axis]) = if negative {
                (axis, o_hi)
            } else {
                (3 + axis, o_lo)
            };
            (f.inv_lo[axis], f.inv_hi[axis]) = (i_lo, i_hi);
        }
        Some(f)
    }

    /// The children of `node` (bit per lane) that a ray of the packet may enter within
    /// `(t_min, t_far)`, `t_far` the largest reach of the packet's rays: never fewer
    /// than those a ray enters; and per child a distance no ray enters it before.
    /// Computed lane by lane.
    #[inline(always)]
    pub(super) fn cull(&self, node: &WideNode, t_min: f32, t_far: f32) -> (u32, [f32; WIDTH]) {
        let mut near = [t_min; WIDTH];
        let mut far = [t_far; WIDTH];
        for axis in 0..3 {
            let (lo, hi) = (self.inv_lo[axis], self.inv_hi[axis]);
            let enter = &node.bounds[self.near_row[axis]];
            let leave = &node.bounds[self.far_row[axis]];
            for i in 0..WIDTH {
                let d = enter[i] - self.near_origin[axis];
                near[i] = near[i].max((d * lo).min(d * hi));
                let d = leave[i] - self.far_origin[axis];
                far[i] = far[i].min((d * lo).max(d * hi));
            }
        }
        let mut mask = 0u32;
        for i in 0..WIDTH {
            mask |= u32::from(near[i] <= far[i]) << i;
        }
        (mask & node.used, near)
    }

    /// [`Frustum::cull`] in AVX instructions (no NaN arises, so `vminps`/`vmaxps` give
    /// what `f32::min`/`max` give).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub(super) unsafe fn cull_avx2(
        &self,
        node: &WideNode,
        t_min: f32,
        t_far: f32,
    ) -> (u32, [f32; WIDTH]) {
        use std::arch::x86_64::{
            _CMP_LE_OQ, _mm256_cmp_ps, _mm256_load_ps, _mm256_max_ps, _mm256_min_ps,
            _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_storeu_ps, _mm256_sub_ps,
        };
        // SAFETY: the caller guarantees AVX; the rows are 32-byte aligned (a 64-byte
        // aligned node of 32-byte rows) and 8 floats long.
        unsafe {
            let mut near = _mm256_set1_ps(t_min);
            let mut far = _mm256_set1_ps(t_far);
            for axis in 0..3 {
                let lo = _mm256_set1_ps(self.inv_lo[axis]);
                let hi = _mm256_set1_ps(self.inv_hi[axis]);
                let enter = _mm256_load_ps(node.bounds[self.near_row[axis]].as_ptr());
                let d = _mm256_sub_ps(enter, _mm256_set1_ps(self.near_origin[axis]));
                let t = _mm256_min_ps(_mm256_mul_ps(d, lo), _mm256_mul_ps(d, hi));
                near = _mm256_max_ps(near, t);
                let leave = _mm256_load_ps(node.bounds[self.far_row[axis]].as_ptr());
                let d = _mm256_sub_ps(leave, _mm256_set1_ps(self.far_origin[axis]));
                let t = _mm256_max_ps(_mm256_mul_ps(d, lo), _mm256_mul_ps(d, hi));
                far = _mm256_min_ps(far, t);
            }
            let inside = _mm256_cmp_ps::<_CMP_LE_OQ>(near, far);
            let mut t = [0.0f32; WIDTH];
            _mm256_storeu_ps(t.as_mut_ptr(), near);
            (_mm256_movemask_ps(inside) as u32 & node.used, t)
        }
    }

    /// The rays in `rays` (bit per ray) that enter child `lane` of `node` within
    /// `(t_min, t_max[ray])`, and the nearest entry among them (infinite when none):
    /// ray by ray the arithmetic of [`Slab::test`].
    #[inline(always)]
    pub(super) fn rays_entering(
        &self,
        node: &WideNode,
        lane: usize,
        rays: u32,
        t_min: f32,
        t_max: &[f32; PACKET],
    ) -> (u32, f32) {
        let mut set = 0u32;
        let mut nearest = f32::INFINITY;
        let mut bits = rays;
        while bits != 0 {
            let r = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let mut near = t_min;
            let mut far = t_max[r];
            for axis in 0..3 {
                let (o, inv) = (self.origin[axis][r], self.inv_dir[axis][r]);
                let t0 = (node.bounds[axis][lane] - o) * inv;
                let t1 = (node.bounds[3 + axis][lane] - o) * inv;
                near = max_or_second(min_or_second(t0, t1), near);
                far = min_or_second(max_or_second(t0, t1), far);
            }
            if near <= far {
                set |= 1 << r;
                nearest = nearest.min(near);
            }
        }
        (set, nearest)
    }

    /// [`Frustum::rays_entering`] in AVX instructions, a ray per lane (the operations
    /// and operand order of the single ray's AVX slab test, so the same results).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub(super) unsafe fn rays_entering_avx2(
        &self,
        node: &WideNode,
        lane: usize,
        rays: u32,
        t_min: f32,
        t_max: &[f32; PACKET],
    ) -> (u32, f32) {
        use std::arch::x86_64::{
            _CMP_LE_OQ, _mm_cvtss_f32, _mm_min_ps, _mm_movehl_ps, _mm_shuffle_ps, _mm256_and_si256,
            _mm256_blendv_ps, _mm256_castps256_ps128, _mm256_castsi256_ps, _mm256_cmp_ps,
            _mm256_cmpeq_epi32, _mm256_extractf128_ps, _mm256_load_ps, _mm256_loadu_ps,
            _mm256_max_ps, _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_epi32,
            _mm256_set1_ps, _mm256_setr_epi32, _mm256_sub_ps,
        };
        // SAFETY: the caller guarantees AVX (AVX2 for the integer compare: the callers
        // run only where the CPU has AVX2); the rows are 32-byte aligned (an aligned
        // struct of 32-byte rows) and every load reads 8 floats.
        unsafe {
            let mut near = _mm256_set1_ps(t_min);
            let mut far = _mm256_loadu_ps(t_max.as_ptr());
            for axis in 0..3 {
                let o = _mm256_load_ps(self.origin[axis].as_ptr());
                let inv = _mm256_load_ps(self.inv_dir[axis].as_ptr());
                let lo = _mm256_set1_ps(node.bounds[axis][lane]);
                let hi = _mm256_set1_ps(node.bounds[3 + axis][lane]);
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
            // The nearest entry of the rays in the set: the others' lanes at +inf.
            let bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            let chosen =
                _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(set as i32), bit), bit);
            let t = _mm256_blendv_ps(
                _mm256_set1_ps(f32::INFINITY),
                near,
                _mm256_castsi256_ps(chosen),
            );
            let half = _mm_min_ps(_mm256_castps256_ps128(t), _mm256_extractf128_ps::<1>(t));
            let pair = _mm_min_ps(half, _mm_movehl_ps(half, half));
            let one = _mm_min_ps(pair, _mm_shuffle_ps::<0b01>(pair, pair));
            (set, _mm_cvtss_f32(one))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::cpu_has_avx2_fma;

    /// A node whose children are the given boxes (`[min, max]` corners).
    fn node(boxes: &[([f32; 3], [f32; 3])]) -> WideNode {
        let mut n = WideNode::UNUSED;
        for (lane, (lo, hi)) in boxes.iter().enumerate() {
            for axis in 0..3 {
                n.bounds[axis][lane] = lo[axis];
                n.bounds[3 + axis][lane] = hi[axis];
            }
            n.used |= 1 << lane;
        }
        n
    }

    fn slab(origin: [f32; 3], dir: [f32; 3]) -> Slab {
        Slab {
            origin,
            inv_dir: dir.map(|d| 1.0 / d),
        }
    }

    /// Four rays from (0, -10, 0) into y, spread over x and z in [0.1, 0.2] per unit.
    fn fan() -> Vec<Slab> {
        [(0.1, 0.1), (0.2, 0.1), (0.1, 0.2), (0.2, 0.2)]
            .map(|(x, z)| slab([0.0, -10.0, 0.0], [x, 1.0, z]))
            .to_vec()
    }

    #[test]
    fn the_bound_culls_a_box_beside_the_packet_and_keeps_the_one_ahead() {
        let f = Frustum::of(&fan()).unwrap_or_else(|| panic!("coherent"));
        // At y in [-1, 1] (t 9..11) the rays are at x, z in [0.9, 2.2]: the box ahead
        // [0, 3]² is entered; a box at x in [5, 6] needs t >= 25 along x (5 / 0.2) but
        // the rays leave y <= 1 at t = 11; a box behind the origin (y < -10) ends before
        // t = 0; a box at x in [1.5, 1.6] sits between two rays' tracks at y = 0 (1.0
        // and 2.0): the bound cannot tell, so it keeps it.
        let n = node(&[
            ([0.0, -1.0, 0.0], [3.0, 1.0, 3.0]),
            ([5.0, -1.0, 0.0], [6.0, 1.0, 3.0]),
            ([0.0, -13.0, 0.0], [3.0, -11.0, 3.0]),
            ([1.5, -1.0, 0.0], [1.6, 1.0, 3.0]),
        ]);
        let expect = 0b1001;
        assert_eq!(f.cull(&n, 0.0, f32::INFINITY).0, expect);
        // A reach that ends before the boxes (t 9) culls them all.
        assert_eq!(f.cull(&n, 0.0, 8.5).0, 0);
        if cpu_has_avx2_fma() {
            // SAFETY: the CPU has AVX2.
            unsafe {
                assert_eq!(f.cull_avx2(&n, 0.0, f32::INFINITY).0, expect);
                assert_eq!(f.cull_avx2(&n, 0.0, 8.5).0, 0);
            }
        }
        // The exact test: box 0 is entered by all four rays, first at t = 9; box 3 by
        // none (x = 0.1 t and 0.2 t at t = 9..11 never fall in [1.5, 1.6] while z does:
        // ray 1 is at x 1.8..2.2, ray 0 at 0.9..1.1).
        let reach = [f32::INFINITY; PACKET];
        assert_eq!(f.rays_entering(&n, 0, 0b1111, 0.0, &reach), (0b1111, 9.0));
        assert_eq!(f.rays_entering(&n, 3, 0b1111, 0.0, &reach).0, 0);
    }

    #[test]
    fn rays_parallel_to_an_axis_or_going_both_ways_have_no_bound() {
        let mut rays = fan();
        rays.push(slab([0.0, -10.0, 0.0], [0.0, 1.0, 0.1]));
        assert!(Frustum::of(&rays).is_none());
        let mut rays = fan();
        rays.push(slab([0.0, -10.0, 0.0], [-0.1, 1.0, 0.1]));
        assert!(Frustum::of(&rays).is_none());
        assert!(Frustum::of(&[]).is_none());
    }

    /// A small xorshift stream in [-1, 1).
    fn stream(mut state: u32) -> impl FnMut() -> f32 {
        move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state as f32 / u32::MAX as f32) * 2.0 - 1.0
        }
    }

    #[test]
    fn the_bound_keeps_every_box_a_ray_enters_and_the_lanes_match_each_ray() {
        let mut next = stream(2024);
        let avx2 = cpu_has_avx2_fma();
        let mut kept_fewer = 0;
        for _ in 0..3000 {
            // Packets of nearby origins and directions, boxes all around them (some
            // flat), so every outcome occurs.
            let base = [next() * 4.0, next() * 4.0, next() * 4.0];
            let dir = [next(), next(), next()];
            let size = 1 + (next().abs() * 8.0) as usize % PACKET;
            let spread = next().abs() * 0.3;
            let rays: Vec<Slab> = (0..size)
                .map(|_| {
                    slab(
                        base.map(|b| b + next() * spread),
                        dir.map(|d| d + next() * spread * 0.5),
                    )
                })
                .collect();
            let Some(f) = Frustum::of(&rays) else {
                continue;
            };
            let boxes: Vec<([f32; 3], [f32; 3])> = (0..WIDTH)
                .map(|i| {
                    let c = [next() * 6.0, next() * 6.0, next() * 6.0];
                    let h = [next().abs(), next().abs(), next().abs() * (i % 3) as f32];
                    (
                        [c[0] - h[0], c[1] - h[1], c[2] - h[2]],
                        [c[0] + h[0], c[1] + h[1], c[2] + h[2]],
                    )
                })
                .collect();
            let n = node(&boxes);
            let mut reach = [f32::INFINITY; PACKET];
            for r in reach.iter_mut().take(size) {
                *r = [f32::INFINITY, 3.0, 8.0][(next().abs() * 3.0) as usize % 3];
            }
            let t_far = reach[..size]
                .iter()
                .fold(f32::NEG_INFINITY, |a, &b| a.max(b));
            let all = (1u32 << size) - 1;
            let (kept, bound) = f.cull(&n, 0.0, t_far);
            if avx2 {
                // SAFETY: the CPU has AVX2.
                assert_eq!(unsafe { f.cull_avx2(&n, 0.0, t_far) }, (kept, bound));
            }
            let mut entered = 0;
            for lane in 0..WIDTH {
                // Each ray alone, with the single-ray step.
                let mut set = 0;
                let mut nearest = f32::INFINITY;
                for (r, ray) in rays.iter().enumerate() {
                    let (mask, near) = ray.test(&n, 0.0, reach[r]);
                    if mask & (1 << lane) != 0 {
                        set |= 1 << r;
                        nearest = nearest.min(near[lane]);
                    }
                }
                entered |= u32::from(set != 0) << lane;
                assert!(
                    set == 0 || bound[lane] <= nearest,
                    "entered before the bound"
                );
                let lanes = f.rays_entering(&n, lane, all, 0.0, &reach);
                assert_eq!(lanes, (set, nearest));
                if avx2 {
                    // SAFETY: the CPU has AVX2.
                    let wide = unsafe { f.rays_entering_avx2(&n, lane, all, 0.0, &reach) };
                    assert_eq!(wide, (set, nearest));
                }
            }
            assert_eq!(kept & entered, entered, "the bound culled an entered box");
            kept_fewer += usize::from(kept.count_ones() < n.used.count_ones());
        }
        // The bound does cull (the test is not vacuous).
        assert!(kept_fewer > 500, "{kept_fewer}");
    }
}

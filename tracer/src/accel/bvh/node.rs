//! The wide BVH's node and its box test, shared by the single-ray traversal
//! ([`super::wide`]) and the packets ([`super::packet`]): a node holds up to [`WIDTH`]
//! children's boxes in structure-of-arrays lanes, and [`Slab`] tests a ray against all of
//! them in one step (in plain lane arithmetic, or in AVX registers where the CPU has
//! them; both give the same distances bit for bit).

use super::Aabb;
use crate::ray::Ray;
use glam::Vec3A;

/// Children per node: one AVX register of f32.
pub const WIDTH: usize = 8;

/// Marks an unused child slot.
pub(super) const EMPTY: u32 = u32::MAX;

/// One node: its children's boxes as lanes, and what each child is.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct WideNode {
    /// `min_x, min_y, min_z, max_x, max_y, max_z` of each child's box; unused slots hold
    /// an empty box (min +inf, max -inf) that no ray enters.
    pub(super) bounds: [[f32; WIDTH]; 6],
    /// An interior child's node index, a leaf child's index in `leaves` with [`LEAF`]
    /// set, or [`EMPTY`].
    pub(super) child: [u32; WIDTH],
    /// Bit per used slot: an empty box can still give a slab interval (a negative
    /// direction turns +inf..-inf into -inf..+inf), so unused slots are masked out.
    pub(super) used: u32,
}

impl WideNode {
    pub(super) const UNUSED: WideNode = WideNode {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [EMPTY; WIDTH],
        used: 0,
    };

    pub(super) fn set(&mut self, lane: usize, bounds: Aabb, child: u32, leaf: bool) {
        let (lo, hi) = (bounds.min.to_array(), bounds.max.to_array());
        for axis in 0..3 {
            self.bounds[axis][lane] = lo[axis];
            self.bounds[3 + axis][lane] = hi[axis];
        }
        self.child[lane] = if leaf { child | LEAF } else { child };
        self.used |= 1 << lane;
    }

    pub(super) fn children(&self) -> usize {
        self.used.count_ones() as usize
    }
}

/// The bit of a child reference that marks a leaf (the rest is its index in `leaves`).
pub(super) const LEAF: u32 = 1 << 31;

/// A ray's slab-test constants.
#[derive(Clone, Copy, Debug)]
pub(super) struct Slab {
    pub(super) origin: [f32; 3],
    pub(super) inv_dir: [f32; 3],
}

impl Slab {
    /// The constants of `ray`.
    #[inline(always)]
    pub(super) fn new<const FROM_EYE: bool>(ray: &Ray<FROM_EYE>) -> Self {
        let inv_dir = Vec3A::ONE / ray.dir.0;
        Slab {
            origin: ray.origin.0.to_array(),
            inv_dir: inv_dir.to_array(),
        }
    }

    /// Which children's boxes the ray enters inside `(t_min, t_max)` (bit per lane)
    /// and where. The same arithmetic as the binary tree's slab test, lane by lane;
    /// written so that a NaN (origin on a slab of a flat box: 0 × inf) drops out of
    /// `min`/`max` as there.
    #[inline(always)]
    pub(super) fn test(&self, node: &WideNode, t_min: f32, t_max: f32) -> (u32, [f32; WIDTH]) {
        let mut near = [t_min; WIDTH];
        let mut far = [t_max; WIDTH];
        for axis in 0..3 {
            let (o, inv) = (self.origin[axis], self.inv_dir[axis]);
            let lo = &node.bounds[axis];
            let hi = &node.bounds[3 + axis];
            for i in 0..WIDTH {
                let t0 = (lo[i] - o) * inv;
                let t1 = (hi[i] - o) * inv;
                near[i] = max_or_second(min_or_second(t0, t1), near[i]);
                far[i] = min_or_second(max_or_second(t0, t1), far[i]);
            }
        }
        let mut mask = 0u32;
        for i in 0..WIDTH {
            mask |= u32::from(near[i] <= far[i]) << i;
        }
        (mask & node.used, near)
    }

    /// [`Slab::test`] in AVX instructions: `vminps`/`vmaxps` follow the same rule as
    /// [`min_or_second`]/[`max_or_second`], so the results are the same.
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub(super) unsafe fn test_avx2(
        &self,
        node: &WideNode,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        use std::arch::x86_64::{_mm256_movemask_ps, _mm256_storeu_ps};
        // SAFETY: the caller guarantees AVX.
        unsafe {
            let (near, inside) = self.near_inside_avx2(node, t_min, t_max);
            let mask = _mm256_movemask_ps(inside) as u32;
            let mut t = [0.0f32; WIDTH];
            _mm256_storeu_ps(t.as_mut_ptr(), near);
            (mask & node.used, t)
        }
    }

    /// The slab test's entry distances and its lane mask (all bits set where the ray
    /// enters the box; unused slots not yet masked out), in AVX registers.
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub(super) unsafe fn near_inside_avx2(
        &self,
        node: &WideNode,
        t_min: f32,
        t_max: f32,
    ) -> (std::arch::x86_64::__m256, std::arch::x86_64::__m256) {
        use std::arch::x86_64::{
            _CMP_LE_OQ, _mm256_cmp_ps, _mm256_load_ps, _mm256_max_ps, _mm256_min_ps, _mm256_mul_ps,
            _mm256_set1_ps, _mm256_sub_ps,
        };
        // SAFETY: the caller guarantees AVX; the rows are 32-byte aligned (a 64-byte
        // aligned node of 32-byte rows) and 8 floats long.
        unsafe {
            let mut near = _mm256_set1_ps(t_min);
            let mut far = _mm256_set1_ps(t_max);
            for axis in 0..3 {
                let o = _mm256_set1_ps(self.origin[axis]);
                let inv = _mm256_set1_ps(self.inv_dir[axis]);
                let lo = _mm256_load_ps(node.bounds[axis].as_ptr());
                let hi = _mm256_load_ps(node.bounds[3 + axis].as_ptr());
                let t0 = _mm256_mul_ps(_mm256_sub_ps(lo, o), inv);
                let t1 = _mm256_mul_ps(_mm256_sub_ps(hi, o), inv);
                near = _mm256_max_ps(_mm256_min_ps(t0, t1), near);
                far = _mm256_min_ps(_mm256_max_ps(t0, t1), far);
            }
            (near, _mm256_cmp_ps::<_CMP_LE_OQ>(near, far))
        }
    }
}

/// `a` if it is the larger, else `b` (a NaN `a` gives `b`: the x86 `maxps` rule).
#[inline(always)]
fn max_or_second(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// `a` if it is the smaller, else `b` (a NaN `a` gives `b`: the x86 `minps` rule).
#[inline(always)]
fn min_or_second(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

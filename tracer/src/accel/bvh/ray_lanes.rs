//! A packet's rays in lanes (a ray per lane): what the coherent traversal
//! (in [`super::packet`]) tests against one box or one triangle at a time, and what its
//! bounds ([`super::frustum`]) are taken over.

use super::node::{Slab, WIDTH};
use crate::ray::Ray;

/// Up to [`WIDTH`] rays, axis by axis; unused lanes repeat the first ray.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(super) struct RayLanes {
    pub(super) origin: [[f32; WIDTH]; 3],
    pub(super) dir: [[f32; WIDTH]; 3],
    /// `1 / dir`, lane by lane ([`Slab::new`]'s reciprocals).
    pub(super) inv_dir: [[f32; WIDTH]; 3],
}

impl RayLanes {
    /// The lanes of `rays` (at least one; at most [`WIDTH`] are taken), on the code
    /// path `AVX2` names.
    #[inline(always)]
    pub(super) fn of<const FROM_EYE: bool, const AVX2: bool>(rays: &[Ray<FROM_EYE>]) -> Self {
        #[cfg(target_arch = "x86_64")]
        if AVX2 && !rays.is_empty() {
            // SAFETY: `AVX2` is set only on CPUs with AVX2 (see `packet_search_avx2`).
            return unsafe { Self::of_avx(rays) };
        }
        let mut lanes = RayLanes {
            origin: [[0.0; WIDTH]; 3],
            dir: [[1.0; WIDTH]; 3],
            inv_dir: [[1.0; WIDTH]; 3],
        };
        for lane in 0..WIDTH {
            let Some(ray) = rays.get(lane).or(rays.first()) else {
                break;
            };
            let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
            for axis in 0..3 {
                lanes.origin[axis][lane] = o[axis];
                lanes.dir[axis][lane] = d[axis];
            }
        }
        lanes.invert::<AVX2>();
        lanes
    }

    /// [`RayLanes::of`] of at least one ray in AVX registers: each ray's origin and
    /// direction loaded whole, turned into rows by a 4×4 transpose per half (rays 0-3
    /// below, 4-7 above), and the rows stored whole. Stored lane by lane instead, the
    /// rows' 256-bit loads waited for eight narrow stores each (a store cannot be
    /// forwarded to a wider load).
    ///
    /// # Safety
    /// The CPU must have AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn of_avx<const FROM_EYE: bool>(rays: &[Ray<FROM_EYE>]) -> Self {
        use std::arch::x86_64::{
            __m128, __m256, _mm256_div_ps, _mm256_set_m128, _mm256_set1_ps, _mm256_shuffle_ps,
            _mm256_store_ps, _mm256_unpackhi_ps, _mm256_unpacklo_ps,
        };
        // Unused lanes repeat the first ray.
        let ray = |lane: usize| rays.get(lane).unwrap_or(&rays[0]);
        let mut lanes = RayLanes {
            origin: [[0.0; WIDTH]; 3],
            dir: [[0.0; WIDTH]; 3],
            inv_dir: [[0.0; WIDTH]; 3],
        };
        // Macros, not closures: a closure would not inherit the caller's AVX.
        macro_rules! rows {
            ($field:ident) => {{
                let pair = |lane: usize| -> (__m128, __m128) {
                    (ray(lane + 4).$field.0.into(), ray(lane).$field.0.into())
                };
                let [a, b, c, d] = [0, 1, 2, 3].map(pair);
                let (a, b, c, d): (__m256, __m256, __m256, __m256) = (
                    _mm256_set_m128(a.0, a.1),
                    _mm256_set_m128(b.0, b.1),
                    _mm256_set_m128(c.0, c.1),
                    _mm256_set_m128(d.0, d.1),
                );
                // Per half: (a.x b.x a.y b.y), (a.z b.z a.w b.w), likewise c and d.
                let (ab_xy, ab_zw) = (_mm256_unpacklo_ps(a, b), _mm256_unpackhi_ps(a, b));
                let (cd_xy, cd_zw) = (_mm256_unpacklo_ps(c, d), _mm256_unpackhi_ps(c, d));
                [
                    _mm256_shuffle_ps::<0x44>(ab_xy, cd_xy),
                    _mm256_shuffle_ps::<0xEE>(ab_xy, cd_xy),
                    _mm256_shuffle_ps::<0x44>(ab_zw, cd_zw),
                ]
            }};
        }
        // SAFETY: the caller guarantees AVX; the rows are 32-byte aligned rows of 8
        // floats.
        unsafe {
            let origin = rows!(origin);
            let dir = rows!(dir);
            for axis in 0..3 {
                _mm256_store_ps(lanes.origin[axis].as_mut_ptr(), origin[axis]);
                _mm256_store_ps(lanes.dir[axis].as_mut_ptr(), dir[axis]);
                let inv = _mm256_div_ps(_mm256_set1_ps(1.0), dir[axis]);
                _mm256_store_ps(lanes.inv_dir[axis].as_mut_ptr(), inv);
            }
        }
        lanes
    }

    /// `inv_dir = 1 / dir`, on the code path `AVX2` names (`vdivps` rounds each lane
    /// as the scalar division does).
    #[inline(always)]
    fn invert<const AVX2: bool>(&mut self) {
        #[cfg(target_arch = "x86_64")]
        if AVX2 {
            use std::arch::x86_64::{
                _mm256_div_ps, _mm256_load_ps, _mm256_set1_ps, _mm256_store_ps,
            };
            // SAFETY: `AVX2` is set only on CPUs with AVX2 (see `packet_search_avx2`);
            // the rows are 32-byte aligned rows of 8 floats.
            unsafe {
                for axis in 0..3 {
                    let d = _mm256_load_ps(self.dir[axis].as_ptr());
                    let inv = _mm256_div_ps(_mm256_set1_ps(1.0), d);
                    _mm256_store_ps(self.inv_dir[axis].as_mut_ptr(), inv);
                }
            }
            return;
        }
        for axis in 0..3 {
            for lane in 0..WIDTH {
                self.inv_dir[axis][lane] = 1.0 / self.dir[axis][lane];
            }
        }
    }

    /// Whether every lane starts at the first lane's origin (eye rays of a pinhole).
    #[inline(always)]
    pub(super) fn one_origin(&self) -> bool {
        let mut same = true;
        for axis in 0..3 {
            for lane in 0..WIDTH {
                same &= self.origin[axis][lane] == self.origin[axis][0];
            }
        }
        same
    }

    /// Lane `r`'s slab-test constants, the same as [`Slab::new`]'s of its ray.
    #[inline(always)]
    pub(super) fn slab(&self, r: usize) -> Slab {
        Slab {
            origin: [self.origin[0][r], self.origin[1][r], self.origin[2][r]],
            inv_dir: [self.inv_dir[0][r], self.inv_dir[1][r], self.inv_dir[2][r]],
        }
    }
}

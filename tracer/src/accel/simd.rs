//! SIMD brute force (variant `simd`): the thesis's "several intersection units in
//! parallel, then one minimum" (8.3.3) in software.
//!
//! Spheres and cylinders are stored in structure-of-arrays chunks of [`LANES`]; one step
//! tests a whole chunk with branch-free lane arithmetic that the compiler turns into
//! vector instructions, and the closest lane is picked at the end of the step. The
//! chunk loop is compiled twice: for the build's baseline target (SSE2 on any x86-64)
//! and with AVX2 + FMA, chosen at run time when the CPU has them. Cones, polygons and
//! patches are tested one by one as in brute force.
//!
//! Counts: every chunk tested issues [`LANES`] lanes (`accel.lanes_issued`), of which
//! those holding a primitive are active (`accel.lanes_active`); their ratio is the
//! lane utilization, low when a scene has fewer primitives of a kind than lanes. Every
//! lane holding a primitive counts one test with the operations of the scalar test
//! (its first stage's `sub` and `dot`s; the second stage's operations where the first
//! neither ruled out a hit nor was accurate enough to keep; a `sqrt` where the
//! discriminant is positive), and a hit where
//! its intersection lies inside the query's reach, as brute force counts them (so
//! closest-hit queries count the same tests and hits as `baseline`; a shadow query
//! stops after the chunk where it found a blocker, brute force after the blocker).

use super::{Intersector, cpu_has_avx2_fma, intersect_primitive, occluded_by_cones_and_planars};
use crate::counter::{Counter, Phase, Stat};
use crate::primitives::{
    first_stage_suffices, quick_miss_margin, sphere_first_disc, sphere_may_hit,
};
use crate::ray::{Hit, PrimKind, PrimRef, Ray};
use crate::scene::Scene;

#[cfg(target_arch = "x86_64")]
mod avx2;

/// Primitives tested per step: one AVX register of f32.
pub const LANES: usize = 8;

/// A chunk of spheres in structure-of-arrays form.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
struct SphereLanes {
    cx: [f32; LANES],
    cy: [f32; LANES],
    cz: [f32; LANES],
    radius_sq: [f32; LANES],
    /// 1.0 where only the inside is visible (negative radius).
    inside: [f32; LANES],
}

/// A chunk of cylinders in structure-of-arrays form.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
struct CylinderLanes {
    bx: [f32; LANES],
    by: [f32; LANES],
    bz: [f32; LANES],
    ax: [f32; LANES],
    ay: [f32; LANES],
    az: [f32; LANES],
    radius_sq: [f32; LANES],
    length: [f32; LANES],
    inside: [f32; LANES],
}

/// Brute force with SIMD lanes.
#[derive(Clone, Debug)]
pub struct Simd<'s> {
    scene: &'s Scene,
    spheres: Vec<SphereLanes>,
    cylinders: Vec<CylinderLanes>,
    avx2: bool,
}

impl<'s> Simd<'s> {
    /// Bytes of the packed lanes (what the structure adds to the scene).
    pub fn memory_bytes(&self) -> usize {
        self.spheres.capacity() * std::mem::size_of::<SphereLanes>()
            + self.cylinders.capacity() * std::mem::size_of::<CylinderLanes>()
    }

    /// Packs the spheres and cylinders of `scene` into lanes and detects AVX2.
    pub fn new(scene: &'s Scene) -> Self {
        let spheres = scene
            .spheres
            .chunks(LANES)
            .map(|chunk| {
                // Empty lanes: a sphere of radius² -inf, never hit (disc = -inf).
                let mut l = SphereLanes {
                    cx: [0.0; LANES],
                    cy: [0.0; LANES],
                    cz: [0.0; LANES],
                    radius_sq: [f32::NEG_INFINITY; LANES],
                    inside: [0.0; LANES],
                };
                for (i, s) in chunk.iter().enumerate() {
                    let [x, y, z] = s.center.to_array();
                    (l.cx[i], l.cy[i], l.cz[i]) = (x, y, z);
                    l.radius_sq[i] = s.radius_sq();
                    l.inside[i] = f32::from(u8::from(s.inside_visible()));
                }
                l
            })
            .collect();
        let cylinders = scene
            .cylinders
            .chunks(LANES)
            .map(|chunk| {
                // Empty lanes: axis 0 makes a = 1, radius² -inf makes disc = -inf.
                let mut l = CylinderLanes {
                    bx: [0.0; LANES],
                    by: [0.0; LANES],
                    bz: [0.0; LANES],
                    ax: [0.0; LANES],
                    ay: [0.0; LANES],
                    az: [0.0; LANES],
                    radius_sq: [f32::NEG_INFINITY; LANES],
                    length: [0.0; LANES],
                    inside: [0.0; LANES],
                };
                for (i, cy) in chunk.iter().enumerate() {
                    let [x, y, z] = cy.base.to_array();
                    (l.bx[i], l.by[i], l.bz[i]) = (x, y, z);
                    let [x, y, z] = cy.axis.to_array();
                    (l.ax[i], l.ay[i], l.az[i]) = (x, y, z);
                    l.radius_sq[i] = cy.radius_sq();
                    l.length[i] = cy.length;
                    l.inside[i] = f32::from(u8::from(cy.inside_visible()));
                }
                l
            })
            .collect();
        Self {
            scene,
            spheres,
            cylinders,
            avx2: cpu_has_avx2_fma(),
        }
    }

    /// Whether the AVX2 + FMA code path runs on this CPU.
    pub fn uses_avx2(&self) -> bool {
        self.avx2
    }

    /// The closest sphere and cylinder hits in `(t_min, t_max)`, or whether any exists
    /// when `any` is set (then the search stops at the first chunk with a hit).
    #[inline(always)]
    fn quadric_pass<C: Counter>(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        any: bool,
        c: &mut C,
    ) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is true only when the CPU reported AVX2 and FMA.
            return unsafe { quadric_pass_avx2(self, ray, t_min, t_max, any, c) };
        }
        quadric_pass_body::<C, false>(self, ray, t_min, t_max, any, c)
    }
}

/// The quadric pass compiled with AVX2 + FMA (the caller checks the CPU has them).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn quadric_pass_avx2<C: Counter>(
    simd: &Simd,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    any: bool,
    c: &mut C,
) -> Option<Hit> {
    quadric_pass_body::<C, true>(simd, ray, t_min, t_max, any, c)
}

/// Lanes of a chunk that hold a primitive.
#[inline(always)]
fn live_lanes(chunk: usize, count: usize) -> usize {
    (count - chunk * LANES).min(LANES)
}

/// The closest hit found by each lane over all chunks so far. Each lane keeps its own
/// shrinking interval, so the chunk loop never needs a horizontal minimum; the lanes
/// are reduced once, at the end.
struct LaneBest {
    t: [f32; LANES],
    chunk: [u32; LANES],
    aux: [f32; LANES],
}

impl LaneBest {
    fn new(t_max: f32) -> Self {
        Self {
            t: [t_max; LANES],
            chunk: [u32::MAX; LANES],
            aux: [0.0; LANES],
        }
    }

    /// Keeps the lanes of `t` closer than the lane's best; whether any lane was kept.
    #[inline(always)]
    fn update(&mut self, chunk: usize, t: &[f32; LANES], aux: &[f32; LANES]) -> bool {
        let mut kept = false;
        for i in 0..LANES {
            let closer = t[i] < self.t[i];
            kept |= closer;
            if closer {
                self.t[i] = t[i];
                self.chunk[i] = chunk as u32;
                self.aux[i] = aux[i];
            }
        }
        kept
    }

    /// The closest lane's hit as `(t, primitive index, aux)`; on equal distances the
    /// lowest primitive index wins, as brute force keeps the first of equal hits.
    fn closest(&self) -> Option<(f32, usize, f32)> {
        let mut best: Option<(f32, usize, f32)> = None;
        for i in 0..LANES {
            if self.chunk[i] == u32::MAX {
                continue;
            }
            let index = self.chunk[i] as usize * LANES + i;
            let better = match best {
                None => true,
                Some((t, j, _)) => self.t[i] < t || (self.t[i] == t && index < j),
            };
            if better {
                best = Some((self.t[i], index, self.aux[i]));
            }
        }
        best
    }
}

/// The closest sphere or cylinder hit in `(t_min, t_max)` (with `any`: the first found).
#[inline(always)]
fn quadric_pass_body<C: Counter, const AVX2: bool>(
    simd: &Simd,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    any: bool,
    c: &mut C,
) -> Option<Hit> {
    let (sphere_count, cylinder_count) = (simd.scene.spheres.len(), simd.scene.cylinders.len());
    // A chunk tests several primitives of one kind at once: the whole pass is the
    // kind's test phase.
    let sphere = {
        let _phase = C::enter_phase(Phase::SphereTest);
        sphere_pass::<C, AVX2>(&simd.spheres, sphere_count, ray, t_min, t_max, any, c)
    };
    let hit = |kind, (t, index, aux): (f32, usize, f32)| Hit {
        t,
        prim: PrimRef {
            kind,
            index: index as u32,
        },
        aux,
    };
    if any && sphere.is_some() {
        return sphere.map(|s| hit(PrimKind::Sphere, s));
    }
    // The cylinders are tested against the query's reach (their hits count whatever
    // the spheres found) and kept only when closer than the closest sphere.
    let closer_than = sphere.map_or(t_max, |(t, _, _)| t);
    let cylinder = {
        let _phase = C::enter_phase(Phase::CylinderTest);
        let chunks = &simd.cylinders;
        cylinder_pass::<C, AVX2>(
            chunks,
            cylinder_count,
            ray,
            t_min,
            t_max,
            closer_than,
            any,
            c,
        )
    };
    match cylinder {
        Some(cy) => Some(hit(PrimKind::Cylinder, cy)),
        None => sphere.map(|s| hit(PrimKind::Sphere, s)),
    }
}

#[inline(always)]
fn sphere_pass<C: Counter, const AVX2: bool>(
    chunks: &[SphereLanes],
    count: usize,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    any: bool,
    c: &mut C,
) -> Option<(f32, usize, f32)> {
    let (origin, dir) = (ray.origin.to_array(), ray.dir.to_array());
    let [ox, oy, oz] = origin;
    let [dx, dy, dz] = dir;
    let mut best = LaneBest::new(t_max);
    for (k, l) in chunks.iter().enumerate() {
        let live = live_lanes(k, count);
        if C::ENABLED {
            count_lanes(c, live, 1, 2, Stat::SphereTest);
        }
        // Step 1, every lane: the scalar test's first stage (the thesis's discriminant,
        // trusted for certain misses). Most chunks miss entirely and stop here.
        #[cfg(target_arch = "x86_64")]
        // SAFETY: AVX2 is set only in the pass compiled for AVX2 (`quadric_pass_avx2`).
        if AVX2 && unsafe { avx2::sphere_first_stage_mask(l, origin, dir) } == 0 {
            continue;
        }
        let SphereFirst {
            half_b,
            oo,
            mut disc,
            passed,
        } = sphere_first_stage(l, origin, dir);
        if !any_lane(&passed) {
            continue;
        }
        // Whether each passing lane's first stage is kept (see the scalar test): decided
        // only for chunks that some lane passed, off the path of the many that none does.
        let (second, any_second) = second_stage_lanes(&passed, &disc, &[1.0; LANES], &oo);
        // Step 2: the second stage where the first was not kept (the discriminant from
        // the centre's offset across the ray, as the scalar test computes it), skipped
        // when no lane needs it.
        if any_second {
            let mut any_positive = false;
            for i in 0..LANES {
                let (vx, vy, vz) = (ox - l.cx[i], oy - l.cy[i], oz - l.cz[i]);
                let (ax, ay, az) = (
                    vx - dx * half_b[i],
                    vy - dy * half_b[i],
                    vz - dz * half_b[i],
                );
                let exact = l.radius_sq[i] - (ax * ax + ay * ay + az * az);
                disc[i] = if second[i] { exact } else { disc[i] };
                any_positive |= passed[i] & (disc[i] > 0.0);
            }
            if C::ENABLED {
                count_second_stage(c, live, &second, &[Stat::Scale, Stat::Sub, Stat::Dot]);
            }
            if !any_positive {
                // Only near misses passed the first stage, and the second ruled them
                // all out: no roots to take (the chunks the margin lets through).
                continue;
            }
        }
        // Step 3: the roots and the query's reach, branch-free per lane.
        let mut t = [f32::INFINITY; LANES];
        let mut disc_positive = [false; LANES];
        for i in 0..LANES {
            let disc = disc[i];
            disc_positive[i] = passed[i] && disc > 0.0;
            let root = C::sqrt_kernel(disc.max(0.0));
            let near = -half_b[i] - root;
            let far = -half_b[i] + root;
            let near_ok = l.inside[i] == 0.0 && near > t_min && near < t_max;
            let far_ok = far > t_min && far < t_max;
            let chosen = if near_ok { near } else { far };
            t[i] = if disc_positive[i] && (near_ok || far_ok) {
                chosen
            } else {
                f32::INFINITY
            };
        }
        if C::ENABLED {
            count_roots_and_hits(c, live, &disc_positive, &t, Stat::SphereHit);
        }
        if best.update(k, &t, &[0.0; LANES]) && any {
            break;
        }
    }
    best.closest()
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn cylinder_pass<C: Counter, const AVX2: bool>(
    chunks: &[CylinderLanes],
    count: usize,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    closer_than: f32,
    any: bool,
    c: &mut C,
) -> Option<(f32, usize, f32)> {
    let (origin, dir) = (ray.origin.to_array(), ray.dir.to_array());
    let [ox, oy, oz] = origin;
    let [dx, dy, dz] = dir;
    let mut best = LaneBest::new(closer_than);
    for (k, l) in chunks.iter().enumerate() {
        let live = live_lanes(k, count);
        if C::ENABLED {
            count_lanes(c, live, 1, 4, Stat::CylinderTest);
        }
        // Step 1, every lane: the quadratic's coefficients and the scalar test's first
        // stage (the thesis's discriminant, trusted for certain misses).
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as for the spheres.
        if AVX2 && unsafe { avx2::cylinder_first_stage_mask(l, origin, dir) } == 0 {
            continue;
        }
        let CylinderFirst {
            rv,
            ov,
            a,
            half_b,
            oo,
            mut disc,
            passed,
        } = cylinder_first_stage(l, origin, dir);
        if !any_lane(&passed) {
            continue;
        }
        // Whether each passing lane's first stage is kept, as for the spheres.
        let (second, any_second) = second_stage_lanes(&passed, &disc, &a, &oo);
        // Step 2: the second stage where the first was not kept (a r² - (V·(Voc × R))²,
        // as the scalar test computes it), skipped when no lane needs it.
        if any_second {
            let mut any_positive = false;
            for i in 0..LANES {
                let (vx, vy, vz) = (ox - l.bx[i], oy - l.by[i], oz - l.bz[i]);
                // Voc × R in the order of the scalar test's cross product.
                let (nx, ny, nz) = (vy * dz - dy * vz, vz * dx - dz * vx, vx * dy - dx * vy);
                let triple = l.ax[i] * nx + l.ay[i] * ny + l.az[i] * nz;
                let exact = a[i] * l.radius_sq[i] - triple * triple;
                disc[i] = if second[i] { exact } else { disc[i] };
                any_positive |= passed[i] & (disc[i] > 0.0);
            }
            if C::ENABLED {
                count_second_stage(c, live, &second, &[Stat::Cross, Stat::Dot]);
            }
            if !any_positive {
                // As for the spheres: only near misses, all ruled out.
                continue;
            }
        }
        // Step 3: the roots, the query's reach and the axial bounds, branch-free per
        // lane.
        let mut t = [f32::INFINITY; LANES];
        let mut m_at = [0.0f32; LANES];
        let mut disc_positive = [false; LANES];
        for i in 0..LANES {
            let disc = disc[i];
            disc_positive[i] = passed[i] && disc > 0.0;
            let root = C::sqrt_kernel(disc.max(0.0));
            let near = (-half_b[i] - root) / a[i];
            let far = (-half_b[i] + root) / a[i];
            let m_near = ov[i] + near * rv[i];
            let m_far = ov[i] + far * rv[i];
            let near_ok = l.inside[i] == 0.0
                && near > t_min
                && near < t_max
                && m_near > 0.0
                && m_near < l.length[i];
            let far_ok = far > t_min && far < t_max && m_far > 0.0 && m_far < l.length[i];
            let (chosen, m) = if near_ok {
                (near, m_near)
            } else {
                (far, m_far)
            };
            (t[i], m_at[i]) = if disc_positive[i] && (near_ok || far_ok) {
                (chosen, m)
            } else {
                (f32::INFINITY, 0.0)
            };
        }
        if C::ENABLED {
            count_roots_and_hits(c, live, &disc_positive, &t, Stat::CylinderHit);
        }
        if best.update(k, &t, &m_at) && any {
            break;
        }
    }
    best.closest()
}

/// Whether any lane is set.
#[inline(always)]
fn any_lane(lanes: &[bool; LANES]) -> bool {
    let mut any = false;
    for &on in lanes {
        any |= on;
    }
    any
}

/// The sphere test's first stage in every lane of a chunk: the thesis's discriminant,
/// trusted for certain misses ([`avx2::sphere_first_stage_mask`] computes `passed` with
/// the same operations in AVX registers, where a chunk that no lane passes ends).
struct SphereFirst {
    half_b: [f32; LANES],
    oo: [f32; LANES],
    disc: [f32; LANES],
    passed: [bool; LANES],
}

#[inline(always)]
fn sphere_first_stage(
    l: &SphereLanes,
    [ox, oy, oz]: [f32; 3],
    [dx, dy, dz]: [f32; 3],
) -> SphereFirst {
    let mut f = SphereFirst {
        half_b: [0.0; LANES],
        oo: [0.0; LANES],
        disc: [0.0; LANES],
        passed: [false; LANES],
    };
    for i in 0..LANES {
        let (vx, vy, vz) = (ox - l.cx[i], oy - l.cy[i], oz - l.cz[i]);
        f.half_b[i] = dx * vx + dy * vy + dz * vz;
        f.oo[i] = vx * vx + vy * vy + vz * vz;
        f.disc[i] = sphere_first_disc(f.half_b[i], f.oo[i], l.radius_sq[i]);
        f.passed[i] = sphere_may_hit(f.disc[i], f.oo[i]);
    }
    f
}

/// The cylinder test's first stage in every lane of a chunk: the quadratic's
/// coefficients and the thesis's discriminant, trusted for certain misses
/// ([`avx2::cylinder_first_stage_mask`] computes `passed` in AVX registers).
struct CylinderFirst {
    rv: [f32; LANES],
    ov: [f32; LANES],
    a: [f32; LANES],
    half_b: [f32; LANES],
    oo: [f32; LANES],
    disc: [f32; LANES],
    passed: [bool; LANES],
}

#[inline(always)]
fn cylinder_first_stage(
    l: &CylinderLanes,
    [ox, oy, oz]: [f32; 3],
    [dx, dy, dz]: [f32; 3],
) -> CylinderFirst {
    let mut f = CylinderFirst {
        rv: [0.0; LANES],
        ov: [0.0; LANES],
        a: [0.0; LANES],
        half_b: [0.0; LANES],
        oo: [0.0; LANES],
        disc: [0.0; LANES],
        passed: [false; LANES],
    };
    for i in 0..LANES {
        let (vx, vy, vz) = (ox - l.bx[i], oy - l.by[i], oz - l.bz[i]);
        f.rv[i] = dx * l.ax[i] + dy * l.ay[i] + dz * l.az[i];
        f.ov[i] = vx * l.ax[i] + vy * l.ay[i] + vz * l.az[i];
        let ro = dx * vx + dy * vy + dz * vz;
        f.oo[i] = vx * vx + vy * vy + vz * vz;
        f.a[i] = 1.0 - f.rv[i] * f.rv[i];
        f.half_b[i] = ro - f.rv[i] * f.ov[i];
        let cc = f.oo[i] - f.ov[i] * f.ov[i] - l.radius_sq[i];
        f.disc[i] = f.half_b[i] * f.half_b[i] - f.a[i] * cc;
        // `&`, not `&&`: a short-circuit here is a branch per lane, and the loop stays
        // scalar (its cylinder tests took 3.3x as long on SPD rings).
        f.passed[i] = (f.disc[i] >= -quick_miss_margin(f.oo[i])) & (f.a[i] > 0.0);
    }
    f
}

/// The lanes that passed the first stage but whose first-stage discriminant is not
/// accurate enough to keep ([`first_stage_suffices`]): the second stage runs there.
/// Also whether there is any.
#[inline(always)]
fn second_stage_lanes(
    passed: &[bool; LANES],
    disc: &[f32; LANES],
    a: &[f32; LANES],
    scale: &[f32; LANES],
) -> ([bool; LANES], bool) {
    let mut second = [false; LANES];
    let mut any = false;
    for i in 0..LANES {
        second[i] = passed[i] & !first_stage_suffices(disc[i], a[i], scale[i]);
        any |= second[i];
    }
    (second, any)
}

/// Counts the tests of one chunk and the first stage's operations of the scalar test.
#[inline(always)]
fn count_lanes<C: Counter>(c: &mut C, live: usize, subs: u64, dots: u64, test: Stat) {
    let n = live as u64;
    c.tally_n(Stat::LanesIssued, LANES as u64);
    c.tally_n(Stat::LanesActive, n);
    c.tally_n(test, n);
    c.tally_n(Stat::Sub, subs * n);
    c.tally_n(Stat::Dot, dots * n);
}

/// Counts the operations of the second stage, `ops` once for each live lane where it
/// ran.
#[inline(always)]
fn count_second_stage<C: Counter>(c: &mut C, live: usize, second: &[bool; LANES], ops: &[Stat]) {
    let lanes = second[..live].iter().filter(|&&s| s).count() as u64;
    for &op in ops {
        c.tally_n(op, lanes);
    }
}

/// Counts a chunk's square roots (lanes whose second-stage discriminant is positive)
/// and hits (lanes with an intersection inside the query's reach).
#[inline(always)]
fn count_roots_and_hits<C: Counter>(
    c: &mut C,
    live: usize,
    disc_positive: &[bool; LANES],
    t: &[f32; LANES],
    hit: Stat,
) {
    let roots = disc_positive[..live].iter().filter(|&&p| p).count();
    c.tally_n(Stat::Sqrt, roots as u64);
    let hits = t[..live].iter().filter(|x| x.is_finite()).count();
    c.tally_n(hit, hits as u64);
}

impl Intersector for Simd<'_> {
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit> {
        c.tally(Stat::Intersect);
        let reach = f32::INFINITY;
        let mut best = self.quadric_pass(ray, t_min, reach, false, c);
        let mut closest = best.map_or(f32::INFINITY, |h| h.t);
        let s = self.scene;
        let rest = [
            (PrimKind::Cone, s.cones.len()),
            (PrimKind::Polygon, s.polygons.len()),
            (PrimKind::Patch, s.patches.len()),
        ];
        for (kind, n) in rest {
            for index in 0..n as u32 {
                let prim = PrimRef { kind, index };
                if let Some((t, aux)) = intersect_primitive(s, prim, ray, t_min, reach, c)
                    && t < closest
                {
                    closest = t;
                    best = Some(Hit { t, prim, aux });
                }
            }
        }
        best
    }

    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool {
        c.tally(Stat::Intersect);
        let s = self.scene;
        self.quadric_pass(ray, t_min, t_max, true, c).is_some()
            || occluded_by_cones_and_planars(s, ray, t_min, t_max, c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::BruteForce;
    use crate::counter::{Count, NoCount};
    use crate::nff::parse_nff;
    use crate::vec3::Vec3;

    fn scene() -> Scene {
        // 19 spheres and 11 cylinders: partial last chunks on both, one inside-only
        // sphere and one inside-only cylinder.
        let mut text = String::from(
            "v\nfrom 0 -12 3\nat 0 0 0\nup 0 0 1\nangle 50\nhither 0\nresolution 8 8\n\
             l 4 -6 8\nf 1 1 1 1 0 1 0 1\ns 0 0 0 -6\nc\n0 0 -1 -7\n0 0 1 -7\n",
        );
        for i in 0..18 {
            let x = i as f32 * 0.7 - 6.0;
            text += &format!("s {x} {} 0.5 0.4\n", (i % 3) as f32);
        }
        for i in 0..10 {
            let x = i as f32 * 1.1 - 5.0;
            text += &format!("c\n{x} 1 -1 0.3\n{x} 1.5 1 0.3\n");
        }
        parse_nff(&text, "lanes.nff").unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn lane_utilization_counts_padding_lanes_as_idle() {
        // 19 spheres: chunks of 8, 8 and 3; 11 cylinders: 8 and 3. A ray that misses
        // everything tests every chunk: 5 chunks issue 40 lanes, 30 of them active.
        let scene = scene();
        let simd = Simd::new(&scene);
        let away: Ray = Ray {
            origin: Vec3::new(0.0, 0.0, 50.0),
            dir: Vec3::new(0.0, 0.0, 1.0),
        };
        let mut c = Count::default();
        assert!(simd.closest_hit(&away, 0.0, &mut c).is_none());
        assert_eq!(c.get(Stat::LanesIssued), 40);
        assert_eq!(c.get(Stat::LanesActive), 30);
        assert_eq!(c.get(Stat::SphereTest) + c.get(Stat::CylinderTest), 30);
        // A shadow query that misses tests the same chunks.
        let mut c = Count::default();
        assert!(!simd.occluded(&away, 0.0, f32::INFINITY, &mut c));
        assert_eq!(
            (c.get(Stat::LanesIssued), c.get(Stat::LanesActive)),
            (40, 30)
        );
    }

    #[test]
    fn lanes_agree_with_brute_force_on_hits_and_blockers() {
        let scene = scene();
        let brute = BruteForce::new(&scene);
        let simd = Simd::new(&scene);
        let mut state = 7u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
        };
        let mut hits = 0;
        for _ in 0..3000 {
            let origin = Vec3::new(next() * 6.0, -10.0 + next(), next() * 2.0);
            let dir = NoCount.normalize(Vec3::new(next() * 0.6, 1.0, next() * 0.4));
            let ray: Ray = Ray { origin, dir };
            let a = brute.closest_hit(&ray, 0.0, &mut NoCount);
            let b = simd.closest_hit(&ray, 0.0, &mut NoCount);
            assert_eq!(a.map(|h| h.prim), b.map(|h| h.prim), "{ray:?}");
            if let (Some(a), Some(b)) = (a, b) {
                assert!((a.t - b.t).abs() <= 1e-4 * a.t.max(1.0), "{a:?} {b:?}");
                hits += 1;
            }
            for limit in [0.5, 4.0, 30.0] {
                assert_eq!(
                    brute.occluded(&ray, 0.0, limit, &mut NoCount),
                    simd.occluded(&ray, 0.0, limit, &mut NoCount)
                );
            }
        }
        assert!(hits > 2000, "{hits}");
    }

    #[test]
    fn counts_cover_live_lanes_only() {
        let scene = scene();
        let simd = Simd::new(&scene);
        let ray: Ray = Ray {
            origin: Vec3::new(0.0, -10.0, 0.0),
            dir: Vec3::new(0.0, 1.0, 0.0),
        };
        let mut c = Count::default();
        simd.closest_hit(&ray, 0.0, &mut c);
        assert_eq!(c.get(Stat::SphereTest), 19);
        assert_eq!(c.get(Stat::CylinderTest), 11);
        // The first stage: one `sub` per live lane, two `dot` per sphere, four per
        // cylinder. Only the inside-only sphere and cylinder around the origin pass it
        // (the small ones are 0.5 or more from the ray, against radii of 0.4 and 0.3,
        // far outside its margin), and the ray passes through their middle: Voc =
        // (0, -10, 0) and (0, -10, 1), b/2 = -10, discriminants 100 - (100 - 36) = 36
        // and 100 - (101 - 1 - 49) = 49, far above |Voc|²/2⁸, so no second stage.
        assert_eq!(c.get(Stat::Sub), 30);
        assert_eq!((c.get(Stat::Scale), c.get(Stat::Cross)), (0, 0));
        assert_eq!(c.get(Stat::Dot), 19 * 2 + 11 * 4);
        assert_eq!(c.get(Stat::Intersect), 1);
        // Near the big sphere's rim, at x = 5.99: its discriminant 36 - 5.99² ≈ 0.12 is
        // below (100 + 5.99²)/2⁸ ≈ 0.53, so its second stage runs (scale, sub, dot);
        // the cylinder's 100 - (136.88 - 1 - 49) ≈ 13.1 is still kept.
        let rim: Ray = Ray {
            origin: Vec3::new(5.99, -10.0, 0.0),
            dir: Vec3::new(0.0, 1.0, 0.0),
        };
        let mut c = Count::default();
        let brute = BruteForce::new(&scene).closest_hit(&rim, 0.0, &mut NoCount);
        assert_eq!(simd.closest_hit(&rim, 0.0, &mut c), brute);
        assert_eq!(c.get(Stat::Sub), 30 + 1);
        assert_eq!((c.get(Stat::Scale), c.get(Stat::Cross)), (1, 0));
        assert_eq!(c.get(Stat::Dot), 19 * 2 + 11 * 4 + 1);
    }
}

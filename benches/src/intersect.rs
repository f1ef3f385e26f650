//! Group `intersect`: one call of each ray-primitive test, for a ray that hits and a
//! ray that misses (a miss usually leaves early: negative discriminant, or the plane
//! hit falls outside the outline), uncounted ([`NoCount`]).
//!
//! Benchmarks are `intersect/<primitive>/<hit|miss>` for sphere, cylinder, cone,
//! polygon, patch and plane (the plane test alone, [`PlanarOutline::intersect_plane`],
//! that polygons and patches run before their crossing test). The plane's miss is a
//! ray parallel to it. All primitives are built from the NFF-style constructors; every
//! ray has a unit direction, as the tracer's tests assume.

use criterion::{BenchmarkId, Criterion};
use std::hint::black_box;
use tracer::primitives::{Cone, Cylinder, Patch, PlanarOutline, Polygon, Sphere};
use tracer::{NoCount, Ray, Vec3};

/// The primitives the group tests, one of each kind.
pub struct Primitives {
    pub sphere: Sphere,
    pub cylinder: Cylinder,
    pub cone: Cone,
    pub polygon: Polygon,
    pub patch: Patch,
    /// The polygon's outline, for the plane test alone.
    pub plane: PlanarOutline,
}

/// A hit ray and a miss ray for one primitive.
#[derive(Clone, Copy, Debug)]
pub struct RayPair {
    pub hit: Ray,
    pub miss: Ray,
}

/// The rays of every primitive, in the order of [`Primitives`].
pub struct Rays {
    pub sphere: RayPair,
    pub cylinder: RayPair,
    pub cone: RayPair,
    pub polygon: RayPair,
    pub patch: RayPair,
    pub plane: RayPair,
}

fn ray(origin: [f32; 3], dir: [f32; 3]) -> Ray {
    Ray {
        origin: Vec3::from_array(origin),
        dir: Vec3::from_array(dir),
    }
}

/// A square in the plane z = 0, counter-clockwise seen from +z.
fn square() -> Vec<Vec3> {
    vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
    ]
}

/// One primitive of each kind: a sphere of radius 1 at the origin, a cylinder and a
/// cone along +z from the origin, a square in z = 0 as polygon and as patch.
pub fn primitives() -> Primitives {
    let z = Vec3::new(0.0, 0.0, 2.0);
    let polygon = Polygon::new(square(), 0).unwrap_or_else(|e| panic!("{e}"));
    let normals = vec![
        Vec3::new(0.0, 0.1, 1.0),
        Vec3::new(0.1, 0.0, 1.0),
        Vec3::new(0.0, -0.1, 1.0),
        Vec3::new(-0.1, 0.0, 1.0),
    ];
    Primitives {
        sphere: Sphere::new(Vec3::ZERO, 1.0, 0),
        cylinder: Cylinder::new(Vec3::ZERO, z, 1.0, 0).unwrap_or_else(|e| panic!("{e}")),
        cone: Cone::new(Vec3::ZERO, 1.0, z, 0.25, 0).unwrap_or_else(|e| panic!("{e}")),
        plane: polygon.outline.clone(),
        polygon,
        patch: Patch::new(square(), normals, 0).unwrap_or_else(|e| panic!("{e}")),
    }
}

/// The hit and miss rays: quadrics are shot at sideways (along +x) at z = 1, hits
/// through the axis, misses 1.5 beside it; the planar ones from above (along -z),
/// hits inside the square, misses beside it (the plane miss runs parallel to it).
pub fn rays() -> Rays {
    let sideways = |y: f32| ray([-5.0, y, 1.0], [1.0, 0.0, 0.0]);
    let down = |x: f32| ray([x, 0.25, 3.0], [0.0, 0.0, -1.0]);
    let quadric = RayPair {
        hit: sideways(0.0),
        miss: sideways(1.5),
    };
    let planar = RayPair {
        hit: down(0.5),
        miss: down(1.5),
    };
    Rays {
        sphere: RayPair {
            hit: ray([-5.0, 0.25, 0.0], [1.0, 0.0, 0.0]),
            miss: ray([-5.0, 1.5, 0.0], [1.0, 0.0, 0.0]),
        },
        cylinder: quadric,
        cone: quadric,
        polygon: planar,
        patch: planar,
        plane: RayPair {
            hit: planar.hit,
            miss: ray([-5.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        },
    }
}

/// The distance at which each test reports a hit for `pick`'s ray of each pair, in the
/// order sphere, cylinder, cone, polygon, patch, plane.
pub fn distances(p: &Primitives, r: &Rays, pick: fn(&RayPair) -> Ray) -> [Option<f32>; 6] {
    let (t0, t1, c) = (0.0, f32::INFINITY, &mut NoCount);
    [
        p.sphere.intersect(&pick(&r.sphere), t0, t1, c),
        p.cylinder
            .intersect(&pick(&r.cylinder), t0, t1, c)
            .map(|h| h.0),
        p.cone.intersect(&pick(&r.cone), t0, t1, c).map(|h| h.0),
        p.polygon.intersect(&pick(&r.polygon), t0, t1, c),
        p.patch.intersect(&pick(&r.patch), t0, t1, c),
        p.plane.intersect_plane(&pick(&r.plane), t0, t1, c),
    ]
}

/// Registers `intersect/<name>/hit` and `intersect/<name>/miss` for `test`.
macro_rules! bench_pair {
    ($group:expr, $name:literal, $rays:expr, |$ray:ident| $test:expr) => {
        for (case, ray) in [("hit", $rays.hit), ("miss", $rays.miss)] {
            $group.bench_function(BenchmarkId::new($name, case), |b| {
                b.iter(|| {
                    let $ray = black_box(&ray);
                    $test
                })
            });
        }
    };
}

/// The `intersect` group.
pub fn bench_intersect(c: &mut Criterion) {
    let p = primitives();
    let r = rays();
    let (t0, t1) = (0.0, f32::INFINITY);
    let mut group = c.benchmark_group("intersect");
    bench_pair!(group, "sphere", r.sphere, |ray| black_box(&p.sphere)
        .intersect(ray, t0, t1, &mut NoCount));
    bench_pair!(group, "cylinder", r.cylinder, |ray| black_box(&p.cylinder)
        .intersect(ray, t0, t1, &mut NoCount));
    bench_pair!(group, "cone", r.cone, |ray| black_box(&p.cone).intersect(
        ray,
        t0,
        t1,
        &mut NoCount
    ));
    bench_pair!(group, "polygon", r.polygon, |ray| black_box(&p.polygon)
        .intersect(ray, t0, t1, &mut NoCount));
    bench_pair!(group, "patch", r.patch, |ray| black_box(&p.patch)
        .intersect(ray, t0, t1, &mut NoCount));
    bench_pair!(group, "plane", r.plane, |ray| black_box(&p.plane)
        .intersect_plane(ray, t0, t1, &mut NoCount));
    group.finish();
}

#[cfg(test)]
mod tests {
    use super::*;
    use tracer::Counter;

    #[test]
    fn every_hit_ray_hits_where_expected() {
        let hits = distances(&primitives(), &rays(), |pair| pair.hit);
        // Sphere: enters at x = -sqrt(1 - 0.25²); cylinder: x = -1; cone at z = 1 has
        // radius 1 - 0.375 = 0.625; planar: 3 above the square.
        let sphere = 5.0 - NoCount.sqrt(1.0 - 0.25 * 0.25);
        let want = [sphere, 4.0, 5.0 - 0.625, 3.0, 3.0, 3.0];
        for (i, (got, want)) in hits.iter().zip(want).enumerate() {
            let got = got.unwrap_or(f32::NAN);
            assert!((got - want).abs() < 1e-5, "primitive {i}: {got} vs {want}");
        }
    }

    #[test]
    fn every_miss_ray_misses() {
        let misses = distances(&primitives(), &rays(), |pair| pair.miss);
        assert_eq!(misses, [None; 6]);
    }
}

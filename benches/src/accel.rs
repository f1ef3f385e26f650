//! Group `accel`: closest-hit queries of the three intersection structures on
//! sphereflakes of growing size, to show how each scales with the primitive count:
//! `baseline` ([`BruteForce`]: every sphere per ray), `simd` ([`Simd`]: eight spheres
//! per step), `bvh` ([`Bvh`]: binned-SAH hierarchy) and `bvh+simd` ([`WideBvh`]: the
//! hierarchy with 8-wide nodes and sphere packs).
//!
//! Each benchmark answers one batch of 256 eye rays (a 16x16 grid over the flake's SPD
//! view narrowed to frame the flake, most of them hitting) and is named `accel/<structure>/<spheres>` for
//! sphereflakes of depth 1 to 5: 10, 91, 820, 7381 and 66430 spheres. Scenes and
//! structures are built before the timed loop. The two largest sizes take fewer
//! samples (brute force there costs tens of milliseconds per batch).

use criterion::{BenchmarkGroup, BenchmarkId, Criterion, Throughput, measurement::WallTime};
use std::hint::black_box;
use std::time::Duration;
use tracer::{
    BruteForce, Bvh, BvhBuilder, Camera, Intersector, NoCount, Ray, Sampling, Scene, Simd, View,
    WideBvh,
};

/// Sphereflake depths the group runs.
pub const DEPTHS: [u32; 5] = [1, 2, 3, 4, 5];

/// Side of the square grid of eye rays in one batch.
pub const RAY_GRID: u32 = 16;

/// The sphereflake of `depth` levels (SPD view and lights, no ground polygon).
pub fn sphereflake(depth: u32) -> Scene {
    let text = tracer::generators::sphereflake(depth).unwrap_or_else(|e| panic!("{e}"));
    tracer::parse_nff(&text, &format!("sphereflake:{depth}")).unwrap_or_else(|e| panic!("{e}"))
}

/// Field of view of the batch: the SPD view narrowed from 45° to 25° so that the grid
/// frames the flake (about 70-85 % of the rays hit, silhouettes included) instead of
/// mostly sky (25-30 % at 45°).
pub const RAY_ANGLE_DEG: f32 = 25.0;

/// The batch of eye rays: the centres of a [`RAY_GRID`]² grid over the scene's view
/// narrowed to [`RAY_ANGLE_DEG`].
pub fn eye_rays(scene: &Scene) -> Vec<Ray> {
    let view = View {
        angle_deg: RAY_ANGLE_DEG,
        ..scene.view.clone()
    };
    let camera = Camera::perspective(
        &view,
        RAY_GRID,
        RAY_GRID,
        Sampling::PixelCenters,
        &mut NoCount,
    )
    .unwrap_or_else(|e| panic!("invalid camera: {e}"));
    (0..RAY_GRID)
        .flat_map(|row| (0..RAY_GRID).map(move |column| (column, row)))
        .map(|(column, row)| camera.ray(column, row, &mut NoCount))
        .collect()
}

/// The closest hit of every ray of the batch; returns how many hit (kept alive so the
/// queries are not optimized away).
#[inline(never)]
pub fn closest_hits<I: Intersector>(accel: &I, rays: &[Ray]) -> usize {
    rays.iter()
        .filter(|ray| accel.closest_hit(ray, 0.0, &mut NoCount).is_some())
        .count()
}

/// Registers `accel/<name>/<spheres>` for one structure.
fn bench_structure<I: Intersector>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    spheres: usize,
    accel: &I,
    rays: &[Ray],
) {
    group.bench_with_input(BenchmarkId::new(name, spheres), rays, |b, rays| {
        b.iter(|| closest_hits(black_box(accel), black_box(rays)))
    });
}

/// The `accel` group.
pub fn bench_accel(c: &mut Criterion) {
    let mut group = c.benchmark_group("accel");
    group.throughput(Throughput::Elements(u64::from(RAY_GRID * RAY_GRID)));
    for depth in DEPTHS {
        let scene = sphereflake(depth);
        let rays = eye_rays(&scene);
        let spheres = scene.spheres.len();
        let (brute_force, simd, bvh, wide) = (
            BruteForce::new(&scene),
            Simd::new(&scene),
            Bvh::build(&scene),
            WideBvh::build_with(&scene, BvhBuilder::BinnedSah),
        );
        if spheres > 5_000 {
            // Brute force at 66430 spheres takes ~50 ms per batch: 10 samples need
            // 55 batches, about 3 s.
            group.sample_size(10);
            group.measurement_time(Duration::from_secs(4));
        } else {
            group.sample_size(50);
            group.measurement_time(Duration::from_secs(2));
        }
        bench_structure(&mut group, "baseline", spheres, &brute_force, &rays);
        bench_structure(&mut group, "simd", spheres, &simd, &rays);
        bench_structure(&mut group, "bvh", spheres, &bvh, &rays);
        bench_structure(&mut group, "bvh+simd", spheres, &wide, &rays);
    }
    group.finish();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphereflake_depths_one_to_five_have_the_expected_sphere_counts() {
        let counts: Vec<usize> = DEPTHS.map(|d| sphereflake(d).spheres.len()).to_vec();
        assert_eq!(counts, [10, 91, 820, 7381, 66430]);
        let generator: Vec<u64> = DEPTHS
            .map(tracer::generators::sphereflake_sphere_count)
            .to_vec();
        assert_eq!(generator, [10, 91, 820, 7381, 66430]);
    }

    #[test]
    fn the_three_structures_agree_and_most_rays_hit() {
        let scene = sphereflake(2);
        let rays = eye_rays(&scene);
        assert_eq!(rays.len(), 256);
        let brute_force = BruteForce::new(&scene);
        let (simd, bvh) = (Simd::new(&scene), Bvh::build(&scene));
        let hits = closest_hits(&brute_force, &rays);
        assert!(hits > 180, "{hits} of 256 rays hit");
        for ray in &rays {
            let want = brute_force.closest_hit(ray, 0.0, &mut NoCount);
            assert_eq!(simd.closest_hit(ray, 0.0, &mut NoCount), want);
            assert_eq!(bvh.closest_hit(ray, 0.0, &mut NoCount), want);
        }
    }
}

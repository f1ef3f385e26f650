//! Rays per second by kind: a clocked pass ([`tracer::counter::QueryClock`]) gives the
//! share of the worker threads' time each kind of query took; applied to the timed,
//! unclocked render, the shares give eye, secondary and shadow rays per second (the
//! table ray-tracing papers publish), and every ray over the whole time.

use std::time::Instant;

use results::RayRates;
use tracer::counter::{QueryClock, QueryTicks, clock_ticks, take_query_ticks};
use tracer::{RayCounts, VariantSet, render_variant_until};

use crate::error::RunError;
use crate::render_setup::RenderSetup;

/// What a clocked pass measured: the query shares of the threads' time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QueryShares {
    /// Eye, secondary, shadow queries and busy rows: shares of threads × wall ticks.
    pub shares: [f64; 4],
    /// Wall seconds of the clocked render.
    pub seconds: f64,
}

/// Renders `set` once with the query clock on `setup`'s pool.
pub fn clocked_pass(setup: &RenderSetup, set: &VariantSet) -> Result<QueryShares, RunError> {
    let pool = setup.pool;
    // Clear what earlier passes left on the workers.
    pool.broadcast(|_| take_query_ticks());
    let start = Instant::now();
    let first = clock_ticks();
    pool.install(|| {
        render_variant_until::<QueryClock>(setup.scene, setup.options, set, &|_| {}, setup.stop)
    })
    .map_err(|e| RunError::render(setup.name, &e))?;
    let wall = clock_ticks().wrapping_sub(first);
    let seconds = start.elapsed().as_secs_f64();
    let mut ticks: QueryTicks = take_query_ticks();
    for worker in pool.broadcast(|_| take_query_ticks()) {
        for (total, t) in ticks.iter_mut().zip(worker) {
            *total += t;
        }
    }
    let capacity = (wall as f64 * pool.current_num_threads() as f64).max(1.0);
    Ok(QueryShares {
        shares: ticks.map(|t| (t as f64 / capacity).min(1.0)),
        seconds,
    })
}

/// The rates of a render of `rays` that took `seconds` (unclocked), split by `shares`.
pub fn ray_rates(shares: &QueryShares, rays: &RayCounts, seconds: f64) -> RayRates {
    let [eye, secondary, shadow, busy] = shares.shares;
    let busy = busy.max(eye + secondary + shadow).min(1.0);
    let secondary_rays = rays.reflection + rays.refraction;
    let rate = |n: u64, share: f64| {
        let time = share * seconds;
        (n > 0 && time > 0.0).then(|| n as f64 / time / 1e6)
    };
    let all = rays.primary + secondary_rays + rays.shadow;
    RayRates {
        eye_fraction: eye,
        secondary_fraction: secondary,
        shadow_fraction: shadow,
        other_fraction: (busy - eye - secondary - shadow).max(0.0),
        idle_fraction: 1.0 - busy,
        eye_mrays_per_s: rate(rays.primary, eye),
        secondary_mrays_per_s: rate(secondary_rays, secondary),
        shadow_mrays_per_s: rate(rays.shadow, shadow),
        all_mrays_per_s: if seconds > 0.0 {
            all as f64 / seconds / 1e6
        } else {
            0.0
        },
        clock_overhead: if seconds > 0.0 {
            shares.seconds / seconds
        } else {
            0.0
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;
    use tracer::{RenderOptions, Sampling, ShadingMode, parse_nff};

    #[test]
    fn rates_divide_each_kind_by_its_share_of_the_time() {
        let rays = RayCounts {
            primary: 1_000_000,
            shadow: 500_000,
            reflection: 200_000,
            refraction: 50_000,
            ..RayCounts::default()
        };
        let shares = QueryShares {
            shares: [0.5, 0.1, 0.25, 0.95],
            seconds: 2.2,
        };
        let r = ray_rates(&shares, &rays, 2.0);
        // Eye: 1 M rays in 0.5 × 2 s = 1 Mrays/s; secondary 250 k in 0.2 s; shadow
        // 500 k in 0.5 s.
        assert!((r.eye_mrays_per_s.unwrap_or(0.0) - 1.0).abs() < 1e-12);
        assert!((r.secondary_mrays_per_s.unwrap_or(0.0) - 1.25).abs() < 1e-12);
        assert!((r.shadow_mrays_per_s.unwrap_or(0.0) - 1.0).abs() < 1e-12);
        assert!((r.other_fraction - 0.10).abs() < 1e-12);
        assert!((r.idle_fraction - 0.05).abs() < 1e-12);
        assert!((r.all_mrays_per_s - 1.75 / 2.0).abs() < 1e-12);
        assert!((r.clock_overhead - 1.1).abs() < 1e-12);
        let none = ray_rates(&shares, &RayCounts::default(), 2.0);
        assert_eq!(none.eye_mrays_per_s, None);
    }

    #[test]
    fn a_clocked_pass_splits_a_render_that_traces_every_kind() {
        // A mirror sphere over a floor lit by one light: eye, reflection and shadow rays.
        let scene = parse_nff(
            "v\nfrom 0 -8 3\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 32 32\n\
             l 3 -3 8\nf 1 1 1 0.5 0.5 8 0 1\ns 0 0 1 1\np 4\n-5 -5 0\n5 -5 0\n5 5 0\n-5 5 0\n",
            "mirror.nff",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let options = RenderOptions::new(32, 32, Sampling::PixelCenters, ShadingMode::Color);
        let pool = crate::pool::thread_pool(Some(2)).unwrap_or_else(|e| panic!("{e}"));
        let stop = AtomicBool::new(false);
        let setup = RenderSetup {
            scene: &scene,
            name: "mirror",
            options: &options,
            pool: &pool,
            counting_pool: &pool,
            stop: &stop,
        };
        let set = VariantSet::parse("baseline").unwrap_or_else(|e| panic!("{e}"));
        let shares = clocked_pass(&setup, &set).unwrap_or_else(|e| panic!("{e}"));
        let [eye, secondary, shadow, busy] = shares.shares;
        assert!(eye > 0.0 && secondary > 0.0 && shadow > 0.0, "{shares:?}");
        // The queries run inside the rows, the rows inside the pass.
        assert!(
            eye + secondary + shadow <= busy && busy <= 1.0,
            "{shares:?}"
        );
    }
}

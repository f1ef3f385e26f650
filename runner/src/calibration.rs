//! The calibration kernel: a fixed amount of floating-point work that does not depend on
//! the tracer's code, timed on the renders' own threads once per timing round. Its time
//! moves with the machine (a busier or slower second run), not with the program, so the
//! gate can judge the reference variant's time relative to it (results::gate).
//!
//! The work is a ray-sphere-like quadratic (products, a square root, a compare) over a
//! pseudo-random stream, in chunks spread over the pool like a render's rows.

use std::hint::black_box;
use std::time::Instant;

use rayon::prelude::*;

/// Chunks of work (more than any pool has threads, so every thread takes part).
const CHUNKS: u64 = 64;
/// Steps per chunk: about 3 ms of work for two threads on the reference machine.
const STEPS: u32 = 6_000;

/// Runs the kernel once on `pool` and returns its wall time in seconds.
pub fn time_kernel(pool: &rayon::ThreadPool) -> f64 {
    let start = Instant::now();
    let total: f64 = pool.install(|| (0..CHUNKS).into_par_iter().map(chunk).sum());
    black_box(total);
    start.elapsed().as_secs_f64()
}

/// One chunk: `STEPS` quadratic solutions from a linear congruential stream.
fn chunk(seed: u64) -> f64 {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut acc = 0.0f64;
    for _ in 0..STEPS {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let u = (state >> 11) as f64 / (1u64 << 53) as f64;
        let b = black_box(u) * 2.0 - 1.0;
        let c = u * u - 0.25;
        let discriminant = b * b - c;
        if discriminant > 0.0 {
            acc += -b - discriminant.sqrt();
        }
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_work_is_fixed_and_takes_time() {
        // The same seed gives the same sum (the work does not depend on anything else).
        assert_eq!(chunk(7).to_bits(), chunk(7).to_bits());
        assert_ne!(chunk(7).to_bits(), chunk(8).to_bits());
        let pool = crate::pool::thread_pool(Some(1)).unwrap();
        let t = time_kernel(&pool);
        assert!(t > 0.0 && t.is_finite());
    }
}

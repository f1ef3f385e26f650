//! The machine's roofs for the roofline model: two floating-point peaks (chains of fused
//! multiply-adds, independent enough to fill both FMA pipes, once in SIMD lanes and
//! once one lane wide in scalar instructions, the roof of code that does not use the
//! lanes, as Intel Advisor draws both) and two bandwidths, the
//! STREAM triad over arrays far larger than the caches (DRAM) and over arrays that stay
//! in L1 (the cache-aware roofline's top memory roof), all on every thread of the
//! renders' pool, in AVX2 where the processor has it (as the tracer's `simd` runs).
//! Each runs a few times and keeps its best, as STREAM does: the roof is what the
//! machine can do, not what it did while busy. For the same reason the compute and L1
//! kernels, which use each core's own units, are timed by the time their threads were
//! on a core (the process's CPU time), not by the wall clock, which on a loaded machine
//! counts the time other work held the cores (`on_every_core`).
//!
//! The kernels are written in intrinsics, the triad unrolled by hand, so that what they
//! measure does not depend on the optimiser: this crate is built at opt-level 1 (the
//! release profile's choice for crates that do no hot work), where LLVM does not
//! vectorise loops, and the triad written as a plain loop ran at a twentieth of the L1
//! bandwidth (about 10 GB/s a core against 200 at opt-level 3 on a Zen 3).

use std::hint::black_box;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use analysis::profile::sampler::process_cpu_time;
use rayon::prelude::*;
use results::MachinePeak;

use crate::error::RunError;

/// Lanes of one vector.
const LANES: usize = 8;
/// Independent FMA chains per thread: latency (4-5 cycles) × 2 pipes, rounded up.
const CHAINS: usize = 12;
/// Repetitions; the best is kept.
const REPEATS: usize = 3;
/// The multiplier and addend of the chains: `x ← x·A + B` stays finite and normal.
const A: f32 = 0.999_999;
const B: f32 = 1e-6;

/// How long each measurement runs.
#[derive(Clone, Copy, Debug)]
pub struct PeakPlan {
    /// Seconds of one FMA run.
    pub fma_seconds: f64,
    /// Elements of each of the triad's three arrays.
    pub stream_elements: usize,
}

impl PeakPlan {
    /// About a second in all: 0.1 s per FMA run, 3 × 32 MiB arrays.
    pub const FULL: PeakPlan = PeakPlan {
        fma_seconds: 0.1,
        stream_elements: 8 << 20,
    };
    /// For `--quick`: a tenth of the FMA time, 3 × 16 MiB (still past the caches).
    pub const QUICK: PeakPlan = PeakPlan {
        fma_seconds: 0.01,
        stream_elements: 4 << 20,
    };
}

/// Seconds of one chunk of a kernel run: each thread reads the stop flag between
/// chunks, so a stop takes effect within about this (a load every few milliseconds
/// costs nothing measurable).
const CHUNK_SECONDS: f64 = 0.005;

/// Measures the roofs on `pool`; [`RunError::Stopped`] within a chunk's time once
/// `stop` is set.
pub fn measure_peak(
    pool: &rayon::ThreadPool,
    plan: PeakPlan,
    stop: &AtomicBool,
) -> Result<MachinePeak, RunError> {
    let threads = pool.current_num_threads();
    let (peak_gflops, fma_kernel) = fma_peak(pool, plan.fma_seconds, stop)?;
    let (scalar_peak_gflops, scalar_kernel) = scalar_peak(pool, plan.fma_seconds, stop)?;
    let bandwidth_gbs = stream_bandwidth(pool, plan.stream_elements, stop)?;
    let cache_bandwidth_gbs = l1_bandwidth(pool, plan.fma_seconds, stop)?;
    Ok(MachinePeak {
        peak_gflops,
        bandwidth_gbs,
        cache_bandwidth_gbs,
        threads: threads as u32,
        fma_kernel,
        stream_bytes: 3 * 4 * plan.stream_elements as u64,
        scalar_peak_gflops: Some(scalar_peak_gflops),
        scalar_kernel: Some(scalar_kernel),
    })
}

/// `Stopped` once `stop` is set.
fn check(stop: &AtomicBool) -> Result<(), RunError> {
    match stop.load(Ordering::Relaxed) {
        true => Err(RunError::Stopped),
        false => Ok(()),
    }
}

/// Runs `kernel` for `total` steps in chunks of `chunk`, reading `stop` before each;
/// the sum of the chunks' results (each chunk starts its chains afresh, which costs
/// nothing beside its thousands of steps).
fn chunked(total: u64, chunk: u64, stop: &AtomicBool, kernel: impl Fn(u64) -> f32) -> f32 {
    let mut left = total;
    let mut sum = 0.0;
    while left > 0 && !stop.load(Ordering::Relaxed) {
        let steps = left.min(chunk.max(1));
        sum += kernel(steps);
        left -= steps;
    }
    sum
}

/// GFLOP/s of the FMA chains in SIMD lanes on every thread of `pool` and what they ran.
fn fma_peak(
    pool: &rayon::ThreadPool,
    seconds: f64,
    stop: &AtomicBool,
) -> Result<(f64, String), RunError> {
    let avx2 = has_avx2_fma();
    let kernel = if avx2 {
        format!("AVX2+FMA, {LANES} lanes × {CHAINS} chains")
    } else {
        format!("portable multiply-add, {LANES} lanes × {CHAINS} chains")
    };
    let flops_per_step = 2 * LANES * CHAINS;
    let best = best_gflops(pool, (seconds, stop), flops_per_step, &|steps, seed| {
        chains(steps, seed, avx2)
    })?;
    Ok((best, kernel))
}

/// GFLOP/s of the same chains one lane wide, in scalar instructions (`vfmadd…ss`
/// where the processor has FMA, a scalar multiply and add otherwise), on every thread
/// of `pool`, and what they ran.
fn scalar_peak(
    pool: &rayon::ThreadPool,
    seconds: f64,
    stop: &AtomicBool,
) -> Result<(f64, String), RunError> {
    let fma = has_fma();
    let kernel = if fma {
        format!("scalar FMA, 1 lane × {CHAINS} chains")
    } else {
        format!("scalar multiply-add, 1 lane × {CHAINS} chains")
    };
    let best = best_gflops(pool, (seconds, stop), 2 * CHAINS, &|steps, seed| {
        scalar_chains(steps, seed, fma)
    })?;
    Ok((best, kernel))
}

/// The best GFLOP/s of [`REPEATS`] runs of `kernel` (`steps` from a seed, doing
/// `flops_per_step` each) on every thread of `pool`, each run sized from a short
/// probe on one thread to last about `seconds`, in chunks that read `stop`.
fn best_gflops(
    pool: &rayon::ThreadPool,
    (seconds, stop): (f64, &AtomicBool),
    flops_per_step: usize,
    kernel: &(dyn Fn(u64, f32) -> f32 + Sync),
) -> Result<f64, RunError> {
    let probe = 20_000u64;
    let start = Instant::now();
    black_box(kernel(probe, 1.0));
    let per_step = start.elapsed().as_secs_f64().max(1e-9) / probe as f64;
    let steps = ((seconds / per_step) as u64).max(probe);
    let chunk = ((CHUNK_SECONDS / per_step) as u64).max(probe);
    let mut best = 0.0f64;
    for _ in 0..REPEATS {
        let (sums, elapsed) = on_every_core(pool, |ctx| {
            chunked(steps, chunk, stop, |n| kernel(n, 1.0 + ctx.index() as f32))
        });
        check(stop)?;
        black_box(sums);
        let flops = flops_per_step as f64 * steps as f64 * pool.current_num_threads() as f64;
        best = best.max(flops / elapsed / 1e9);
    }
    Ok(best)
}

/// Runs `work` once on every thread of `pool`; its results and the seconds a thread
/// spent on a core: the process's CPU time over the threads, at most the wall time.
/// The compute and L1 kernels use each core's own units, so what a core does while it
/// runs them is the machine's roof, even when other load (another process, a build)
/// takes the cores away for part of the wall time: the wall time would count those
/// gaps as the kernel's. (The DRAM triad, on a shared bus, keeps the wall time.)
fn on_every_core<T: Send>(
    pool: &rayon::ThreadPool,
    work: impl Fn(rayon::BroadcastContext<'_>) -> T + Sync,
) -> (Vec<T>, f64) {
    let (cpu, start) = (process_cpu_time(), Instant::now());
    let results = pool.broadcast(work);
    let wall = start.elapsed().as_secs_f64();
    let cpu = process_cpu_time().saturating_sub(cpu).as_secs_f64();
    (
        results,
        on_core_seconds(wall, cpu, pool.current_num_threads()),
    )
}

/// The seconds one of `threads` threads was on a core, from the wall time and the
/// process's CPU time over that time: the CPU time's share, at most the wall time (a
/// process clock that read nothing leaves the wall time).
fn on_core_seconds(wall: f64, cpu: f64, threads: usize) -> f64 {
    let share = cpu / threads.max(1) as f64;
    if share > 0.0 { share.min(wall) } else { wall }
}

/// Runs `steps` of every chain from `seed`; the sum of the final values.
fn chains(steps: u64, seed: f32, avx2: bool) -> f32 {
    #[cfg(target_arch = "x86_64")]
    if avx2 {
        // SAFETY: the caller checked that the processor has AVX2 and FMA.
        return unsafe { chains_avx2(steps, seed) };
    }
    let _ = avx2;
    chains_portable(steps, seed)
}

fn chains_portable(steps: u64, seed: f32) -> f32 {
    let mut x = [[seed; LANES]; CHAINS];
    for _ in 0..steps {
        for chain in &mut x {
            for lane in chain.iter_mut() {
                *lane = *lane * A + B;
            }
        }
        black_box(&mut x);
    }
    x.iter().flatten().sum()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn chains_avx2(steps: u64, seed: f32) -> f32 {
    use std::arch::x86_64::{
        __m256, _mm256_add_ps, _mm256_fmadd_ps, _mm256_set1_ps, _mm256_storeu_ps,
    };
    let (a, b) = (_mm256_set1_ps(A), _mm256_set1_ps(B));
    let mut x: [__m256; CHAINS] = [_mm256_set1_ps(seed); CHAINS];
    for _ in 0..steps {
        for chain in &mut x {
            *chain = _mm256_fmadd_ps(*chain, a, b);
        }
    }
    let mut total = _mm256_set1_ps(0.0);
    for chain in x {
        total = _mm256_add_ps(total, chain);
    }
    let mut lanes = [0.0f32; LANES];
    // SAFETY: `lanes` holds 8 floats.
    unsafe { _mm256_storeu_ps(lanes.as_mut_ptr(), total) };
    lanes.iter().sum()
}

/// Runs `steps` of [`CHAINS`] scalar chains from `seed`; the sum of the final values.
fn scalar_chains(steps: u64, seed: f32, fma: bool) -> f32 {
    #[cfg(target_arch = "x86_64")]
    {
        if fma {
            // SAFETY: the caller checked that the processor has FMA.
            return unsafe { scalar_chains_fma(steps, seed) };
        }
        // SAFETY: every x86-64 processor has SSE.
        unsafe { scalar_chains_sse(steps, seed) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = fma;
        scalar_chains_portable(steps, seed)
    }
}

/// The chains in `vfmadd…ss`: one lane of an XMM register each, written with the
/// scalar intrinsics so that no optimiser packs them into vectors.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
fn scalar_chains_fma(steps: u64, seed: f32) -> f32 {
    use std::arch::x86_64::{__m128, _mm_cvtss_f32, _mm_fmadd_ss, _mm_set_ss};
    let (a, b) = (_mm_set_ss(A), _mm_set_ss(B));
    let mut x: [__m128; CHAINS] = [_mm_set_ss(seed); CHAINS];
    for _ in 0..steps {
        for chain in &mut x {
            *chain = _mm_fmadd_ss(*chain, a, b);
        }
    }
    x.iter().map(|&chain| _mm_cvtss_f32(chain)).sum()
}

/// The chains as a scalar multiply and add (SSE, every x86-64 has it).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "sse")]
fn scalar_chains_sse(steps: u64, seed: f32) -> f32 {
    use std::arch::x86_64::{__m128, _mm_add_ss, _mm_cvtss_f32, _mm_mul_ss, _mm_set_ss};
    let (a, b) = (_mm_set_ss(A), _mm_set_ss(B));
    let mut x: [__m128; CHAINS] = [_mm_set_ss(seed); CHAINS];
    for _ in 0..steps {
        for chain in &mut x {
            *chain = _mm_add_ss(_mm_mul_ss(*chain, a), b);
        }
    }
    x.iter().map(|&chain| _mm_cvtss_f32(chain)).sum()
}

/// The chains in plain f32 (other architectures), kept in memory between steps.
#[cfg(not(target_arch = "x86_64"))]
fn scalar_chains_portable(steps: u64, seed: f32) -> f32 {
    let mut x = [seed; CHAINS];
    for _ in 0..steps {
        for chain in &mut x {
            *chain = *chain * A + B;
        }
        black_box(&mut x);
    }
    x.iter().sum()
}

fn has_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

fn has_avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// GB/s of the triad `a = b + s·c` over `n` elements per array, split over `pool`.
/// A pass reads the stop flag before it starts: one pass over 3 × 32 MiB is a few
/// hundredths of a second.
fn stream_bandwidth(
    pool: &rayon::ThreadPool,
    n: usize,
    stop: &AtomicBool,
) -> Result<f64, RunError> {
    let avx2 = has_avx2_fma();
    pool.install(|| {
        let chunk = n.div_ceil(pool.current_num_threads() * 4).max(1);
        // First touch in parallel, so each thread's pages are its own.
        let mut a = vec![0.0f32; n];
        let mut b = vec![0.0f32; n];
        let mut c = vec![0.0f32; n];
        b.par_chunks_mut(chunk).for_each(|s| s.fill(1.0));
        c.par_chunks_mut(chunk).for_each(|s| s.fill(2.0));
        a.par_chunks_mut(chunk).for_each(|s| s.fill(0.0));
        let scalar = black_box(3.0f32);
        let mut best = 0.0f64;
        for _ in 0..REPEATS + 2 {
            check(stop)?;
            let start = Instant::now();
            a.par_chunks_mut(chunk)
                .zip(b.par_chunks(chunk).zip(c.par_chunks(chunk)))
                .for_each(|(a, (b, c))| triad_best(a, b, c, scalar, avx2));
            let elapsed = start.elapsed().as_secs_f64();
            black_box(&a);
            best = best.max((12 * n) as f64 / elapsed / 1e9);
        }
        Ok(best)
    })
}

/// Elements of each array of the L1 triad: 3 × 2 KiB, well inside a 32 KiB L1.
const L1_ELEMENTS: usize = 512;

/// GB/s of the triad over arrays in each thread's L1, repeated for about `seconds`.
fn l1_bandwidth(
    pool: &rayon::ThreadPool,
    seconds: f64,
    stop: &AtomicBool,
) -> Result<f64, RunError> {
    let avx2 = has_avx2_fma();
    let run = |passes: u64| {
        let (mut a, b, c) = (
            [0.0f32; L1_ELEMENTS],
            [1.0f32; L1_ELEMENTS],
            [2.0f32; L1_ELEMENTS],
        );
        let s = black_box(3.0f32);
        for _ in 0..passes {
            triad_best(&mut a, black_box(&b), black_box(&c), s, avx2);
            black_box(&mut a);
        }
        a[0]
    };
    let probe = 2_000u64;
    let start = Instant::now();
    black_box(run(probe));
    let per_pass = start.elapsed().as_secs_f64().max(1e-9) / probe as f64;
    let passes = ((seconds / per_pass) as u64).max(probe);
    let chunk = ((CHUNK_SECONDS / per_pass) as u64).max(probe);
    let mut best = 0.0f64;
    for _ in 0..REPEATS {
        let (sums, elapsed) = on_every_core(pool, |_| chunked(passes, chunk, stop, run));
        check(stop)?;
        black_box(sums);
        let bytes = (12 * L1_ELEMENTS) as f64 * passes as f64 * pool.current_num_threads() as f64;
        best = best.max(bytes / elapsed / 1e9);
    }
    Ok(best)
}

/// The triad in AVX2 where the processor has it.
fn triad_best(a: &mut [f32], b: &[f32], c: &[f32], s: f32, avx2: bool) {
    #[cfg(target_arch = "x86_64")]
    if avx2 {
        // SAFETY: the caller checked that the processor has AVX2 and FMA.
        return unsafe { triad_avx2(a, b, c, s) };
    }
    let _ = avx2;
    triad(a, b, c, s);
}

/// The triad in AVX2, four vectors (32 elements) a step, the rest element by element.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn triad_avx2(a: &mut [f32], b: &[f32], c: &[f32], s: f32) {
    use std::arch::x86_64::{_mm256_fmadd_ps, _mm256_loadu_ps, _mm256_set1_ps, _mm256_storeu_ps};
    let n = a.len().min(b.len()).min(c.len());
    let whole = n / 32 * 32;
    let scalar = _mm256_set1_ps(s);
    let (pa, pb, pc) = (a.as_mut_ptr(), b.as_ptr(), c.as_ptr());
    let mut i = 0;
    while i < whole {
        // SAFETY: i + 31 < whole <= n, which no slice is shorter than, so every load
        // and store of 8 floats from i, i + 8, i + 16 and i + 24 is inside them; `a`
        // is borrowed mutably, so it overlaps neither `b` nor `c`.
        unsafe {
            let v0 = _mm256_fmadd_ps(
                scalar,
                _mm256_loadu_ps(pc.add(i)),
                _mm256_loadu_ps(pb.add(i)),
            );
            let v1 = _mm256_fmadd_ps(
                scalar,
                _mm256_loadu_ps(pc.add(i + 8)),
                _mm256_loadu_ps(pb.add(i + 8)),
            );
            let v2 = _mm256_fmadd_ps(
                scalar,
                _mm256_loadu_ps(pc.add(i + 16)),
                _mm256_loadu_ps(pb.add(i + 16)),
            );
            let v3 = _mm256_fmadd_ps(
                scalar,
                _mm256_loadu_ps(pc.add(i + 24)),
                _mm256_loadu_ps(pb.add(i + 24)),
            );
            _mm256_storeu_ps(pa.add(i), v0);
            _mm256_storeu_ps(pa.add(i + 8), v1);
            _mm256_storeu_ps(pa.add(i + 16), v2);
            _mm256_storeu_ps(pa.add(i + 24), v3);
        }
        i += 32;
    }
    triad(&mut a[whole..n], &b[whole..n], &c[whole..n], s);
}

/// STREAM's triad on one chunk.
#[inline(always)]
fn triad(a: &mut [f32], b: &[f32], c: &[f32], s: f32) {
    for ((a, b), c) in a.iter_mut().zip(b).zip(c) {
        *a = b + s * c;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x ← x·A + B` from `x0`, n times: `A^n x0 + B (1 - A^n) / (1 - A)`.
    fn closed_form(x0: f64, n: u64) -> f64 {
        let (a, b) = (f64::from(A), f64::from(B));
        let an = a.powi(n as i32);
        an * x0 + b * (1.0 - an) / (1.0 - a)
    }

    #[test]
    fn the_chains_do_the_steps_they_are_credited_with() {
        let steps = 10_000;
        let expected = (CHAINS * LANES) as f64 * closed_form(1.0, steps);
        for avx2 in [false, has_avx2_fma()] {
            let sum = f64::from(chains(steps, 1.0, avx2));
            assert!(
                (sum / expected - 1.0).abs() < 1e-3,
                "avx2 {avx2}: {sum} vs {expected}"
            );
        }
        // Fewer steps leave a different value: the loop is not folded away.
        assert!((f64::from(chains(steps / 2, 1.0, false)) - expected).abs() > 1e-3);
    }

    #[test]
    fn the_scalar_chains_do_the_steps_they_are_credited_with() {
        let steps = 10_000;
        let expected = CHAINS as f64 * closed_form(1.0, steps);
        for fma in [false, has_fma()] {
            let sum = f64::from(scalar_chains(steps, 1.0, fma));
            assert!(
                (sum / expected - 1.0).abs() < 1e-3,
                "fma {fma}: {sum} vs {expected}"
            );
        }
        assert!((f64::from(scalar_chains(steps / 2, 1.0, false)) - expected).abs() > 1e-3);
    }

    #[test]
    fn the_triad_computes_b_plus_s_c() {
        let (b, c) = ([1.0, 2.0, 3.0], [0.5, 0.25, 2.0]);
        let mut a = [0.0; 3];
        triad(&mut a, &b, &c, 2.0);
        assert_eq!(a, [2.0, 2.5, 7.0]);
    }

    #[test]
    fn a_kernel_is_timed_by_its_threads_time_on_a_core() {
        // Two threads that were on a core for half of a second's wall time each.
        assert_eq!(on_core_seconds(1.0, 1.0, 2), 0.5);
        // Never longer than the wall time; without a CPU clock, the wall time.
        assert_eq!(on_core_seconds(1.0, 3.0, 2), 1.0);
        assert_eq!(on_core_seconds(1.0, 0.0, 2), 1.0);
        assert_eq!(on_core_seconds(0.25, 0.5, 0), 0.25);
    }

    #[test]
    fn the_vector_triad_computes_b_plus_s_c_at_every_length() {
        // Small whole numbers: b + s c is exact with or without the fused multiply-add.
        for n in [0, 1, 7, 31, 32, 33, 64, 100] {
            let b: Vec<f32> = (0..n).map(|i| i as f32).collect();
            let c: Vec<f32> = (0..n).map(|i| (i % 7) as f32).collect();
            let expected: Vec<f32> = (0..n).map(|i| i as f32 + 3.0 * (i % 7) as f32).collect();
            for avx2 in [false, has_avx2_fma()] {
                let mut a = vec![-1.0; n];
                triad_best(&mut a, &b, &c, 3.0, avx2);
                assert_eq!(a, expected, "n {n}, avx2 {avx2}");
            }
        }
    }

    #[test]
    fn a_stop_ends_the_measurement_within_a_second() {
        // A plan of many seconds (3 kernels × 3 runs of 3 s), stopped after 0.2 s.
        let pool = crate::pool::thread_pool(Some(2)).unwrap_or_else(|e| panic!("{e}"));
        let plan = PeakPlan {
            fma_seconds: 3.0,
            stream_elements: 1 << 16,
        };
        let stop = AtomicBool::new(false);
        let (outcome, late) = std::thread::scope(|s| {
            let worker = s.spawn(|| measure_peak(&pool, plan, &stop));
            std::thread::sleep(std::time::Duration::from_millis(200));
            let raised = Instant::now();
            stop.store(true, Ordering::SeqCst);
            let outcome = worker.join().unwrap();
            (outcome, raised.elapsed())
        });
        assert!(
            matches!(outcome, Err(RunError::Stopped)),
            "stopped, not finished"
        );
        assert!(late.as_secs_f64() < 1.0, "ended {late:?} after the flag");
        // Chunked or not, a kernel does the steps it is asked for.
        let count = std::sync::atomic::AtomicU64::new(0);
        let never = AtomicBool::new(false);
        chunked(1000, 300, &never, |n| {
            count.fetch_add(n, Ordering::Relaxed);
            0.0
        });
        assert_eq!(count.load(Ordering::Relaxed), 1000);
    }

    #[test]
    fn the_peaks_are_positive_and_the_ridge_is_their_ratio() {
        let pool = crate::pool::thread_pool(Some(1)).unwrap_or_else(|e| panic!("{e}"));
        let plan = PeakPlan {
            fma_seconds: 0.002,
            stream_elements: 1 << 16,
        };
        let peak = measure_peak(&pool, plan, &AtomicBool::new(false)).unwrap();
        assert!(
            peak.peak_gflops > 0.0 && peak.bandwidth_gbs > 0.0,
            "{peak:?}"
        );
        assert!(peak.cache_bandwidth_gbs > 0.0, "{peak:?}");
        // One lane against eight (four on a machine without AVX2, in the portable
        // kernel's vectors at best): the scalar roof is the lower one.
        let scalar = peak
            .scalar_peak_gflops
            .expect("the scalar peak is measured");
        assert!(0.0 < scalar && scalar < peak.peak_gflops, "{peak:?}");
        let ridge = peak.ridge_intensity();
        assert!((peak.roof_gflops(ridge) - peak.peak_gflops).abs() < 1e-9 * peak.peak_gflops);
        assert!(peak.roof_gflops(ridge / 2.0) < peak.peak_gflops);
    }
}

//! How close a render runs to the machine: the machine's measured peaks
//! ([`MachinePeak`], once per suite), each variant's floating-point work and memory
//! traffic as a point under that roof ([`Efficiency`]) and its time split by ray kind
//! ([`RayRates`]).
//!
//! The model is the cache-aware roofline (Ilic, Pratas and Sousa 2014; Intel Advisor's
//! CARM): the bytes are every byte the render asks of the memory system, wherever they
//! are found, so the roof that bounds them is the fastest level's bandwidth (L1); the
//! DRAM bandwidth is drawn too, as the roof of a render whose records all came from
//! memory.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The machine's limits, measured by two short kernels on the suite's threads.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MachinePeak {
    /// Single-precision GFLOP/s of the FMA-throughput kernel (a fused multiply-add is
    /// 2 flops).
    pub peak_gflops: f64,
    /// GB/s of the streaming kernel from DRAM (the STREAM triad, `a = b + s c`, over
    /// arrays far larger than the caches: 12 bytes an element, write-allocate traffic
    /// not counted, as STREAM does).
    pub bandwidth_gbs: f64,
    /// GB/s of the same triad over arrays that stay in each core's L1 cache: the roof
    /// of [`Efficiency::bytes_moved`], which counts bytes at every level.
    #[serde(default)]
    pub cache_bandwidth_gbs: f64,
    /// Threads both kernels ran on.
    pub threads: u32,
    /// What the FMA kernel used, e.g. `AVX2+FMA, 8 lanes × 10 chains`.
    pub fma_kernel: String,
    /// Bytes the streaming kernel's arrays held together.
    pub stream_bytes: u64,
}

impl MachinePeak {
    /// The bandwidth that bounds [`Efficiency::bytes_moved`]: the L1 triad's (the DRAM
    /// triad's in files without it).
    pub fn roof_bandwidth_gbs(&self) -> f64 {
        if self.cache_bandwidth_gbs > 0.0 {
            self.cache_bandwidth_gbs
        } else {
            self.bandwidth_gbs
        }
    }

    /// The roof at arithmetic intensity `flops_per_byte`: the lower of the compute peak
    /// and what the L1 bandwidth can feed.
    pub fn roof_gflops(&self, flops_per_byte: f64) -> f64 {
        self.peak_gflops
            .min(self.roof_bandwidth_gbs() * flops_per_byte)
    }

    /// The roof of a render whose bytes all came from DRAM.
    pub fn dram_roof_gflops(&self, flops_per_byte: f64) -> f64 {
        self.peak_gflops.min(self.bandwidth_gbs * flops_per_byte)
    }

    /// The intensity where the compute roof meets the L1 roof (flops per byte).
    pub fn ridge_intensity(&self) -> f64 {
        self.peak_gflops / self.roof_bandwidth_gbs()
    }
}

/// A variant's render as a point of the roofline model.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Efficiency {
    /// Floating-point operations of the render, from the exact counts and the flop
    /// table (each counter's `flops` in `rtprof count --list`).
    pub flops: u64,
    /// Estimated bytes the render reads: every primitive record tested, every BVH node
    /// and primitive reference visited, every SIMD lane loaded, wherever in the memory
    /// hierarchy they are found (the cache-aware roofline's bytes).
    pub bytes_moved: u64,
    /// flops / bytes_moved.
    pub arithmetic_intensity: f64,
    /// flops / the median tracing time, GFLOP/s.
    pub achieved_gflops: f64,
    /// The roof at this intensity, [`MachinePeak::roof_gflops`] (`None` without a
    /// measured peak).
    pub roof_gflops: Option<f64>,
    /// achieved / roof.
    pub fraction_of_roof: Option<f64>,
}

/// The tracing time split by the query that spent it, measured in a separate clocked
/// pass (a time-stamp counter read around every closest-hit and shadow query), and the
/// rays per second of each kind that the split gives the timed render.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RayRates {
    /// Shares of the worker threads' time (they sum to 1 with `other_fraction` and
    /// `idle_fraction`).
    pub eye_fraction: f64,
    /// Reflection and refraction closest-hit queries.
    pub secondary_fraction: f64,
    pub shadow_fraction: f64,
    /// Camera rays, shading, the secondary rays' set-up, framebuffer work.
    pub other_fraction: f64,
    /// Worker threads waiting for work (a small frame has few rows to share).
    #[serde(default)]
    pub idle_fraction: f64,
    /// Rays of each kind per second of the time its queries took, millions; `None`
    /// when the render traced none of that kind.
    pub eye_mrays_per_s: Option<f64>,
    pub secondary_mrays_per_s: Option<f64>,
    pub shadow_mrays_per_s: Option<f64>,
    /// Every ray over the whole tracing time, millions per second.
    pub all_mrays_per_s: f64,
    /// Clocked pass time / unclocked time: what the clock reads cost.
    pub clock_overhead: f64,
}

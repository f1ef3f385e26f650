//! How close a render runs to the machine: the machine's measured peaks
//! ([`MachinePeak`], once per suite), each variant's floating-point work and memory
//! traffic as a point under those roofs ([`Efficiency`]) and its time split by ray kind
//! ([`RayRates`]).
//!
//! The model is the cache-aware roofline (Ilic, Pratas and Sousa 2014; Intel Advisor's
//! CARM): the bytes are every byte the render asks of the memory system, wherever they
//! are found, so the roof that bounds them is the fastest level's bandwidth (L1); the
//! DRAM bandwidth is drawn too, as the roof of a render whose records all came from
//! memory. As in Advisor, there are two compute roofs: the SIMD peak (fused
//! multiply-adds in every lane) and the scalar peak (the same chains one lane wide).
//! A render is held to the compute roof of its code ([`CodeKind`]): a variant that
//! tests primitives in SIMD lanes to the SIMD peak, every other one to the scalar peak.
//! The roof that applies to a point ([`MachinePeak::roof`]) is
//! `min(compute roof of its code, L1 bandwidth × intensity)`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::VariantName;

/// Whether a render's hot loops use the SIMD lanes: which compute roof bounds it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CodeKind {
    /// One primitive, one ray at a time (brute force, the binary BVH, their variants).
    Scalar,
    /// Several primitives or boxes per step in SIMD lanes (`simd`, the wide BVH of
    /// `bvh+simd`, Embree).
    Simd,
}

impl CodeKind {
    /// The code of a render with `accel`.
    pub fn of_accelerator(accel: tracer::Accelerator) -> CodeKind {
        use tracer::Accelerator as A;
        match accel {
            A::Simd | A::WideBvh | A::Embree | A::EmbreeNative | A::EmbreePackets => CodeKind::Simd,
            A::BruteForce | A::Bvh => CodeKind::Scalar,
        }
    }

    /// The code of variant `name` (scalar if the name no longer parses: it was
    /// checked when read, so only a change of tracer's variants can do that).
    pub fn of_variant(name: &VariantName) -> CodeKind {
        name.set().map_or(CodeKind::Scalar, |set| {
            CodeKind::of_accelerator(set.config().accel)
        })
    }

    /// `scalar` or `SIMD`, as the reports name the roof.
    pub fn name(self) -> &'static str {
        match self {
            CodeKind::Scalar => "scalar",
            CodeKind::Simd => "SIMD",
        }
    }
}

/// Which line of the roofline caps a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// A compute roof: the peak of this kind of code.
    Compute(CodeKind),
    /// The bandwidth roof ([`MachinePeak::roof_bandwidth_gbs`] × intensity).
    Bandwidth,
}

/// The roof over one point: its height and which line it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roof {
    /// GFLOP/s.
    pub gflops: f64,
    pub bound: Bound,
}

/// The machine's limits, measured by short kernels on the suite's threads.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MachinePeak {
    /// Single-precision GFLOP/s of the FMA-throughput kernel in SIMD lanes (a fused
    /// multiply-add is 2 flops): the SIMD compute roof.
    pub peak_gflops: f64,
    /// GB/s of the streaming kernel from DRAM (the STREAM triad, `a = b + s c`, over
    /// arrays far larger than the caches: 12 bytes an element, write-allocate traffic
    /// not counted, as STREAM does).
    pub bandwidth_gbs: f64,
    /// GB/s of the same triad over arrays that stay in each core's L1 cache: the roof
    /// of [`Efficiency::bytes_moved`], which counts bytes at every level.
    #[serde(default)]
    pub cache_bandwidth_gbs: f64,
    /// Threads the kernels ran on.
    pub threads: u32,
    /// What the FMA kernel used, e.g. `AVX2+FMA, 8 lanes × 10 chains`.
    pub fma_kernel: String,
    /// Bytes the streaming kernel's arrays held together.
    pub stream_bytes: u64,
    /// Single-precision GFLOP/s of the same multiply-add chains one lane wide (scalar
    /// instructions), measured the same way: the compute roof of code that does not
    /// use the SIMD lanes. `None` in files from before it was measured.
    #[serde(default)]
    pub scalar_peak_gflops: Option<f64>,
    /// What the scalar kernel used, e.g. `scalar FMA, 1 lane × 12 chains`.
    #[serde(default)]
    pub scalar_kernel: Option<String>,
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

    /// The measured scalar peak, when the file has a usable one.
    pub fn scalar_peak(&self) -> Option<f64> {
        self.scalar_peak_gflops
            .filter(|p| p.is_finite() && *p > 0.0)
    }

    /// The compute roof that holds code of `kind`, and whose roof it is: the SIMD peak
    /// for SIMD code; for scalar code the scalar peak, or the SIMD peak in files
    /// without one (then the roof is `Simd`'s, and a report says so).
    pub fn compute_roof(&self, kind: CodeKind) -> (f64, CodeKind) {
        match (kind, self.scalar_peak()) {
            (CodeKind::Scalar, Some(scalar)) => (scalar, CodeKind::Scalar),
            _ => (self.peak_gflops, CodeKind::Simd),
        }
    }

    /// The roof that applies to a render of `kind` at `flops_per_byte`: the lower of
    /// its compute roof and what the L1 bandwidth can feed.
    pub fn roof(&self, kind: CodeKind, flops_per_byte: f64) -> Roof {
        let (compute, whose) = self.compute_roof(kind);
        let fed = self.roof_bandwidth_gbs() * flops_per_byte;
        if fed < compute {
            Roof {
                gflops: fed,
                bound: Bound::Bandwidth,
            }
        } else {
            Roof {
                gflops: compute,
                bound: Bound::Compute(whose),
            }
        }
    }

    /// The SIMD roofline at `flops_per_byte`: the lower of the SIMD peak and what the
    /// L1 bandwidth can feed.
    pub fn roof_gflops(&self, flops_per_byte: f64) -> f64 {
        self.roof(CodeKind::Simd, flops_per_byte).gflops
    }

    /// The roof of a render whose bytes all came from DRAM.
    pub fn dram_roof_gflops(&self, flops_per_byte: f64) -> f64 {
        self.peak_gflops.min(self.bandwidth_gbs * flops_per_byte)
    }

    /// The intensity where the compute roof of `kind` meets the L1 roof (flops per
    /// byte): below it that code is bandwidth-bound, above it compute-bound.
    pub fn ridge(&self, kind: CodeKind) -> f64 {
        self.compute_roof(kind).0 / self.roof_bandwidth_gbs()
    }

    /// The intensity where the SIMD peak meets the L1 roof (flops per byte).
    pub fn ridge_intensity(&self) -> f64 {
        self.ridge(CodeKind::Simd)
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
    /// The roof that applies at this intensity, [`MachinePeak::roof`] for the
    /// variant's [`CodeKind`] (`None` without a measured peak; files from before the
    /// scalar peak hold the SIMD roofline's).
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

#[cfg(test)]
mod tests {
    use super::*;

    /// 100 GFLOP/s in SIMD lanes, 12.5 scalar, 200 GB/s from L1, 10 from DRAM.
    fn peak(scalar: Option<f64>) -> MachinePeak {
        MachinePeak {
            peak_gflops: 100.0,
            bandwidth_gbs: 10.0,
            cache_bandwidth_gbs: 200.0,
            threads: 2,
            fma_kernel: "AVX2+FMA, 8 lanes × 12 chains".to_string(),
            stream_bytes: 1 << 20,
            scalar_peak_gflops: scalar,
            scalar_kernel: scalar.map(|_| "scalar FMA, 1 lane × 12 chains".to_string()),
        }
    }

    #[test]
    fn each_code_kind_meets_its_own_compute_roof() {
        let p = peak(Some(12.5));
        // At 0.01 flop/byte L1 feeds 2 GFLOP/s: bandwidth-bound for both kinds.
        let low = Roof {
            gflops: 2.0,
            bound: Bound::Bandwidth,
        };
        assert_eq!(p.roof(CodeKind::Scalar, 0.01), low);
        assert_eq!(p.roof(CodeKind::Simd, 0.01), low);
        // At 0.25 flop/byte L1 feeds 50: above the scalar peak, below the SIMD one.
        assert_eq!(
            p.roof(CodeKind::Scalar, 0.25),
            Roof {
                gflops: 12.5,
                bound: Bound::Compute(CodeKind::Scalar)
            }
        );
        assert_eq!(
            p.roof(CodeKind::Simd, 0.25),
            Roof {
                gflops: 50.0,
                bound: Bound::Bandwidth
            }
        );
        // The ridges: 12.5 / 200 and 100 / 200 flop/byte.
        assert_eq!(p.ridge(CodeKind::Scalar), 0.0625);
        assert_eq!(p.ridge(CodeKind::Simd), 0.5);
        assert_eq!(p.ridge_intensity(), 0.5);
        assert_eq!(p.roof_gflops(0.25), 50.0);
        // DRAM alone: 10 GB/s × 0.25 = 2.5.
        assert_eq!(p.dram_roof_gflops(0.25), 2.5);
    }

    #[test]
    fn without_a_scalar_peak_scalar_code_meets_the_simd_roof_and_says_so() {
        for missing in [None, Some(0.0), Some(f64::NAN)] {
            let p = peak(missing);
            assert_eq!(p.scalar_peak(), None);
            assert_eq!(p.compute_roof(CodeKind::Scalar), (100.0, CodeKind::Simd));
            assert_eq!(
                p.roof(CodeKind::Scalar, 1.0),
                Roof {
                    gflops: 100.0,
                    bound: Bound::Compute(CodeKind::Simd)
                }
            );
        }
    }

    #[test]
    fn a_file_without_the_scalar_peak_reads() {
        let json = r#"{"peak_gflops": 53.3, "bandwidth_gbs": 4.27, "cache_bandwidth_gbs": 4.49,
            "threads": 2, "fma_kernel": "AVX2+FMA, 8 lanes × 12 chains", "stream_bytes": 100663296}"#;
        let p: MachinePeak = serde_json::from_str(json).expect("an older peak reads");
        assert_eq!((p.scalar_peak_gflops, p.scalar_kernel), (None, None));
    }

    #[test]
    fn variants_that_use_lanes_are_simd_code() {
        let kind = |name: &str| CodeKind::of_variant(&VariantName::parse(name).expect(name));
        for scalar in ["baseline", "bvh", "fast-sqrt", "ortho", "bvh+fast-sqrt"] {
            assert_eq!(kind(scalar), CodeKind::Scalar, "{scalar}");
        }
        for simd in ["simd", "bvh+simd", "bvh+simd+packets", "simd+fast-sqrt"] {
            assert_eq!(kind(simd), CodeKind::Simd, "{simd}");
        }
    }
}

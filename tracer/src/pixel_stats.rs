//! Per-sample records of a render (`RenderOptions::per_sample`): where in the picture
//! the work goes, as pbrt-v4's `--pixelstats` and the traversal heat maps of GPU ray
//! tracing analyzers show it.
//!
//! Each traced sample runs on its own counter and ray log, which are then added to its
//! row's; its counts are therefore exactly the work done for that sample, and summed
//! over the samples they give the render's counters, less the work done once per frame
//! or per row (the camera's set-up, the `bounded` variant's row bases), which belongs
//! to no sample ([`SampleStats::frame_level`]). Rows are kept in row order, so the
//! records, like the counts, are the same for any thread count. The time of a sample
//! is read from the monotonic clock around it; [`clock_resolution`] says how fine that
//! is. Time it on an uncounted render: counting slows the tracer several times.
//!
//! The grid is the grid of traced samples: the pixels, or the (W+1)×(H+1) pixel
//! corners with SPD sampling.

use crate::counter::{Counter, CounterDef, Counts, RayCounts, STAT_COUNT};
use crate::shading::RayLog;
use std::time::{Duration, Instant};

/// The records of one render's samples, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleStats {
    pub columns: u32,
    pub rows: u32,
    /// Each sample's counts (index `Stat as usize`); `None` for an uncounted render.
    pub counts: Option<Vec<[u64; STAT_COUNT]>>,
    /// Each sample's ray counts.
    pub rays: Vec<RayCounts>,
    /// Deepest ray-tree level each sample reached (eye ray 1; 0: not traced, as the
    /// filled samples of `pixel-avg`).
    pub depth: Vec<u8>,
    /// Tracing time of each sample, nanoseconds.
    pub nanos: Vec<u32>,
}

impl SampleStats {
    pub(crate) fn new(columns: u32, rows: u32, counted: bool) -> Self {
        let n = columns as usize * rows as usize;
        SampleStats {
            columns,
            rows,
            counts: counted.then(|| Vec::with_capacity(n)),
            rays: Vec::with_capacity(n),
            depth: Vec::with_capacity(n),
            nanos: Vec::with_capacity(n),
        }
    }

    pub(crate) fn append(&mut self, row: SampleRows) {
        let SampleRows {
            counts,
            rays,
            depth,
            nanos,
        } = row;
        if let (Some(all), Some(part)) = (&mut self.counts, counts) {
            all.extend(part);
        }
        self.rays.extend(rays);
        self.depth.extend(depth);
        self.nanos.extend(nanos);
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.rays.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.rays.is_empty()
    }

    /// One counter of the counter table for every sample; `None` when the counter is
    /// an operation count and the render did not count.
    pub fn map(&self, def: &CounterDef) -> Option<Vec<u64>> {
        let none = [0u64; STAT_COUNT];
        match (&self.counts, def.stat) {
            (None, Some(_)) => None,
            (counts, _) => Some(
                self.rays
                    .iter()
                    .enumerate()
                    .map(|(i, rays)| {
                        let totals = counts.as_ref().map_or(&none, |c| &c[i]);
                        (def.value)(&Counts::from_parts(totals, *rays))
                    })
                    .collect(),
            ),
        }
    }

    /// The secondary rays (reflection and refraction) of each sample.
    pub fn secondary_rays(&self) -> Vec<u64> {
        self.rays
            .iter()
            .map(|r| r.reflection + r.refraction)
            .collect()
    }

    /// The counts of `total` (the render's) that belong to no sample: `total` minus
    /// the sum over the samples, per counter (the camera's set-up and the row bases).
    pub fn frame_level(&self, total: &[u64; STAT_COUNT]) -> Option<[u64; STAT_COUNT]> {
        let counts = self.counts.as_ref()?;
        let mut rest = *total;
        for sample in counts {
            for (r, v) in rest.iter_mut().zip(sample) {
                *r -= v;
            }
        }
        Some(rest)
    }
}

/// The records of one row, built by its worker.
#[derive(Debug)]
pub(crate) struct SampleRows {
    counts: Option<Vec<[u64; STAT_COUNT]>>,
    rays: Vec<RayCounts>,
    depth: Vec<u8>,
    nanos: Vec<u32>,
}

impl SampleRows {
    pub(crate) fn with_capacity(n: usize, counted: bool) -> Self {
        SampleRows {
            counts: counted.then(|| Vec::with_capacity(n)),
            rays: Vec::with_capacity(n),
            depth: Vec::with_capacity(n),
            nanos: Vec::with_capacity(n),
        }
    }

    pub(crate) fn push<C: Counter>(&mut self, time: Duration, counter: &C, rays: &RayLog) {
        if let (Some(counts), Some(totals)) = (&mut self.counts, counter.totals()) {
            counts.push(totals);
        }
        self.rays.push(rays.counts);
        self.depth
            .push(u8::try_from(rays.deepest).unwrap_or(u8::MAX));
        self.nanos
            .push(u32::try_from(time.as_nanos()).unwrap_or(u32::MAX));
    }

    pub(crate) fn push_untraced(&mut self) {
        if let Some(counts) = &mut self.counts {
            counts.push([0; STAT_COUNT]);
        }
        self.rays.push(RayCounts::default());
        self.depth.push(0);
        self.nanos.push(0);
    }
}

/// The smallest step of the clock that times the samples: the least non-zero
/// difference between consecutive readings (a few tens of nanoseconds on Linux).
pub fn clock_resolution() -> Duration {
    let mut best = Duration::MAX;
    for _ in 0..1000 {
        let a = Instant::now();
        let mut b = Instant::now();
        while b == a {
            b = Instant::now();
        }
        best = best.min(b - a);
    }
    best
}

//! Collection into results: measurements become the plain `rtprof.results` data
//! (counts under their counter keys, image metrics, profiles with their files saved
//! beside results.json).

use std::collections::BTreeMap;
use std::path::Path;

use analysis::Comparison;
use analysis::profile::folded::flamegraph_svg;
use results::{AmdahlRow, FlatRow, Profile, Quality, VariantName, slug};

use crate::error::RunError;
use crate::profile_job::VariantProfile;
use crate::staging::save;

/// Every count under its counter key (`ops.dot`, `tests.sphere.tests`, …).
pub fn count_map(counts: &tracer::Counts) -> BTreeMap<String, u64> {
    counts
        .rows()
        .into_iter()
        .map(|(key, n)| (key.to_string(), n))
        .collect()
}

/// Image error against the reference.
pub fn quality(c: &Comparison) -> Quality {
    Quality {
        rms: c.rms,
        band: c.band,
        psnr: c.psnr.is_finite().then_some(c.psnr),
        ssim: c.ssim,
        max_abs_diff: u32::from(c.max_abs_diff),
    }
}

/// Saves a profile's texts and flamegraph under `out/dir` and returns its results entry.
pub fn save_profile(
    out: &Path,
    dir: &str,
    p: &VariantProfile,
    title: &str,
) -> Result<Profile, RunError> {
    let v = slug(&p.variant);
    let flat_text = save(out, &format!("{dir}/flat-{v}.txt"), p.flat_text.as_bytes())?;
    let callgraph_text = save(
        out,
        &format!("{dir}/callgraph-{v}.txt"),
        p.call_graph_text.as_bytes(),
    )?;
    save(out, &format!("{dir}/folded-{v}.txt"), p.folded.as_bytes())?;
    let svg = flamegraph_svg(&p.folded, title).map_err(|e| RunError::Profile(e.to_string()))?;
    let flame_svg = save(out, &format!("{dir}/flame-{v}.svg"), svg.as_bytes())?;
    Ok(Profile {
        variant: VariantName::parse(&p.variant)?,
        samples: p.samples,
        seconds_per_sample: p.seconds_per_sample,
        flat: p
            .flat
            .rows
            .iter()
            .map(|r| FlatRow {
                name: r.name.clone(),
                percent: r.percent,
                self_seconds: r.self_seconds,
                total_seconds: r.self_seconds + r.children_seconds,
                calls: r.calls,
            })
            .collect(),
        flat_text,
        callgraph_text,
        flame_svg,
        amdahl: p
            .amdahl
            .iter()
            .map(|a| AmdahlRow {
                name: a.name.clone(),
                fraction: a.fraction,
                speedup_2x: a.speedup_2x,
                speedup_10x: a.speedup_10x,
                speedup_limit: a.speedup_limit,
            })
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_map_keys_are_the_counter_keys() {
        let mut c = tracer::Counts::default();
        c.ops.dot = 5;
        c.tests.sphere.hits = 2;
        c.rays.primary = 9;
        let m = count_map(&c);
        assert_eq!(m["ops.dot"], 5);
        assert_eq!(m["tests.sphere.hits"], 2);
        assert_eq!(m["rays.primary"], 9);
        assert_eq!(m.len(), c.rows().len());
    }
}

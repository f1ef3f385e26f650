//! Collection into results: measurements become the plain `rtprof.results` data
//! (counts under their counter keys, image metrics); profiles are saved by
//! [`crate::profile_files`].

use std::collections::BTreeMap;

use analysis::Comparison;
use results::Quality;

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

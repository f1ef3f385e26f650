//! The suite's profile: which scene is profiled (the named `profile_scene`, else the
//! heaviest) and with which variants (the reference and the fastest variant that kept
//! its picture), and the profile itself at the profile size. The outside tracers the
//! suite records ([`super::tracers`]) are recorded on the same scene.

use analysis::Band;
use results::{ProfileResult, SceneResult, VariantName, VariantResult};
use tracer::{RenderOptions, Sampling, ShadingMode, VariantSet, parse_nff};

use super::SceneRunner;
use crate::error::RunError;
use crate::pool::thread_pool;
use crate::profile_job::ProfileJob;
use crate::scenes::SceneSpec;

/// The fastest of rtprof's own variants of `scene` whose picture stays visually
/// identical to the reference variant's (an outside tracer is recorded, not profiled
/// in-process).
fn best_kept_picture(scene: &SceneResult) -> Option<VariantName> {
    scene
        .variants
        .iter()
        .filter(|v| !v.variant.is_reference() && !v.variant.is_outside())
        .filter(|v| {
            v.quality
                .as_ref()
                .is_some_and(|q| q.band == Band::VisuallyIdentical)
        })
        .max_by(|a, b| {
            let s = |v: &VariantResult| v.speedup.unwrap_or(f64::NEG_INFINITY);
            s(a).total_cmp(&s(b))
        })
        .map(|v| v.variant.clone())
}

impl SceneRunner<'_> {
    /// The scene to profile and the variant beside the reference: the named scene
    /// (`profile_scene`: in a shard other than the first, none) or else the heaviest;
    /// the fastest variant whose picture stays visually identical on the suite's run of
    /// the same scene. `None` when the suite profiles nothing.
    pub(super) fn profile_choice<'s>(
        &self,
        specs: &'s [SceneSpec],
        results: &[SceneResult],
        named: Option<&'s SceneSpec>,
    ) -> Option<(&'s SceneSpec, Option<VariantName>)> {
        if !self.def.profile || (self.def.profile_scene.is_some() && named.is_none()) {
            return None;
        }
        if let Some(spec) = named {
            let small = format!("{}-small", spec.name);
            let ran = results
                .iter()
                .filter(|s| s.name == spec.name || s.name == small)
                .max_by_key(|s| s.variants.len());
            return Some((spec, ran.and_then(best_kept_picture)));
        }
        let reference = |s: &SceneResult| {
            let v = s.variants.iter().find(|v| v.variant.is_reference())?;
            Some(v.time.median)
        };
        let candidate = |s: &&SceneResult| {
            specs
                .iter()
                .any(|spec| spec.name == s.name && spec.profile_candidate)
        };
        let heaviest = results
            .iter()
            .filter(candidate)
            .filter_map(|s| Some((s, reference(s)?)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(s, _)| s)?;
        let spec = specs.iter().find(|s| s.name == heaviest.name)?;
        Some((spec, best_kept_picture(heaviest)))
    }

    /// Profiles `spec` at the profile size: baseline and `best`.
    pub(super) fn profile_spec(
        &self,
        spec: &SceneSpec,
        best: Option<VariantName>,
    ) -> Result<Option<ProfileResult>, RunError> {
        let scene = parse_nff(&spec.text, &spec.source).map_err(|e| RunError::Scene {
            scene: spec.name.clone(),
            message: e.to_string(),
        })?;
        let [w, h] = self.def.profile_size;
        let pool = thread_pool(None)?;
        let job = ProfileJob {
            scene: &scene,
            options: RenderOptions::new(w, h, Sampling::PixelCenters, ShadingMode::Color),
            pool: &pool,
            frequency: self.def.profile_frequency,
            name: &spec.name,
            min_samples: self.def.profile_samples,
            stop: self.ctx.stop,
        };
        let base_set = VariantSet::default();
        let best = best.map(|name| VariantSet::parse(&name)).transpose()?;
        let report = job.report(&base_set, best.as_ref(), false, self.ctx.progress)?;
        report.save(self.ctx.out, "profile/").map(Some)
    }
}

//! One scene of the sample as the sample builds it, and the variant names it uses.

use results::{SceneFamily, VariantName};

/// One scene of the sample: name, family, spheres, cylinders, polygons, size.
pub(super) struct SceneSpec {
    pub(super) name: &'static str,
    pub(super) family: SceneFamily,
    pub(super) spheres: u64,
    pub(super) cylinders: u64,
    pub(super) polygons: u64,
    pub(super) width: u32,
    pub(super) height: u32,
}

/// The name of one of `SAMPLE_VARIANTS` (all are tracer's single variants).
pub(super) fn variant_name(name: &str) -> VariantName {
    tracer::Variant::ALL
        .into_iter()
        .find(|v| v.name() == name)
        .map_or_else(VariantName::reference, VariantName::from)
}

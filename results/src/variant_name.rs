//! The name of a variant (or combination) as results record it: the canonical form of
//! [`tracer::VariantSet`] (`"baseline"`, `"bvh"`, `"bvh+bounded"`).

use std::fmt;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use tracer::{Variant, VariantError, VariantSet};

/// A variant set's name, always in [`VariantSet`]'s canonical spelling: names in
/// lower case, joined with `+`. Reading one checks it with [`VariantSet::parse`], so
/// an unknown or conflicting name is refused where it is read.
#[derive(
    Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(try_from = "String", into = "String")]
#[schemars(extend("pattern" = r"^[a-z0-9-]+(\+[a-z0-9-]+)*$"))]
pub struct VariantName(String);

impl VariantName {
    /// Parses `"a,b"` or `"a+b"` into the canonical name.
    pub fn parse(list: &str) -> Result<Self, VariantError> {
        VariantSet::parse(list).map(|set| Self::of(&set))
    }

    /// The name of `set`.
    pub fn of(set: &VariantSet) -> Self {
        Self(set.to_string())
    }

    /// `baseline`: the unoptimized tracer every other variant is measured against.
    pub fn reference() -> Self {
        Self(Variant::Baseline.name().to_string())
    }

    /// True for the reference (`baseline`).
    pub fn is_reference(&self) -> bool {
        self.0 == Variant::Baseline.name()
    }

    /// The variant set it names (the name was checked when made; this fails only if
    /// tracer's variants changed since).
    pub fn set(&self) -> Result<VariantSet, VariantError> {
        VariantSet::parse(&self.0)
    }

    /// Whether the variant counts the work inside its queries (Embree does not: its
    /// `tests.*` are absent, not zero).
    pub fn counts_its_work(&self) -> bool {
        self.set()
            .map_or(true, |s| s.config().accel.counts_its_work())
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl From<Variant> for VariantName {
    /// A single variant is always a valid set.
    fn from(variant: Variant) -> Self {
        Self(variant.name().to_string())
    }
}

impl TryFrom<String> for VariantName {
    type Error = VariantError;

    fn try_from(text: String) -> Result<Self, Self::Error> {
        Self::parse(&text)
    }
}

impl From<VariantName> for String {
    fn from(name: VariantName) -> String {
        name.0
    }
}

impl fmt::Display for VariantName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(&self.0)
    }
}

impl std::ops::Deref for VariantName {
    type Target = str;

    fn deref(&self) -> &str {
        &self.0
    }
}

impl PartialEq<str> for VariantName {
    fn eq(&self, other: &str) -> bool {
        self.0 == other
    }
}

impl PartialEq<&str> for VariantName {
    fn eq(&self, other: &&str) -> bool {
        self.0 == *other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_canonical_and_checked() {
        let name = |s: &str| VariantName::parse(s).map(|n| n.to_string());
        assert_eq!(name("Baseline").ok().as_deref(), Some("baseline"));
        assert_eq!(name("bvh,bounded").ok().as_deref(), Some("bvh+bounded"));
        assert!(name("warp-drive").is_err());
        assert!(name("baseline+bvh").is_err());
        assert!(VariantName::reference().is_reference());
        assert!(!VariantName::parse("bvh").is_ok_and(|n| n.is_reference()));
        let json: Result<VariantName, _> = serde_json::from_str("\"fast-sqrt\"");
        assert_eq!(json.ok().map(String::from).as_deref(), Some("fast-sqrt"));
        let bad: Result<VariantName, _> = serde_json::from_str("\"simd+embree\"");
        assert!(bad.is_err());
        // Embree's queries are not counted inside; rtprof's own structures are.
        let counts = |s: &str| VariantName::parse(s).is_ok_and(|n| n.counts_its_work());
        assert!(counts("bvh+simd") && counts("baseline") && counts("simd"));
        assert!(!counts("embree") && !counts("embree-native"));
    }
}

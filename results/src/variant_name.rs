//! The name of a variant (or combination) as results record it: the canonical form of
//! [`tracer::VariantSet`] (`"baseline"`, `"bvh"`, `"bvh+bounded"`), or an outside
//! tracer's, its definition's name after [`OUTSIDE_PREFIX`] (`"tracer:povray"`).

use std::fmt;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use tracer::{Variant, VariantError, VariantSet};

/// What starts an outside tracer's name: it is a program run by its definition
/// (docs/tracers.md), not a variant of rtprof's tracer.
pub const OUTSIDE_PREFIX: &str = "tracer:";

/// A variant set's name, always in [`VariantSet`]'s canonical spelling: names in
/// lower case, joined with `+`. Reading one checks it with [`VariantSet::parse`], so
/// an unknown or conflicting name is refused where it is read.
#[derive(
    Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(try_from = "String", into = "String")]
#[schemars(extend("pattern" = r"^([a-z0-9-]+(\+[a-z0-9-]+)*|tracer:[A-Za-z0-9._-]+)$"))]
pub struct VariantName(String);

impl VariantName {
    /// Parses `"a,b"` or `"a+b"` into the canonical name; `tracer:NAME` is an outside
    /// tracer's.
    pub fn parse(list: &str) -> Result<Self, VariantError> {
        match list.strip_prefix(OUTSIDE_PREFIX) {
            Some(name) => Self::outside(name),
            None => VariantSet::parse(list).map(|set| Self::of(&set)),
        }
    }

    /// The name of the outside tracer `name` (letters, digits, `-`, `_`, `.`).
    pub fn outside(name: &str) -> Result<Self, VariantError> {
        if name.is_empty()
            || !name
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b"-_.".contains(&b))
        {
            return Err(VariantError::Unknown {
                name: format!("{OUTSIDE_PREFIX}{name}"),
                known: "an outside tracer's name is letters, digits, '-', '_' and '.'".into(),
            });
        }
        Ok(Self(format!("{OUTSIDE_PREFIX}{name}")))
    }

    /// The outside tracer's own name (`povray` of `tracer:povray`); `None` for
    /// rtprof's variants.
    pub fn outside_name(&self) -> Option<&str> {
        self.0.strip_prefix(OUTSIDE_PREFIX)
    }

    /// Whether an outside program drew it, not rtprof's tracer.
    pub fn is_outside(&self) -> bool {
        self.outside_name().is_some()
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
        if self.is_outside() {
            // What it counts is its probe's to say; nothing is known to be zero.
            return false;
        }
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
        // An outside tracer's name keeps its spelling; its set is none of rtprof's.
        assert_eq!(
            name("tracer:POV-Ray_3.7").ok().as_deref(),
            Some("tracer:POV-Ray_3.7")
        );
        assert!(name("tracer:").is_err() && name("tracer:a b").is_err());
        let outside = VariantName::parse("tracer:tachyon").unwrap();
        assert_eq!(outside.outside_name(), Some("tachyon"));
        assert!(outside.set().is_err() && !outside.counts_its_work());
        assert!(VariantName::parse("bvh").unwrap().outside_name().is_none());
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

//! Named optimization variants (`--variant a,b,…`). `baseline` is the thesis's
//! software reference: brute force over all primitives, std sqrt, perspective camera.

use std::fmt;

/// One named variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    /// Brute force, std sqrt, perspective (the software reference).
    Baseline,
}

impl Variant {
    /// Every variant, in the order reports list them.
    pub const ALL: [Variant; 1] = [Variant::Baseline];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Baseline => "baseline",
        }
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A variant name that is not known.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown variant '{name}' (known: {known})")]
pub struct UnknownVariant {
    pub name: String,
    pub known: String,
}

/// A combination of variants, parsed from a comma-separated list.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VariantSet(Vec<Variant>);

impl Default for VariantSet {
    fn default() -> Self {
        Self(vec![Variant::Baseline])
    }
}

impl VariantSet {
    /// Parses `"a,b"`; names are case-insensitive, duplicates collapse.
    pub fn parse(list: &str) -> Result<Self, UnknownVariant> {
        let mut out = Vec::new();
        for name in list.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            let variant = Variant::ALL
                .into_iter()
                .find(|v| v.name().eq_ignore_ascii_case(name))
                .ok_or_else(|| UnknownVariant {
                    name: name.to_string(),
                    known: Variant::ALL.map(Variant::name).join(", "),
                })?;
            if !out.contains(&variant) {
                out.push(variant);
            }
        }
        if out.is_empty() {
            out.push(Variant::Baseline);
        }
        Ok(Self(out))
    }

    /// The variants in the set.
    pub fn variants(&self) -> &[Variant] {
        &self.0
    }
}

impl fmt::Display for VariantSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<_> = self.0.iter().map(|v| v.name()).collect();
        f.write_str(&names.join(","))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_lists_and_rejects_unknown_names() {
        assert_eq!(
            VariantSet::parse("baseline").map(|s| s.to_string()),
            Ok("baseline".into())
        );
        assert_eq!(
            VariantSet::parse(" Baseline, baseline ").map(|s| s.variants().len()),
            Ok(1)
        );
        let err = VariantSet::parse("baseline,warp-drive")
            .err()
            .map(|e| e.to_string());
        assert_eq!(
            err.as_deref(),
            Some("unknown variant 'warp-drive' (known: baseline)")
        );
    }
}

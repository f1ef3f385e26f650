//! Function names in profiles: demangled symbols cleaned into stable paths, the short
//! names the reports print (`Sphere::intersect`, and the thesis's bare `dot`, `sub`, …
//! for the counted vector operations), and the exact call counts that go with them.

use super::CallCounts;
use tracer::Counts;

/// A demangled symbol as a plain path: no hash suffix, no generic arguments, and
/// `<Type as Trait>::method` written `Type::method`.
pub fn clean_symbol(raw: &str) -> String {
    let mut name = raw.trim();
    // Legacy mangling leaves `::h` + 16 hex digits at the end.
    if let Some(at) = name.rfind("::h") {
        let hash = &name[at + 3..];
        if hash.len() == 16 && hash.bytes().all(|b| b.is_ascii_hexdigit()) {
            name = &name[..at];
        }
    }
    let name = rewrite_qualified(name);
    strip_generics(&name)
}

/// `<A as B>::rest` → `A::rest` (the implementing type names the function best).
fn rewrite_qualified(name: &str) -> String {
    let Some(inner) = name.strip_prefix('<') else {
        return name.to_string();
    };
    let mut depth = 1usize;
    for (i, ch) in inner.char_indices() {
        match ch {
            '<' => depth += 1,
            '>' => {
                depth -= 1;
                if depth == 0 {
                    let qualified = &inner[..i];
                    let rest = &inner[i + 1..];
                    let implementor = match qualified.find(" as ") {
                        Some(at) => &qualified[..at],
                        None => qualified,
                    };
                    return format!("{implementor}{rest}");
                }
            }
            _ => {}
        }
    }
    name.to_string()
}

/// Removes every `<…>` group (generic arguments), keeping `{{closure}}` and the like.
fn strip_generics(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    let mut depth = 0usize;
    for ch in name.chars() {
        match ch {
            '<' => {
                // `f::<T>` (v0 demangling) keeps no dangling `::`.
                if depth == 0 && out.ends_with("::") {
                    out.truncate(out.len() - 2);
                }
                depth += 1;
            }
            '>' if depth > 0 => depth -= 1,
            _ if depth == 0 => out.push(ch),
            _ => {}
        }
    }
    out
}

/// The counted vector and scalar operations, named as in the thesis's table 6.
const OPERATIONS: [&str; 8] = [
    "dot",
    "sub",
    "add",
    "cross",
    "scale",
    "normalize",
    "sqrt",
    "pow",
];

/// Types whose methods are the counting layer.
const COUNTERS: [&str; 4] = ["Counter", "NoCount", "Count", "WithSqrt"];

/// The name a report prints: the last two path segments (`Sphere::intersect`,
/// `shading::color_contribution`), and the bare operation name for the counting
/// layer's maths (`dot`). Names outside any module are kept whole.
pub fn display_name(clean: &str) -> String {
    let segments: Vec<&str> = clean.split("::").collect();
    match segments.as_slice() {
        [.., owner, op] if COUNTERS.contains(owner) && OPERATIONS.contains(op) => op.to_string(),
        [.., owner, "{{closure}}"] => format!("{owner}::{{{{closure}}}}"),
        [.., owner, function] => format!("{owner}::{function}"),
        _ => clean.to_string(),
    }
}

/// Exact call counts, by display name, for the functions the tracer counts. Each
/// accelerator's query functions get the query counts; functions whose calls the
/// counters do not determine are left out (their `calls` column stays blank).
pub fn call_counts(counts: &Counts) -> CallCounts {
    let (o, c, t, r) = (&counts.ops, &counts.calls, &counts.tests, &counts.rays);
    let mut m = CallCounts::new();
    let mut put = |name: &str, n: u64| {
        m.insert(name.to_string(), n);
    };
    for (name, n) in [
        ("dot", o.dot),
        ("sub", o.sub),
        ("add", o.add),
        ("cross", o.cross),
        ("scale", o.scale),
        ("normalize", o.normalize),
        ("sqrt", o.sqrt),
        ("pow", o.pow),
        ("Sphere::intersect", t.sphere.tests),
        ("Cylinder::intersect", t.cylinder.tests),
        ("Cone::intersect", t.cone.tests),
        ("Polygon::intersect", t.polygon.tests),
        ("Patch::intersect", t.patch.tests),
        ("PlanarOutline::intersect_plane", t.plane.tests),
        ("Shader::shade", c.shade),
        // Eye rays start in `primary`; `trace` is every later (secondary) ray.
        ("Shader::primary", r.primary),
        ("Shader::primary_from_eye", r.primary),
        ("Shader::trace", c.trace.saturating_sub(r.primary)),
        ("shading::color_contribution", c.color_contribution),
        ("Camera::ray", r.primary),
        ("Camera::ray_from_eye", r.primary),
    ] {
        put(name, n);
    }
    // Closest-hit queries are one per traced ray, occlusion queries one per shadow ray.
    for accel in ["BruteForce", "Simd", "Bvh"] {
        put(&format!("{accel}::closest_hit"), c.trace);
        put(&format!("{accel}::closest"), c.trace);
        put(&format!("{accel}::occluded"), r.shadow);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_lose_hashes_generics_and_qualification() {
        assert_eq!(
            clean_symbol("tracer::primitives::sphere::Sphere::intersect::h0123456789abcdef"),
            "tracer::primitives::sphere::Sphere::intersect"
        );
        assert_eq!(
            clean_symbol("<tracer::accel::bvh::Bvh as tracer::accel::Intersector>::occluded"),
            "tracer::accel::bvh::Bvh::occluded"
        );
        assert_eq!(
            clean_symbol(
                "tracer::render::render<tracer::counter::NoCount, tracer::accel::bvh::Bvh>::{{closure}}"
            ),
            "tracer::render::render::{{closure}}"
        );
        assert_eq!(
            clean_symbol("std::panicking::catch_unwind::<fn(), ()>"),
            "std::panicking::catch_unwind"
        );
        // A hash-like tail that is not 16 hex digits stays.
        assert_eq!(clean_symbol("a::hello"), "a::hello");
    }

    #[test]
    fn display_names_are_short_and_operations_bare() {
        assert_eq!(display_name("tracer::counter::Counter::dot"), "dot");
        assert_eq!(display_name("tracer::fast_sqrt::WithSqrt::sqrt"), "sqrt");
        assert_eq!(
            display_name("tracer::primitives::sphere::Sphere::intersect"),
            "Sphere::intersect"
        );
        assert_eq!(
            display_name("tracer::render::render::{{closure}}"),
            "render::{{closure}}"
        );
        assert_eq!(display_name("main"), "main");
    }

    #[test]
    fn call_counts_take_the_counter_values() {
        let mut counts = Counts::default();
        counts.ops.dot = 42;
        counts.tests.sphere.tests = 7;
        counts.calls.trace = 10;
        counts.rays.primary = 4;
        counts.rays.shadow = 3;
        let m = call_counts(&counts);
        assert_eq!(m.get("dot"), Some(&42));
        assert_eq!(m.get("Sphere::intersect"), Some(&7));
        assert_eq!(m.get("Shader::trace"), Some(&6));
        assert_eq!(m.get("Bvh::occluded"), Some(&3));
        assert_eq!(m.get("shading::reflect"), None);
    }
}

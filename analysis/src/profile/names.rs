//! Function names in profiles: demangled symbols cleaned into stable paths, and the
//! short names the reports print (`Sphere::intersect`, and the bare `dot`, `sub`, …
//! the thesis prints for the counted vector operations). Which methods print bare is
//! the profiled program's knowledge, so the caller passes it ([`BareMethods`]); so is
//! the table of exact calls by short name ([`super::CallCounts`]).

/// The name of a frame whose symbol is empty (or nothing but generic arguments): perf's
/// own name for it. gprof text, folded stacks and flamegraphs all need a name to show;
/// gprof2dot rejects a call-graph entry without one.
pub const UNNAMED_FRAME: &str = "[unknown]";

/// A demangled symbol as a plain path: no hash suffix, no generic arguments, and
/// `<Type as Trait>::method` written `Type::method`. Never empty: see [`UNNAMED_FRAME`].
pub fn clean_symbol(raw: &str) -> String {
    let clean = clean_path(raw);
    if clean.trim().is_empty() {
        UNNAMED_FRAME.to_string()
    } else {
        clean
    }
}

fn clean_path(raw: &str) -> String {
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

/// Methods a profile prints by their bare name, as the thesis's table 6 prints the
/// counted operations (`dot`, not `Counter::dot`): the methods `methods` of the types
/// (or traits) `owners`. For rtprof these are the tracer's counting layer,
/// `tracer::counter::COUNTING_LAYER` and `tracer::counter::counted_operations()`:
/// declared beside the counters, so this crate keeps no copy of the tracer's names.
#[derive(Clone, Copy, Debug, Default)]
pub struct BareMethods<'a> {
    pub owners: &'a [&'a str],
    pub methods: &'a [&'a str],
}

/// The name a report prints: the last two path segments (`Sphere::intersect`,
/// `shading::color_contribution`), and the bare method name for the `bare` methods
/// (`dot`). Names outside any module are kept whole.
pub fn display_name(clean: &str, bare: &BareMethods<'_>) -> String {
    let segments: Vec<&str> = clean.split("::").collect();
    match segments.as_slice() {
        [.., owner, method] if bare.owners.contains(owner) && bare.methods.contains(method) => {
            method.to_string()
        }
        [.., owner, "{{closure}}"] => format!("{owner}::{{{{closure}}}}"),
        [.., owner, function] => format!("{owner}::{function}"),
        _ => clean.to_string(),
    }
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
    fn an_empty_symbol_still_has_a_name() {
        // An empty symbol, or one that is all generic arguments, once broke gprof2dot's
        // reading of the call graph (an entry with no name).
        for raw in ["", "   ", "<>", "::<T>"] {
            assert_eq!(clean_symbol(raw), "[unknown]", "{raw:?}");
        }
    }

    #[test]
    fn display_names_are_short_and_operations_bare() {
        let bare = BareMethods {
            owners: &["Counter", "WithSqrt"],
            methods: &["dot", "sqrt"],
        };
        assert_eq!(display_name("tracer::counter::Counter::dot", &bare), "dot");
        assert_eq!(
            display_name("tracer::variants::fast_sqrt::WithSqrt::sqrt", &bare),
            "sqrt"
        );
        // Only the listed methods of the listed owners lose their owner.
        assert_eq!(
            display_name("tracer::counter::Counter::tally", &bare),
            "Counter::tally"
        );
        assert_eq!(display_name("core::f32::sqrt", &bare), "f32::sqrt");
        assert_eq!(
            display_name("tracer::counter::Counter::dot", &BareMethods::default()),
            "Counter::dot"
        );
        assert_eq!(
            display_name("tracer::primitives::sphere::Sphere::intersect", &bare),
            "Sphere::intersect"
        );
        assert_eq!(
            display_name("tracer::render::render::{{closure}}", &bare),
            "render::{{closure}}"
        );
        assert_eq!(display_name("main", &bare), "main");
    }
}

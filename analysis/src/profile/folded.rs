//! Folded stacks (Brendan Gregg's format: `root;caller;callee count` per line) and the
//! flamegraphs drawn from them with inferno, including the differential flamegraph of
//! two profiles (red: grew in the second, blue: shrank).

use super::StackSamples;
use std::io::BufReader;

/// Why a flamegraph could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the flamegraph: {0}")]
pub struct FlamegraphError(#[from] std::io::Error);

/// One line per stack, root first, frames joined by `;`, then a space and the count.
/// Semicolons inside names (none in Rust paths) would split frames, so they are
/// replaced by `,`.
pub fn folded(samples: &StackSamples) -> String {
    let mut lines: Vec<String> = samples
        .stacks
        .iter()
        .filter(|s| s.count > 0 && !s.frames.is_empty())
        .map(|s| {
            let frames: Vec<String> = s.frames.iter().map(|f| f.replace(';', ",")).collect();
            format!("{} {}", frames.join(";"), s.count)
        })
        .collect();
    lines.sort();
    let mut text = lines.join("\n");
    text.push('\n');
    text
}

fn options(title: &str, count_name: &str) -> inferno::flamegraph::Options<'static> {
    let mut options = inferno::flamegraph::Options::default();
    options.title = title.to_string();
    options.count_name = count_name.to_string();
    // Same input, same SVG: colours from the names, not from a random generator.
    options.hash = true;
    options.deterministic = true;
    options
}

/// An interactive flamegraph (SVG) of folded stacks.
pub fn flamegraph_svg(folded_text: &str, title: &str) -> Result<String, FlamegraphError> {
    let mut svg = Vec::new();
    let mut opts = options(title, "samples");
    inferno::flamegraph::from_lines(&mut opts, folded_text.lines(), &mut svg)?;
    Ok(String::from_utf8_lossy(&svg).into_owned())
}

/// A differential flamegraph: the shape of `after`, coloured by the change from
/// `before` (counts normalized so that different run lengths compare).
pub fn differential_svg(before: &str, after: &str, title: &str) -> Result<String, FlamegraphError> {
    let mut diff = Vec::new();
    let diff_options = inferno::differential::Options {
        normalize: true,
        ..Default::default()
    };
    inferno::differential::from_readers(
        diff_options,
        BufReader::new(before.as_bytes()),
        BufReader::new(after.as_bytes()),
        &mut diff,
    )?;
    let diff_text = String::from_utf8_lossy(&diff).into_owned();
    let mut svg = Vec::new();
    let mut opts = options(title, "samples");
    inferno::flamegraph::from_lines(&mut opts, diff_text.lines(), &mut svg)?;
    Ok(String::from_utf8_lossy(&svg).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Stack;

    fn samples() -> StackSamples {
        let stack = |frames: &[&str], count| Stack {
            frames: frames.iter().map(|f| f.to_string()).collect(),
            count,
        };
        StackSamples {
            stacks: vec![
                stack(&["render", "trace", "Sphere::intersect"], 30),
                stack(&["render", "trace"], 5),
                stack(&["render", "shade"], 10),
            ],
            seconds_per_sample: 0.001,
        }
    }

    #[test]
    fn folded_lines_are_root_first_with_counts() {
        let text = folded(&samples());
        assert_eq!(
            text,
            "render;shade 10\nrender;trace 5\nrender;trace;Sphere::intersect 30\n"
        );
    }

    #[test]
    fn flamegraphs_are_svg_with_the_function_names() {
        let text = folded(&samples());
        let svg = flamegraph_svg(&text, "rings").unwrap_or_else(|e| panic!("{e}"));
        assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains("Sphere::intersect"));
        let after = "render;shade 40\nrender;trace 5\n";
        let diff = differential_svg(&text, after, "diff").unwrap_or_else(|e| panic!("{e}"));
        assert!(diff.contains("<svg") && diff.contains("shade"));
    }
}

//! The formats a command prints its table in.

/// How a table is printed: aligned text for a terminal, GitHub-flavoured Markdown (a
/// pull-request comment, a CI job summary), CSV or JSON.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    #[default]
    Text,
    Markdown,
    Csv,
    Json,
}

//! Where a byte offset of a text file is, as compilers say it (`FILE:LINE:COLUMN`): the
//! one place the suite definition and the tracer definitions turn a TOML error's span
//! into a line and column.

/// The 1-based line and column (in characters) of byte `offset` of `text`.
pub fn line_and_column(text: &str, offset: usize) -> (usize, usize) {
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

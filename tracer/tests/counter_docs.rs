//! docs/counters.md is the counter table's text: each counter's meaning has one home,
//! the table, and the page is made from it.

use std::path::PathBuf;
use tracer::Counts;

#[test]
fn the_counter_page_is_the_counter_table() {
    let page = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/counters.md");
    let expected = Counts::table_markdown();
    if std::env::var_os("RTPROF_BLESS").is_some() {
        std::fs::write(&page, &expected).unwrap_or_else(|e| panic!("{e}"));
    }
    let written = std::fs::read_to_string(&page).unwrap_or_default();
    assert!(
        written == expected,
        "docs/counters.md differs from the counter table; run \
         RTPROF_BLESS=1 cargo test -p tracer --test counter_docs"
    );
    // Every counter of the table is on the page.
    for def in tracer::COUNTERS {
        assert!(written.contains(&format!("`{}`", def.key)), "{}", def.key);
    }
}

//! The figures the docs give for the statistics are the code's: each bootstrap's
//! resample count, next to the constant that holds it (a reader found 2,000 in one page
//! and 10,000 in another, both right, neither saying which interval it was).

fn doc(name: &str) -> String {
    let path = format!("{}/../docs/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `n` as the docs write it (10,000): the reports' one formatter of counts.
fn grouped(n: usize) -> String {
    reports::format::count(n as u64)
}

/// The page gives `count` resamples in the same sentence as `constant`'s name.
fn states(page: &str, count: usize, constant: &str) {
    let text = doc(page).replace('\n', " ");
    let figure = format!("{} resamples", grouped(count));
    let sentence = text
        .split(". ")
        .find(|s| s.contains(&format!("`{constant}`")))
        .unwrap_or_else(|| panic!("docs/{page} does not name {constant}"));
    assert!(
        sentence.contains(&figure),
        "docs/{page}: the sentence naming {constant} does not say {figure}: {sentence}"
    );
}

#[test]
fn the_docs_give_each_bootstrap_s_resamples_with_its_constant() {
    let (times, changes) = (runner::timing::RESAMPLES, results::change::RESAMPLES);
    states("suite-and-reports.md", times, "runner::timing::RESAMPLES");
    states(
        "suite-and-reports.md",
        changes,
        "results::change::RESAMPLES",
    );
    states("gate.md", changes, "results::change::RESAMPLES");
    states("gate.md", times, "runner::timing::RESAMPLES");
}

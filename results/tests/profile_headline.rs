//! The profile's headline rows: the bottleneck by self share and the largest inclusive
//! share (whole-run frames, threads' roots and noise left out of both), on hand-made
//! rows shaped like SPD rings' profile.

use results::{FlatRow, Profile, ProfileView, VariantName};

fn row(name: &str, percent: f64, inclusive: Option<f64>, noise: bool) -> FlatRow {
    FlatRow {
        name: name.to_string(),
        percent,
        self_seconds: percent / 100.0,
        total_seconds: inclusive.unwrap_or(percent) / 100.0,
        calls: None,
        inclusive_percent: inclusive,
        self_interval: None,
        inclusive_interval: None,
        noise,
        root: false,
    }
}

fn profile(flat: Vec<FlatRow>) -> Profile {
    Profile {
        variant: VariantName::parse("baseline").unwrap(),
        samples: 1000,
        seconds_per_sample: 0.001,
        renders: Some(3),
        samples_asked: Some(4000),
        timer: None,
        cpu_seconds: Some(1.0),
        counts: Default::default(),
        view: ProfileView::Phases,
        flat,
        flat_text: "flat-baseline.txt".into(),
        callgraph_text: "callgraph-baseline.txt".into(),
        flame_svg: "flame-baseline.svg".into(),
        amdahl: Vec::new(),
        second_view: None,
        exports: Vec::new(),
    }
}

#[test]
fn the_bottleneck_is_the_most_self_time_and_the_largest_parent_is_named_apart() {
    let p = profile(vec![
        row("sample row", 0.0, Some(100.0), true),
        row("root", 0.2, Some(99.6), true),
        row("shading", 1.0, Some(74.0), false),
        row("cylinder test", 64.5, Some(64.5), false),
        row("sphere test", 34.3, Some(34.3), false),
        // Noise never headlines, whatever its share says.
        row("camera ray", 0.1, Some(80.0), true),
        row("noise leaf", 70.0, Some(70.0), true),
        // Nor does a thread's root, which holds that thread's whole work.
        FlatRow {
            root: true,
            ..row("worker", 66.0, Some(95.7), false)
        },
        // Nor a frame on (nearly) every sample.
        row("everywhere", 80.0, Some(99.7), false),
    ]);
    assert_eq!(
        p.bottleneck().map(|r| r.name.as_str()),
        Some("cylinder test")
    );
    assert_eq!(
        p.largest_inclusive().map(|r| r.name.as_str()),
        Some("shading")
    );
    // A /2 profile has no inclusive shares: no claim either way.
    let old = profile(vec![row("Cylinder::intersect", 90.8, None, false)]);
    assert!(old.bottleneck().is_none());
    assert!(old.largest_inclusive().is_none());
}

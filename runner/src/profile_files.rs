//! The files of a profile, with one naming scheme for `rtprof profile` and the suite.
//! For variant `v` (slugged) in the profile's directory:
//!
//! | file | what |
//! |---|---|
//! | `flat-v.txt`, `callgraph-v.txt` | gprof flat profile and call graph, phase view |
//! | `folded-v.txt`, `flame-v.svg` | folded stacks and flamegraph, phase view |
//! | `…-v-native.…` | the same four for native symbols |
//! | `amdahl-v.txt` | Amdahl table on self and inclusive time (phase view) |
//! | `profile-v.pb.gz`, `profile-v-native.pb.gz` | pprof protobuf (`go tool pprof`) |
//! | `speedscope-v.json` | both views for speedscope |
//! | `flame-diff-a-b.svg`, `flame-diff-a-b-shrunk.svg` | differential: what grew, what shrank |

use std::path::Path;
use std::time::Duration;

use analysis::profile::StackSamples;
use analysis::profile::amdahl::amdahl_text;
use analysis::profile::export::{PprofRun, pprof_profile_gz, speedscope_json};
use analysis::profile::folded::{DiffSide, differential_svgs, flamegraph_svg};
use results::{
    AmdahlFigures, AmdahlRow, FlatRow, Profile, ProfileResult, ProfileView, ProfileViewFiles,
    VariantName, slug,
};

use crate::error::RunError;
use crate::profile_job::{ProfileReport, VariantProfile, ViewProfile};
use crate::staging::save;

fn profile_error(e: impl std::fmt::Display) -> RunError {
    RunError::Profile(e.to_string())
}

/// The suffix of a view's file names.
fn suffix(view: ProfileView) -> &'static str {
    match view {
        ProfileView::Phases => "",
        ProfileView::Native => "-native",
    }
}

pub fn view_label(view: ProfileView) -> &'static str {
    match view {
        ProfileView::Phases => "phases",
        ProfileView::Native => "native symbols",
    }
}

/// One view to write, and the suffix of its files' names.
pub struct ViewToSave<'a> {
    pub view: &'a ViewProfile,
    pub suffix: &'a str,
}

/// What one profile's files are made from, whoever sampled it: `rtprof profile`'s
/// renders (two views) or `rtprof record`'s outside program (native symbols only).
pub struct ProfileToSave<'a> {
    /// Names the files (slugged): the variant, or the recorded command.
    pub stem: &'a str,
    pub title: &'a str,
    pub wall_seconds: f64,
    /// pprof's comment on what was sampled ("3 renders sampled").
    pub sampled: String,
    /// The first view's Amdahl table is written.
    pub views: Vec<ViewToSave<'a>>,
}

/// The files written: each view's, then the exports (each view's pprof, speedscope,
/// the Amdahl table).
pub struct SavedProfile {
    pub views: Vec<ProfileViewFiles>,
    pub exports: Vec<String>,
}

/// Writes one view's texts, folded stacks, flamegraph and pprof file under
/// `out/dir`; returns its results entry and the pprof file's path.
fn save_view(
    out: &Path,
    dir: &str,
    p: &ProfileToSave,
    v: &ViewToSave,
) -> Result<(ProfileViewFiles, String), RunError> {
    let (stem, suffix, view) = (slug(p.stem), v.suffix, v.view);
    let name = |kind: &str, ext: &str| format!("{dir}{kind}-{stem}{suffix}.{ext}");
    let flat_text = save(out, &name("flat", "txt"), view.flat_text.as_bytes())?;
    let callgraph_text = save(
        out,
        &name("callgraph", "txt"),
        view.call_graph_text.as_bytes(),
    )?;
    save(out, &name("folded", "txt"), view.folded.as_bytes())?;
    let title = format!("{}, {}", p.title, view_label(view.view));
    let svg = flamegraph_svg(&view.folded, &title).map_err(profile_error)?;
    let flame_svg = save(out, &name("flame", "svg"), svg.as_bytes())?;
    let run = PprofRun {
        duration: Duration::from_secs_f64(p.wall_seconds),
        comments: vec![
            title,
            format!("view: {}", view_label(view.view)),
            p.sampled.clone(),
        ],
    };
    let pprof = pprof_profile_gz(&view.stacks, &run).map_err(profile_error)?;
    let pprof_path = save(out, &format!("{dir}profile-{stem}{suffix}.pb.gz"), &pprof)?;
    let flat = view
        .flat
        .rows
        .iter()
        .map(|r| FlatRow {
            name: r.name.clone(),
            percent: r.percent,
            self_seconds: r.self_seconds,
            total_seconds: r.inclusive_seconds,
            calls: r.calls,
            inclusive_percent: Some(r.inclusive_percent),
            self_interval: Some([r.self_interval.low, r.self_interval.high]),
            inclusive_interval: Some([r.inclusive_interval.low, r.inclusive_interval.high]),
            noise: r.noise,
            root: r.root,
        })
        .collect();
    Ok((
        ProfileViewFiles {
            view: view.view,
            flat,
            flat_text,
            callgraph_text,
            flame_svg,
        },
        pprof_path,
    ))
}

/// Writes every file of one profile under `out/dir` (`dir` empty or ending in `/`):
/// per view the gprof texts, folded stacks, flamegraph and pprof file; then the
/// speedscope file of all views and the first view's Amdahl table. The one writer of
/// `rtprof profile`, the suite's profile and `rtprof record`.
pub fn save_profile_files(
    out: &Path,
    dir: &str,
    p: &ProfileToSave,
) -> Result<SavedProfile, RunError> {
    let mut views = Vec::with_capacity(p.views.len());
    let mut exports = Vec::new();
    for v in &p.views {
        let (files, pprof) = save_view(out, dir, p, v)?;
        views.push(files);
        exports.push(pprof);
    }
    let stem = slug(p.stem);
    let named: Vec<(&str, &StackSamples)> = p
        .views
        .iter()
        .map(|v| (view_label(v.view.view), &v.view.stacks))
        .collect();
    let speedscope = speedscope_json(p.title, &named);
    exports.push(save(
        out,
        &format!("{dir}speedscope-{stem}.json"),
        speedscope.as_bytes(),
    )?);
    if let Some(first) = p.views.first() {
        let amdahl_file = format!("{dir}amdahl-{stem}.txt");
        save(
            out,
            &amdahl_file,
            amdahl_text(&first.view.amdahl).as_bytes(),
        )?;
        exports.push(amdahl_file);
    }
    Ok(SavedProfile { views, exports })
}

/// Saves every file of one variant's profile under `out/dir` (`dir` empty or ending
/// in `/`) and returns its results entry.
pub fn save_profile(
    out: &Path,
    dir: &str,
    scene: &str,
    p: &VariantProfile,
) -> Result<Profile, RunError> {
    let title = format!("{scene} ({})", p.variant);
    let views = [&p.phases, &p.native]
        .into_iter()
        .map(|view| ViewToSave {
            view,
            suffix: suffix(view.view),
        })
        .collect();
    let saved = save_profile_files(
        out,
        dir,
        &ProfileToSave {
            stem: &p.variant,
            title: &title,
            wall_seconds: p.wall_seconds,
            sampled: format!("{} renders sampled", p.renders),
            views,
        },
    )?;
    let mut files = saved.views.into_iter();
    let (Some(phases), native) = (files.next(), files.next()) else {
        return Err(RunError::Profile("the phase view was not written".into()));
    };
    Ok(Profile {
        variant: VariantName::parse(&p.variant)?,
        samples: p.samples,
        seconds_per_sample: p.seconds_per_sample(),
        renders: Some(p.renders),
        samples_asked: Some(p.samples_asked),
        timer: Some(p.timer),
        cpu_seconds: Some(p.cpu_seconds),
        counts: crate::collect::count_map(&p.counts),
        view: ProfileView::Phases,
        flat: phases.flat,
        flat_text: phases.flat_text,
        callgraph_text: phases.callgraph_text,
        flame_svg: phases.flame_svg,
        amdahl: p
            .phases
            .amdahl
            .iter()
            .map(|a| AmdahlRow {
                name: a.name.clone(),
                fraction: a.fraction,
                speedup_2x: a.speedup_2x,
                speedup_10x: a.speedup_10x,
                speedup_limit: a.speedup_limit,
                inclusive: Some(AmdahlFigures {
                    fraction: a.inclusive_fraction,
                    speedup_2x: a.inclusive_speedup_2x,
                    speedup_10x: a.inclusive_speedup_10x,
                    speedup_limit: a.inclusive_speedup_limit,
                }),
            })
            .collect(),
        second_view: native,
        exports: saved.exports,
    })
}

/// The differential flamegraphs `before` → `after` (phase view): what grew, drawn on
/// `after`, and what shrank or vanished, drawn on `before`; returns their paths.
pub fn save_differential(
    out: &Path,
    dir: &str,
    scene: &str,
    before: &VariantProfile,
    after: &VariantProfile,
) -> Result<(String, String), RunError> {
    let per_render = |p: &VariantProfile| p.cpu_seconds / p.renders.max(1) as f64;
    let side = |p: &'_ VariantProfile| (p.phases.folded.clone(), p.variant.clone(), per_render(p));
    let (bf, bl, bs) = side(before);
    let (af, al, as_) = side(after);
    let svgs = differential_svgs(
        &DiffSide {
            folded: &bf,
            label: &bl,
            seconds_per_render: bs,
            unit: "render",
        },
        &DiffSide {
            folded: &af,
            label: &al,
            seconds_per_render: as_,
            unit: "render",
        },
        scene,
    )
    .map_err(profile_error)?;
    let stem = format!("{dir}flame-diff-{}-{}", slug(&bl), slug(&al));
    let grown = save(out, &format!("{stem}.svg"), svgs.grown.as_bytes())?;
    let shrunk = save(out, &format!("{stem}-shrunk.svg"), svgs.shrunk.as_bytes())?;
    Ok((grown, shrunk))
}

impl ProfileReport {
    /// Saves the profile (and the second variant's, with the differentials) under
    /// `out/dir` and returns the results entry.
    pub fn save(&self, out: &Path, dir: &str) -> Result<ProfileResult, RunError> {
        let baseline = save_profile(out, dir, &self.scene, &self.profile)?;
        let (best, diff) = match &self.diff {
            Some(d) => (
                Some(save_profile(out, dir, &self.scene, d)?),
                Some(save_differential(out, dir, &self.scene, &self.profile, d)?),
            ),
            None => (None, None),
        };
        let (grown, shrunk) = diff.unzip();
        Ok(ProfileResult {
            scene: self.scene.clone(),
            width: self.width,
            height: self.height,
            baseline,
            best,
            diff_flame_svg: grown,
            diff_shrunk_flame_svg: shrunk,
        })
    }

    /// The summary the command prints; `dir` is where the files were written.
    pub fn to_text(&self, dir: &Path, saved: &ProfileResult) -> String {
        let r = self;
        let p = &r.profile;
        let mut out = format!(
            "{} {}x{}, variant {}, {} thread{}: {} render{} sampled; {} samples taken ({} asked), {:.3} s CPU, {:.3} s wall, {} of CPU per sample\n{}\n",
            r.scene,
            r.width,
            r.height,
            p.variant,
            r.threads,
            if r.threads == 1 { "" } else { "s" },
            p.renders,
            if p.renders == 1 { "" } else { "s" },
            p.samples,
            p.samples_asked,
            p.cpu_seconds,
            p.wall_seconds,
            reports::format::seconds(p.seconds_per_sample()),
            p.timer_text(),
        );
        if let Some(o) = &r.overhead {
            out += &o.to_text();
        }
        let flat = &p.phases.flat;
        if let Some(top) = analysis::profile::flat::bottleneck(flat) {
            let limit = analysis::profile::amdahl::speedup(top.percent / 100.0, f64::INFINITY);
            out += &format!(
                "bottleneck: {} takes {:.1} % (95 % interval {:.1}-{:.1} %) of the time itself; free, the render would run {limit:.2}x faster\n",
                top.name, top.percent, top.self_interval.low, top.self_interval.high
            );
            let parent = analysis::profile::flat::largest_inclusive(flat);
            if let Some(parent) = parent.filter(|r| r.name != top.name) {
                out += &format!(
                    "largest with everything it calls: {} holds {:.1} %, {:.1} % itself: the rest is the work it calls\n",
                    parent.name, parent.inclusive_percent, parent.percent
                );
            }
        }
        out += "\nPhase view (the tracer's record of what each thread was doing; the native-symbol view is in the *-native files)\n";
        out += &p.phases.flat_text;
        out.push('\n');
        out += &amdahl_text(&p.phases.amdahl);
        let mut files: Vec<&str> = vec![
            &saved.baseline.flat_text,
            &saved.baseline.callgraph_text,
            &saved.baseline.flame_svg,
        ];
        files.extend(saved.baseline.exports.iter().map(String::as_str));
        if let Some(v) = &saved.baseline.second_view {
            files.extend([
                v.flat_text.as_str(),
                v.callgraph_text.as_str(),
                v.flame_svg.as_str(),
            ]);
        }
        if let Some(best) = &saved.best {
            files.extend([best.flat_text.as_str(), best.flame_svg.as_str()]);
        }
        files.extend(saved.diff_flame_svg.iter().map(String::as_str));
        files.extend(saved.diff_shrunk_flame_svg.iter().map(String::as_str));
        out += &format!("\nwrote {}/{{{}}}\n", dir.display(), files.join(", "));
        out
    }
}

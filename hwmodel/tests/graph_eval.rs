//! The block graphs the model schedules (and the RTL is generated from), evaluated on
//! values, against the emulator: the same picture bit for bit on every test-bench
//! scene, for one intersection unit and for several (the tree keeps the first
//! primitive in memory on ties, as one unit does).

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::emulator::render;
use hwmodel::graph_eval::{self, EvalError};
use hwmodel::hw_scene::HwScene;
use hwmodel::library::Library;
use std::path::Path;

fn test_bench() -> Vec<(String, HwScene)> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/"));
    let mut scenes = Vec::new();
    for family in ["balls", "cylinder", "both"] {
        for n in 1..=7 {
            let path = dir.join(format!("{family}{n}.nff"));
            let scene = tracer::load_nff(&path).unwrap_or_else(|e| panic!("{e}"));
            let hw = HwScene::from_scene(&scene).unwrap_or_else(|e| panic!("{e}"));
            scenes.push((format!("{family}{n}"), hw));
        }
    }
    scenes
}

#[test]
fn the_thesis_graphs_compute_the_emulators_picture_on_the_test_bench() {
    let lib = Library::cyclone_iv_e();
    let (width, height) = (24, 18);
    for units in [1, 2, 3] {
        let pipeline = Pipeline::build(
            &lib,
            &Design {
                units,
                ..Design::thesis()
            },
        );
        for (name, scene) in test_bench() {
            let emulated = render(&scene, width, height);
            let evaluated = graph_eval::render(&pipeline, &scene, width, height)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let differing: Vec<usize> = (0..emulated.pixels.len())
                .filter(|&i| emulated.pixels[i] != evaluated.pixels[i])
                .collect();
            assert!(
                differing.is_empty(),
                "{name}, K={units}: {} pixels differ, first at index {:?}",
                differing.len(),
                differing.first()
            );
            // Not a blank picture: the comparison would be empty.
            let distinct = emulated
                .pixels
                .iter()
                .collect::<std::collections::BTreeSet<_>>();
            assert!(
                distinct.len() > 2,
                "{name}: only {} gray levels",
                distinct.len()
            );
        }
    }
}

#[test]
fn the_fast_sqrt_graph_differs_from_the_exact_root_but_stays_close() {
    // The bit-trick root is off by up to ~6 %: the hit distances move, so some
    // silhouette and shading pixels change; the picture stays recognisably the same.
    let lib = Library::cyclone_iv_e();
    let fast = Pipeline::build(
        &lib,
        &Design {
            fast_sqrt: true,
            ..Design::thesis()
        },
    );
    let scene = &test_bench()[1].1;
    let exact = render(scene, 32, 24);
    let approx = graph_eval::render(&fast, scene, 32, 24).unwrap_or_else(|e| panic!("{e}"));
    let differing = exact
        .pixels
        .iter()
        .zip(&approx.pixels)
        .filter(|(a, b)| a != b)
        .count();
    assert!(differing > 0, "the bit-trick root changed nothing");
    assert!(
        differing < exact.pixels.len() / 2,
        "{differing} pixels differ"
    );
}

#[test]
fn the_orthographic_design_is_refused_with_a_reason() {
    let lib = Library::cyclone_iv_e();
    let ortho = Pipeline::build(
        &lib,
        &Design {
            ortho: true,
            ..Design::thesis()
        },
    );
    let scene = &test_bench()[0].1;
    let err = graph_eval::render(&ortho, scene, 4, 4).err();
    assert!(matches!(err, Some(EvalError::Unsupported(_))), "{err:?}");
}

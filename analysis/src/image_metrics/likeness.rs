//! Is an outside renderer's picture the scene rtprof drew, and drawn the same way?
//!
//! Three answers:
//! - [`Likeness::Same`]: the same scene with the same tones; the pictures differ at
//!   most by noise and aliasing, so their difference is an error (relMSE, FLIP, RMS).
//! - [`Likeness::OtherConventions`]: the same scene (the same edges in the same
//!   places) with other tones: brighter lights, another background colour, a gamma.
//!   The picture's differences are conventions, not errors: judge it against its own
//!   program's baseline run. Its time still compares.
//! - [`Likeness::Different`]: the edges are not where the reference's are: another
//!   scene, another camera, a mirror image, a blank or broken picture (Tachyon draws
//!   the SPD gears all white). Its time is not a comparison.
//!
//! # Criterion
//!
//! Structure first, from edges, which survive a global tone change: the
//! chance-corrected boundary F-measure of the two pictures' edge maps (the `edges`
//! module). Below [`SAME_SCENE_MIN_EDGE_AGREEMENT`] the scenes differ. Otherwise the
//! tones decide: the RMS difference of the two pictures after a Gaussian blur (which
//! averages a path tracer's zero-mean noise away but keeps a systematic shift), below
//! [`SAME_TONES_MAX_RMS`] is the same conventions.
//!
//! A picture of the same scene framed otherwise (another field of view, a camera
//! moved) has its edges elsewhere and comes out different: Tachyon's SPD balls, framed
//! wider than rtprof's (its sphereflake about 0.8 times the size), scored 0.001. Telling a reframed scene from another one would take registering the
//! two pictures, which this does not attempt.
//!
//! Edges and not a correlation of luma: a rank correlation (Spearman) is blind to a
//! gamma or a gain, but a background that turns from black to white moves half the
//! pixels from the bottom ranks to the top; gradient magnitudes ignore the sign of an
//! edge's contrast, so a silhouette stays one against any background.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::RgbImage;
use super::check_same_size;
use super::edges::{EdgeMap, agreement, gaussian_blur};
use crate::error::MetricsError;

/// The lowest edge agreement (chance-corrected F, 0 to 1) of two pictures of one scene.
/// Chosen from pairs measured while writing this, synthetic (the tests' spheres at
/// 96x72 and 200x150) and real (rtprof's and Tachyon's SPD balls and gears at 200x200):
/// - one scene: a gamma of 2.2 or 0.5 scored 0.72 to 0.96, a 1.5 gain 0.92 to 1, a
///   blue or white sky instead of a dark one 0.55 to 0.72, uniform noise of ±40 to ±80
///   levels per value (a path tracer at a few samples) 0.57 to 0.83;
/// - not one: moved by 8 or 12 pixels 0.03 to 0.22, mirrored or upside down 0.02 to
///   0.26, another SPD scene 0.00, a blank or noise picture 0.00 to 0.01.
///
/// 0.4 lies midway between the lowest of the first (0.55) and the highest of the
/// second (0.26). A move of 4 pixels or less scored 0.55 and more: within the edges'
/// tolerance, it counts as the same scene.
pub const SAME_SCENE_MIN_EDGE_AGREEMENT: f64 = 0.4;

/// The highest RMS difference (0-255 levels, all channels) of the blurred pictures
/// that is still the same tones: where the thesis's "visually identical" band ends
/// (the `band` module). Measured: noise of ±80 levels per value blurs to an RMS of 9,
/// a 1.1 gain gives 7; a 1.5 gain 32 to 42, a gamma of 0.5 40, a gamma of 2.2 61 to 67,
/// a blue sky instead of a dark one 102. A gamma of 1.2 (14) and a dark grey sky
/// instead of a dark blue one (13) stay the same tones, as the band says.
pub const SAME_TONES_MAX_RMS: f64 = 15.0;

/// The blur before the tone comparison, in pixels: it divides independent pixel noise
/// by about 2 sqrt(pi) sigma = 7, and a systematic tone shift not at all.
const TONE_BLUR_SIGMA: f64 = 2.0;

/// What [`likeness`] measured, for a report to print.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LikenessMeasures {
    /// Chance-corrected boundary F-measure of the two edge maps: 1 = the same edges,
    /// 0 = no more alike than chance (or one picture has no edges at all).
    pub edge_agreement: f64,
    /// Edge pixels of the picture and of the reference.
    pub picture_edges: u64,
    pub reference_edges: u64,
    /// RMS difference of the blurred pictures, 0-255 levels.
    pub tone_rms: f64,
}

/// Why two pictures are not of one scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Mismatch {
    /// The picture is flat (no edges) and the reference is not: a blank render.
    PictureFlat,
    /// The reference is flat and the picture is not.
    ReferenceFlat,
    /// Both have edges, in different places.
    EdgesDisagree,
}

/// Whether a picture shows the reference's scene, and drawn with the same conventions.
/// Serialized with a `likeness` tag: `{"likeness": "other_conventions", "measures":
/// {...}}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "likeness", rename_all = "snake_case")]
pub enum Likeness {
    /// The same scene and tones: compare the pictures as error.
    Same { measures: LikenessMeasures },
    /// The same scene with other tones: judge the picture against its own baseline.
    OtherConventions { measures: LikenessMeasures },
    /// Not the same scene: its time is no comparison.
    Different {
        reason: Mismatch,
        measures: LikenessMeasures,
    },
}

impl Likeness {
    pub fn measures(&self) -> &LikenessMeasures {
        match self {
            Likeness::Same { measures }
            | Likeness::OtherConventions { measures }
            | Likeness::Different { measures, .. } => measures,
        }
    }

    /// One line for a report: the verdict and the figures behind it.
    pub fn describe(&self) -> String {
        let m = self.measures();
        let figures = format!(
            "edge agreement {:.2} (same scene from {SAME_SCENE_MIN_EDGE_AGREEMENT}), \
             tone RMS {:.1} (same tones below {SAME_TONES_MAX_RMS})",
            m.edge_agreement, m.tone_rms
        );
        match self {
            Likeness::Same { .. } => format!("same scene, same conventions: {figures}"),
            Likeness::OtherConventions { .. } => format!(
                "same scene, other conventions (judge it against its own baseline): {figures}"
            ),
            Likeness::Different { reason, .. } => {
                let why = match reason {
                    Mismatch::PictureFlat => format!(
                        "the picture is flat (no edges), the reference has {} edge pixels",
                        m.reference_edges
                    ),
                    Mismatch::ReferenceFlat => format!(
                        "the reference is flat (no edges), the picture has {} edge pixels",
                        m.picture_edges
                    ),
                    Mismatch::EdgesDisagree => {
                        "the edges are elsewhere: another scene, framing or camera".to_string()
                    }
                };
                format!("a different picture ({why}; its time is no comparison): {figures}")
            }
        }
    }
}

/// Judges `picture` against `reference` (see the module documentation); they must
/// have the same size.
pub fn likeness(picture: &RgbImage, reference: &RgbImage) -> Result<Likeness, MetricsError> {
    check_same_size(picture, reference)?;
    let (picture_map, reference_map) = (EdgeMap::of(picture), EdgeMap::of(reference));
    let measures = LikenessMeasures {
        edge_agreement: agreement(&picture_map, &reference_map).f,
        picture_edges: picture_map.count(),
        reference_edges: reference_map.count(),
        tone_rms: blurred_rms(picture, reference),
    };
    let reason = match (measures.picture_edges, measures.reference_edges) {
        (0, r) if r > 0 => Some(Mismatch::PictureFlat),
        (p, 0) if p > 0 => Some(Mismatch::ReferenceFlat),
        _ if measures.edge_agreement < SAME_SCENE_MIN_EDGE_AGREEMENT => {
            Some(Mismatch::EdgesDisagree)
        }
        _ => None,
    };
    Ok(match reason {
        Some(reason) => Likeness::Different { reason, measures },
        None if measures.tone_rms < SAME_TONES_MAX_RMS => Likeness::Same { measures },
        None => Likeness::OtherConventions { measures },
    })
}

/// RMS over all channels of the difference of the two pictures, each channel blurred
/// at [`TONE_BLUR_SIGMA`].
fn blurred_rms(a: &RgbImage, b: &RgbImage) -> f64 {
    let (width, height) = (a.width as usize, a.height as usize);
    let channel = |img: &RgbImage, c: usize| -> Vec<f64> {
        let plane: Vec<f64> = img
            .data
            .iter()
            .skip(c)
            .step_by(3)
            .map(|&v| f64::from(v))
            .collect();
        gaussian_blur(&plane, width, height, TONE_BLUR_SIGMA)
    };
    let mut sum_sq = 0.0;
    for c in 0..3 {
        for (x, y) in channel(a, c).iter().zip(channel(b, c)) {
            sum_sq += (x - y) * (x - y);
        }
    }
    (sum_sq / a.data.len() as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_metrics::test_scenes::{
        discs, gain, gamma, mirrored, noise, shifted, uniform, upside_down, with_noise,
    };

    const SKY: [u8; 3] = [25, 30, 45];

    fn scene() -> RgbImage {
        discs(96, 72, SKY)
    }

    fn verdict(picture: &RgbImage) -> Likeness {
        likeness(picture, &scene()).expect("same size")
    }

    #[test]
    fn identical_pictures_are_the_same() {
        let l = verdict(&scene());
        assert!(matches!(l, Likeness::Same { .. }), "{l:?}");
        assert_eq!(l.measures().edge_agreement, 1.0);
        assert_eq!(l.measures().tone_rms, 0.0);
    }

    /// A path tracer's picture against its converged run: noisy, but the same.
    #[test]
    fn a_noisy_render_of_the_same_scene_is_the_same() {
        let l = verdict(&with_noise(&scene(), 40, 3));
        assert!(matches!(l, Likeness::Same { .. }), "{}", l.describe());
    }

    #[test]
    fn a_gamma_curve_is_another_convention() {
        for g in [2.2, 0.5] {
            let l = verdict(&gamma(&scene(), g));
            assert!(
                matches!(l, Likeness::OtherConventions { .. }),
                "gamma {g}: {}",
                l.describe()
            );
        }
    }

    #[test]
    fn brighter_lights_with_clipping_are_another_convention() {
        let l = verdict(&gain(&scene(), 1.5));
        assert!(
            l.describe().starts_with("same scene, other conventions"),
            "{}",
            l.describe()
        );
        assert!(
            matches!(l, Likeness::OtherConventions { .. }),
            "{}",
            l.describe()
        );
    }

    #[test]
    fn another_background_colour_is_another_convention() {
        for sky in [[120, 170, 230], [255, 255, 255]] {
            let l = verdict(&discs(96, 72, sky));
            assert!(
                matches!(l, Likeness::OtherConventions { .. }),
                "sky {sky:?}: {}",
                l.describe()
            );
        }
    }

    #[test]
    fn a_blank_white_picture_is_different() {
        let l = verdict(&uniform(96, 72, [255; 3]));
        assert_eq!(
            l,
            Likeness::Different {
                reason: Mismatch::PictureFlat,
                measures: *l.measures()
            }
        );
        assert_eq!(l.measures().edge_agreement, 0.0);
        assert!(
            l.describe().contains("the picture is flat"),
            "{}",
            l.describe()
        );
        // And the other way round.
        let r = likeness(&scene(), &uniform(96, 72, [255; 3])).expect("same size");
        assert!(
            matches!(
                r,
                Likeness::Different {
                    reason: Mismatch::ReferenceFlat,
                    ..
                }
            ),
            "{r:?}"
        );
    }

    #[test]
    fn a_moved_or_mirrored_scene_is_different() {
        for (what, picture) in [
            ("shifted", shifted(&scene(), 8)),
            ("mirrored", mirrored(&scene())),
            ("upside down", upside_down(&scene())),
        ] {
            let l = verdict(&picture);
            assert!(
                matches!(
                    l,
                    Likeness::Different {
                        reason: Mismatch::EdgesDisagree,
                        ..
                    }
                ),
                "{what}: {}",
                l.describe()
            );
        }
    }

    /// Noise has next to no edges once the threshold rises above its own gradients:
    /// different either way (edges elsewhere, or none).
    #[test]
    fn noise_is_different() {
        let l = verdict(&noise(96, 72, 11));
        assert!(matches!(l, Likeness::Different { .. }), "{}", l.describe());
        assert!(l.measures().edge_agreement < 0.05, "{}", l.describe());
    }

    #[test]
    fn two_flat_pictures_differ_only_in_tone() {
        let grey = uniform(8, 8, [128; 3]);
        assert!(matches!(likeness(&grey, &grey), Ok(Likeness::Same { .. })));
        let l = likeness(&uniform(8, 8, [200; 3]), &grey).expect("same size");
        assert!(matches!(l, Likeness::OtherConventions { .. }), "{l:?}");
        assert!((l.measures().tone_rms - 72.0).abs() < 1e-9, "{l:?}");
    }

    #[test]
    fn the_verdict_round_trips_through_json_with_a_tag() {
        let l = verdict(&uniform(96, 72, [255; 3]));
        let json = serde_json::to_value(l).expect("serialize");
        assert_eq!(json["likeness"], "different");
        assert_eq!(json["reason"], "picture_flat");
        assert_eq!(json["measures"]["picture_edges"], 0);
        let back: Likeness = serde_json::from_value(json).expect("parse");
        assert_eq!(back, l);
    }

    #[test]
    fn same_tones_end_where_the_visually_identical_band_does() {
        assert_eq!(
            Some(SAME_TONES_MAX_RMS),
            crate::image_metrics::Band::VisuallyIdentical.upper_edge()
        );
    }

    #[test]
    fn mismatched_sizes_are_an_error() {
        let other = discs(72, 96, SKY);
        assert!(matches!(
            likeness(&other, &scene()),
            Err(MetricsError::SizeMismatch { .. })
        ));
    }
}

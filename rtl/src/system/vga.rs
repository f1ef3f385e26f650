//! The VGA side of the system: a video mode's timing ([`VgaTiming`], the parameters of
//! `rtl/verilog/vga_controller.v`) and a monitor's view of the signals
//! ([`decode`]): from one sample per pixel clock of hsync, vsync, blanking and RGB, the
//! sync polarities, widths, porches, line and frame lengths as measured, and the
//! picture of one whole frame.
//!
//! The decoder knows no mode: it finds the syncs' active levels (the level a sync
//! holds the shorter time), measures every line and frame, and refuses a trace whose
//! lines or frames differ from one another; a test then holds the measurement against
//! the standard's figures.

use hwmodel::emulator::HwImage;
use serde::Serialize;

use crate::RtlError;

/// A video mode's timing: horizontal figures in pixel clocks, vertical ones in lines.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct VgaTiming {
    pub h_visible: u32,
    pub h_front: u32,
    pub h_sync: u32,
    pub h_back: u32,
    pub v_visible: u32,
    pub v_front: u32,
    pub v_sync: u32,
    pub v_back: u32,
    /// The horizontal sync pulse is low (negative polarity).
    pub hsync_negative: bool,
    /// The vertical sync pulse is low (negative polarity).
    pub vsync_negative: bool,
    /// The pixel clock the mode is specified for, in Hz.
    pub pixel_clock_hz: f64,
}

impl VgaTiming {
    /// 640 × 480 at 60 Hz, the "industry standard" entry of VESA's Display Monitor
    /// Timing standard (DMT): 25.175 MHz, lines of 640 + 16 + 96 + 48 clocks, frames of
    /// 480 + 10 + 2 + 33 lines, both syncs negative.
    pub const VESA_640X480_60: VgaTiming = VgaTiming {
        h_visible: 640,
        h_front: 16,
        h_sync: 96,
        h_back: 48,
        v_visible: 480,
        v_front: 10,
        v_sync: 2,
        v_back: 33,
        hsync_negative: true,
        vsync_negative: true,
        pixel_clock_hz: 25_175_000.0,
    };

    /// A mode of `width` × `height` visible pixels with short porches and syncs (4, 8
    /// and 6 clocks; 2, 2 and 3 lines), negative syncs like the standard's: the same
    /// timing generator at a frame a simulation runs through quickly. The pixel clock
    /// is the standard's.
    pub const fn small(width: u32, height: u32) -> VgaTiming {
        VgaTiming {
            h_visible: width,
            h_front: 4,
            h_sync: 8,
            h_back: 6,
            v_visible: height,
            v_front: 2,
            v_sync: 2,
            v_back: 3,
            hsync_negative: true,
            vsync_negative: true,
            pixel_clock_hz: 25_175_000.0,
        }
    }

    /// Pixel clocks per line.
    pub fn h_total(&self) -> u32 {
        self.h_visible + self.h_front + self.h_sync + self.h_back
    }

    /// Lines per frame.
    pub fn v_total(&self) -> u32 {
        self.v_visible + self.v_front + self.v_sync + self.v_back
    }

    /// Pixel clocks per frame.
    pub fn frame_clocks(&self) -> u64 {
        u64::from(self.h_total()) * u64::from(self.v_total())
    }

    /// Frames per second at the mode's pixel clock.
    pub fn frame_rate_hz(&self) -> f64 {
        self.pixel_clock_hz / self.frame_clocks() as f64
    }

    /// Address bits of the frame memory (one byte per visible pixel), at least 1.
    pub fn fb_address_bits(&self) -> u32 {
        let words = u64::from(self.h_visible) * u64::from(self.v_visible);
        (64 - words.saturating_sub(1).leading_zeros()).max(1)
    }

    /// The mode can be generated: a visible area and a sync pulse in each direction,
    /// counters within the controller's 16-bit `column` and `row`.
    pub fn check(&self) -> Result<(), RtlError> {
        let bad = |what: &str| Err(RtlError::Generate(format!("VGA timing: {what}")));
        if self.h_visible == 0 || self.v_visible == 0 {
            return bad("the visible area is empty");
        }
        if self.h_sync == 0 || self.v_sync == 0 {
            return bad("a sync pulse of zero length");
        }
        if self.h_total() > 1 << 16 || self.v_total() > 1 << 16 {
            return bad("more than 65,536 clocks per line or lines per frame");
        }
        Ok(())
    }

    /// `vga_controller`'s parameters for this mode.
    pub fn parameters(&self) -> Vec<(&'static str, u32)> {
        vec![
            ("H_VISIBLE", self.h_visible),
            ("H_FRONT", self.h_front),
            ("H_SYNC", self.h_sync),
            ("H_BACK", self.h_back),
            ("V_VISIBLE", self.v_visible),
            ("V_FRONT", self.v_front),
            ("V_SYNC", self.v_sync),
            ("V_BACK", self.v_back),
            ("HSYNC_ACTIVE", u32::from(!self.hsync_negative)),
            ("VSYNC_ACTIVE", u32::from(!self.vsync_negative)),
            ("FB_ADDRESS_BITS", self.fb_address_bits()),
        ]
    }
}

/// The VGA pins in one pixel clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VgaSample {
    /// Line levels (true: high).
    pub hsync: bool,
    pub vsync: bool,
    /// The DAC's blanking input: the pixel is shown.
    pub video_on: bool,
    pub rgb: [u8; 3],
}

impl VgaSample {
    /// Bytes per sample in a testbench's trace: flags (bit 0 hsync, 1 vsync, 2
    /// video_on), then red, green, blue.
    pub const BYTES: usize = 4;

    /// The samples of a testbench's trace.
    pub fn parse_trace(bytes: &[u8]) -> Vec<VgaSample> {
        bytes
            .chunks_exact(Self::BYTES)
            .map(|b| VgaSample {
                hsync: b[0] & 1 != 0,
                vsync: b[0] & 2 != 0,
                video_on: b[0] & 4 != 0,
                rgb: [b[1], b[2], b[3]],
            })
            .collect()
    }
}

/// What a monitor measures on the pins: every figure as counted in the trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct VgaMeasurement {
    /// The horizontal sync pulse is low.
    pub hsync_negative: bool,
    pub vsync_negative: bool,
    /// Pixel clocks from one hsync pulse to the next.
    pub line_clocks: u64,
    /// Pixel clocks of the hsync pulse.
    pub hsync_clocks: u64,
    /// Pixel clocks from the end of the hsync pulse to the first visible pixel.
    pub h_back: u64,
    /// Visible pixels per line.
    pub h_visible: u64,
    /// Pixel clocks from the last visible pixel to the next hsync pulse.
    pub h_front: u64,
    /// Lines from one vsync pulse to the next.
    pub frame_lines: u64,
    /// Lines of the vsync pulse.
    pub vsync_lines: u64,
    /// Whole lines from the end of the vsync pulse to the first visible line.
    pub v_back: u64,
    /// Visible lines per frame.
    pub v_visible: u64,
    /// Whole lines from the end of the last visible line to the next vsync pulse.
    pub v_front: u64,
    /// Samples outside the visible area whose RGB is not black (a monitor takes the
    /// blanking level as black).
    pub blank_not_black: u64,
    /// Visible pixels whose three channels differ (the design shows gray).
    pub not_gray: u64,
}

impl VgaMeasurement {
    /// The measurement is `timing`'s mode exactly.
    pub fn matches(&self, timing: &VgaTiming) -> bool {
        let t = timing;
        self.hsync_negative == t.hsync_negative
            && self.vsync_negative == t.vsync_negative
            && self.line_clocks == u64::from(t.h_total())
            && self.hsync_clocks == u64::from(t.h_sync)
            && self.h_back == u64::from(t.h_back)
            && self.h_visible == u64::from(t.h_visible)
            && self.h_front == u64::from(t.h_front)
            && self.frame_lines == u64::from(t.v_total())
            && self.vsync_lines == u64::from(t.v_sync)
            && self.v_back == u64::from(t.v_back)
            && self.v_visible == u64::from(t.v_visible)
            && self.v_front == u64::from(t.v_front)
    }
}

/// One frame decoded from the pins.
#[derive(Clone, Debug, PartialEq)]
pub struct DecodedFrame {
    pub measurement: VgaMeasurement,
    /// The visible pixels of the first whole frame (red channel).
    pub image: HwImage,
}

/// Intervals `[start, end)` where `level(sample)` is `active`.
fn runs(samples: &[VgaSample], level: impl Fn(&VgaSample) -> bool) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, s) in samples.iter().enumerate() {
        match (level(s), start) {
            (true, None) => start = Some(i),
            (false, Some(a)) => {
                out.push((a, i));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(a) = start {
        out.push((a, samples.len()));
    }
    out
}

/// The one value all of `values` share, else an error naming `what`.
fn all_equal(what: &str, values: impl IntoIterator<Item = u64>) -> Result<u64, RtlError> {
    let values: Vec<u64> = values.into_iter().collect();
    match values.first() {
        None => Err(decode_error(format!("no {what} in the trace"))),
        Some(&first) if values.iter().all(|&v| v == first) => Ok(first),
        Some(_) => {
            let mut distinct = values.clone();
            distinct.sort_unstable();
            distinct.dedup();
            Err(decode_error(format!("{what} varies: {distinct:?}")))
        }
    }
}

fn decode_error(message: String) -> RtlError {
    RtlError::Tool {
        tool: "VGA decoder",
        message,
    }
}

/// Decodes a trace of one sample per pixel clock that holds at least two vsync pulses'
/// leading edges: the measurement and the picture of the frame between them.
pub fn decode(samples: &[VgaSample]) -> Result<DecodedFrame, RtlError> {
    // A sync's active level is the one it holds the shorter time.
    let low = |f: fn(&VgaSample) -> bool| samples.iter().filter(|s| !f(s)).count();
    let hsync_negative = low(|s| s.hsync) * 2 < samples.len();
    let vsync_negative = low(|s| s.vsync) * 2 < samples.len();
    let hsync_active = move |s: &VgaSample| s.hsync != hsync_negative;
    let vsync_active = move |s: &VgaSample| s.vsync != vsync_negative;

    // Only whole pulses: a run cut by either end of the trace is left out.
    let whole = |r: &(usize, usize)| r.0 > 0 && r.1 < samples.len();
    let hsyncs: Vec<(usize, usize)> = runs(samples, hsync_active)
        .into_iter()
        .filter(whole)
        .collect();
    let vsyncs: Vec<(usize, usize)> = runs(samples, vsync_active)
        .into_iter()
        .filter(whole)
        .collect();
    if vsyncs.len() < 2 {
        return Err(decode_error(format!(
            "{} whole vsync pulse(s) in {} samples: a frame needs two",
            vsyncs.len(),
            samples.len()
        )));
    }
    let (frame_start, frame_end) = (vsyncs[0].0, vsyncs[1].0);
    let line_clocks = all_equal(
        "the line period (hsync to hsync)",
        hsyncs.windows(2).map(|w| (w[1].0 - w[0].0) as u64),
    )?;
    let hsync_clocks = all_equal(
        "the hsync pulse",
        hsyncs.iter().map(|(a, b)| (b - a) as u64),
    )?;
    let frame_clocks = all_equal(
        "the frame period (vsync to vsync)",
        vsyncs.windows(2).map(|w| (w[1].0 - w[0].0) as u64),
    )?;
    let vsync_clocks = all_equal(
        "the vsync pulse",
        vsyncs.iter().map(|(a, b)| (b - a) as u64),
    )?;
    let whole_lines = |what: &str, clocks: u64| {
        if clocks.is_multiple_of(line_clocks) {
            Ok(clocks / line_clocks)
        } else {
            Err(decode_error(format!(
                "{what} is {clocks} clocks, not a whole number of {line_clocks}-clock lines"
            )))
        }
    };
    let frame_lines = whole_lines("the frame", frame_clocks)?;
    let vsync_lines = whole_lines("the vsync pulse", vsync_clocks)?;

    // The visible runs of the frame, each placed against the hsync pulses around it.
    let visible: Vec<(usize, usize)> = runs(&samples[frame_start..frame_end], |s| s.video_on)
        .into_iter()
        .map(|(a, b)| (a + frame_start, b + frame_start))
        .collect();
    let mut backs = Vec::new();
    let mut fronts = Vec::new();
    for &(a, b) in &visible {
        let before = hsyncs.iter().rev().find(|h| h.1 <= a);
        let after = hsyncs.iter().find(|h| h.0 >= b);
        match (before, after) {
            (Some(h0), Some(h1)) => {
                backs.push((a - h0.1) as u64);
                fronts.push((h1.0 - b) as u64);
            }
            _ => {
                return Err(decode_error(format!(
                    "the visible run at clock {a} has no whole hsync pulse on each side"
                )));
            }
        }
    }
    let h_visible = all_equal(
        "the visible run",
        visible.iter().map(|(a, b)| (b - a) as u64),
    )?;
    let h_back = all_equal("the horizontal back porch", backs)?;
    let h_front = all_equal("the horizontal front porch", fronts)?;
    let (first, last) = match (visible.first(), visible.last()) {
        (Some(f), Some(l)) => (f.0, l.1),
        _ => return Err(decode_error("no visible pixel in the frame".into())),
    };
    let v_back = (first - vsyncs[0].1) as u64 / line_clocks;
    let v_front = (frame_end - last) as u64 / line_clocks;

    let mut pixels = Vec::with_capacity(visible.len() * h_visible as usize);
    let mut not_gray = 0;
    for &(a, b) in &visible {
        for s in &samples[a..b] {
            if s.rgb[1] != s.rgb[0] || s.rgb[2] != s.rgb[0] {
                not_gray += 1;
            }
            pixels.push(s.rgb[0]);
        }
    }
    let blank_not_black = samples
        .iter()
        .filter(|s| !s.video_on && s.rgb != [0; 3])
        .count() as u64;
    let to_u32 = |v: u64| u32::try_from(v).map_err(|_| decode_error(format!("{v} pixels")));
    Ok(DecodedFrame {
        measurement: VgaMeasurement {
            hsync_negative,
            vsync_negative,
            line_clocks,
            hsync_clocks,
            h_back,
            h_visible,
            h_front,
            frame_lines,
            vsync_lines,
            v_back,
            v_visible: visible.len() as u64,
            v_front,
            blank_not_black,
            not_gray,
        },
        image: HwImage {
            width: to_u32(h_visible)?,
            height: to_u32(visible.len() as u64)?,
            pixels,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pins of `frames` frames of a mode drawn by hand: syncs at the VESA places
    /// (after the visible area and the front porch), a gray ramp as the picture.
    fn pins(t: &VgaTiming, frames: u32, skip: usize) -> Vec<VgaSample> {
        let mut out = Vec::new();
        for _ in 0..frames {
            for v in 0..t.v_total() {
                for h in 0..t.h_total() {
                    let on = h < t.h_visible && v < t.v_visible;
                    let hs =
                        (t.h_visible + t.h_front..t.h_visible + t.h_front + t.h_sync).contains(&h);
                    let vs =
                        (t.v_visible + t.v_front..t.v_visible + t.v_front + t.v_sync).contains(&v);
                    let g = if on { (h + 3 * v) as u8 } else { 0 };
                    out.push(VgaSample {
                        hsync: hs != t.hsync_negative,
                        vsync: vs != t.vsync_negative,
                        video_on: on,
                        rgb: [g; 3],
                    });
                }
            }
        }
        out.split_off(skip)
    }

    #[test]
    fn the_standard_mode_is_800_clocks_by_525_lines_at_59_94_hz() {
        let t = VgaTiming::VESA_640X480_60;
        assert_eq!((t.h_total(), t.v_total()), (800, 525));
        // 25.175 MHz / (800 × 525) = 59.94 Hz.
        assert!((t.frame_rate_hz() - 59.94).abs() < 0.005);
        assert_eq!(t.fb_address_bits(), 19);
        assert_eq!(VgaTiming::small(80, 60).fb_address_bits(), 13);
    }

    #[test]
    fn a_drawn_mode_decodes_to_its_figures_and_picture() {
        for t in [VgaTiming::small(12, 5), VgaTiming::VESA_640X480_60] {
            // Starting mid-frame: the first vsync pulse comes before the frame decoded.
            let d = decode(&pins(&t, 3, t.frame_clocks() as usize / 2 + 7)).unwrap();
            assert!(d.measurement.matches(&t), "{:?}", d.measurement);
            assert_eq!(
                (d.measurement.blank_not_black, d.measurement.not_gray),
                (0, 0)
            );
            assert_eq!((d.image.width, d.image.height), (t.h_visible, t.v_visible));
            assert_eq!(d.image.gray_at(5, 2), Some(11));
        }
    }

    #[test]
    fn positive_syncs_are_recognised() {
        let t = VgaTiming {
            hsync_negative: false,
            vsync_negative: false,
            ..VgaTiming::small(16, 8)
        };
        let d = decode(&pins(&t, 3, 0)).unwrap();
        assert!(d.measurement.matches(&t));
        assert!(!d.measurement.matches(&VgaTiming::small(16, 8)));
    }

    #[test]
    fn an_irregular_line_and_a_short_trace_are_refused() {
        let t = VgaTiming::small(12, 5);
        let mut samples = pins(&t, 3, 0);
        // One hsync pulse a clock late: two line periods differ.
        let at = 10 * t.h_total() as usize + (t.h_visible + t.h_front) as usize;
        samples[at].hsync = !samples[at].hsync;
        let e = decode(&samples).unwrap_err().to_string();
        assert!(e.contains("varies"), "{e}");
        let e = decode(&pins(&t, 1, 0)).unwrap_err().to_string();
        assert!(e.contains("a frame needs two"), "{e}");
    }
}

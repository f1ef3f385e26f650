//! The hardware model's charts: software against hardware frame time and speed-up per
//! scene (thesis fig. 49, 50), and the devices' utilization.

use hwmodel::device::ROUTING_HEADROOM_PERCENT;
use plotters::prelude::*;

use super::Chart;
use super::bars::Slots;
use super::categories::{Categories, category_chart};
use super::data::{RESOURCES, device_shares, hardware_scenes};
use super::marks::{Dashed, Key, Place, cap, keyed, stem};
use super::numbers::{format_number, truncate};
use super::scale::{Axis, Ticks, finite_positive, tight_log_range};
use super::style::{ALARM, GUIDE_TEXT, INK, PALETTE, VALUE_PX, text_width};
use crate::results::Results;

/// Software and hardware bars of a scene.
const SW_HW: Slots = Slots {
    groups: 2,
    span: 0.76,
    gap: 0.04,
};

/// The resources' bars of a device.
const RESOURCE_SLOTS: Slots = Slots {
    groups: RESOURCES.len(),
    span: 0.7,
    gap: 0.02,
};

/// A dashed line across the plot that marks a limit.
const LIMIT: Dashed = Dashed {
    colour: ALARM,
    width: 2,
    dash: 6,
    gap: 4,
};

/// The routing headroom's line: a guide, not a limit (`hwmodel::device`).
const HEADROOM: Dashed = Dashed {
    colour: GUIDE_TEXT,
    ..LIMIT
};

/// Scene names as category labels.
fn scenes_axis<'s>(names: impl Iterator<Item = &'s str>) -> Categories {
    Categories::fitted(names.map(|n| truncate(n, 24)).collect(), 0.0, "scene")
}

/// Software against hardware frame time per scene, grouped bars, log y (thesis fig. 49).
pub fn sw_hw_times_chart(results: &Results) -> Option<Chart> {
    let scenes = hardware_scenes(results);
    let hardware: Vec<_> = scenes.iter().map(|(_, h)| *h).collect();
    let values = hardware
        .iter()
        .flat_map(|h| [h.seconds, h.software_seconds.low, h.software_seconds.high]);
    let (lo, hi) = tight_log_range(values)?;
    Some(category_chart(
        (
            "sw-hw-times",
            "Software and hardware frame time per scene".to_string(),
            "Thesis fig. 49. Software: median time of the baseline diffuse-only gray render with its 95 % interval; hardware: the model's frame time at 50 MHz (eq. 49). Log scale.".to_string(),
        ),
        scenes_axis(scenes.iter().map(|(s, _)| s.name.as_str())),
        // Room above the bars for the legend.
        Axis::log((lo, hi * 3.0), "", Some(30), "frame time (s, log scale)", 64),
        move |plot| {
            let (sw, hw) = (PALETTE[0], PALETTE[1]);
            let software = hardware.iter().map(|h| h.software_seconds.median);
            let anno = plot.columns(SW_HW, 0, software.enumerate(), lo, sw)?;
            keyed(anno, "software (baseline, diffuse gray)", Key::Box(sw));
            plot.chart.draw_series(hardware.iter().enumerate().flat_map(|(i, h)| {
                let (l, u) = (h.software_seconds.low, h.software_seconds.high);
                let whisker = finite_positive(l) && finite_positive(u);
                whisker
                    .then(|| error_bar(SW_HW.centre(i, 0), l, u))
                    .into_iter()
                    .flatten()
            }))?;
            let model = hardware.iter().map(|h| h.seconds);
            let anno = plot.columns(SW_HW, 1, model.enumerate(), lo, hw)?;
            keyed(anno, "hardware model (50 MHz)", Key::Box(hw));
            plot.legend(SeriesLabelPosition::UpperLeft)
        },
    ))
}

/// An interval from `low` to `high` at `x`, with caps.
fn error_bar(x: f64, low: f64, high: f64) -> [PathElement<(f64, f64)>; 3] {
    let style = INK.stroke_width(1);
    [
        stem(x, (low, high), style),
        cap(x, low, style),
        cap(x, high, style),
    ]
}

/// Hardware speed-up over software per scene (thesis fig. 50).
pub fn hw_speedup_chart(results: &Results) -> Option<Chart> {
    let scenes: Vec<_> = hardware_scenes(results)
        .into_iter()
        .filter(|(_, h)| h.speedup.is_finite())
        .collect();
    if scenes.is_empty() {
        return None;
    }
    let speedups: Vec<f64> = scenes.iter().map(|(_, h)| h.speedup.max(0.0)).collect();
    let max = speedups.iter().copied().fold(1.0, f64::max) * 1.18;
    Some(category_chart(
        (
            "hw-speedup",
            "Hardware speed-up over software per scene".to_string(),
            "Thesis fig. 50 (the thesis found 4.6 to 18). Software median time / hardware model frame time; above the dashed line the hardware is faster.".to_string(),
        ),
        scenes_axis(scenes.iter().map(|(s, _)| s.name.as_str())),
        Axis::linear(0.0, max, Ticks::Numbers, "hardware speed-up (×)", 56),
        move |plot| {
            let n = speedups.len();
            plot.columns(Slots::single(0.64), 0, speedups.iter().copied().enumerate(), 0.0, PALETTE[2])?;
            let even = Dashed { colour: PALETTE[3], ..LIMIT };
            plot.reference_line(1.0, even, "break-even (1×)")?;
            if n > 30 {
                return Ok(());
            }
            let values: Vec<String> = speedups.iter().map(|s| format!("{}×", format_number(*s))).collect();
            // Side by side when every value fits its bar's slot, else reading upwards.
            let slot = f64::from(plot.chart.plotting_area().dim_in_pixel().0) / n as f64;
            let upright = values.iter().all(|v| text_width(v, VALUE_PX) + 4.0 <= slot);
            let place = if upright { Place::Above } else { Place::AboveUpwards };
            for (i, (s, value)) in speedups.iter().zip(&values).enumerate() {
                plot.text(value, (i as f64, *s), place, BLACK)?;
            }
            Ok(())
        },
    ))
}

/// Device utilization of the thesis design: LEs, multipliers, memory and PLLs in % of
/// each device, with the 100 % line.
pub fn device_utilization_chart(results: &Results) -> Option<Chart> {
    let hardware = results.hardware.as_ref()?;
    if hardware.devices.is_empty() {
        return None;
    }
    let devices: Vec<(String, [f64; 4])> = hardware.devices.iter().map(device_shares).collect();
    let max = devices
        .iter()
        .flat_map(|g| g.1)
        .filter(|v| v.is_finite())
        .fold(100.0, f64::max)
        * 1.4;
    let labels: Vec<String> = devices.iter().map(|g| truncate(&g.0, 32)).collect();
    Some(category_chart(
        (
            "device-utilization",
            format!(
                "Device utilization of the thesis design ({})",
                hardware.family
            ),
            format!(
                "Share of each device's logic elements, 9-bit multiplier elements (all in use means the rest is built in logic, counted in the logic elements), memory bits and PLLs; above the dashed 100 % line the resource runs out; logic elements or memory bits above the grey {ROUTING_HEADROOM_PERCENT} % line fit on paper only (the routing-headroom rule)."
            ),
        ),
        Categories::fitted(labels, 0.0, "device"),
        Axis::linear(0.0, max, Ticks::Whole, "utilization (% of the device)", 56),
        move |plot| {
            for (r, resource) in RESOURCES.iter().enumerate() {
                let colour = PALETTE[r];
                let shares: Vec<f64> = devices
                    .iter()
                    .map(|g| if g.1[r].is_finite() { g.1[r] } else { 0.0 })
                    .collect();
                let anno = plot.columns(
                    RESOURCE_SLOTS,
                    r,
                    shares.iter().copied().enumerate(),
                    0.0,
                    colour,
                )?;
                keyed(anno, resource, Key::Box(colour));
                for (i, v) in shares.iter().enumerate() {
                    let at = (RESOURCE_SLOTS.centre(i, r), *v);
                    plot.text(&format!("{v:.0} %"), at, Place::Above, BLACK)?;
                }
            }
            plot.reference_line(100.0, LIMIT, "device capacity (100 %)")?;
            // The headroom's note at the right end, clear of the capacity line's at the
            // left (the devices after the thesis's are the larger, emptier ones).
            let headroom = ROUTING_HEADROOM_PERCENT as f64;
            let (x0, x1) = (plot.chart.x_range().start, plot.chart.x_range().end);
            plot.dashed([(x0, headroom), (x1, headroom)], HEADROOM)?;
            plot.text(
                &format!("routing headroom ({ROUTING_HEADROOM_PERCENT} %)"),
                (x1, headroom),
                Place::AboveLeft,
                HEADROOM.colour,
            )?;
            plot.legend(SeriesLabelPosition::UpperRight)
        },
    ))
}

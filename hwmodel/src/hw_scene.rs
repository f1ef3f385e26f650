//! The scene as the thesis hardware holds it (ch. 6.1.1).
//!
//! The hardware's scene block keeps the observer, the screen geometry, one light and a
//! memory of primitives. A primitive is eight IEEE-754 single-precision floats (centre
//! x, y, z, radius, axis vector V x, y, z, m max) plus a type bit (0 sphere, 1
//! cylinder). For a sphere V = 0 and m max = 0; for a cylinder the "centre" is the base
//! point Cb, V the unit axis from base to apex and m max = |apex − base|, so the hit
//! body bounds it with 0 < m < m max.
//!
//! [`HwScene::from_scene`] converts a parsed NFF scene and refuses what the hardware
//! cannot render: polygons, patches, cones (NFF `c` entities with different radii;
//! the parser already stores equal-radius ones as cylinders), inside-only surfaces
//! (negative radii: the hardware has no notion of a visible side), scenes without a
//! light or without any primitive. Only the first light is kept: the hardware shades
//! with one. Primitives are stored spheres first, then cylinders, because
//! [`tracer::Scene`] groups primitives by kind and no longer knows the file order.

use serde::{Deserialize, Serialize};
use std::fmt;

/// The primitive type bit of the scene memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[repr(u32)]
pub enum HwKind {
    Sphere = 0,
    Cylinder = 1,
}

impl HwKind {
    /// The type bit as the hardware stores it (0 sphere, 1 cylinder).
    pub fn type_bit(self) -> u32 {
        self as u32
    }

    /// The kind a type word names, or `None` for anything but 0 and 1.
    pub fn from_type_word(word: u32) -> Option<Self> {
        match word {
            0 => Some(Self::Sphere),
            1 => Some(Self::Cylinder),
            _ => None,
        }
    }

    /// Lower-case name ("sphere", "cylinder").
    pub fn name(self) -> &'static str {
        match self {
            Self::Sphere => "sphere",
            Self::Cylinder => "cylinder",
        }
    }
}

/// One primitive of the scene memory.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HwPrimitive {
    pub kind: HwKind,
    /// Sphere centre, or the base point Cb of a cylinder.
    pub center: [f32; 3],
    pub radius: f32,
    /// Unit axis V from base to apex; zero for a sphere.
    pub axis: [f32; 3],
    /// |apex − base| for a cylinder (the hit body's bound on m); zero for a sphere.
    pub m_max: f32,
}

impl HwPrimitive {
    /// Memory words per primitive: the eight floats, then the type in a word of its own.
    pub const WORDS: usize = 9;

    /// What each of the [`Self::WORDS`] words holds, in memory order.
    pub const WORD_NAMES: [&'static str; Self::WORDS] = [
        "centre.x", "centre.y", "centre.z", "radius", "axis.x", "axis.y", "axis.z", "m_max", "type",
    ];

    /// A sphere (V = 0, m max = 0).
    pub fn sphere(center: [f32; 3], radius: f32) -> Self {
        Self {
            kind: HwKind::Sphere,
            center,
            radius,
            axis: [0.0; 3],
            m_max: 0.0,
        }
    }

    /// A cylinder from its base point, unit axis and length.
    pub fn cylinder(base: [f32; 3], axis: [f32; 3], radius: f32, m_max: f32) -> Self {
        Self {
            kind: HwKind::Cylinder,
            center: base,
            radius,
            axis,
            m_max,
        }
    }

    /// The eight floats in memory order (centre, radius, axis, m max).
    pub fn floats(&self) -> [f32; 8] {
        let [cx, cy, cz] = self.center;
        let [vx, vy, vz] = self.axis;
        [cx, cy, cz, self.radius, vx, vy, vz, self.m_max]
    }

    /// The memory words: the eight floats' IEEE-754 bit patterns, then the type bit.
    pub fn to_words(&self) -> [u32; Self::WORDS] {
        let mut words = [0u32; Self::WORDS];
        for (word, value) in words.iter_mut().zip(self.floats()) {
            *word = value.to_bits();
        }
        words[8] = self.kind.type_bit();
        words
    }

    /// The primitive stored in `words`, or `None` when the type word is neither 0 nor 1.
    pub fn from_words(words: &[u32; Self::WORDS]) -> Option<Self> {
        let kind = HwKind::from_type_word(words[8])?;
        let f = |i: usize| f32::from_bits(words[i]);
        Some(Self {
            kind,
            center: [f(0), f(1), f(2)],
            radius: f(3),
            axis: [f(4), f(5), f(6)],
            m_max: f(7),
        })
    }
}

/// A scene the hardware can render.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HwScene {
    /// The observer.
    pub eye: [f32; 3],
    /// The point looked at (NFF `at`).
    pub look_at: [f32; 3],
    /// The up vector (NFF `up`, not necessarily unit or orthogonal).
    pub up: [f32; 3],
    /// NFF `angle`: degrees from the centre of the top pixel row to the centre of the
    /// bottom one (the tracer's convention).
    pub angle_deg: f32,
    /// Position of the light (the scene's first).
    pub light: [f32; 3],
    /// Background luminance, 0..1 (Rec. 601 luma of the NFF `b` colour, as the
    /// software's gray modes use).
    pub background_gray: f32,
    /// The scene memory, in memory order.
    pub primitives: Vec<HwPrimitive>,
}

/// Counts of what a scene has that the hardware cannot render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Unsupported {
    pub polygons: usize,
    pub patches: usize,
    pub cones: usize,
    /// Spheres with a negative radius (only the inside visible).
    pub inside_only_spheres: usize,
    /// Cylinders with a negative radius (only the inside visible).
    pub inside_only_cylinders: usize,
}

impl Unsupported {
    fn is_empty(&self) -> bool {
        *self == Self::default()
    }
}

impl fmt::Display for Unsupported {
    /// A list such as `2 polygons, 1 cone, 1 inside-only sphere (negative radius)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let items = [
            (self.polygons, "polygon", "polygons"),
            (self.patches, "patch", "patches"),
            (self.cones, "cone", "cones"),
            (
                self.inside_only_spheres,
                "inside-only sphere (negative radius)",
                "inside-only spheres (negative radius)",
            ),
            (
                self.inside_only_cylinders,
                "inside-only cylinder (negative radius)",
                "inside-only cylinders (negative radius)",
            ),
        ];
        let parts: Vec<String> = items
            .iter()
            .filter(|(n, _, _)| *n > 0)
            .map(|&(n, one, many)| format!("{n} {}", if n == 1 { one } else { many }))
            .collect();
        f.write_str(&parts.join(", "))
    }
}

/// Why a scene cannot go to the hardware.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum HwSceneError {
    #[error(
        "the hardware renders spheres and cylinders (outside surfaces) only; this scene also has {0}"
    )]
    Unsupported(Unsupported),
    #[error("the hardware shades with one light; this scene has none")]
    NoLight,
    #[error("the scene has no primitives; the hardware needs at least one sphere or cylinder")]
    NoPrimitives,
    #[error("invalid view: {0}")]
    View(String),
}

impl HwScene {
    /// The hardware's copy of `scene` (see the module doc for what is refused).
    pub fn from_scene(scene: &tracer::Scene) -> Result<Self, HwSceneError> {
        let unsupported = Unsupported {
            polygons: scene.polygons.len(),
            patches: scene.patches.len(),
            cones: scene.cones.len(),
            inside_only_spheres: scene.spheres.iter().filter(|s| s.radius < 0.0).count(),
            inside_only_cylinders: scene.cylinders.iter().filter(|c| c.radius < 0.0).count(),
        };
        if !unsupported.is_empty() {
            return Err(HwSceneError::Unsupported(unsupported));
        }
        let light = scene.lights.first().ok_or(HwSceneError::NoLight)?;
        if scene.spheres.is_empty() && scene.cylinders.is_empty() {
            return Err(HwSceneError::NoPrimitives);
        }
        // A hand-built scene has not been through the parser's check.
        tracer::nff::check_view_basis(&scene.view).map_err(HwSceneError::View)?;

        let spheres = scene
            .spheres
            .iter()
            .map(|s| HwPrimitive::sphere(s.center.to_array(), s.radius));
        // The tracer keeps the unit axis and |apex − base| of every cylinder: exactly the
        // hardware's V and m max.
        let cylinders = scene.cylinders.iter().map(|c| {
            HwPrimitive::cylinder(c.base.to_array(), c.axis.to_array(), c.radius, c.length)
        });
        let view = &scene.view;
        Ok(Self {
            eye: view.from.to_array(),
            look_at: view.at.to_array(),
            up: view.up.to_array(),
            angle_deg: view.angle_deg,
            light: light.position.to_array(),
            background_gray: scene.background.luminance(),
            primitives: spheres.chain(cylinders).collect(),
        })
    }

    /// Number of primitives in the scene memory (the thesis's n).
    pub fn primitive_count(&self) -> usize {
        self.primitives.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_round_trip_and_type_word_is_checked() {
        let c = HwPrimitive::cylinder([1.0, -2.5, 3.0], [0.0, 1.0, 0.0], 0.5, 4.0);
        let words = c.to_words();
        assert_eq!(words[0], 1.0f32.to_bits());
        assert_eq!(words[7], 4.0f32.to_bits());
        assert_eq!(words[8], 1);
        assert_eq!(HwPrimitive::from_words(&words), Some(c));
        let mut bad = words;
        bad[8] = 2;
        assert_eq!(HwPrimitive::from_words(&bad), None);
    }

    #[test]
    fn unsupported_list_reads_naturally() {
        let u = Unsupported {
            polygons: 2,
            cones: 1,
            ..Unsupported::default()
        };
        assert_eq!(u.to_string(), "2 polygons, 1 cone");
    }
}

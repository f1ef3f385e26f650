//! The scene: view, lights, materials and primitives, grouped by kind so that the
//! brute-force loop (and later SIMD) walks each kind as one contiguous array.

use crate::color::Rgb;
use crate::primitives::{Cone, Cylinder, Patch, Polygon, Sphere};
use crate::vec3::Vec3;

/// The NFF `v` block.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    pub from: Vec3,
    pub at: Vec3,
    pub up: Vec3,
    /// Degrees from the centre of the top sample row to the centre of the bottom one.
    pub angle_deg: f32,
    /// Near distance as written; parsed and kept, not used to clip (SPD statistics
    /// count every object in front of the eye).
    pub hither: f32,
    pub width: u32,
    pub height: u32,
}

/// A positional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub position: Vec3,
    /// Intensity per channel.
    pub color: Rgb,
    /// Whether the NFF line gave a colour (otherwise `color` is the SPD default).
    pub color_given: bool,
}

/// An NFF `f` material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    pub color: Rgb,
    /// Diffuse coefficient.
    pub kd: f32,
    /// Specular coefficient: Phong highlight weight and reflection coefficient.
    pub ks: f32,
    /// Phong exponent.
    pub shine: f32,
    /// Transmittance; transmitters are two-sided and refract.
    pub t: f32,
    /// Index of refraction.
    pub ior: f32,
}

impl Default for Material {
    /// The material of objects that precede any `f` line: white, diffuse.
    fn default() -> Self {
        Self {
            color: Rgb::WHITE,
            kd: 1.0,
            ks: 0.0,
            shine: 1.0,
            t: 0.0,
            ior: 1.0,
        }
    }
}

/// The SPD generator's surface terms of one material, which the NFF `f` line cannot
/// hold: `ka` and `ks_spec` of `lib_output_color`. Nothing renders them, neither rtprof's
/// renderer nor the NFF writer; the POV-Ray writer writes them as the SPD's POV-Ray
/// output did. Kept beside the materials ([`Scene::surface_terms`]), not in
/// [`Material`], which shading copies per hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceTerms {
    /// The ambient term (`ka`): POV-Ray's `ambient`.
    pub ambient: f32,
    /// The Phong highlight weight (`ks_spec`), separate from the reflection weight
    /// [`Material::ks`]: POV-Ray's `phong`.
    pub highlight: f32,
}

/// A whole scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub view: View,
    pub background: Rgb,
    pub lights: Vec<Light>,
    pub materials: Vec<Material>,
    pub spheres: Vec<Sphere>,
    pub cylinders: Vec<Cylinder>,
    pub cones: Vec<Cone>,
    pub polygons: Vec<Polygon>,
    pub patches: Vec<Patch>,
    /// Each material's [`SurfaceTerms`], by material index, where a generator gave
    /// them (the `spd` crate's scenes); empty for a scene read from an NFF file.
    pub surface_terms: Vec<Option<SurfaceTerms>>,
}

impl Scene {
    /// An empty scene with the given view and a black background.
    pub fn new(view: View) -> Self {
        Self {
            view,
            background: Rgb::BLACK,
            lights: Vec::new(),
            materials: Vec::new(),
            spheres: Vec::new(),
            cylinders: Vec::new(),
            cones: Vec::new(),
            polygons: Vec::new(),
            patches: Vec::new(),
            surface_terms: Vec::new(),
        }
    }

    /// Material `material`'s generator surface terms, if the scene has them.
    pub fn surface_terms(&self, material: usize) -> Option<SurfaceTerms> {
        self.surface_terms.get(material).copied().flatten()
    }

    /// Number of primitives of every kind.
    pub fn primitive_count(&self) -> usize {
        self.spheres.len()
            + self.cylinders.len()
            + self.cones.len()
            + self.polygons.len()
            + self.patches.len()
    }

    /// Bytes the parsed scene holds: its vectors and every polygon's and patch's
    /// vertex lists (what a render keeps in memory besides its structure and image).
    pub fn memory_bytes(&self) -> usize {
        fn vec_bytes<T>(v: &Vec<T>) -> usize {
            v.capacity() * std::mem::size_of::<T>()
        }
        let outlines: usize = self
            .polygons
            .iter()
            .map(|p| p.outline.heap_bytes())
            .chain(self.patches.iter().map(|p| {
                p.outline.heap_bytes() + vec_bytes(&p.normals) + vec_bytes(&p.written_normals)
            }))
            .sum();
        std::mem::size_of::<Self>()
            + vec_bytes(&self.lights)
            + vec_bytes(&self.materials)
            + vec_bytes(&self.spheres)
            + vec_bytes(&self.cylinders)
            + vec_bytes(&self.cones)
            + vec_bytes(&self.polygons)
            + vec_bytes(&self.patches)
            + outlines
    }

    /// The SPD intensity for lights given without a colour: `sqrt(n) / (2 n)` each for
    /// `n` lights, so that the sum over lights grows like `sqrt(n) / 2`.
    pub fn default_light_intensity(light_count: usize) -> f32 {
        let n = light_count.max(1) as f32;
        #[allow(clippy::disallowed_methods)] // scene set-up, not the counted render
        let root = n.sqrt();
        root / (2.0 * n)
    }

    /// A one-line summary such as `4200 spheres, 4200 cylinders, 1 polygon, 3 lights`.
    pub fn summary(&self) -> String {
        let mut parts = Vec::new();
        let mut add = |n: usize, one: &str, many: &str| {
            if n > 0 {
                parts.push(format!("{n} {}", if n == 1 { one } else { many }));
            }
        };
        add(self.spheres.len(), "sphere", "spheres");
        add(self.cylinders.len(), "cylinder", "cylinders");
        add(self.cones.len(), "cone", "cones");
        add(self.polygons.len(), "polygon", "polygons");
        add(self.patches.len(), "patch", "patches");
        add(self.lights.len(), "light", "lights");
        if parts.is_empty() {
            "empty scene".to_string()
        } else {
            parts.join(", ")
        }
    }
}

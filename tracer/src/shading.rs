//! Whitted shading under the SPD rules.
//!
//! Colour = ambient + Σ over lights reached by a shadow ray of (Lambert diffuse + Phong
//! highlight), + Ks × reflected colour + T × refracted colour, to depth 5 with the eye
//! ray at depth 1. Rules (the SPD rules; README.md, "SPD rules as implemented"), and
//! how they are read here:
//! - every surface is hit from both sides and shaded with its normal turned toward the
//!   incoming ray (a negative radius makes a quadric inside-only instead); NFF allows
//!   opaque one-sided surfaces but does not require them, and two-sided shading keeps
//!   open cylinders, the teapot's lid gap and transmitters correct;
//! - no shadow ray toward a light the (viewer-facing) normal faces away from, none on
//!   background; any primitive blocks a shadow ray, transmitters included;
//! - every hit on a reflective (Ks > 0) or transmitting (T > 0) surface below the
//!   maximum depth spawns a reflection ray; every hit on a transmitter spawns a
//!   refraction ray (Snell) unless at maximum depth or on total internal reflection,
//!   where the reflection ray carries the transmitted weight too (Ks + T).
//!
//! Phases: a hit's shading is `shading`; inside it the shadow rays' queries are
//! `shadow query` and the reflection and refraction rays' set-up is
//! `reflection/refraction set-up`, with the rays it traces (`closest hit`, their own
//! `shading`) nested inside, so the phase stack follows the ray tree.
//!
//! `ShadingMode::DiffuseOnly` is the thesis hardware's shading: the Lambert term of the
//! first light with both vectors normalized, ×255, background where N·L < 0, nothing else.
//!
//! With [`DiffuseForm::Squared`] (variant `no-rsqrt-shading`) the Lambert term of
//! spheres is the sqrt-free form of [`crate::variants::diffuse`].

use crate::accel::Intersector;
use crate::color::Rgb;
use crate::counter::{Counter, Phase, RayCounts, Stat};
use crate::ray::{Hit, PrimKind, Ray};
use crate::scene::{Light, Material, Scene};
use crate::variants::diffuse::{DiffuseForm, SpherePeaks};
use crate::vec3::Vec3;

mod packets;

/// How surfaces are shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ShadingMode {
    /// Full Whitted colour.
    #[default]
    Color,
    /// Full Whitted shading converted to gray (Rec. 601 luma).
    Gray,
    /// The thesis hardware's diffuse-only grayscale.
    DiffuseOnly,
}

/// What the shader records of the rays it traces: the SPD ray counts, and the deepest
/// ray-tree level reached (a maximum, so it is not one of the counts, which add up).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayLog {
    pub counts: RayCounts,
    /// Deepest level traced, the eye ray being 1 (0: nothing traced).
    pub deepest: u32,
}

impl RayLog {
    fn reached(&mut self, depth: u32) {
        self.deepest = self.deepest.max(depth);
    }

    /// Adds `other`'s counts and keeps the deeper of the two levels.
    pub fn merge(&mut self, other: &RayLog) {
        self.counts.merge(&other.counts);
        self.deepest = self.deepest.max(other.deepest);
    }
}

/// Maximum ray-tree depth; the eye ray is depth 1 (SPD rule 7).
pub const MAX_DEPTH: u32 = 5;

/// Ambient light intensity (NFF gives none; a dim white keeps unlit sides readable).
pub const AMBIENT: f32 = 0.1;

/// Secondary rays start this far (relative to the hit point's magnitude) off the
/// surface, so they do not hit it again through rounding.
const OFFSET_SCALE: f32 = 1e-4;

/// What the shader needs to know about a hit.
struct Surface {
    point: Vec3,
    /// Shading normal, on the incoming ray's side.
    normal: Vec3,
    /// Geometric normal, on the incoming ray's side (offsets and sidedness).
    facing: Vec3,
    /// Whether the ray hit the front (visible-side) face: entering a transmitter.
    front: bool,
    material: Material,
}

/// A hit being shaded: its surface, the colour so far, and where its shadow and
/// secondary rays start.
struct LitPoint {
    s: Surface,
    color: Rgb,
    /// The offset off the surface, toward the incoming ray.
    lift: Vec3,
    /// The point lifted off the surface: where reflection and shadow rays start.
    above: Vec3,
    reflective: bool,
    mirror: Option<Vec3>,
}

/// A shadow ray toward one light, with what the light's diffuse term needs.
struct ShadowRay {
    ray: Ray,
    /// Distance to the light: the ray's reach.
    distance: f32,
    /// `N · (light - point)`, unnormalized.
    n_dot: f32,
}

impl LitPoint {
    /// The shadow ray toward `light` (counted in `rays.shadow`), or `None` when the
    /// normal faces away from it (no ray, no light).
    fn shadow_ray<C: Counter>(
        &self,
        light: &Light,
        c: &mut C,
        rays: &mut RayLog,
    ) -> Option<ShadowRay> {
        let to_light = c.sub(light.position, self.s.point);
        let n_dot = c.dot(self.s.normal, to_light);
        if n_dot <= 0.0 {
            return None;
        }
        let distance_sq = c.dot(to_light, to_light);
        let distance = c.sqrt(distance_sq);
        let l = c.scale(to_light, 1.0 / distance);
        rays.counts.shadow += 1;
        Some(ShadowRay {
            ray: Ray {
                origin: self.above,
                dir: l,
            },
            distance,
            n_dot,
        })
    }
}

/// Traces rays through a scene with one intersector.
pub struct Shader<'s, I> {
    scene: &'s Scene,
    accel: &'s I,
    mode: ShadingMode,
    max_depth: u32,
    /// For [`DiffuseForm::Squared`]: each sphere's brightest point per light.
    peaks: Option<SpherePeaks>,
}

impl<'s, I: Intersector> Shader<'s, I> {
    /// A shader for `scene` using `accel` for its queries, Lambert diffuse.
    pub fn new(scene: &'s Scene, accel: &'s I, mode: ShadingMode) -> Self {
        Self::with_diffuse(scene, accel, mode, DiffuseForm::Lambert)
    }

    /// A shader with a chosen diffuse form for spheres. The squared form's peaks are
    /// computed here, once (uncounted preprocessing).
    pub fn with_diffuse(
        scene: &'s Scene,
        accel: &'s I,
        mode: ShadingMode,
        diffuse: DiffuseForm,
    ) -> Self {
        let peaks = (diffuse == DiffuseForm::Squared).then(|| SpherePeaks::new(scene));
        Self {
            scene,
            accel,
            mode,
            max_depth: MAX_DEPTH,
            peaks,
        }
    }

    /// The same shader with another maximum ray-tree depth (the eye ray is depth 1;
    /// [`crate::render()`] checks it against [`crate::Limits::max_ray_depth`]).
    pub fn with_max_depth(mut self, max_depth: u32) -> Self {
        self.max_depth = max_depth;
        self
    }

    /// The sample value of one eye ray (depth 1). Counts `rays.primary` and
    /// `rays.primary_hit`.
    pub fn primary<C: Counter>(&self, ray: &Ray, c: &mut C, rays: &mut RayLog) -> Rgb {
        rays.counts.primary += 1;
        rays.reached(1);
        c.tally(Stat::Trace);
        let hit = {
            let _phase = C::enter_phase(Phase::ClosestHit);
            self.accel.closest_hit(ray, 0.0, c)
        };
        self.primary_after(ray, hit, c, rays)
    }

    /// [`Shader::primary`] for an eye ray that starts at the origin (`bounded`).
    pub fn primary_from_eye<C: Counter>(
        &self,
        ray: &Ray<true>,
        c: &mut C,
        rays: &mut RayLog,
    ) -> Rgb {
        rays.counts.primary += 1;
        rays.reached(1);
        c.tally(Stat::Trace);
        let hit = {
            let _phase = C::enter_phase(Phase::ClosestHit);
            self.accel.closest_hit_from_eye(ray, c)
        };
        self.primary_after(&ray.plain(), hit, c, rays)
    }

    /// What a ray that hits nothing shows, in the shading mode's colours.
    fn background(&self) -> Rgb {
        match self.mode {
            ShadingMode::Color => self.scene.background,
            ShadingMode::Gray | ShadingMode::DiffuseOnly => {
                Rgb::gray(self.scene.background.luminance())
            }
        }
    }

    fn primary_after<C: Counter>(
        &self,
        ray: &Ray,
        hit: Option<Hit>,
        c: &mut C,
        rays: &mut RayLog,
    ) -> Rgb {
        let background = self.background();
        let Some(hit) = hit else {
            return background;
        };
        rays.counts.primary_hit += 1;
        match self.mode {
            ShadingMode::Color => self.shade(ray, &hit, 1, c, rays),
            ShadingMode::Gray => Rgb::gray(self.shade(ray, &hit, 1, c, rays).luminance()),
            ShadingMode::DiffuseOnly => self.diffuse_only(ray, &hit, c).unwrap_or(background),
        }
    }

    /// Colour seen along a secondary `ray` at tree depth `depth` (> 1).
    pub fn trace<C: Counter>(&self, ray: &Ray, depth: u32, c: &mut C, rays: &mut RayLog) -> Rgb {
        rays.reached(depth);
        c.tally(Stat::Trace);
        let hit = {
            let _phase = C::enter_phase(Phase::ClosestHit);
            self.accel.closest_hit(ray, 0.0, c)
        };
        let Some(hit) = hit else {
            return self.scene.background;
        };
        self.shade(ray, &hit, depth, c, rays)
    }

    /// The squared-form diffuse term of a sphere hit for light `light`, when the
    /// shader uses it.
    #[inline]
    fn sphere_diffuse<C: Counter>(
        &self,
        hit: &Hit,
        point: Vec3,
        light: usize,
        c: &mut C,
    ) -> Option<f32> {
        self.peaks
            .as_ref()?
            .cos_theta(self.scene, hit, point, light, c)
    }

    fn shade<C: Counter>(
        &self,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        c: &mut C,
        rays: &mut RayLog,
    ) -> Rgb {
        let _phase = C::enter_phase(Phase::Shading);
        let mut lit = self.lit_point(ray, hit, c);
        for (light_index, light) in self.scene.lights.iter().enumerate() {
            let Some(shadow) = lit.shadow_ray(light, c, rays) else {
                continue;
            };
            let blocked = {
                let _phase = C::enter_phase(Phase::ShadowQuery);
                self.accel.occluded(&shadow.ray, 0.0, shadow.distance, c)
            };
            if blocked {
                rays.counts.shadow_blocked += 1;
            } else {
                self.add_light(&mut lit, hit, light_index, &shadow, c);
            }
        }
        self.add_secondary(lit, ray, depth, c, rays)
    }

    /// The start of a hit's shading: the surface, the ambient term, the lifted point
    /// that secondary and shadow rays leave from, and the mirror direction. Inlined:
    /// called, it returned its 176 bytes through memory and a `memcpy` into the packet's
    /// array (4 % of a teapot render).
    #[inline(always)]
    fn lit_point<C: Counter>(&self, ray: &Ray, hit: &Hit, c: &mut C) -> LitPoint {
        c.tally(Stat::Shade);
        let s = self.surface(ray, hit, c);
        let m = s.material;
        let color = m.color * (AMBIENT * m.kd);
        let offset = OFFSET_SCALE * (1.0 + s.point.max_abs());
        let lift = c.scale(s.facing, offset);
        let above = c.add(s.point, lift);
        let reflective = m.ks > 0.0 || m.t > 0.0;
        // The mirror direction serves both the highlight and the reflection ray.
        let mirror = reflective.then(|| {
            let _phase = C::enter_phase(Phase::SecondaryRays);
            reflect(ray.dir, s.normal, c)
        });
        LitPoint {
            s,
            color,
            lift,
            above,
            reflective,
            mirror,
        }
    }

    /// Adds the diffuse and highlight terms of an unblocked light.
    fn add_light<C: Counter>(
        &self,
        lit: &mut LitPoint,
        hit: &Hit,
        light_index: usize,
        shadow: &ShadowRay,
        c: &mut C,
    ) {
        let light = &self.scene.lights[light_index];
        let cos_theta = match self.sphere_diffuse(hit, lit.s.point, light_index, c) {
            Some(cos_theta) => cos_theta.max(0.0),
            None => shadow.n_dot / shadow.distance,
        };
        lit.color += color_contribution(
            &lit.s.material,
            light,
            cos_theta,
            lit.mirror,
            shadow.ray.dir,
            c,
        );
    }

    /// The end of a hit's shading: the reflected and refracted rays below the maximum
    /// depth, added to the colour.
    fn add_secondary<C: Counter>(
        &self,
        lit: LitPoint,
        ray: &Ray,
        depth: u32,
        c: &mut C,
        rays: &mut RayLog,
    ) -> Rgb {
        let LitPoint {
            s,
            mut color,
            lift,
            above,
            reflective,
            mirror,
        } = lit;
        let m = s.material;
        if depth < self.max_depth && reflective {
            // The secondary rays' set-up; the rays they trace nest inside.
            let _phase = C::enter_phase(Phase::SecondaryRays);
            let mut reflect_weight = m.ks;
            if m.t > 0.0 {
                let eta = if s.front { 1.0 / m.ior } else { m.ior };
                match refract(ray.dir, s.normal, eta, c) {
                    Some(dir) => {
                        rays.counts.refraction += 1;
                        let below = c.sub(s.point, lift);
                        let refracted = self.trace(&Ray { origin: below, dir }, depth + 1, c, rays);
                        color += refracted * m.t;
                    }
                    // Total internal reflection: the transmitted light is reflected.
                    None => reflect_weight += m.t,
                }
            }
            if let Some(dir) = mirror {
                rays.counts.reflection += 1;
                let reflected = self.trace(&Ray { origin: above, dir }, depth + 1, c, rays);
                color += reflected * reflect_weight;
            }
        }
        color
    }

    /// The thesis hardware's shading of one eye ray's hit; `None` shows background.
    #[inline]
    fn diffuse_only<C: Counter>(&self, ray: &Ray, hit: &Hit, c: &mut C) -> Option<Rgb> {
        let _phase = C::enter_phase(Phase::Shading);
        c.tally(Stat::Shade);
        let light = self.scene.lights.first()?;
        let along = c.scale(ray.dir, hit.t);
        let point = c.add(ray.origin, along);
        let lambert = match self.sphere_diffuse(hit, point, 0, c) {
            Some(cos_theta) => cos_theta,
            None => {
                // The hardware's normal: the primitive's own (outward) normal, never
                // turned toward the viewer.
                let (normal, _) = self.normals(hit, point, c);
                let to_light = c.sub(light.position, point);
                let l = c.normalize(to_light);
                c.dot(normal, l)
            }
        };
        (lambert >= 0.0).then(|| Rgb::gray(lambert))
    }

    /// The visible side's shading and geometric normals at `point`.
    fn normals<C: Counter>(&self, hit: &Hit, point: Vec3, c: &mut C) -> (Vec3, Vec3) {
        let s = self.scene;
        let i = hit.prim.index as usize;
        match hit.prim.kind {
            PrimKind::Sphere => {
                let n = s.spheres[i].normal(point, c);
                (n, n)
            }
            PrimKind::Cylinder => {
                let n = s.cylinders[i].normal(point, hit.aux, c);
                (n, n)
            }
            PrimKind::Cone => {
                let n = s.cones[i].normal(point, hit.aux, c);
                (n, n)
            }
            PrimKind::Polygon => {
                let n = s.polygons[i].normal();
                (n, n)
            }
            PrimKind::Patch => {
                let patch = &s.patches[i];
                (patch.shading_normal(point, c), patch.outline.normal)
            }
        }
    }

    fn material_of(&self, hit: &Hit) -> Material {
        let s = self.scene;
        let i = hit.prim.index as usize;
        let index = match hit.prim.kind {
            PrimKind::Sphere => s.spheres[i].material,
            PrimKind::Cylinder => s.cylinders[i].material,
            PrimKind::Cone => s.cones[i].material,
            PrimKind::Polygon => s.polygons[i].material,
            PrimKind::Patch => s.patches[i].material,
        };
        s.materials.get(index as usize).copied().unwrap_or_default()
    }

    /// The hit body: point, normals turned toward the ray, material.
    fn surface<C: Counter>(&self, ray: &Ray, hit: &Hit, c: &mut C) -> Surface {
        let along = c.scale(ray.dir, hit.t);
        let point = c.add(ray.origin, along);
        let (mut normal, mut facing) = self.normals(hit, point, c);
        // A hit point that rounds onto a sphere's centre or a cylinder's or cone's axis
        // (a radius below the f32 spacing of the coordinates, or a cone's tip) has no
        // radial direction, and normalizing the zero vector gives NaN. Such a point
        // shows no orientation at any resolution: shade it as facing the ray.
        // (Polygon and patch planes are unit vectors checked when they are built.)
        if !facing.is_finite() || !normal.is_finite() {
            facing = ray.dir.flipped();
            normal = facing;
        }
        let front = c.dot(facing, ray.dir) < 0.0;
        if !front {
            facing = facing.flipped();
        }
        // Keep an interpolated normal in the facing hemisphere (it equals `facing`
        // for every primitive but patches).
        if hit.prim.kind == PrimKind::Patch {
            if c.dot(normal, facing) < 0.0 {
                normal = normal.flipped();
            }
        } else {
            normal = facing;
        }
        Surface {
            point,
            normal,
            facing,
            front,
            material: self.material_of(hit),
        }
    }
}

/// Diffuse and highlight from one unblocked light (`cos_theta` = N·L > 0).
fn color_contribution<C: Counter>(
    m: &Material,
    light: &Light,
    cos_theta: f32,
    mirror: Option<Vec3>,
    l: Vec3,
    c: &mut C,
) -> Rgb {
    c.tally(Stat::ColorContribution);
    let mut color = m.color * light.color * (m.kd * cos_theta);
    // Phong highlight (R·V)^shine, with R·V computed as (mirrored view)·L.
    if let (Some(mirror), true) = (mirror, m.ks > 0.0) {
        let cos_alpha = c.dot(mirror, l);
        if cos_alpha > 0.0 {
            // Unit vectors give cos ≤ 1, but the approximate square roots can leave it a
            // few per cent above, where SPD's exponent 100000 would overflow to infinity.
            color += light.color * (m.ks * c.pow(cos_alpha.min(1.0), m.shine));
        }
    }
    color
}

/// Mirror direction of `dir` about `normal`: `D - 2 (D·N) N`.
#[inline]
pub fn reflect<C: Counter>(dir: Vec3, normal: Vec3, c: &mut C) -> Vec3 {
    let d_n = c.dot(dir, normal);
    let twice_projection = c.scale(normal, 2.0 * d_n);
    c.sub(dir, twice_projection)
}

/// Refracted direction by Snell's law for relative index `eta` = n1 / n2, with `normal`
/// on the incoming side; `None` on total internal reflection.
#[inline]
pub fn refract<C: Counter>(dir: Vec3, normal: Vec3, eta: f32, c: &mut C) -> Option<Vec3> {
    let cos_i = -c.dot(dir, normal);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return None;
    }
    let cos_t = c.sqrt(k);
    let tangential = c.scale(dir, eta);
    let normal_part = c.scale(normal, eta * cos_i - cos_t);
    Some(c.add(tangential, normal_part))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::NoCount;

    fn close(a: Vec3, b: [f32; 3]) -> bool {
        a.to_array()
            .iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() < 1e-5)
    }

    #[test]
    fn snell_refraction_matches_hand_computation() {
        // 45° incidence from air (n = 1) into glass (n = 1.5): sin t = sin 45° / 1.5.
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let dir = Vec3::new(h, -h, 0.0);
        let normal = Vec3::new(0.0, 1.0, 0.0);
        let t = refract(dir, normal, 1.0 / 1.5, &mut NoCount).unwrap_or(Vec3::ZERO);
        let sin_t = h / 1.5;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        assert!(close(t, [sin_t, -cos_t, 0.0]), "{t:?}");
        // Normal incidence passes straight through.
        let straight = refract(Vec3::new(0.0, -1.0, 0.0), normal, 1.0 / 1.5, &mut NoCount);
        assert!(close(straight.unwrap_or(Vec3::ZERO), [0.0, -1.0, 0.0]));
    }

    #[test]
    fn total_internal_reflection_beyond_the_critical_angle() {
        // From glass to air the critical angle is asin(1/1.5) = 41.8°; at 45° there is
        // no refracted ray, at 30° there is one.
        let normal = Vec3::new(0.0, 1.0, 0.0);
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert_eq!(
            refract(Vec3::new(h, -h, 0.0), normal, 1.5, &mut NoCount),
            None
        );
        let (s, co) = (0.5f32, 0.75f32.sqrt());
        let t = refract(Vec3::new(s, -co, 0.0), normal, 1.5, &mut NoCount);
        assert!(close(
            t.unwrap_or(Vec3::ZERO),
            [0.75, -(1.0f32 - 0.5625).sqrt(), 0.0]
        ));
    }

    #[test]
    fn highlight_of_slightly_long_vectors_stays_finite_at_spd_exponents() {
        // An approximate root that underestimates (fast-sqrt-tuned) leaves "unit" vectors
        // a few per cent too long: aligned, their dot is 1.03² ≈ 1.06, and 1.06^100000
        // overflows. With the cosine clamped the highlight is that of aligned unit
        // vectors: Ks × light colour.
        let m = Material {
            color: Rgb::BLACK,
            kd: 0.0,
            ks: 0.5,
            shine: 100_000.0,
            t: 0.0,
            ior: 1.0,
        };
        let light = Light {
            position: Vec3::ZERO,
            color: Rgb::new(0.2, 0.4, 0.8),
            color_given: true,
        };
        let long = Vec3::new(0.0, 1.03, 0.0);
        let got = color_contribution(&m, &light, 1.0, Some(long), long, &mut NoCount);
        assert_eq!(got, Rgb::new(0.1, 0.2, 0.4));
    }

    #[test]
    fn reflection_mirrors_about_the_normal() {
        let r = reflect(
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            &mut NoCount,
        );
        assert_eq!(r.to_array(), [1.0, 1.0, 0.0]);
    }
}

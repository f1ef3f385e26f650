//! Shading in packets (variant `packets`): neighbouring eye rays go to the intersector
//! together, and so do the rays their hits spawn, level by level of the ray tree: each
//! light's shadow rays of a packet as one shadow packet, the packet's refraction rays as
//! one packet and its reflection rays as another, each shaded as a packet in turn (as
//! Embree's users trace them, and as the Embree yardstick does).
//!
//! Each ray's colour is the one [`Shader::shade`] gives it alone, bit for bit: a packet
//! finds each ray's own closest hit and blockers, and every ray's terms are added in the
//! scalar order (local terms, then the refracted colour × T, then the reflected colour
//! × its weight). Counts and ray logs are each ray's own, in the same phases; only the
//! order in which the rays of a tree are traced differs (a level at a time instead of
//! depth first), which no count depends on.

use super::{LitPoint, RayLog, Shader, ShadingMode, ShadowRay, refract};
use crate::accel::{Intersector, PACKET};
use crate::color::Rgb;
use crate::counter::{Counter, Phase, Stat};
use crate::ray::{Hit, Ray};

/// The rays one packet level spawns toward the next (refraction or reflection): each
/// ray with the lane of the packet it came from and the weight its colour is added with.
struct Spawned {
    rays: [Ray; PACKET],
    from: [usize; PACKET],
    weight: [f32; PACKET],
    len: usize,
}

impl Spawned {
    /// Inlined, so built in place (returned, it was a `memcpy` each).
    #[inline(always)]
    fn new(fill: Ray) -> Self {
        Spawned {
            rays: [fill; PACKET],
            from: [0; PACKET],
            weight: [0.0; PACKET],
            len: 0,
        }
    }

    fn push(&mut self, ray: Ray, from: usize) {
        self.rays[self.len] = ray;
        self.from[self.len] = from;
        self.len += 1;
    }
}

impl<I: Intersector> Shader<'_, I> {
    /// The sample values of a packet of eye rays traced together (variant `packets`):
    /// `out[i]` for `rays[i]`, each ray's work counted on `counters[i]` and `logs[i]`
    /// as [`Shader::primary`] counts it.
    pub fn primaries<C: Counter>(
        &self,
        rays: &[Ray],
        counters: &mut [C],
        logs: &mut [RayLog],
        out: &mut [Rgb],
    ) {
        self.packet(rays, counters, logs, out, |hits, cs| {
            self.accel.closest_hits(rays, hits, cs)
        });
    }

    /// [`Shader::primaries`] for eye rays that start at the origin (`bounded`).
    pub fn primaries_from_eye<C: Counter>(
        &self,
        rays: &[Ray<true>],
        counters: &mut [C],
        logs: &mut [RayLog],
        out: &mut [Rgb],
    ) {
        self.packet(rays, counters, logs, out, |hits, cs| {
            self.accel.closest_hits_from_eye(rays, hits, cs)
        });
    }

    fn packet<C: Counter, const FROM_EYE: bool>(
        &self,
        rays: &[Ray<FROM_EYE>],
        counters: &mut [C],
        logs: &mut [RayLog],
        out: &mut [Rgb],
        query: impl FnOnce(&mut [Option<Hit>], &mut [C]),
    ) {
        let n = rays.len().min(PACKET);
        for (c, log) in counters.iter_mut().zip(logs.iter_mut()).take(n) {
            log.counts.primary += 1;
            log.reached(1);
            c.tally(Stat::Trace);
        }
        let mut hits = [None; PACKET];
        {
            let _phase = C::enter_phase(Phase::ClosestHit);
            query(&mut hits[..n], &mut counters[..n]);
        }
        if self.mode == ShadingMode::DiffuseOnly {
            // Inline, the background once per packet: a call per ray returning its
            // colour through memory stalled on the reload (47 % of the row loop's own
            // samples on tetra).
            let background = self.background();
            for i in 0..n {
                out[i] = match &hits[i] {
                    None => background,
                    Some(hit) => {
                        logs[i].counts.primary_hit += 1;
                        self.diffuse_only(&rays[i].plain(), hit, &mut counters[i])
                            .unwrap_or(background)
                    }
                };
            }
        } else {
            let plain: [Ray; PACKET] = std::array::from_fn(|i| rays[i.min(n - 1)].plain());
            self.shade_packet(&plain[..n], &hits[..n], 1, counters, logs, out);
        }
    }

    /// The colours of a packet of secondary rays at tree depth `depth` (> 1), as
    /// [`Shader::trace`] gives each alone.
    fn trace_packet<C: Counter>(
        &self,
        rays: &[Ray],
        depth: u32,
        counters: &mut [C],
        logs: &mut [RayLog],
        out: &mut [Rgb],
    ) {
        let n = rays.len().min(PACKET);
        for (c, log) in counters.iter_mut().zip(logs.iter_mut()).take(n) {
            log.reached(depth);
            c.tally(Stat::Trace);
        }
        let mut hits = [None; PACKET];
        {
            let _phase = C::enter_phase(Phase::ClosestHit);
            self.accel
                .closest_hits(&rays[..n], &mut hits[..n], &mut counters[..n]);
        }
        self.shade_packet(&rays[..n], &hits[..n], depth, counters, logs, out);
    }

    /// [`Shader::shade`] for a packet of hits at depth `depth` (a miss shows the
    /// background): each light's shadow rays go to the intersector as one packet (they
    /// leave neighbouring points for one light), then the refraction rays and the
    /// reflection rays as a packet each.
    fn shade_packet<C: Counter>(
        &self,
        rays: &[Ray],
        hits: &[Option<Hit>],
        depth: u32,
        counters: &mut [C],
        logs: &mut [RayLog],
        out: &mut [Rgb],
    ) {
        let n = hits.len().min(rays.len());
        if n == 0 {
            return;
        }
        let _phase = C::enter_phase(Phase::Shading);
        if hits[..n].iter().all(Option::is_none) {
            // All missed (most of an open scene's eye packets): no light or secondary
            // packet to set up.
            out[..n].fill(self.miss_colour(depth));
            return;
        }
        let mut lit: [Option<LitPoint>; PACKET] = std::array::from_fn(|_| None);
        for i in 0..n {
            match &hits[i] {
                None => out[i] = self.miss_colour(depth),
                Some(hit) => {
                    if depth == 1 {
                        logs[i].counts.primary_hit += 1;
                    }
                    lit[i] = Some(self.lit_point(&rays[i], hit, &mut counters[i]));
                }
            }
        }
        self.lights_packet(rays, hits, &mut lit[..n], counters, logs);
        let mut color: [Rgb; PACKET] = std::array::from_fn(|i| match &lit[i] {
            Some(point) => point.color,
            None => Rgb::BLACK,
        });
        if depth < self.max_depth {
            self.secondary_packet(rays, &lit[..n], depth, counters, logs, &mut color);
        }
        for i in 0..n {
            if lit[i].is_some() {
                out[i] = match self.mode {
                    ShadingMode::Gray if depth == 1 => Rgb::gray(color[i].luminance()),
                    _ => color[i],
                };
            }
        }
    }

    /// What a ray at tree depth `depth` that hits nothing shows: the eye ray's
    /// background is in the shading mode's colours; a secondary ray's is the scene's,
    /// its luminance taken with the whole sample's.
    fn miss_colour(&self, depth: u32) -> Rgb {
        if depth == 1 {
            self.background()
        } else {
            self.scene.background
        }
    }

    /// Each light's shadow rays from the packet's lit points, as one shadow packet per
    /// light; the unblocked lights' terms added to the points.
    fn lights_packet<C: Counter>(
        &self,
        rays: &[Ray],
        hits: &[Option<Hit>],
        lit: &mut [Option<LitPoint>],
        counters: &mut [C],
        logs: &mut [RayLog],
    ) {
        let Some(&fill) = rays.first() else {
            return;
        };
        for (light_index, light) in self.scene.lights.iter().enumerate() {
            // The packet's shadow rays toward this light, gathered with their counters.
            let mut shadows: [Option<ShadowRay>; PACKET] = std::array::from_fn(|_| None);
            let mut from = [0usize; PACKET];
            let mut shadow_rays = [fill; PACKET];
            let mut reach = [0.0f32; PACKET];
            let mut shadow_counters: [C; PACKET] = Default::default();
            let mut k = 0;
            for (i, point) in lit.iter().enumerate() {
                let Some(point) = point else { continue };
                let Some(shadow) = point.shadow_ray(light, &mut counters[i], &mut logs[i]) else {
                    continue;
                };
                shadow_rays[k] = shadow.ray;
                reach[k] = shadow.distance;
                from[k] = i;
                shadow_counters[k] = std::mem::take(&mut counters[i]);
                shadows[i] = Some(shadow);
                k += 1;
            }
            if k == 0 {
                continue;
            }
            let mut blocked = [false; PACKET];
            {
                let _phase = C::enter_phase(Phase::ShadowQuery);
                self.accel.occluded_packet(
                    &shadow_rays[..k],
                    &reach[..k],
                    &mut blocked[..k],
                    &mut shadow_counters[..k],
                );
            }
            for j in 0..k {
                let i = from[j];
                counters[i] = std::mem::take(&mut shadow_counters[j]);
                if blocked[j] {
                    logs[i].counts.shadow_blocked += 1;
                } else if let (Some(point), Some(shadow), Some(hit)) =
                    (&mut lit[i], &shadows[i], &hits[i])
                {
                    self.add_light(point, hit, light_index, shadow, &mut counters[i]);
                }
            }
        }
    }

    /// [`Shader::add_secondary`] for a packet below the maximum depth: the refraction
    /// rays traced as one packet, then the reflection rays, their colours added to
    /// `color` in that order with their weights.
    fn secondary_packet<C: Counter>(
        &self,
        rays: &[Ray],
        lit: &[Option<LitPoint>],
        depth: u32,
        counters: &mut [C],
        logs: &mut [RayLog],
        color: &mut [Rgb; PACKET],
    ) {
        let Some(&fill) = rays.first() else {
            return;
        };
        if !lit.iter().flatten().any(|p| p.reflective) {
            return;
        }
        // The secondary rays' set-up; the rays they trace nest inside.
        let _phase = C::enter_phase(Phase::SecondaryRays);
        let mut refracted = Spawned::new(fill);
        let mut reflected = Spawned::new(fill);
        for (i, point) in lit.iter().enumerate() {
            let Some(point) = point.as_ref().filter(|p| p.reflective) else {
                continue;
            };
            let (s, c) = (&point.s, &mut counters[i]);
            let m = s.material;
            let mut reflect_weight = m.ks;
            if m.t > 0.0 {
                let eta = if s.front { 1.0 / m.ior } else { m.ior };
                match refract(rays[i].dir, s.normal, eta, c) {
                    Some(dir) => {
                        logs[i].counts.refraction += 1;
                        let below = c.sub(s.point, point.lift);
                        refracted.weight[refracted.len] = m.t;
                        refracted.push(Ray { origin: below, dir }, i);
                    }
                    // Total internal reflection: the transmitted light is reflected.
                    None => reflect_weight += m.t,
                }
            }
            if let Some(dir) = point.mirror {
                logs[i].counts.reflection += 1;
                reflected.weight[reflected.len] = reflect_weight;
                reflected.push(
                    Ray {
                        origin: point.above,
                        dir,
                    },
                    i,
                );
            }
        }
        for spawned in [&refracted, &reflected] {
            let k = spawned.len;
            if k == 0 {
                continue;
            }
            // The spawning rays' counters and logs go with their rays, and come back.
            let mut cs: [C; PACKET] = Default::default();
            let mut ls = [RayLog::default(); PACKET];
            for j in 0..k {
                cs[j] = std::mem::take(&mut counters[spawned.from[j]]);
                ls[j] = std::mem::take(&mut logs[spawned.from[j]]);
            }
            let mut seen = [Rgb::BLACK; PACKET];
            self.trace_packet(&spawned.rays[..k], depth + 1, &mut cs, &mut ls, &mut seen);
            for j in 0..k {
                let i = spawned.from[j];
                counters[i] = std::mem::take(&mut cs[j]);
                logs[i] = ls[j];
                color[i] += seen[j] * spawned.weight[j];
            }
        }
    }
}

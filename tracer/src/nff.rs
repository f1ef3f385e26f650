//! NFF (Neutral File Format 3.x) parser.
//!
//! The format is line-oriented: one entity per keyword line, `c` followed by two lines
//! (base, apex), `p n` / `pp n` followed by `n` vertex lines; `#` starts a comment.
//! Blank lines, tabs and CRLF line ends are accepted anywhere. Every malformed input
//! becomes an [`NffError`] naming the file, the line and what was expected; sizes that
//! would need absurd allocations are refused by [`Limits`] before anything is allocated.

use crate::color::Rgb;
use crate::counter::{Counter, NoCount};
use crate::huge_pages;
use crate::primitives::{Cone, Cylinder, GeometryError, Patch, Polygon, Sphere};
use crate::scene::{Light, Material, Scene, View};
use crate::vec3::Vec3;
use std::io::Read as _;
use std::path::Path;

mod limits;
pub use limits::{Limit, LimitError, Limits};

/// A parse error at a place in a file.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct NffError {
    pub file: String,
    /// 1-based line number (the last line with content for errors found at the end of
    /// the file).
    pub line: usize,
    pub message: String,
    /// The limit the file exceeded, when that is the error.
    pub limit: Option<Limit>,
}

/// Why a scene file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error("cannot read {path}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error(
        "{path} is {bytes} bytes, over the limit of {limit} bytes for a scene file {}",
        Limit::MaxFileBytes.hint()
    )]
    TooLarge {
        path: String,
        bytes: u64,
        limit: u64,
    },
    #[error(transparent)]
    Parse(#[from] NffError),
}

impl LoadError {
    /// The limit the file exceeded, when that is the error.
    pub fn limit(&self) -> Option<Limit> {
        match self {
            LoadError::Io { .. } => None,
            LoadError::TooLarge { .. } => Some(Limit::MaxFileBytes),
            LoadError::Parse(e) => e.limit,
        }
    }
}

/// Reads and parses an NFF file with the default limits.
pub fn load_nff(path: &Path) -> Result<Scene, LoadError> {
    load_nff_with_limits(path, &Limits::default())
}

/// Reads and parses an NFF file, refusing a file larger than `limits.max_file_bytes`
/// before reading it (and sizes beyond the other limits while parsing).
pub fn load_nff_with_limits(path: &Path, limits: &Limits) -> Result<Scene, LoadError> {
    let name = path.display().to_string();
    let io = |source| LoadError::Io {
        path: name.clone(),
        source,
    };
    let too_large = |bytes: u64| LoadError::TooLarge {
        path: name.clone(),
        bytes,
        limit: limits.max_file_bytes,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let length = file.metadata().map_err(io)?.len();
    if limits.check_file_size(length).is_err() {
        return Err(too_large(length));
    }
    // The metadata may understate (pipes, /proc): read at most one byte past the limit.
    let mut bytes = Vec::with_capacity(usize::try_from(length).unwrap_or(0));
    file.take(limits.max_file_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if limits.check_file_size(bytes.len() as u64).is_err() {
        return Err(too_large(bytes.len() as u64));
    }
    let text = match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let line = 1 + e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count();
            return Err(NffError {
                file: name,
                line,
                message: "not a text file (invalid UTF-8); NFF scenes are plain ASCII".into(),
                limit: None,
            }
            .into());
        }
    };
    Ok(parse_nff_with_limits(&text, &name, limits)?)
}

/// Parses NFF text with the default limits; `file` names the source in errors.
pub fn parse_nff(text: &str, file: &str) -> Result<Scene, NffError> {
    parse_nff_with_limits(text, file, &Limits::default())
}

/// Parses NFF text, refusing sizes beyond `limits`.
pub fn parse_nff_with_limits(text: &str, file: &str, limits: &Limits) -> Result<Scene, NffError> {
    if let Err(e) = limits.check_file_size(text.len() as u64) {
        return Err(NffError {
            file: file.to_string(),
            line: 1,
            message: format!("the scene text is {e}"),
            limit: e.limit,
        });
    }
    Parser {
        lines: text.split('\n').enumerate().peekable(),
        file,
        limits,
        last_line: 1,
        primitives: 0,
    }
    .parse()
}

/// A number for an error message: plain where that is short, in exponent form for very
/// large or small magnitudes (`1e19`, not twenty digits).
fn shown(v: f32) -> String {
    if v == 0.0 || (1e-3..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The entity keywords, for the unknown-keyword message.
const KEYWORDS: &str = "v, b, l, f, c, s, p, pp";

/// Largest accepted magnitude of a coordinate, radius or direction component. f32 keeps
/// about seven significant digits, so no scene that renders with visible detail comes
/// near it (the SPD scenes stay below 150). Within it every product the tracer forms stays
/// finite: a difference of two points is at most 2·√3·1e9 ≈ 3.5e9 long, its square
/// 1.2e19, and the fourth-degree terms of the polygon and view checks at most 1.4e38,
/// below f32::MAX (3.4e38). Beyond it, a light and a hit point far enough apart make
/// `light - point` overflow to infinity and the shading NaN.
pub const MAX_COORDINATE: f32 = 1e9;

/// Accepted index of refraction of a transmitting material (real materials lie between
/// 1 and 4). Snell's law computes the refracted direction as `eta (D + cos_i N) - cos_t N`,
/// which scales the rounding error of `D + cos_i N` by the relative index `eta`: its
/// length is off by up to 2e-6 at `eta` = 100, but by 1e14 at 5e18 (measured near normal
/// incidence), and the intersection tests, which rely on unit directions, then reported
/// hits whose shading was NaN or infinite.
pub const IOR_RANGE: (f32, f32) = (0.01, 100.0);

/// Largest accepted colour channel, light intensity, Kd, Ks or T. NFF colours and
/// coefficients lie in [0, 1]; the margin admits over-bright lights while keeping the
/// ray tree's products (at most nine such factors down to depth 5) far from f32 overflow,
/// so a finite scene never renders an infinite pixel.
pub const MAX_COEFFICIENT: f32 = 1000.0;

struct Parser<'a> {
    lines: std::iter::Peekable<std::iter::Enumerate<std::str::Split<'a, char>>>,
    file: &'a str,
    limits: &'a Limits,
    last_line: usize,
    /// Primitives parsed so far (for `Limits::max_primitives`).
    primitives: u64,
}

/// One significant line: its number and its tokens (comments removed).
struct Line<'a> {
    number: usize,
    tokens: Vec<&'a str>,
}

fn tokens(raw: &str) -> Vec<&str> {
    let code = raw.split('#').next().unwrap_or("");
    code.split_whitespace().collect()
}

impl<'a> Parser<'a> {
    fn error(&self, line: usize, message: impl Into<String>) -> NffError {
        NffError {
            file: self.file.to_string(),
            line,
            message: message.into(),
            limit: None,
        }
    }

    /// The error of a size over `limit` (its hint ends the message).
    fn over_limit(&self, line: usize, limit: Limit, message: String) -> NffError {
        NffError {
            limit: Some(limit),
            ..self.error(line, format!("{message} {}", limit.hint()))
        }
    }

    /// The next line with at least one token.
    fn next_line(&mut self) -> Option<Line<'a>> {
        for (index, raw) in self.lines.by_ref() {
            let tokens = tokens(raw);
            if !tokens.is_empty() {
                self.last_line = index + 1;
                return Some(Line {
                    number: index + 1,
                    tokens,
                });
            }
        }
        None
    }

    /// The first token of the next significant line, without consuming it.
    fn peek_keyword(&mut self) -> Option<&'a str> {
        while let Some((_, raw)) = self.lines.peek() {
            if let Some(first) = tokens(raw).first() {
                return Some(first);
            }
            self.lines.next();
        }
        None
    }

    /// A continuation line that must exist (vertex lines, cone ends).
    fn required_line(&mut self, what: &str) -> Result<Line<'a>, NffError> {
        self.next_line().ok_or_else(|| {
            self.error(
                self.last_line,
                format!("unexpected end of file: expected {what}"),
            )
        })
    }

    fn number(&self, line: usize, token: &str, what: &str) -> Result<f32, NffError> {
        let value: f32 = token.parse().map_err(|_| {
            self.error(line, format!("'{token}' is not a number (expected {what})"))
        })?;
        if !value.is_finite() {
            return Err(self.error(
                line,
                format!("'{token}' is not a finite number (expected {what})"),
            ));
        }
        Ok(value)
    }

    /// Exactly `N` numbers in `tokens`.
    fn numbers<const N: usize>(
        &self,
        line: usize,
        tokens: &[&str],
        what: &str,
    ) -> Result<[f32; N], NffError> {
        if tokens.len() != N {
            return Err(self.error(
                line,
                format!(
                    "expected {N} numbers ({what}), found {} values",
                    tokens.len()
                ),
            ));
        }
        let mut out = [0.0; N];
        for (slot, token) in out.iter_mut().zip(tokens) {
            *slot = self.number(line, token, what)?;
        }
        Ok(out)
    }

    /// Counts one more primitive, refused (on its keyword line, before its data is read)
    /// beyond `Limits::max_primitives`.
    fn count_primitive(&mut self, line: usize) -> Result<(), NffError> {
        if self.primitives >= self.limits.max_primitives {
            return Err(self.over_limit(
                line,
                Limit::MaxPrimitives,
                format!(
                    "too many primitives: the scene exceeds the limit of {} primitives",
                    self.limits.max_primitives
                ),
            ));
        }
        self.primitives += 1;
        Ok(())
    }

    /// Exactly `N` numbers in `tokens`, each a coordinate (see [`MAX_COORDINATE`]).
    fn coordinates<const N: usize>(
        &self,
        line: usize,
        tokens: &[&str],
        what: &str,
    ) -> Result<[f32; N], NffError> {
        let values = self.numbers::<N>(line, tokens, what)?;
        if let Some(v) = values.iter().find(|v| !(v.abs() <= MAX_COORDINATE)) {
            return Err(self.error(
                line,
                format!(
                    "{} is beyond the supported coordinate range ±{} (expected {what})",
                    shown(*v),
                    shown(MAX_COORDINATE)
                ),
            ));
        }
        Ok(values)
    }

    /// Checks a colour channel or shading coefficient against `[0, MAX_COEFFICIENT]`.
    fn coefficient(&self, line: usize, value: f32, what: &str) -> Result<f32, NffError> {
        if !(0.0..=MAX_COEFFICIENT).contains(&value) {
            return Err(self.error(
                line,
                format!(
                    "{what} {} must lie between 0 and {MAX_COEFFICIENT}",
                    shown(value)
                ),
            ));
        }
        Ok(value)
    }

    /// An RGB triple whose channels are coefficients (see [`Parser::coefficient`]).
    fn color(&self, line: usize, [r, g, b]: [f32; 3], what: &str) -> Result<Rgb, NffError> {
        let channel = |v: f32| self.coefficient(line, v, what);
        Ok(Rgb::new(channel(r)?, channel(g)?, channel(b)?))
    }

    fn geometry(&self, line: usize, what: &str, e: GeometryError) -> NffError {
        self.error(line, format!("invalid {what}: {e}"))
    }

    fn parse(mut self) -> Result<Scene, NffError> {
        let mut view: Option<(usize, View)> = None;
        let mut background = Rgb::BLACK;
        let mut lights: Vec<Light> = Vec::new();
        let mut materials: Vec<Material> = Vec::new();
        let mut scene_parts = ScenePrimitives::default();

        while let Some(line) = self.next_line() {
            let n = line.number;
            let args = &line.tokens[1..];
            // The material of the next primitive: the last `f`, or the default one.
            let current_material = |materials: &mut Vec<Material>| {
                if materials.is_empty() {
                    materials.push(Material::default());
                }
                (materials.len() - 1) as u32
            };
            match line.tokens[0] {
                "v" => {
                    if let Some((first, _)) = view {
                        return Err(self.error(
                            n,
                            format!("second view block (the first is at line {first})"),
                        ));
                    }
                    if !args.is_empty() {
                        return Err(self.error(
                            n,
                            "unexpected text after 'v' (the view block starts on its own line)",
                        ));
                    }
                    view = Some((n, self.view_block(n)?));
                }
                "b" => {
                    let rgb = self.numbers(n, args, "background colour r g b")?;
                    background = self.color(n, rgb, "background colour channel")?;
                }
                "l" => {
                    let (position, color) = match args.len() {
                        3 => (
                            self.coordinates::<3>(n, args, "light position x y z")?,
                            None,
                        ),
                        6 => {
                            let position =
                                self.coordinates::<3>(n, &args[..3], "light position x y z")?;
                            let rgb = self.numbers::<3>(n, &args[3..], "light colour r g b")?;
                            (position, Some(self.color(n, rgb, "light colour channel")?))
                        }
                        found => {
                            return Err(self.error(
                                n,
                                format!("expected 3 numbers (light x y z) or 6 (x y z r g b), found {found} values"),
                            ));
                        }
                    };
                    lights.push(Light {
                        position: Vec3::from_array(position),
                        color: color.unwrap_or(Rgb::WHITE),
                        color_given: color.is_some(),
                    });
                }
                "f" => {
                    let [r, g, b, kd, ks, shine, t, ior] =
                        self.numbers(n, args, "material r g b Kd Ks Shine T index_of_refraction")?;
                    let color = self.color(n, [r, g, b], "material colour channel")?;
                    let kd = self.coefficient(n, kd, "diffuse coefficient Kd")?;
                    let ks = self.coefficient(n, ks, "specular coefficient Ks")?;
                    let t = self.coefficient(n, t, "transmittance T")?;
                    // A negative Phong exponent would make the highlight grow without
                    // bound as the angle widens.
                    if !(shine >= 0.0) {
                        return Err(self.error(
                            n,
                            format!("Phong exponent Shine {} must not be negative", shown(shine)),
                        ));
                    }
                    // SPD files write ior 0 for opaque materials; only a transmitter uses it.
                    if t > 0.0 && !(IOR_RANGE.0..=IOR_RANGE.1).contains(&ior) {
                        return Err(self.error(
                            n,
                            format!(
                                "index of refraction {} of a transmitting material (T = {t}) must lie between {} and {}",
                                shown(ior),
                                IOR_RANGE.0,
                                IOR_RANGE.1
                            ),
                        ));
                    }
                    materials.push(Material {
                        color,
                        kd,
                        ks,
                        shine,
                        t,
                        ior,
                    });
                }
                "s" => {
                    self.count_primitive(n)?;
                    let [x, y, z, r] =
                        self.coordinates(n, args, "sphere centre x y z and radius")?;
                    let m = current_material(&mut materials);
                    scene_parts
                        .spheres
                        .push(Sphere::new(Vec3::new(x, y, z), r, m));
                }
                "c" => {
                    self.count_primitive(n)?;
                    // Base and apex on the next two lines (NFF), or all eight numbers on
                    // the `c` line itself (as the SPD generators write them).
                    let [bx, by, bz, br, ax, ay, az, ar] = if args.is_empty() {
                        let base = self.required_line("cone base line 'x y z radius'")?;
                        let [bx, by, bz, br] =
                            self.coordinates(base.number, &base.tokens, "cone base x y z radius")?;
                        let apex = self.required_line("cone apex line 'x y z radius'")?;
                        let [ax, ay, az, ar] =
                            self.coordinates(apex.number, &apex.tokens, "cone apex x y z radius")?;
                        [bx, by, bz, br, ax, ay, az, ar]
                    } else {
                        self.coordinates(n, args, "cone base x y z radius and apex x y z radius")?
                    };
                    let m = current_material(&mut materials);
                    let (b, a) = (Vec3::new(bx, by, bz), Vec3::new(ax, ay, az));
                    if br == ar {
                        let cyl = Cylinder::new(b, a, br, m)
                            .map_err(|e| self.geometry(n, "cylinder", e))?;
                        scene_parts.cylinders.push(cyl);
                    } else {
                        let cone =
                            Cone::new(b, br, a, ar, m).map_err(|e| self.geometry(n, "cone", e))?;
                        scene_parts.cones.push(cone);
                    }
                }
                keyword @ ("p" | "pp") => {
                    let patch = keyword == "pp";
                    let what = if patch { "patch" } else { "polygon" };
                    self.count_primitive(n)?;
                    let count = self.vertex_count(n, args, what)?;
                    let mut vertices = Vec::with_capacity(count.min(1024));
                    let mut normals = Vec::new();
                    for i in 0..count {
                        let expect = if patch {
                            format!("patch vertex {} of {count} 'x y z nx ny nz'", i + 1)
                        } else {
                            format!("polygon vertex {} of {count} 'x y z'", i + 1)
                        };
                        let v = self.required_line(&expect)?;
                        if patch {
                            let [x, y, z, nx, ny, nz] = self.coordinates(
                                v.number,
                                &v.tokens,
                                "patch vertex x y z nx ny nz",
                            )?;
                            vertices.push(Vec3::new(x, y, z));
                            normals.push(Vec3::new(nx, ny, nz));
                        } else {
                            let [x, y, z] =
                                self.coordinates(v.number, &v.tokens, "polygon vertex x y z")?;
                            vertices.push(Vec3::new(x, y, z));
                        }
                    }
                    let m = current_material(&mut materials);
                    if patch {
                        let p = Patch::new(vertices, normals, m)
                            .map_err(|e| self.geometry(n, what, e))?;
                        scene_parts.patches.push(p);
                    } else {
                        let p = Polygon::new(vertices, m).map_err(|e| self.geometry(n, what, e))?;
                        scene_parts.polygons.push(p);
                    }
                }
                other => {
                    return Err(self.error(
                        n,
                        format!("unknown keyword '{other}' (expected one of {KEYWORDS})"),
                    ));
                }
            }
        }

        let Some((_, view)) = view else {
            return Err(self.error(
                self.last_line,
                "no view block: an NFF scene needs a 'v' line followed by from, at, up, angle, hither and resolution",
            ));
        };
        let default_intensity = Scene::default_light_intensity(lights.len());
        for light in lights.iter_mut().filter(|l| !l.color_given) {
            light.color = Rgb::gray(default_intensity);
        }
        let mut scene = Scene::new(view);
        scene.background = background;
        scene.lights = lights;
        scene.materials = materials;
        scene.spheres = huge_pages::rehoused(scene_parts.spheres);
        scene.cylinders = huge_pages::rehoused(scene_parts.cylinders);
        scene.cones = huge_pages::rehoused(scene_parts.cones);
        scene.polygons = huge_pages::rehoused(scene_parts.polygons);
        scene.patches = huge_pages::rehoused(scene_parts.patches);
        Ok(scene)
    }

    fn vertex_count(&self, line: usize, args: &[&str], what: &str) -> Result<usize, NffError> {
        let [token] = args else {
            return Err(self.error(
                line,
                format!(
                    "expected the {what}'s vertex count, found {} values",
                    args.len()
                ),
            ));
        };
        let count: i64 = token.parse().map_err(|_| {
            self.error(
                line,
                format!("'{token}' is not a whole number (expected the {what}'s vertex count)"),
            )
        })?;
        if count < 3 {
            return Err(self.error(
                line,
                format!("a {what} needs at least 3 vertices, found {count}"),
            ));
        }
        if count as u64 > self.limits.max_polygon_vertices {
            return Err(self.over_limit(
                line,
                Limit::MaxPolygonVertices,
                format!(
                    "{what} vertex count {count} exceeds the limit of {}",
                    self.limits.max_polygon_vertices
                ),
            ));
        }
        usize::try_from(count)
            .map_err(|_| self.error(line, format!("{what} vertex count {count} is too large")))
    }

    /// The lines after `v`: from, at, up, angle, hither, resolution, in any order.
    fn view_block(&mut self, v_line: usize) -> Result<View, NffError> {
        const VIEW_KEYS: [&str; 6] = ["from", "at", "up", "angle", "hither", "resolution"];
        let mut from = None;
        let mut at = None;
        let mut up = None;
        let mut angle = None;
        let mut hither = None;
        let mut resolution = None;
        while let Some(key) = self.peek_keyword() {
            if !VIEW_KEYS.contains(&key) {
                break;
            }
            let Some(line) = self.next_line() else { break };
            let (n, args) = (line.number, &line.tokens[1..]);
            let duplicate = |set: bool| -> Result<(), NffError> {
                if set {
                    Err(self.error(n, format!("'{key}' given twice in the view block")))
                } else {
                    Ok(())
                }
            };
            match key {
                "from" => {
                    duplicate(from.is_some())?;
                    from = Some(Vec3::from_array(self.coordinates(
                        n,
                        args,
                        "eye position x y z",
                    )?));
                }
                "at" => {
                    duplicate(at.is_some())?;
                    at = Some(Vec3::from_array(self.coordinates(
                        n,
                        args,
                        "look-at point x y z",
                    )?));
                }
                "up" => {
                    duplicate(up.is_some())?;
                    up = Some(Vec3::from_array(self.coordinates(
                        n,
                        args,
                        "up vector x y z",
                    )?));
                }
                "angle" => {
                    duplicate(angle.is_some())?;
                    let [a] = self.numbers(n, args, "field of view in degrees")?;
                    if !(a > 0.0 && a < 180.0) {
                        return Err(
                            self.error(n, format!("angle {a} must be between 0 and 180 degrees"))
                        );
                    }
                    angle = Some(a);
                }
                "hither" => {
                    duplicate(hither.is_some())?;
                    let [h] = self.numbers(n, args, "hither distance")?;
                    hither = Some(h);
                }
                _ => {
                    duplicate(resolution.is_some())?;
                    resolution = Some(self.resolution(n, args)?);
                }
            }
        }
        let missing =
            |name: &str| self.error(v_line, format!("the view block has no '{name}' line"));
        let view = View {
            from: from.ok_or_else(|| missing("from"))?,
            at: at.ok_or_else(|| missing("at"))?,
            up: up.ok_or_else(|| missing("up"))?,
            angle_deg: angle.ok_or_else(|| missing("angle"))?,
            hither: hither.unwrap_or(0.0),
            width: resolution.ok_or_else(|| missing("resolution"))?.0,
            height: resolution.ok_or_else(|| missing("resolution"))?.1,
        };
        check_view_basis(&view).map_err(|message| self.error(v_line, message))?;
        Ok(view)
    }

    fn resolution(&self, line: usize, args: &[&str]) -> Result<(u32, u32), NffError> {
        let [w, h] = args else {
            return Err(self.error(
                line,
                format!(
                    "expected 2 whole numbers (resolution width height), found {} values",
                    args.len()
                ),
            ));
        };
        let parse = |t: &str| -> Result<i64, NffError> {
            t.parse().map_err(|_| {
                self.error(
                    line,
                    format!("'{t}' is not a whole number (expected resolution width height)"),
                )
            })
        };
        let (w, h) = (parse(w)?, parse(h)?);
        if w <= 0 || h <= 0 {
            return Err(self.error(line, format!("resolution {w}x{h} must be positive")));
        }
        self.limits
            .check_size(w as u64, h as u64)
            .map_err(|e| NffError {
                limit: e.limit,
                ..self.error(line, e.to_string())
            })?;
        Ok((w as u32, h as u32))
    }
}

/// Checks that `from`, `at` and `up` define a camera: distinct eye and target, and an
/// up vector not parallel to the view direction.
pub fn check_view_basis(view: &View) -> Result<(), String> {
    let c = &mut NoCount;
    let forward = c.sub(view.at, view.from);
    let f_sq = c.dot(forward, forward);
    if !(f_sq > 0.0) {
        return Err("'from' and 'at' are the same point: the view has no direction".into());
    }
    let up_sq = c.dot(view.up, view.up);
    let side = c.cross(forward, view.up);
    // sin² of the angle between view direction and up must exceed 1e-10.
    if !(c.dot(side, side) > 1e-10 * f_sq * up_sq) {
        return Err("the 'up' vector is parallel to the view direction (or zero): choose an up vector across the line of sight".into());
    }
    Ok(())
}

#[derive(Default)]
struct ScenePrimitives {
    spheres: Vec<Sphere>,
    cylinders: Vec<Cylinder>,
    cones: Vec<Cone>,
    polygons: Vec<Polygon>,
    patches: Vec<Patch>,
}

#[cfg(test)]
mod tests;

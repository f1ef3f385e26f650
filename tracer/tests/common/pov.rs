//! Reading POV-Ray scene files for the POV writer's tests: the SPD's own files
//! (`../shared/peers/povray/*.pov.gz`, POV-Ray 3.1 syntax) and rtprof's
//! (`tracer::scene_to_pov`), both reduced to the same plain data. Only the subset the
//! two writers use: no expressions, no transformations.

use std::collections::HashMap;
use std::io::Read as _;
use std::path::PathBuf;

/// `../shared/peers/povray` beside the project root.
pub fn povray_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/peers/povray");
    assert!(
        dir.is_dir(),
        "the SPD's POV-Ray files are expected at {} (shared/ beside the project)",
        dir.display()
    );
    dir
}

/// The SPD's POV-Ray file of scene `name`, decompressed.
pub fn spd_pov_text(name: &str) -> String {
    let path = povray_dir().join(format!("{name}.pov.gz"));
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text
}

/// One item of a POV-Ray file: a word, a number, a vector or a `{ }` block.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Word(String),
    Num(f64),
    Vector([f64; 3]),
    Block(Vec<Item>),
}

/// A texture's values (a `#declare`d texture or material), `None` when not written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Texture {
    pub color: [f64; 3],
    pub filter: Option<f64>,
    pub ambient: Option<f64>,
    pub diffuse: Option<f64>,
    pub phong: Option<f64>,
    pub phong_size: Option<f64>,
    pub reflection: Option<f64>,
    pub ior: Option<f64>,
}

/// A primitive: its kind, its numbers and vectors in order, and its texture's values.
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    pub kind: String,
    /// Every number, vectors flattened, in the order written.
    pub numbers: Vec<f64>,
    /// Whether the `open` keyword was given (cones).
    pub open: bool,
    pub texture: Texture,
}

/// A POV-Ray scene as plain data.
#[derive(Clone, Debug, Default)]
pub struct PovScene {
    pub background: [f64; 3],
    /// location, direction, right, up.
    pub camera: [[f64; 3]; 4],
    /// Position and colour of each light.
    pub lights: Vec<([f64; 3], [f64; 3])>,
    pub textures: Vec<(String, Texture)>,
    pub primitives: Vec<Primitive>,
}

impl PovScene {
    /// The primitives of one kind (`sphere`, `cone`, `triangle`, `smooth_triangle`).
    pub fn of_kind<'a>(&'a self, kind: &'a str) -> impl Iterator<Item = &'a Primitive> + 'a {
        self.primitives.iter().filter(move |p| p.kind == kind)
    }
}

/// Splits the text into items, `//` comments dropped, `#declare` kept as a word.
fn tokenize(text: &str) -> Vec<Item> {
    let mut tokens = Vec::new();
    let mut words = Vec::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let spaced = code
            .replace('{', " { ")
            .replace('}', " } ")
            .replace('<', " < ")
            .replace('>', " > ")
            .replace([',', ';'], " ");
        words.extend(spaced.split_whitespace().map(str::to_string));
    }
    let mut stack: Vec<Vec<Item>> = vec![Vec::new()];
    let mut i = 0;
    while i < words.len() {
        let w = &words[i];
        match w.as_str() {
            "{" => stack.push(Vec::new()),
            "}" => {
                let block = stack.pop().unwrap_or_else(|| panic!("unbalanced }}"));
                stack
                    .last_mut()
                    .unwrap_or_else(|| panic!("unbalanced }}"))
                    .push(Item::Block(block));
            }
            "<" => {
                let v: Vec<f64> = words[i + 1..i + 4]
                    .iter()
                    .map(|s| s.parse().unwrap_or_else(|e| panic!("vector {s}: {e}")))
                    .collect();
                assert_eq!(words[i + 4], ">", "vector of three at word {i}");
                stack
                    .last_mut()
                    .unwrap_or_else(|| panic!("no block"))
                    .push(Item::Vector([v[0], v[1], v[2]]));
                i += 4;
            }
            _ => {
                let item = match w.parse::<f64>() {
                    Ok(x) => Item::Num(x),
                    Err(_) => Item::Word(w.clone()),
                };
                stack
                    .last_mut()
                    .unwrap_or_else(|| panic!("no block"))
                    .push(item);
            }
        }
        i += 1;
    }
    assert_eq!(stack.len(), 1, "unbalanced {{");
    tokens.append(&mut stack[0]);
    tokens
}

/// Every item of `items`, blocks opened, in order.
fn flatten(items: &[Item], out: &mut Vec<Item>) {
    for item in items {
        match item {
            Item::Block(inner) => flatten(inner, out),
            other => out.push(other.clone()),
        }
    }
}

/// The number after keyword `key` in a flattened block.
fn value_after(flat: &[Item], key: &str) -> Option<f64> {
    flat.windows(2).find_map(|w| match w {
        [Item::Word(k), Item::Num(x)] if k == key => Some(*x),
        _ => None,
    })
}

/// `color red r green g blue b` (or `rgb <r, g, b>`) in a flattened block.
fn color_of(flat: &[Item]) -> [f64; 3] {
    if let Some(v) = flat.windows(2).find_map(|w| match w {
        [Item::Word(k), Item::Vector(v)] if k == "rgb" => Some(*v),
        _ => None,
    }) {
        return v;
    }
    ["red", "green", "blue"].map(|k| value_after(flat, k).unwrap_or(0.0))
}

fn texture_of(block: &[Item]) -> Texture {
    let mut flat = Vec::new();
    flatten(block, &mut flat);
    Texture {
        color: color_of(&flat),
        filter: value_after(&flat, "filter"),
        ambient: value_after(&flat, "ambient"),
        diffuse: value_after(&flat, "diffuse"),
        phong: value_after(&flat, "phong"),
        phong_size: value_after(&flat, "phong_size"),
        reflection: value_after(&flat, "reflection"),
        ior: value_after(&flat, "ior"),
    }
}

const KINDS: [&str; 4] = ["sphere", "cone", "triangle", "smooth_triangle"];

/// Parses a scene written by either writer.
pub fn parse_pov(text: &str) -> PovScene {
    let items = tokenize(text);
    let mut scene = PovScene::default();
    let mut textures: HashMap<String, Texture> = HashMap::new();
    // Primitives with their texture's name, resolved once all are declared.
    let mut pending: Vec<(String, Vec<f64>, bool, String)> = Vec::new();
    let mut i = 0;
    while i < items.len() {
        match (&items[i], items.get(i + 1)) {
            (Item::Word(w), Some(Item::Num(_))) if w == "#version" => {
                i += 2;
                continue;
            }
            (Item::Word(w), _) if w == "#declare" => {
                let (Some(Item::Word(name)), Some(Item::Block(block))) =
                    (items.get(i + 1), items.get(i + 4))
                else {
                    panic!("#declare at item {i}: {:?}", &items[i..i + 5]);
                };
                let texture = texture_of(block);
                textures.insert(name.clone(), texture.clone());
                scene.textures.push((name.clone(), texture));
                i += 5;
                continue;
            }
            (Item::Word(w), Some(Item::Block(block))) => {
                let mut flat = Vec::new();
                flatten(block, &mut flat);
                match w.as_str() {
                    "background" => scene.background = color_of(&flat),
                    "camera" => {
                        for (slot, key) in
                            ["location", "direction", "right", "up"].iter().enumerate()
                        {
                            scene.camera[slot] = flat
                                .windows(2)
                                .find_map(|w| match w {
                                    [Item::Word(k), Item::Vector(v)] if k == key => Some(*v),
                                    _ => None,
                                })
                                .unwrap_or_else(|| panic!("camera without {key}"));
                        }
                    }
                    "light_source" => {
                        let Some(Item::Vector(position)) = flat.first() else {
                            panic!("light_source without a position");
                        };
                        scene.lights.push((*position, color_of(&flat)));
                    }
                    "object" => {
                        // The SPD's `object { triangle { ... } texture { name } }`.
                        let kind = block
                            .iter()
                            .zip(block.iter().skip(1))
                            .find_map(|p| match p {
                                (Item::Word(k), Item::Block(inner))
                                    if KINDS.contains(&k.as_str()) =>
                                {
                                    Some((k.clone(), inner))
                                }
                                _ => None,
                            });
                        let (kind, inner) =
                            kind.unwrap_or_else(|| panic!("object without primitive"));
                        pending.push(primitive(&kind, inner, block));
                    }
                    k if KINDS.contains(&k) => pending.push(primitive(k, block, block)),
                    other => panic!("unexpected top-level {other}"),
                }
                i += 2;
                continue;
            }
            other => panic!("unexpected item {i}: {other:?}"),
        }
    }
    for (kind, numbers, open, name) in pending {
        let texture = textures
            .get(&name)
            .unwrap_or_else(|| panic!("texture {name} not declared"))
            .clone();
        scene.primitives.push(Primitive {
            kind,
            numbers,
            open,
            texture,
        });
    }
    scene
}

/// A primitive's numbers (from `shape`, nested blocks left out) and its texture name
/// (`texture { name }` or `material { name }` anywhere in `whole`).
fn primitive(kind: &str, shape: &[Item], whole: &[Item]) -> (String, Vec<f64>, bool, String) {
    let mut numbers = Vec::new();
    let mut open = false;
    for item in shape {
        match item {
            Item::Num(x) => numbers.push(*x),
            Item::Vector(v) => numbers.extend(v),
            Item::Word(w) if w == "open" => open = true,
            _ => {}
        }
    }
    let mut flat = Vec::new();
    flatten(whole, &mut flat);
    let name = flat
        .windows(2)
        .find_map(|w| match w {
            [Item::Word(k), Item::Word(name)] if k == "texture" || k == "material" => {
                Some(name.clone())
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("{kind} without a texture"));
    (kind.to_string(), numbers, open, name)
}

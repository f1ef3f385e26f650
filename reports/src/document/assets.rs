//! The files a document embeds, named by virtual paths (`/assets/3.svg`): the HTML
//! inlines them, the PDF hands them to typst as files.

/// What an asset holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AssetKind {
    Png,
    Svg,
}

impl AssetKind {
    fn extension(self) -> &'static str {
        match self {
            AssetKind::Png => "png",
            AssetKind::Svg => "svg",
        }
    }
}

/// One embedded file.
#[derive(Clone, Debug, PartialEq)]
pub struct Asset {
    pub path: String,
    pub kind: AssetKind,
    pub bytes: Vec<u8>,
}

/// Every asset of a document, in the order they were added.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assets {
    list: Vec<Asset>,
    /// Paths are numbered by this counter, so a removal never frees a path for reuse.
    next: usize,
}

impl Assets {
    /// Adds a file; returns its virtual path.
    pub fn add(&mut self, kind: AssetKind, bytes: Vec<u8>) -> String {
        let path = format!("/assets/{}.{}", self.next, kind.extension());
        self.next += 1;
        self.list.push(Asset {
            path: path.clone(),
            kind,
            bytes,
        });
        path
    }

    pub fn get(&self, path: &str) -> Option<&Asset> {
        self.list.iter().find(|a| a.path == path)
    }

    pub fn iter(&self) -> impl Iterator<Item = &Asset> {
        self.list.iter()
    }

    pub fn len(&self) -> usize {
        self.list.len()
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Drops the assets whose paths `gone` holds.
    pub fn remove_all(&mut self, gone: &std::collections::BTreeSet<String>) {
        self.list.retain(|a| !gone.contains(&a.path));
    }
}

/// The size of an SVG from its root element (viewBox, else width and height); for
/// flamegraph files, which come from elsewhere and say their size only there.
pub fn svg_size(svg: &str) -> Option<(f64, f64)> {
    let start = svg.find("<svg")?;
    let end = start + svg[start..].find('>')?;
    let tag = &svg[start..end];
    if let Some(vb) = attribute(tag, "viewBox") {
        let nums: Vec<f64> = vb
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .filter_map(|s| s.parse().ok())
            .collect();
        if let [_, _, w, h] = nums[..]
            && w > 0.0
            && h > 0.0
            && w.is_finite()
            && h.is_finite()
        {
            return Some((w, h));
        }
    }
    let w = leading_number(attribute(tag, "width")?)?;
    let h = leading_number(attribute(tag, "height")?)?;
    (w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()).then_some((w, h))
}

/// The value of attribute `name` in a start tag.
fn attribute<'t>(tag: &'t str, name: &str) -> Option<&'t str> {
    let mut from = 0;
    while let Some(pos) = tag[from..].find(name) {
        let at = from + pos;
        from = at + name.len();
        let before_ok = tag[..at]
            .chars()
            .next_back()
            .is_some_and(char::is_whitespace);
        let rest = tag[from..].trim_start();
        if !before_ok || !rest.starts_with('=') {
            continue;
        }
        let rest = rest[1..].trim_start();
        let quote = rest.chars().next()?;
        if quote != '"' && quote != '\'' {
            continue;
        }
        let value = &rest[1..];
        return value.find(quote).map(|e| &value[..e]);
    }
    None
}

/// The number a length starts with ("10px" -> 10); `None` for a percentage.
fn leading_number(s: &str) -> Option<f64> {
    let end = s
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(s.len());
    if s[end..].trim_start().starts_with('%') {
        return None;
    }
    s[..end].parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_sizes_come_from_the_view_box_or_the_lengths() {
        assert_eq!(
            svg_size(r#"<svg width="800" height="400" xmlns="x">"#),
            Some((800.0, 400.0))
        );
        assert_eq!(
            svg_size(r#"<?xml?><svg version="1.1" viewBox="0 0 1200 300" width="100%">"#),
            Some((1200.0, 300.0))
        );
        assert_eq!(
            svg_size(r#"<svg stroke-width="3" width="10px" height="5px">"#),
            Some((10.0, 5.0))
        );
        assert_eq!(svg_size(r#"<svg width="100%" height="5">"#), None);
        assert_eq!(svg_size("<svg>"), None);
        assert_eq!(svg_size("no svg"), None);
    }

    #[test]
    fn assets_get_distinct_paths() {
        let mut assets = Assets::default();
        let a = assets.add(AssetKind::Png, vec![1]);
        let b = assets.add(AssetKind::Svg, vec![2]);
        assert_eq!((a.as_str(), b.as_str()), ("/assets/0.png", "/assets/1.svg"));
        assert_eq!(assets.get(&b).map(|x| x.bytes.clone()), Some(vec![2]));
        assets.remove_all(&[a.clone()].into_iter().collect());
        assert!(assets.get(&a).is_none() && assets.len() == 1);
    }
}

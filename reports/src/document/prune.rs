//! A document without some of its assets: each picture that used one becomes a note
//! saying why it is not there (the PDF leaves out what typst cannot read).

use std::collections::BTreeSet;

use super::{Block, Document, Visual};

impl Document {
    /// This document with the assets at `gone` left out; each picture that used one
    /// reads "`<its name>`: `why`" instead.
    pub fn without_assets(&self, gone: &BTreeSet<String>, why: &str) -> Document {
        let mut doc = self.clone();
        doc.assets.remove_all(gone);
        let prune = |visual: &mut Visual, name: &str| {
            if let Visual::Image(image) = visual
                && gone.contains(&image.asset)
            {
                let name = if name.is_empty() { &image.alt } else { name };
                *visual = Visual::Missing {
                    text: format!("{name}: {why}"),
                };
            }
        };
        for section in &mut doc.sections {
            for block in &mut section.blocks {
                match block {
                    Block::Figure(f) => {
                        let title = f.title.clone();
                        prune(&mut f.visual, &title);
                    }
                    Block::Flamegraph(f) => {
                        let title = f.title.clone();
                        prune(&mut f.visual, &title);
                    }
                    Block::ImageGrid(g) => {
                        for tile in &mut g.tiles {
                            prune(&mut tile.visual, "");
                        }
                    }
                    _ => {}
                }
            }
        }
        doc
    }
}

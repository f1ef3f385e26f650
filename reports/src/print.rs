//! The document as paper shows it ([`crate::pdf`]): the sections marked HTML-only keep
//! their opening, and the flamegraphs are drawn without their interface.

use crate::document::{Block, Document, Tone};

impl Document {
    /// The document as the PDF prints it: each [`html_only`](crate::document::Section::html_only) section keeps
    /// its first paragraph and says where the rest is, and the flamegraphs lose their
    /// interface (paper cannot search or zoom: [`crate::flame_static`]).
    pub fn for_print(&self) -> Document {
        let mut doc = crate::flame_static::for_print(self);
        for section in doc.sections.iter_mut().filter(|s| s.html_only) {
            let opening = section
                .blocks
                .iter()
                .find(|b| matches!(b, Block::Paragraph { .. }))
                .cloned();
            section.blocks = opening.into_iter().collect();
            section.blocks.push(Block::note(
                Tone::Neutral,
                "The rest of this section is in the HTML report (report.html), and its figures are in results.json (and variants.csv): its tables of every scene would take pages of numbers here.",
            ));
        }
        doc
    }
}

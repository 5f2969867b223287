//! How the explorer draws: marker, themes, characters, the footer (the command line's look
//! flags and the config's, resolved once).

use ratatui::symbols::Marker;

use super::{Look, Theme, glyphs};
use crate::scenario::theme::ThemeSpec;

/// How to draw.
#[derive(Clone, Debug)]
pub struct UiOptions {
    /// Canvas marker (`--marker`).
    pub marker: Marker,
    /// The themes `T` cycles through, the starting one first.
    pub themes: Vec<Theme>,
    /// `NO_COLOR`: every colour is off; shapes, density and bold tell the curves apart.
    pub no_color: bool,
    /// What the terminal can show ([`glyphs::Charset::detect`]); other than Unicode, every
    /// canvas draws one point per cell and every cell is folded into the set.
    pub charset: glyphs::Charset,
    /// The key hints on the last row (off in an exported cast or page: nobody can press them).
    pub footer: bool,
    /// The status bar says `● REC` whatever the app's own journal: a recording's frames drawn
    /// as the lecturer saw them, recording (`rattleback serve`).
    pub recorded: bool,
}

impl Default for UiOptions {
    fn default() -> Self {
        Self {
            marker: Marker::Braille,
            themes: vec![Theme::default()],
            no_color: false,
            charset: glyphs::Charset::Unicode,
            footer: true,
            recorded: false,
        }
    }
}

impl UiOptions {
    /// Options starting from `first`, then every other theme of `all`; `no_color` (the
    /// `NO_COLOR` convention) drops every colour, leaving the shapes, bold and reverse-video
    /// cues that do not depend on it.
    #[must_use]
    pub fn new(marker: Marker, first: &ThemeSpec, all: &[ThemeSpec], no_color: bool) -> Self {
        let mut themes = vec![Theme::from_spec(first, no_color)];
        for spec in all {
            let t = Theme::from_spec(spec, no_color);
            if !themes.iter().any(|x| x.name == t.name) {
                themes.push(t);
            }
        }
        Self {
            marker,
            themes,
            no_color,
            charset: glyphs::Charset::Unicode,
            footer: true,
            recorded: false,
        }
    }

    /// The same options drawing a recording as the lecturer saw it: `● REC` in the status
    /// bar (the lecturer was recording every frame of it), so the status bar reads as theirs.
    #[must_use]
    pub fn as_recorded(self) -> Self {
        Self {
            recorded: true,
            ..self
        }
    }

    /// The same options without the key hints (an exported cast or page).
    #[must_use]
    pub fn without_footer(self) -> Self {
        Self {
            footer: false,
            ..self
        }
    }

    /// The same options for a terminal that shows `charset`.
    #[must_use]
    pub fn with_charset(self, charset: glyphs::Charset) -> Self {
        Self { charset, ..self }
    }

    /// The theme names, in `T` order.
    #[must_use]
    pub fn theme_names(&self) -> Vec<String> {
        self.themes.iter().map(|t| t.name.clone()).collect()
    }

    /// The marker, theme and characters one frame draws with (`theme`: the index `T` cycles).
    #[must_use]
    pub fn look(&self, theme: usize) -> Look<'_> {
        Look {
            // Braille and half blocks need glyphs only the Unicode set has.
            marker: if self.charset == glyphs::Charset::Unicode {
                self.marker
            } else {
                Marker::Dot
            },
            theme: &self.themes[theme % self.themes.len().max(1)],
            no_color: self.no_color,
            charset: self.charset,
        }
    }
}

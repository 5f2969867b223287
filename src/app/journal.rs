//! What the app did, as semantic events: the content of a recorded session. The app appends
//! to its journal while recording; the explorer stamps each entry with the wall clock and
//! writes it out. Names and fields are a file format: add, never rename.

use serde::{Deserialize, Serialize};

/// One semantic event.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Event {
    /// A parameter took a new value (the value as typed, parsed by the field).
    Set {
        /// Field name, as in presets.
        field: String,
        /// The value, as text that round-trips exactly.
        value: String,
    },
    /// The panel's selected row moved (format 4 on: the highlight is part of the screen).
    Select {
        /// Field name, as in presets.
        field: String,
    },
    /// Started playing.
    Play,
    /// Paused.
    Pause,
    /// One frame forward while paused.
    Step,
    /// Back to t = 0.
    Reset,
    /// New speed.
    Speed {
        /// Simulated seconds per wall second.
        value: f64,
    },
    /// Zoom, pan or wrap changed.
    View {
        /// Zoom factor.
        zoom: f64,
        /// Horizontal pan.
        pan_x: f64,
        /// Vertical pan.
        pan_y: f64,
        /// Wrapped `alpha`.
        wrap: bool,
    },
    /// Overlay or pane toggled: the overlay and the panes a key shows, as a list (written
    /// from the comparison on; a new pane is a new name, never a new field).
    Layout {
        /// Effective overlay shown.
        effective: bool,
        /// The panes shown, by name, in layout order.
        panes: Vec<super::panes::Pane>,
    },
    /// The comparison's partner was chosen (inline, so the file stands alone).
    Partner {
        /// Its preset as TOML.
        toml: String,
    },
    /// Overlay or pane toggled, as files before the comparison wrote it (still read).
    Panes {
        /// Effective overlay shown.
        effective: bool,
        /// Time-series pane shown.
        series: bool,
        /// Stiffness-sweep pane shown. Written only when true, so the lines of files made before
        /// the pane (whose hash chain covers their exact bytes) serialize as they were.
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        sweep: bool,
        /// Weak-* pane shown (written only when true).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        weak: bool,
        /// Regime-map pane shown (written only when true).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        map: bool,
        /// Body pane shown (written only when true).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        body: bool,
    },
    /// The trail was cleared.
    ClearTrail,
    /// The map's cursor moved, or the map took or gave back the arrows (format 12): a replay
    /// draws the cursor where the lecturer had it, and the pane's title as it was (its keys
    /// while the map had the arrows). Written while the map pane is shown, when either changed.
    MapCursor {
        /// The cursor's column (0 is the left).
        column: usize,
        /// Its row (0 is the bottom).
        row: usize,
        /// Whether the map had the arrows.
        focused: bool,
    },
    /// The lecturer's terminal was resized while recording (format 14): the cast, the page and
    /// `serve` draw from here on at this size, as the lecturer saw it (issue 80: a recording
    /// begun in a small terminal and then enlarged exported its "terminal too small" alone).
    Terminal {
        /// Columns (1 to 1000).
        width: u16,
        /// Rows (1 to 1000).
        height: u16,
    },
    /// The weak-* pane's averaging window was changed (`<`, `>`; format 7).
    Window {
        /// The window in simulated seconds, as shown.
        value: f64,
    },
    /// A preset was loaded (inline, so the file stands alone).
    Preset {
        /// The preset as TOML.
        toml: String,
    },
    /// A note typed in the explorer.
    Note {
        /// Its text.
        text: String,
    },
    /// A chapter marker typed in the explorer.
    Chapter {
        /// Its title.
        title: String,
    },
    /// A lesson's step began (what it says, so the file stands alone).
    LessonStep {
        /// The lesson's title.
        lesson: String,
        /// The step's index (0 is the first).
        step: usize,
        /// How many steps the lesson has.
        steps: usize,
        /// The step's title.
        title: String,
        /// Its text.
        text: String,
    },
    /// The answer given to a step's question, before its run (format 10 on: a replay shows
    /// "your answer" from then, as the lecturer's pane did).
    Given {
        /// The step's index.
        step: usize,
        /// What the student answered.
        given: String,
    },
    /// The last step's condition held and `n` ended the lesson (format 10 on).
    LessonDone,
    /// The answer to a step's question, revealed after the run.
    Answer {
        /// The step's index.
        step: usize,
        /// What the student answered.
        given: String,
        /// Whether it was right.
        correct: bool,
    },
    /// The recording was stopped: the last line of a finished session. Format 4 on it counts
    /// the lines before it (the header included), so a file cut short is found, and may carry
    /// the lecturer's signature over the chain.
    End {
        /// Lines of the file before this one (format 4 on).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        lines: Option<usize>,
        /// The signer's name (a signed format-4 session).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        signer: Option<String>,
        /// The signer's ed25519 public key, hex.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        public_key: Option<String>,
        /// The ed25519 signature of the chain value before this line, hex.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        signature: Option<String>,
    },
    /// The displayed time while playing (format 4 on): a follower never shows a time the
    /// lecturer has not shown, and a replay moves between these exactly.
    Clock,
    /// What the lecturer's screen showed (format 4 on), at each pause, step, chapter, note,
    /// lesson step and at the end: the status bar's values at the line's `t`. `replay --verify`
    /// rebuilds the screen and compares them.
    Screen(Shown),
    /// The concrete plan a run integrates (what `auto` resolved to), so replay uses it and no
    /// later change of `auto` can change an old session (format 2 on).
    Plan {
        /// The key's model, by name (format 11 on): the key is read as the model it names, never
        /// as another whose fields it happens to have (files before it tell the models apart by
        /// their keys' fields).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        model: Option<String>,
        /// What it was resolved for.
        key: crate::sim::PlanKey,
        /// The plan.
        plan: crate::physics::Resolved,
        /// `auto`'s error estimate the status bar showed (format 4 on), so a replay shows it too;
        /// `"inf"` where no bound was found (format 14 on, `physics::json`).
        #[serde(
            default,
            skip_serializing_if = "Option::is_none",
            with = "crate::physics::json::option"
        )]
        #[schemars(with = "Option<crate::physics::json::Number>")]
        estimate: Option<f64>,
    },
    /// The exact state of the run at simulated time `t`.
    Checkpoint {
        /// The model's state vector: the rattleback's `(gamma, alpha, gamma_dot, alpha_dot)`,
        /// the pendulum's `(theta, theta_dot)`.
        state: Vec<f64>,
        /// Reversals of the full motion up to `t`.
        reversals: usize,
        /// FNV-1a of the bits of `t`, the state and the count, in hex.
        hash: String,
    },
}

impl Event {
    /// The plan line of `key`, naming its model.
    #[must_use]
    pub fn plan(
        key: crate::sim::PlanKey,
        plan: crate::physics::Resolved,
        estimate: Option<f64>,
    ) -> Self {
        Self::Plan {
            model: Some(key.model().name().to_owned()),
            key,
            plan,
            estimate,
        }
    }
}

impl Event {
    /// Whether the event opens a chapter of the session: a chapter the lecturer marked, or a
    /// lesson's step. Replay's `[` and `]` jump between them; the cast and the page mark them.
    #[must_use]
    pub fn starts_chapter(&self) -> bool {
        matches!(self, Self::Chapter { .. } | Self::LessonStep { .. })
    }

    /// The overlay and the panes shown, of a layout line or of an older `panes` line.
    #[must_use]
    pub fn layout(&self) -> Option<(bool, Vec<super::panes::Pane>)> {
        use super::panes::Pane;
        match self {
            Self::Layout { effective, panes } => Some((*effective, panes.clone())),
            Self::Panes {
                effective,
                series,
                sweep,
                weak,
                map,
                body,
            } => {
                let shown = [
                    (Pane::Series, *series),
                    (Pane::Sweep, *sweep),
                    (Pane::Weak, *weak),
                    (Pane::Map, *map),
                    (Pane::Body, *body),
                ];
                let panes = shown.iter().filter(|(_, on)| *on).map(|(p, _)| *p);
                Some((*effective, panes.collect()))
            }
            _ => None,
        }
    }

    /// An unsigned end line with no count (formats 1 to 3, and the app's own request).
    #[must_use]
    pub fn end() -> Self {
        Self::End {
            lines: None,
            signer: None,
            public_key: None,
            signature: None,
        }
    }
}

/// The values of the status bar at a displayed time (the numbers a student reads).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Shown {
    /// Playing (else paused or done).
    pub playing: bool,
    /// Events of the full motion shown (reversals, or the pendulum's swings).
    pub events: usize,
    /// Events of the limit shown, when the limit is drawn.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limit_events: Option<usize>,
    /// The pendulum's falls shown.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub falls: Option<usize>,
    /// The celt's spin crossings shown.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossings: Option<usize>,
    /// What the compare pane showed of its partner, when it was open.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compare: Option<Compared>,
    /// The displayed point: the slow coordinate, its rate and the energy error (none before the
    /// first sample).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::physics::json::triple"
    )]
    #[schemars(with = "Option<[crate::physics::json::Number; 3]>")]
    pub point: Option<[f64; 3]>,
    /// The method integrating, as the status bar names it.
    pub method: String,
    /// `auto`'s error estimate shown (`"inf"`: no bound, format 14 on).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::physics::json::option"
    )]
    #[schemars(with = "Option<crate::physics::json::Number>")]
    pub estimate: Option<f64>,
}

/// What the compare pane showed of the partner at a displayed time (part of a recorded
/// screen).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Compared {
    /// The partner's preset name.
    pub partner: String,
    /// Its reversals shown.
    pub events: usize,
    /// Its second events shown (the celt's crossings), when its model has them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossings: Option<usize>,
    /// Its spin at the displayed time (none before its first sample, or when it failed).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "crate::physics::json::option"
    )]
    #[schemars(with = "Option<crate::physics::json::Number>")]
    pub spin: Option<f64>,
}

impl Shown {
    /// The first field whose value differs from `other`'s, with both values (bits compared).
    #[must_use]
    pub fn difference(&self, other: &Self) -> Option<String> {
        use crate::physics::json::bits as key;
        let bits = |p: &Option<[f64; 3]>| p.map(|a| a.map(key));
        let name = if self.playing != other.playing {
            "playing"
        } else if self.events != other.events {
            "event count"
        } else if self.limit_events != other.limit_events {
            "limit's event count"
        } else if self.falls != other.falls {
            "falls"
        } else if self.crossings != other.crossings {
            "crossings"
        } else if self
            .compare
            .as_ref()
            .map(|c| (&c.partner, c.events, c.crossings))
            != other
                .compare
                .as_ref()
                .map(|c| (&c.partner, c.events, c.crossings))
            || self.compare.as_ref().and_then(|c| c.spin).map(key)
                != other.compare.as_ref().and_then(|c| c.spin).map(key)
        {
            "compared partner"
        } else if bits(&self.point) != bits(&other.point) {
            "displayed point"
        } else if self.method != other.method {
            "method"
        } else if self.estimate.map(key) != other.estimate.map(key) {
            "estimate"
        } else {
            return None;
        };
        Some(format!(
            "{name}: recorded {}, replayed {}",
            serde_json::to_string(self).unwrap_or_default(),
            serde_json::to_string(other).unwrap_or_default()
        ))
    }
}

/// FNV-1a (64-bit) of the bits of a checkpoint: stable across platforms and Rust versions.
#[must_use]
pub fn state_hash(t: f64, state: &[f64], reversals: usize) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        for b in x.to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    eat(t.to_bits());
    for v in state {
        eat(v.to_bits());
    }
    eat(reversals as u64);
    format!("{h:016x}")
}

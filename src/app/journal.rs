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
    /// Overlay or pane toggled.
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
    /// The answer to a step's question, revealed after the run.
    Answer {
        /// The step's index.
        step: usize,
        /// What the student answered.
        given: String,
        /// Whether it was right.
        correct: bool,
    },
    /// The recording was stopped: the last line of a finished session.
    End,
    /// The concrete plan a run integrates (what `auto` resolved to), so replay uses it and no
    /// later change of `auto` can change an old session (format 2 on).
    Plan {
        /// What it was resolved for.
        key: crate::sim::PlanKey,
        /// The plan.
        plan: crate::physics::Resolved,
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

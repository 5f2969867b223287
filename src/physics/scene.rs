//! What every layer above `physics/` needs to know about a model, said once by the model in its
//! own folder (`rattleback/scene.rs`, `kapitza/scene.rs`):
//!
//! - [`Scene`], the model's fixed facts: its names and words, its parameters as a table
//!   ([`ParamSpec`]), its methods, its small parameter and ladder (or none), which studies apply;
//! - [`Posed`], the facts of one validated problem: its parameter values, the panel's derived
//!   lines, its slow start, how to build, plan, price and run it.
//!
//! Neither trait has a default method for a model fact, so a model that forgets one does not
//! compile. `Model` and `ModelKind` (in `models.rs`) are the one dispatch to them.
use crate::physics::numerics::elementary::Elementary;

use super::flow::Flow;
use super::method::{Method, StepError};
use super::params::{ParamError, ParamSpec};
use super::plan::{PlanRequest, Resolution};
use crate::physics::flow::GoOn;
use crate::physics::method::Arithmetic;
use crate::physics::method::Asked;

/// What resolving a plan gives.
pub type Planned = Result<Resolution, StepError>;

/// Labels of a model's variables, events and monitors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Words {
    /// The slow coordinate's name in presets, CSV columns and JSON (ASCII).
    pub q_name: &'static str,
    /// Its rate's.
    pub q_dot_name: &'static str,
    /// The slow coordinate, for people.
    pub q: &'static str,
    /// Its rate.
    pub q_dot: &'static str,
    /// The fast coordinate.
    pub fast: &'static str,
    /// Its name in ASCII (`gamma`, `ripple`, `tilt`).
    pub fast_name: &'static str,
    /// One event of the slow coordinate.
    pub event: &'static str,
    /// Events.
    pub events: &'static str,
    /// What one is, for the legend.
    pub event_meaning: &'static str,
    /// The second kind of event the explorer counts (the pendulum's falls, the celt's
    /// crossings), if any.
    pub second_events: Option<SecondEvents>,
    /// What the status bar, the series pane and the export monitor of the run (issue 83: the
    /// scene's own; `None`, a scene with no conserved quantity to watch, shows none).
    pub monitor: Option<Monitor>,
}

/// A scene's monitor of its run: a quantity its motion conserves, whose error is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Monitor {
    /// As the status bar shows it (`ΔE/E` of a conserved energy, `ΔE_eff` of the limit's
    /// energy for a forced model).
    pub label: &'static str,
    /// Its CSV column (`energy_error`, `energy_drift`).
    pub column: &'static str,
    /// What it is, for the legend.
    pub meaning: &'static str,
}

/// A model's second kind of event: its name and where it is found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SecondEvents {
    /// The name, plural (`falls`, `crossings`).
    pub name: &'static str,
    /// What one is, for the legend.
    pub meaning: &'static str,
    /// Where they are found.
    pub found: Found,
}

/// Where a model's second events are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Found {
    /// Between consecutive samples, where the slow angle `q − fast` passes the horizontal going
    /// down (`cos` from positive to non-positive): the pendulum's falls.
    SlowAngleFalls,
    /// By the flow inside its steps ([`crate::physics::flow::Flow::marks`]): the celt's spin
    /// crossings.
    Flow,
}

/// The small parameter a model's limit is about, and how the sweep steps it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmallParameter {
    /// Its key among the model's parameters ([`Scene::params`]).
    pub key: &'static str,
    /// Its symbol for people (`k`, `ε`).
    pub symbol: &'static str,
    /// The limit, for people (`k → ∞`, `ε → 0`).
    pub limit: &'static str,
    /// The sweep's CSV and JSON column (a contract: `stiffness`, `epsilon`).
    pub column: &'static str,
    /// Its tag in the sweep's curve columns (`alpha_k1e4`, `theta_eps1e-3`).
    pub tag: &'static str,
    /// What the sweep measures, in ASCII words.
    pub sup: &'static str,
    /// The same, short, for tables.
    pub sup_short: &'static str,
    /// The default ladder, one value per decade.
    pub ladder: &'static [f64],
}

/// The studies a model offers (what the panes and `study` commands may ask of it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Studies {
    /// The weak-* convergence of the fast coordinate's square, and its words (`None`: the scene
    /// has no weak-* pane).
    pub weak: Option<WeakWords>,
    /// Its chart's words (the map pane `M`, `study map`): every scene has a chart, said here
    /// in the scene's folder (issue 69: they were a match over the scenes in `study/`).
    pub chart: ChartWords,
    /// The shipped preset the compare pane sets beside this scene when no partner was chosen
    /// (the paper's contrast: the holonomic rattleback beside the rolling celt).
    pub counterpart: &'static str,
}

/// The words of a scene's chart, for the map pane's legend and heading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChartWords {
    /// The legend's heading.
    pub title: &'static str,
    /// What the curve is.
    pub curve: &'static str,
    /// The axes, in a line.
    pub note: &'static str,
    /// Short names of the axes.
    pub axes: (&'static str, &'static str),
    /// Whether `f` switches the source (the rattleback's limit or full model).
    pub sources: bool,
    /// The largest grid the explorer's pane draws (a recorded cursor lies inside it).
    pub pane: (usize, usize),
    /// The names of the output's axes (`study map`'s JSON; a part is read back against them).
    pub axis_keys: [&'static str; 2],
    /// What the text table is of (its first words).
    pub heading: &'static str,
    /// The text table's key to its glyphs.
    pub legend: &'static str,
    /// What the map pane's cells mean, for its legend: a cell with an answer (its count's
    /// shades, or a yes), and an undecided one.
    pub pane_legend: [&'static str; 2],
    /// The fields of its cells, in order: the CSV's columns, and the JSON cell's fields
    /// (issue 83: the scene's own [`Field`](super::chart::Field)s among them, one its
    /// answer, a count or a yes/no).
    pub csv: &'static [super::chart::Column],
    /// The `study map` flags its chart takes (every other is refused, naming the scene).
    pub flags: &'static [super::chart::MapFlag],
}

/// One read-only line the panel shows under a model's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SummaryLine {
    /// The label.
    pub label: &'static str,
    /// What it is, for the legend.
    pub meaning: &'static str,
    /// The value.
    pub value: Shown,
    /// It predicts the run (a criterion, a regime): a lesson hides its value while a question
    /// is open, so the panel does not answer it.
    pub predicts: bool,
}

impl SummaryLine {
    /// A line: its label, its meaning, its value.
    #[must_use]
    pub const fn new(label: &'static str, meaning: &'static str, value: Shown) -> Self {
        Self {
            label,
            meaning,
            value,
            predicts: false,
        }
    }

    /// The same line, marked as predicting the run ([`Self::predicts`]).
    #[must_use]
    pub const fn prediction(mut self) -> Self {
        self.predicts = true;
        self
    }
}

/// A derived value, as the panel shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shown {
    /// A number (`-` when there is none).
    Number(Option<f64>),
    /// A signed fraction, shown as a percentage (`-` when there is none).
    Percent(Option<f64>),
    /// A verdict in words, shown in bold.
    Verdict(&'static str),
}

impl Shown {
    /// The verdict `yes` when `holds`, else `no`.
    #[must_use]
    pub const fn verdict(holds: bool, yes: &'static str, no: &'static str) -> Self {
        Self::Verdict(if holds { yes } else { no })
    }
}

/// A model's fixed facts: one `static` per model, in its folder. A struct, so a model that
/// forgets a fact does not compile.
#[derive(Debug)]
pub struct Scene {
    /// The name used in presets and JSON.
    pub name: &'static str,
    /// The name for people.
    pub title: &'static str,
    /// Labels of its variables and events.
    pub words: Words,
    /// Its parameters, in the panel's order (the physical ones, then the start).
    pub params: &'static [ParamSpec],
    /// Whether presets must name the model (`[preset] model`); the first model is the default.
    pub model_required: bool,
    /// The methods it offers, `auto` first.
    pub methods: &'static [Method],
    /// The tolerance of the limit's own run, whatever the user's.
    pub limit_tolerance: f64,
    /// Its small parameter, or `None` for a model without a limit.
    pub small: Option<SmallParameter>,
    /// The studies it offers.
    pub studies: Studies,
}

/// The slow coordinate of one run, sampled on a grid.
#[derive(Clone, Debug, PartialEq)]
pub struct SlowCurve {
    /// Sample times.
    pub t: Vec<f64>,
    /// The slow coordinate at those times.
    pub q: Vec<f64>,
    /// What ran.
    pub method: Method,
    /// `auto`'s error estimate (0 for a concrete method).
    pub estimate: f64,
}

/// What a scene's weak-* pane shows, in words (its legend).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WeakWords {
    /// The observable, pointwise.
    pub observable: &'static str,
    /// What its averages approach.
    pub reference: &'static str,
}

/// The weak-* view of one run: an observable that converges only weakly-* as the small
/// parameter goes to its limit, pointwise at evenly spaced times (the explorer averages it over
/// the window the user picks).
#[derive(Clone, Debug, PartialEq)]
pub struct WeakView {
    /// Sample times (evenly spaced).
    pub t: Vec<f64>,
    /// The observable at those times.
    pub pointwise: Vec<f64>,
    /// A constant its averages approach (the rattleback's `θ`), or 0 when `reference` is given.
    pub level: f64,
    /// The limit's own curve, averaged the same way (the pendulum's `θ̇`), or empty.
    pub reference: Vec<f64>,
}

/// What the body pane draws of a posed problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Drawing {
    /// A body seen from above: its half-extents along its own x and y axes (any unit: the pane
    /// draws their ratio), and its profile for side and end views when it has one (the celt's
    /// ellipsoidal bottom; the paper's rattleback has no shape beyond its inertia).
    Body {
        /// Half-extents along the body's x and y axes.
        plan: [f64; 2],
        /// The profile, for the side and end views.
        side: Option<SideView>,
    },
    /// A pendulum of unit length on a pivot shaken along the vertical (Kapitza's).
    Pendulum(Pivot),
    /// A figure the scene draws itself (issue 83): a body of a new kind is drawn from its
    /// folder, with no edit to the pane.
    Figure(Figure),
}

/// A scene's own figure (see [`Drawing::Figure`]): its shapes at the point shown, in a square
/// of half-side 1 about the origin (`y` up; the pane keeps it square and shows a margin), and
/// its legend. Plain data, so a drawing stays `Copy`: the scene's numbers travel in `knobs`.
#[derive(Clone, Copy, Debug)]
pub struct Figure {
    /// What the pane calls it ("a mass on a spring").
    pub title: &'static str,
    /// The scene's own numbers its `shapes` reads (a length, an amplitude).
    pub knobs: [f64; 4],
    /// The shapes at time `t` for the sample shown (its slow coordinate, rate and fast one).
    pub shapes: fn(knobs: &[f64; 4], t: f64, now: &super::flow::Sample) -> Vec<Shape>,
    /// The legend: each ink and what it marks.
    pub legend: &'static [(Ink, &'static str)],
}

/// Two figures are the same when they say the same and read the same numbers (a function's
/// address is not a fact to compare).
impl PartialEq for Figure {
    fn eq(&self, other: &Self) -> bool {
        self.title == other.title && self.knobs == other.knobs && self.legend == other.legend
    }
}

/// A mark of a scene's [`Figure`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A straight line from `from` to `to`.
    Line {
        /// One end.
        from: (f64, f64),
        /// The other.
        to: (f64, f64),
        /// Its colour.
        ink: Ink,
    },
    /// A character at a point (bold in [`Ink::Current`]).
    Glyph {
        /// Where.
        at: (f64, f64),
        /// Which.
        glyph: char,
        /// Its colour.
        ink: Ink,
    },
}

/// The colours a [`Figure`] draws with: the theme's own, so it follows the palette, `NO_COLOR`
/// and the legend.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ink {
    /// The body itself.
    Body,
    /// A fixed reference (a wall, an axis).
    Fixed,
    /// Where the body is now.
    Current,
    /// A counted event.
    Event,
    /// Background detail.
    Dim,
}

impl Drawing {
    /// Whether the pane draws side and end views too.
    #[must_use]
    pub fn has_sides(&self) -> bool {
        matches!(self, Self::Body { side: Some(_), .. })
    }
}

/// A pivot shaken along the vertical: its height above its mean position is
/// `−stroke · cos(t/ε)` (in rod lengths), so that its acceleration is `(stroke/ε²) cos(t/ε)`,
/// the pendulum's `(b/ε) cos(t/ε)` when `stroke = b ε`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pivot {
    /// The half-travel, in rod lengths.
    pub stroke: f64,
    /// The fast time scale: the pivot's angular frequency is `1/ε`.
    pub epsilon: f64,
    /// Whether the scene's fast coordinate is a ripple about an averaged angle `Θ` (Kapitza's),
    /// drawn as the averaged rod; a pendulum without one draws its rod alone (issue 83).
    pub averaged: bool,
}

impl Pivot {
    /// The pivot's height above its mean position at time `t`, in rod lengths.
    #[must_use]
    pub fn height(&self, t: f64) -> f64 {
        -self.stroke * (t / self.epsilon).e_cos()
    }
}

/// A body's profile seen from the side: a half-ellipsoid, flat on top, its mass centre below
/// its centre (any unit: the body pane draws the shape to scale).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideView {
    /// Semi-axis along the body's x (long) axis.
    pub long: f64,
    /// Semi-axis along its y (cross) axis.
    pub cross: f64,
    /// Semi-axis along its z axis (the depth of the bottom).
    pub height: f64,
    /// How far the mass centre lies below the centre.
    pub offset: f64,
}

/// A scene's weak-* pane (`W`): what it costs and what it computes ([`Posed::weak`]).
pub trait WeakStudy {
    /// Predicted seconds of [`WeakStudy::view`] over `t_end` (its cost model, asked before the
    /// pane's job starts).
    fn seconds(&self, t_end: f64) -> f64;
    /// The weak-* view over a bounded horizon within `[0, t_end]` (at most a few thousand fast
    /// periods, whatever the small parameter).
    ///
    /// # Errors
    /// A failed or stopped integration.
    fn view(&self, t_end: f64, go_on: &mut dyn FnMut(f64) -> bool) -> Result<WeakView, StepError>;
}

/// The facts of one validated problem of a model.
pub trait Posed {
    /// Its scene.
    fn scene(&self) -> &'static Scene;
    /// Its parameter values, in the order of [`Scene::params`].
    fn values(&self) -> Vec<f64>;
    /// Its values, each checked against its row of its scene's table.
    ///
    /// # Errors
    /// The first value outside its range.
    fn checked_values(&self) -> Result<Vec<f64>, ParamError> {
        let values = self.values();
        ParamSpec::check_all(self.scene().params, &values)?;
        Ok(values)
    }
    /// The panel's derived lines.
    fn summary(&self) -> Vec<SummaryLine>;
    /// The slow start `(q0, q̇0)`.
    fn slow_start(&self) -> (f64, f64);
    /// Default fixed step of `method` at `tolerance` over `[0, t_end]`.
    fn default_step(&self, method: Method, tolerance: f64, t_end: f64) -> f64;
    /// What the body pane (`B`) draws of it.
    fn drawing(&self) -> Drawing;
    /// The slow coordinate's limit as the phase portrait draws it (issue 83: the scene's own,
    /// a [`FreeRotor`] for a scene without a limit).
    fn slow_limit(&self) -> std::sync::Arc<dyn SlowLimit>;
    /// Builds a concrete method's integration at `t = 0`, following `arithmetic` (a replay of
    /// an old file: the rules it was recorded with; each model follows the rules it has).
    ///
    /// # Errors
    /// `auto`, or a problem the method cannot represent.
    fn build(&self, ask: &Asked, arithmetic: Arithmetic) -> Result<Box<dyn Flow>, StepError>;
    /// Resolves `method` (the model's own `auto`).
    ///
    /// # Errors
    /// A failed or refused probe.
    fn resolve(&self, ask: &PlanRequest, go_on: &mut dyn FnMut(f64) -> bool) -> Planned;
    /// Predicted seconds of a run (the model's cost model).
    fn predicted_seconds(&self, ask: &Asked) -> f64;
    /// Its point on the scene's chart's axes ([`Studies::chart`]'s `axes`).
    fn chart_point(&self) -> (f64, f64);
    /// The scene's weak-* study (its cost and its computation), or `None` for a scene without
    /// one, whose [`Studies::weak`] is `None` too (`tests/it/scenes.rs` checks that both agree
    /// on every shipped preset). No default: a new scene says which it is (issue 69).
    fn weak(&self) -> Option<&dyn WeakStudy>;
    /// The slow coordinate on `samples` points of `[0, t_end]`: `auto` as the model plans it,
    /// `Method::Effective` the limit at [`Scene::limit_tolerance`].
    ///
    /// # Errors
    /// A failed, refused or stopped integration.
    fn slow_curve(&self, ask: &Asked, samples: usize, go_on: GoOn) -> Result<SlowCurve, StepError>;
}

/// A model's `Problem::from_values` and `Problem::table_values`, for a model whose parameter
/// table lists its `Params`' fields and then its `Start`'s, one number each, in the order given
/// here (the scene's `PARAMS`; `tests/it/scenes.rs` round-trips every shipped preset through
/// them).
macro_rules! table_order {
    (Params { $($p:ident),+ }, Start { $($s:ident),+ }) => {
        impl Problem {
            /// The problem of `values`, in the order of [`PARAMS`] (a missing value is NaN,
            /// refused as out of range).
            ///
            /// # Errors
            /// The first value outside its range, or a derived quantity that overflows.
            pub fn from_values(values: &[f64]) -> Result<Self, ParamError> {
                let mut v = values.iter().copied();
                let mut next = || v.next().unwrap_or(f64::NAN);
                Self::new(Params { $($p: next()),+ }, Start { $($s: next()),+ })
            }

            /// Its values in the order of [`PARAMS`].
            fn table_values(&self) -> Vec<f64> {
                let (p, s) = (self.params(), self.start());
                vec![$(p.$p),+, $(s.$s),+]
            }
        }
    };
}
pub(crate) use table_order;

/// The limit of a model as the phase portrait sees it: `E = ½ m q̇² + V(q)` with a periodic
/// `V`. Each scene gives its own ([`Posed::slow_limit`]); a scene without a limit gives a
/// [`FreeRotor`].
pub trait SlowLimit: std::fmt::Debug + Send + Sync {
    /// The mass of the slow coordinate.
    fn mass(&self) -> f64;
    /// The period of `V`.
    fn period(&self) -> f64;
    /// The centre of the period a wrapped portrait shows.
    fn wrap_centre(&self) -> f64;
    /// The period of the fast motion, when the explorer's samples could miss it.
    fn fast_period(&self) -> Option<f64>;
    /// `V(q)`.
    fn potential(&self, q: f64) -> f64;
    /// The highest separatrix level (the lowest potential when there is none).
    fn potential_max(&self) -> f64;
    /// The lowest potential.
    fn potential_min(&self) -> f64;
    /// Every separatrix level.
    fn separatrices(&self) -> Vec<f64>;
    /// `E_eff` of the start.
    fn energy(&self) -> f64;
    /// The start's slow rate, as a scale.
    fn rate_hint(&self) -> f64;
}

/// No limit: the free rotor `V = 0` (period π), whose level `½ m q̇² = E − E_rest` is the
/// largest rate the energy allows if none of it were in the fast motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeRotor {
    /// The moment of inertia of the slow coordinate.
    pub mass: f64,
    /// The energy above rest.
    pub energy: f64,
    /// The start's rate.
    pub q_dot0: f64,
}

impl SlowLimit for FreeRotor {
    fn mass(&self) -> f64 {
        self.mass
    }
    fn period(&self) -> f64 {
        std::f64::consts::PI
    }
    fn wrap_centre(&self) -> f64 {
        0.0
    }
    fn fast_period(&self) -> Option<f64> {
        None
    }
    fn potential(&self, _: f64) -> f64 {
        0.0
    }
    fn potential_max(&self) -> f64 {
        0.0
    }
    fn potential_min(&self) -> f64 {
        0.0
    }
    fn separatrices(&self) -> Vec<f64> {
        Vec::new()
    }
    fn energy(&self) -> f64 {
        self.energy
    }
    fn rate_hint(&self) -> f64 {
        self.q_dot0.abs()
    }
}

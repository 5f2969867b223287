//! The closed set of models: [`Model`] is the only door through which the worker (`sim`), the
//! explorer (`app`, `ui`), presets (`scenario`) and `simulate` reach a model.
//!
//! Each model lives in its own folder (`rattleback`: the files named in `physics/mod.rs`;
//! `kapitza/`) and is registered here once: its [`ModelKind`] (name, title, methods), its
//! [`Model`] variant (a validated problem), how it builds a [`Flow`], resolves `auto`, and the
//! [`LimitView`] the portrait draws (the slow coordinate's effective potential). Adding a third
//! model touches its folder and the arms of the matches in this file; the preset schema
//! (`scenario/preset.rs`), the parameter panel's rows (`app/fields.rs`) and `simulate`'s report
//! (`simulate/`) each add the model's own table, listed in docs/architecture.md.

use serde::Serialize;

use super::flow::{Flow, Sample};
use super::kapitza;
use super::rattleback::Problem;
use super::rattleback::effective::Effective;
use super::rattleback::integrators::{self, Integrator, Method, Settings, Stats, StepError};

/// Which model: names as in presets (`[preset] model = "kapitza"`; absent means the rattleback).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// The holonomic rattleback (a rigid body on a stiff spring).
    Rattleback,
    /// Kapitza's inverted pendulum (a pendulum on a fast-shaken pivot).
    Kapitza,
}

impl ModelKind {
    /// Every model, in the order lists show them.
    pub const ALL: [Self; 2] = [Self::Rattleback, Self::Kapitza];

    /// The tolerance of the limit's own run, whatever the user's (the one-degree-of-freedom ODE
    /// is cheap): `simulate` reports it and the explorer draws, counts and exports the same
    /// run. The rattleback's is then good to about 1e-12 (`tests/it/auto_honest.rs`).
    #[must_use]
    pub fn limit_tolerance(self) -> f64 {
        match self {
            Self::Rattleback => 1e-14,
            Self::Kapitza => 1e-13,
        }
    }

    /// The name used in presets and JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Rattleback => "rattleback",
            Self::Kapitza => "kapitza",
        }
    }

    /// The name for people.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::Rattleback => "holonomic rattleback",
            Self::Kapitza => "Kapitza's pendulum",
        }
    }

    /// Parses a name from [`ModelKind::name`] (any case).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name.trim()))
    }

    /// Comma-separated names, for error messages.
    #[must_use]
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// The methods this model offers, `auto` first.
    #[must_use]
    pub fn methods(self) -> &'static [Method] {
        match self {
            Self::Rattleback => &Method::ALL,
            Self::Kapitza => &kapitza::flows::METHODS,
        }
    }

    /// Whether this model offers `method`.
    #[must_use]
    pub fn offers(self, method: Method) -> bool {
        self.methods().contains(&method)
    }

    /// Comma-separated names of [`ModelKind::methods`].
    #[must_use]
    pub fn method_names(self) -> String {
        self.methods()
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Whether the model counts falls past the horizontal (the pendulum's second event).
    #[must_use]
    pub fn has_falls(self) -> bool {
        self == Self::Kapitza
    }

    /// What the model calls its slow coordinate and its events, for labels.
    #[must_use]
    pub fn words(self) -> Words {
        match self {
            Self::Rattleback => Words {
                parameter: "k",
                sup: "sup|alpha_k − alpha_eff|",
                q_name: "alpha",
                q_dot_name: "alpha_dot",
                q: "α",
                q_dot: "α̇",
                fast: "γ",
                event: "reversal",
                events: "reversals",
            },
            Self::Kapitza => Words {
                parameter: "epsilon",
                sup: "sup|theta_eps − theta_lim|",
                q_name: "theta",
                q_dot_name: "theta_dot",
                q: "θ",
                q_dot: "θ̇",
                fast: "θ−Θ",
                event: "swing",
                events: "swings",
            },
        }
    }
}

/// Labels of a model's variables and events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Words {
    /// The small parameter the limit is about (`k → ∞`, `ε → 0`), as in presets.
    pub parameter: &'static str,
    /// What the sweep measures, in words.
    pub sup: &'static str,
    /// The slow coordinate's name in presets (ASCII).
    pub q_name: &'static str,
    /// Its rate's.
    pub q_dot_name: &'static str,
    /// The slow coordinate.
    pub q: &'static str,
    /// Its rate.
    pub q_dot: &'static str,
    /// The fast coordinate.
    pub fast: &'static str,
    /// One event.
    pub event: &'static str,
    /// Events.
    pub events: &'static str,
}

/// A validated problem of one model.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Model {
    /// The rattleback: body, spring and start.
    Rattleback(Problem),
    /// The pendulum: `a`, `b`, `ε` and start.
    Kapitza(kapitza::Problem),
}

impl From<Problem> for Model {
    fn from(p: Problem) -> Self {
        Self::Rattleback(p)
    }
}

impl From<kapitza::Problem> for Model {
    fn from(p: kapitza::Problem) -> Self {
        Self::Kapitza(p)
    }
}

impl Model {
    /// Which model.
    #[must_use]
    pub fn kind(&self) -> ModelKind {
        match self {
            Self::Rattleback(_) => ModelKind::Rattleback,
            Self::Kapitza(_) => ModelKind::Kapitza,
        }
    }

    /// The rattleback's problem, when this is one.
    #[must_use]
    pub fn rattleback(&self) -> Option<&Problem> {
        match self {
            Self::Rattleback(p) => Some(p),
            Self::Kapitza(_) => None,
        }
    }

    /// The pendulum's problem, when this is one.
    #[must_use]
    pub fn kapitza(&self) -> Option<&kapitza::Problem> {
        match self {
            Self::Kapitza(p) => Some(p),
            Self::Rattleback(_) => None,
        }
    }

    /// The slow start `(q0, q̇0)`.
    #[must_use]
    pub fn slow_start(&self) -> (f64, f64) {
        match self {
            Self::Rattleback(p) => (p.start().alpha, p.start().alpha_dot),
            Self::Kapitza(p) => (p.start().theta, p.start().theta_dot),
        }
    }

    /// Default fixed step of `method` at `tolerance` over `[0, t_end]`.
    #[must_use]
    pub fn default_step(&self, method: Method, tolerance: f64, t_end: f64) -> f64 {
        match self {
            Self::Rattleback(p) => integrators::default_step(method, p, tolerance, t_end),
            Self::Kapitza(p) => kapitza::flows::default_step(method, p, tolerance, t_end),
        }
    }

    /// Builds a concrete method's integration at `t = 0`.
    ///
    /// # Errors
    /// `auto` ([`StepError::Unplanned`]), a method the model does not offer, or a problem the
    /// method cannot represent.
    pub fn build(
        &self,
        method: Method,
        settings: Settings,
        t_end: f64,
    ) -> Result<Box<dyn Flow>, StepError> {
        match self {
            Self::Rattleback(p) => Ok(Box::new(RattlebackFlow(integrators::build(
                method, p, settings, t_end,
            )?))),
            Self::Kapitza(p) => kapitza::flows::build(method, p, settings, t_end),
        }
    }

    /// Resolves `method` for this problem (see [`super::rattleback::plan::resolve`] for the rattleback's
    /// verified `auto`; the pendulum's `auto` is [`kapitza::plan::resolve`], chosen from the
    /// limit's predicted model error).
    ///
    /// # Errors
    /// As [`super::rattleback::plan::resolve`]; a method the model does not offer.
    pub fn resolve(
        &self,
        method: Method,
        tolerance: f64,
        t_end: f64,
        policy: super::plan::AutoPolicy,
        budget: f64,
        go_on: &mut dyn FnMut(f64) -> bool,
    ) -> Result<super::rattleback::plan::Resolution, StepError> {
        if !self.kind().offers(method) {
            return Err(StepError::NotOffered {
                method: method.name(),
                model: self.kind().name(),
            });
        }
        match self {
            Self::Rattleback(p) => {
                super::rattleback::plan::resolve(p, method, tolerance, t_end, policy, budget, go_on)
            }
            Self::Kapitza(p) => {
                let (plan, estimate) = if method == Method::Auto {
                    let c = kapitza::plan::resolve(p, tolerance, t_end);
                    let plan = super::plan::Resolved {
                        method: c.method,
                        tolerance: c.settings.tolerance,
                        step: None,
                    };
                    (plan, Some(c.estimate))
                } else {
                    let plan = super::plan::Resolved {
                        method,
                        tolerance,
                        step: None,
                    };
                    (plan, None)
                };
                Ok(super::rattleback::plan::Resolution {
                    plan,
                    verified: None,
                    estimate,
                })
            }
        }
    }

    /// Predicted seconds of a run of `method` (`auto` as it would plan) over `[0, t_end]`: the
    /// scene's own cost model, asked by every entry point before a run starts.
    #[must_use]
    pub fn predicted_seconds(
        &self,
        method: Method,
        tolerance: f64,
        step: Option<f64>,
        t_end: f64,
    ) -> f64 {
        match self {
            Self::Rattleback(p) => {
                super::rattleback::plan::predicted_seconds(p, method, tolerance, step, t_end)
            }
            Self::Kapitza(p) => kapitza::budget::cost_seconds(p, method, tolerance, step, t_end),
        }
    }

    /// What the portrait draws of the limit.
    #[must_use]
    pub fn limit_view(&self) -> LimitView {
        match self {
            Self::Rattleback(p) => LimitView::Rattleback(Effective::new(p)),
            Self::Kapitza(p) => {
                let limit = kapitza::limit::Limit::new(p.params());
                let s = p.start();
                LimitView::Kapitza {
                    limit,
                    // The limit as the theorem states it, from (θ0, θ̇0): the overlay's level.
                    energy: limit.energy_of(s.theta, s.theta_dot),
                    q_dot0: p.start().theta_dot,
                    epsilon: p.params().epsilon,
                }
            }
        }
    }
}

/// The rattleback's integrators seen through [`Flow`]: `q = α`, the event is `α̇`, the fast
/// coordinate `γ`; the state vector is `(γ, α, γ̇, α̇)`.
pub struct RattlebackFlow(pub Box<dyn Integrator>);

impl RattlebackFlow {
    fn at(&mut self, t: f64) -> super::rattleback::State {
        if t >= self.0.time() {
            self.0.state()
        } else {
            self.0.interpolate(t)
        }
    }
}

impl Flow for RattlebackFlow {
    fn boxed(&self) -> Box<dyn Flow> {
        Box::new(Self(self.0.boxed()))
    }
    fn method(&self) -> Method {
        self.0.method()
    }
    fn time(&self) -> f64 {
        self.0.time()
    }
    fn time_prev(&self) -> f64 {
        self.0.time_prev()
    }
    fn step(&mut self, t_limit: f64) -> Result<(), StepError> {
        self.0.step(t_limit)
    }
    fn sample(&mut self, t: f64) -> Sample {
        let y = self.at(t);
        Sample {
            q: y[super::rattleback::model::ALPHA],
            q_dot: y[super::rattleback::model::ALPHA_DOT],
            fast: y[super::rattleback::model::GAMMA],
        }
    }
    fn state_at(&mut self, t: f64) -> Vec<f64> {
        self.at(t).iter().copied().collect()
    }
    fn event_value(&self) -> f64 {
        self.0.alpha_dot()
    }
    fn locate_event(&mut self) -> f64 {
        self.0.locate_alpha_dot_zero()
    }
    fn energy(&self) -> f64 {
        self.0.energy()
    }
    fn stats(&self) -> Stats {
        self.0.stats()
    }
}

/// The limit of a model as the portrait sees it: `E = ½ m q̇² + V(q)` with a periodic `V`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LimitView {
    /// The rattleback's effective motion (`m = iz`, period π).
    Rattleback(Effective),
    /// The pendulum's limit (`m = 1`, period 2π).
    Kapitza {
        /// The limit.
        limit: kapitza::limit::Limit,
        /// `E_eff` of the averaged start.
        energy: f64,
        /// The start's rate.
        q_dot0: f64,
        /// The fast time scale.
        epsilon: f64,
    },
}

impl LimitView {
    /// The rattleback's effective motion, when this is one.
    #[must_use]
    pub fn effective(&self) -> Option<&Effective> {
        match self {
            Self::Rattleback(e) => Some(e),
            Self::Kapitza { .. } => None,
        }
    }

    /// The period of the fast motion, when the explorer's samples could miss it (the
    /// pendulum's `2π ε`; the rattleback's fast tilt is drawn only as an envelope).
    #[must_use]
    pub fn fast_period(&self) -> Option<f64> {
        match self {
            Self::Rattleback(_) => None,
            Self::Kapitza { epsilon, .. } => Some(2.0 * std::f64::consts::PI * epsilon),
        }
    }

    /// The mass of the slow coordinate.
    #[must_use]
    pub fn mass(&self) -> f64 {
        match self {
            Self::Rattleback(e) => e.params().iz,
            Self::Kapitza { .. } => 1.0,
        }
    }

    /// The period of `V`.
    #[must_use]
    pub fn period(&self) -> f64 {
        match self {
            Self::Rattleback(_) => std::f64::consts::PI,
            Self::Kapitza { .. } => 2.0 * std::f64::consts::PI,
        }
    }

    /// The centre of the period a wrapped portrait shows: the rattleback's potential minimum,
    /// the pendulum's upright.
    #[must_use]
    pub fn wrap_centre(&self) -> f64 {
        match self {
            Self::Rattleback(e) => {
                let p = e.params();
                if p.ix >= p.iy {
                    0.0
                } else {
                    std::f64::consts::FRAC_PI_2
                }
            }
            Self::Kapitza { .. } => 0.0,
        }
    }

    /// `V(q)`.
    #[must_use]
    pub fn potential(&self, q: f64) -> f64 {
        match self {
            Self::Rattleback(e) => e.potential(q),
            Self::Kapitza { limit, .. } => limit.potential(q),
        }
    }

    /// The highest separatrix level.
    #[must_use]
    pub fn potential_max(&self) -> f64 {
        match self {
            Self::Rattleback(e) => e.potential_max(),
            Self::Kapitza { limit, .. } => limit.potential_max(),
        }
    }

    /// The lowest potential.
    #[must_use]
    pub fn potential_min(&self) -> f64 {
        match self {
            Self::Rattleback(e) => e.potential_min(),
            Self::Kapitza { limit, .. } => limit.potential_min(),
        }
    }

    /// Every separatrix level (the rattleback has one; the pendulum one per unstable
    /// equilibrium).
    #[must_use]
    pub fn separatrices(&self) -> Vec<f64> {
        match self {
            Self::Rattleback(e) => {
                if e.potential_max() > e.potential_min() {
                    vec![e.potential_max()]
                } else {
                    Vec::new()
                }
            }
            Self::Kapitza { limit, .. } => limit.separatrices(),
        }
    }

    /// `E_eff` of the start.
    #[must_use]
    pub fn energy(&self) -> f64 {
        match self {
            Self::Rattleback(e) => e.energy(),
            Self::Kapitza { energy, .. } => *energy,
        }
    }

    /// `E_eff` of any slow state.
    #[must_use]
    pub fn energy_of(&self, q: f64, q_dot: f64) -> f64 {
        0.5 * self.mass() * q_dot * q_dot + self.potential(q)
    }

    /// The scale of the slow rate: the separatrix's height, the start's level, the start's rate.
    #[must_use]
    pub fn rate_scale(&self) -> f64 {
        let m = self.mass();
        let (lo, hi) = (self.potential_min(), self.potential_max());
        let sep = (2.0 * (hi - lo) / m).max(0.0).sqrt();
        let top = (2.0 * (self.energy() - lo) / m).max(0.0).sqrt();
        let q_dot0 = match self {
            Self::Rattleback(e) => e.spin_scale(),
            Self::Kapitza { q_dot0, .. } => q_dot0.abs(),
        };
        sep.max(top).max(q_dot0)
    }
}

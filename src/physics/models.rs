//! The closed set of models: [`Model`] is the only door through which the worker (`sim`), the
//! explorer (`app`, `ui`), presets (`scenario`) and `simulate` reach a model.
//!
//! Each model lives in its own folder and describes itself once there (`scene.rs`: a
//! [`Scene`] of fixed facts, [`Posed`] for a validated problem). It is registered here by one
//! line of the `registry!` list, which generates [`ModelKind`], [`Model`], [`Chart`],
//! [`ModelKind::ALL`], [`PlanKey`] and their dispatch, and the folders as modules; the [`LimitView`] the
//! portrait draws (the slow coordinate's effective potential) are still written here. The
//! recipe is in docs/architecture.md.

use serde::{Deserialize, Serialize};

use super::chart::{ChartError, ChartOf, PaneAsk, SceneChart, StudyAsk};
use super::kapitza;
use super::method::{Method, StepError};
use super::params::{ParamError, ParamSpec};
use super::plan::PlanRequest;
use super::rattleback::Problem;
use super::scene::{Planned, Posed, Scene, SlowLimit, SmallParameter, Studies, Words};

/// From the registry's list: the enums [`ModelKind`], [`Model`] and [`Chart`], their
/// conversions, [`ModelKind::ALL`] (test scenes included by their `cfg`) and every dispatch on
/// the kind. Each folder gives `Problem` (a [`Posed`]), `scene::SCENE` (a [`Scene`]) and its
/// chart type (a [`ChartOf`]).
macro_rules! registry {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $name:ident: $folder:ident, $chart:ident;
    )*) => {
        #[doc = "Which model: names as in presets (`[preset] model = \"kapitza\"`; absent means the rattleback)."]
        #[derive(
            Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, serde::Deserialize,
            schemars::JsonSchema,
        )]
        #[serde(rename_all = "kebab-case")]
        pub enum ModelKind {
            $( $(#[doc = $doc])* $(#[cfg($cfg)])? $name, )*
        }

        /// A validated problem of one model.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize)]
        #[serde(untagged)]
        pub enum Model {
            $( $(#[doc = $doc])* $(#[cfg($cfg)])? $name(crate::physics::$folder::Problem), )*
        }

        /// A chart of one scene: each scene's own type, in its folder (`SCENE/chart.rs`, issue
        /// 69), reached through [`SceneChart`] (this type derefs to it).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum Chart {
            $( $(#[doc = $doc])* $(#[cfg($cfg)])? $name(crate::physics::$folder::chart::$chart), )*
        }

        $(
            $(#[cfg($cfg)])?
            impl From<crate::physics::$folder::chart::$chart> for Chart {
                fn from(c: crate::physics::$folder::chart::$chart) -> Self {
                    Self::$name(c)
                }
            }

            $(#[cfg($cfg)])?
            impl From<crate::physics::$folder::Problem> for Model {
                fn from(p: crate::physics::$folder::Problem) -> Self {
                    Self::$name(p)
                }
            }
        )*

        /// Every model, in the registry's order.
        const LIST: &[ModelKind] = &[ $( $(#[cfg($cfg)])? ModelKind::$name, )* ];

        /// [`LIST`] as an array.
        const fn list<const N: usize>() -> [ModelKind; N] {
            let mut out = [LIST[0]; N];
            let mut i = 0;
            while i < N {
                out[i] = LIST[i];
                i += 1;
            }
            out
        }

        impl ModelKind {
            /// Every model, in the order lists show them (the scene contract's with the
            /// library's own tests).
            pub const ALL: [Self; LIST.len()] = list::<{ LIST.len() }>();

            /// The model's own description (the one dispatch on the kind).
            #[must_use]
            pub fn scene(self) -> &'static Scene {
                match self {
                    $( $(#[cfg($cfg)])? Self::$name => &crate::physics::$folder::scene::SCENE, )*
                }
            }

            /// A validated problem of this model from its parameter values, in the order of
            /// [`Scene::params`].
            ///
            /// # Errors
            /// The first value outside its range, or a derived quantity that overflows.
            pub fn problem(self, values: &[f64]) -> Result<Model, ParamError> {
                Ok(match self {
                    $( $(#[cfg($cfg)])?
                    Self::$name => Model::$name(crate::physics::$folder::Problem::from_values(values)?), )*
                })
            }
        }

        impl Model {
            /// The facts of this problem (the one dispatch on the problem).
            #[must_use]
            pub fn posed(&self) -> &(dyn Posed + 'static) {
                match self {
                    $( $(#[cfg($cfg)])? Self::$name(p) => p, )*
                }
            }

            /// Which model.
            #[must_use]
            pub fn kind(&self) -> ModelKind {
                match self {
                    $( $(#[cfg($cfg)])? Self::$name(_) => ModelKind::$name, )*
                }
            }
        }

        impl std::ops::Deref for Chart {
            type Target = dyn SceneChart;

            fn deref(&self) -> &Self::Target {
                match self {
                    $( $(#[cfg($cfg)])? Self::$name(c) => c, )*
                }
            }
        }

        impl Chart {
            /// The scene.
            #[must_use]
            pub fn model(&self) -> ModelKind {
                match self {
                    $( $(#[cfg($cfg)])? Self::$name(_) => ModelKind::$name, )*
                }
            }

            /// The explorer's map pane's chart of `model`.
            #[must_use]
            pub fn for_pane(model: &Model, ask: PaneAsk) -> Self {
                match model {
                    $( $(#[cfg($cfg)])?
                    Model::$name(p) => Self::$name(ChartOf::for_pane(p, ask)), )*
                }
            }

            /// `study map`'s chart of `model` as `ask` says.
            ///
            /// # Errors
            /// A flag of another scene's chart, a range out of order, or a corner the model
            /// refuses.
            pub fn for_study(model: &Model, ask: &StudyAsk) -> Result<Self, ChartError> {
                let title = model.kind().title();
                // Every flag the scene does not take, refused here for all (issue 80).
                crate::physics::chart::refuse_flags(
                    ask,
                    model.kind().studies().chart.flags,
                    title,
                )?;
                Ok(match model {
                    $( $(#[cfg($cfg)])?
                    Model::$name(p) => Self::$name(ChartOf::for_study(p, ask, title)?), )*
                })
            }

            /// `model` moved to the point `(x, y)` of this chart's axes (the scene's
            /// [`ChartOf::load`]).
            ///
            /// # Errors
            /// When the model is another scene's or the point is not a valid problem.
            pub fn load(&self, model: &Model, point: (f64, f64)) -> Result<Model, ChartError> {
                match (self, model) {
                    $( $(#[cfg($cfg)])?
                    (Self::$name(c), Model::$name(p)) => c.load(p, point).map(Model::from), )*
                    _ => return Err(ChartError::OtherScene),
                }
                .map_err(ChartError::Cell)
            }
        }

        /// What a plan was resolved for: `auto`'s choice depends on these only. Each scene's
        /// own shape (`SCENE/scene.rs`'s `PlanKey`), told apart by their fields, so files
        /// written before the pendulum existed read as before.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(untagged)]
        pub enum PlanKey {
            $( $(#[doc = $doc])* $(#[cfg($cfg)])? $name(crate::physics::$folder::scene::PlanKey), )*
        }

        impl PlanKey {
            /// The model it is a key of.
            #[must_use]
            pub const fn model(&self) -> ModelKind {
                match self {
                    $( $(#[cfg($cfg)])? Self::$name(_) => ModelKind::$name, )*
                }
            }

            /// The key of `model` run to `t_end` at `tolerance`.
            #[must_use]
            pub fn for_model(model: &Model, tolerance: f64, t_end: f64) -> Self {
                match model {
                    $( $(#[cfg($cfg)])?
                    Model::$name(p) => Self::$name(
                        crate::physics::$folder::scene::PlanKey::of(p, tolerance, t_end),
                    ), )*
                }
            }
        }
    };
}

/// The registry: one line a scene (its name, its folder under `physics`, its chart type). Every
/// dispatch over the scenes is generated from it: `with_scenes!(then)` calls the macro `then`
/// with the list (here `registry`; `simulate`'s dispatch to each folder's `report.rs`; …). A test scene carries its
/// `cfg` on its own line.
macro_rules! with_scenes {
    ($then:ident) => {
        $then! {
            /// The holonomic rattleback (a rigid body on a stiff spring).
            Rattleback: rattleback, RegimeChart;
            /// Kapitza's inverted pendulum (a pendulum on a fast-shaken pivot).
            Kapitza: kapitza, PendulumChart;
            #[doc = "The classical rattleback (an ellipsoidal bottom rolling without slipping)."]
            Celt: celt, CeltChart;
            /// The scene contract's oscillator (the library's own tests only).
            #[cfg(test)]
            Oscillator: oscillator, CrossingChart;
        }
    };
}
pub(crate) use with_scenes;

/// The scenes' folders as modules of `physics` (`with_scenes!(scene_modules)` in
/// `physics/mod.rs`): a scene's registry line declares its folder too.
macro_rules! scene_modules {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $name:ident: $folder:ident, $chart:ident;
    )*) => {
        $( $(#[cfg($cfg)])? pub mod $folder; )*
    };
}
pub(crate) use scene_modules;

with_scenes!(registry);

impl ModelKind {
    /// The model a preset without `[preset] model` is of: the one whose scene does not require
    /// the key (the first model, so that every older file keeps its meaning).
    #[must_use]
    pub fn default_kind() -> Self {
        Self::ALL
            .into_iter()
            .find(|m| !m.scene().model_required)
            .unwrap_or(Self::ALL[0])
    }

    /// The tolerance of the limit's own run, whatever the user's (the one-degree-of-freedom ODE
    /// is cheap): `simulate` reports it and the explorer draws, counts and exports the same
    /// run.
    #[must_use]
    pub fn limit_tolerance(self) -> f64 {
        self.scene().limit_tolerance
    }

    /// The name used in presets and JSON.
    #[must_use]
    pub fn name(self) -> &'static str {
        self.scene().name
    }

    /// The name for people.
    #[must_use]
    pub fn title(self) -> &'static str {
        self.scene().title
    }

    /// Parses a name from [`ModelKind::name`] (any case).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        super::method::named(&Self::ALL, Self::name, name)
    }

    /// Comma-separated names, for error messages.
    #[must_use]
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// The methods this model offers, `auto` first.
    #[must_use]
    pub fn methods(self) -> &'static [Method] {
        self.scene().methods
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

    /// What the model calls its slow coordinate and its events, for labels.
    #[must_use]
    pub fn words(self) -> Words {
        self.scene().words
    }

    /// Its parameters, in the panel's order.
    #[must_use]
    pub fn params(self) -> &'static [ParamSpec] {
        self.scene().params
    }

    /// Its small parameter, if it has a limit.
    #[must_use]
    pub fn small(self) -> Option<SmallParameter> {
        self.scene().small
    }

    /// The studies it offers.
    #[must_use]
    pub fn studies(self) -> Studies {
        self.scene().studies
    }
}

/// A model is its posed problem: `model.values()`, `model.build(…)`, `model.slow_curve(…)` and
/// every other fact of [`Posed`] are the model's own.
impl std::ops::Deref for Model {
    type Target = dyn Posed;
    fn deref(&self) -> &Self::Target {
        self.posed()
    }
}

impl Model {
    /// The rattleback's problem, when this is one.
    #[must_use]
    pub fn rattleback(&self) -> Option<&Problem> {
        if let Self::Rattleback(p) = self {
            Some(p)
        } else {
            None
        }
    }

    /// The pendulum's problem, when this is one.
    #[must_use]
    pub fn kapitza(&self) -> Option<&kapitza::Problem> {
        if let Self::Kapitza(p) = self {
            Some(p)
        } else {
            None
        }
    }

    /// The celt's problem, when this is one.
    #[must_use]
    pub fn celt(&self) -> Option<&super::celt::Problem> {
        if let Self::Celt(p) = self {
            Some(p)
        } else {
            None
        }
    }

    /// The value of the parameter `key`, if the model has one.
    #[must_use]
    pub fn value(&self, key: &str) -> Option<f64> {
        let i = self.kind().params().iter().position(|p| p.key == key)?;
        self.values().get(i).copied()
    }

    /// The same problem with the parameter `key` set to `value`, validated.
    ///
    /// # Errors
    /// The value, or a quantity derived from it, is out of range; a key the model does not
    /// have.
    pub fn with_value(&self, key: &'static str, value: f64) -> Result<Self, ParamError> {
        let kind = self.kind();
        let Some(i) = kind.params().iter().position(|p| p.key == key) else {
            return Err(ParamError::OutOfRange {
                field: key,
                value,
                allowed: "a parameter of the model",
            });
        };
        let mut values = self.values();
        values[i] = value;
        kind.problem(&values)
    }

    /// Resolves `method` for this problem: the model's own `auto` (the rattleback's verified
    /// one; the pendulum's chosen from the limit's predicted model error).
    ///
    /// # Errors
    /// The model's; a method the model does not offer.
    pub fn resolve(&self, ask: &PlanRequest, go_on: &mut dyn FnMut(f64) -> bool) -> Planned {
        if !self.kind().offers(ask.method) {
            return Err(StepError::NotOffered {
                method: ask.method.name(),
                model: self.kind().name(),
            });
        }
        self.posed().resolve(ask, go_on)
    }

    /// What the portrait draws of the limit (the scene's [`Posed::slow_limit`]).
    #[must_use]
    pub fn limit_view(&self) -> LimitView {
        LimitView {
            of: *self,
            view: self.posed().slow_limit(),
        }
    }
}

/// The limit of a problem as the portrait sees it (the scene's own [`SlowLimit`]), with the
/// problem it is of: two are equal when their problems are.
#[derive(Clone, Debug)]
pub struct LimitView {
    of: Model,
    view: std::sync::Arc<dyn SlowLimit>,
}

impl PartialEq for LimitView {
    fn eq(&self, other: &Self) -> bool {
        self.of == other.of
    }
}

impl std::ops::Deref for LimitView {
    type Target = dyn SlowLimit;

    fn deref(&self) -> &Self::Target {
        &*self.view
    }
}

impl LimitView {
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
        sep.max(top).max(self.rate_hint())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 83: the registry's one list gives every generated part: each kind once, the test
    /// scene among them in tests, each name leading back to its kind (each kind's problem and
    /// chart: `tests/it/scenes.rs`, on the shipped presets).
    #[test]
    fn each_registered_scene_is_listed_once_with_the_test_scene_in_tests() {
        for (i, kind) in ModelKind::ALL.into_iter().enumerate() {
            assert!(!ModelKind::ALL[..i].contains(&kind), "{kind:?} twice");
            assert_eq!(ModelKind::from_name(kind.name()), Some(kind));
        }
    }
}

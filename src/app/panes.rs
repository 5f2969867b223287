//! The panes of the explorer as a closed set with a visible set: the layout is computed from
//! the set, so a new pane is one variant, not a new branch per combination.

use super::key::{Binding, Key};

/// A pane of the main area. Its name in a recorded layout (and a lesson's `pane`) is the
/// variant's in snake case: a file format, so never rename one.
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Hash,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Pane {
    /// The parameter panel (left column).
    Params,
    /// The phase portrait.
    Portrait,
    /// The time series of `alpha_dot` and the energy error.
    Series,
    /// The stiffness sweep: `sup |α_k − α_eff|` against `k` (issue 12).
    Sweep,
    /// Weak-* convergence: `γ̇² g^{3/2}` pointwise and averaged (issue 12).
    Weak,
    /// The regime map: reversals over `(α̇0²/γ̇0², iy/ix)` with the critical curve (issue 12).
    Map,
    /// The current step of a lesson.
    Lesson,
    /// The body seen from above (issue 14).
    Body,
    /// The comparison: the run and a partner preset on one time axis (issue 26).
    Compare,
}

impl Pane {
    /// Every pane, in layout order.
    pub const ALL: [Self; 9] = [
        Self::Params,
        Self::Lesson,
        Self::Body,
        Self::Portrait,
        Self::Compare,
        Self::Series,
        Self::Sweep,
        Self::Weak,
        Self::Map,
    ];

    /// The panes a key shows, in the order the keymap (help, the footer) lists them.
    pub const KEYED: [Self; 6] = [
        Self::Series,
        Self::Sweep,
        Self::Weak,
        Self::Body,
        Self::Compare,
        Self::Map,
    ];

    /// Its row in the keymap, when a key shows and hides it (an empty `label` folds the row
    /// into the one above in help); its action is the pane (the keymap toggles it:
    /// `keys::pane_binding`).
    #[must_use]
    pub fn binding(self) -> Option<Binding<Self>> {
        let row = |key: &'static [Key], label, help, footer| Binding {
            keys: key,
            label,
            action: self,
            help,
            footer: Some(footer),
        };
        match self {
            Self::Series => Some(row(&[Key::Char('t')], "", "", ("t", "series", 7))),
            Self::Sweep => Some(row(
                &[Key::Char('K')],
                "K W M B / < >",
                "k-sweep / weak-* / map / body panes; < > window",
                ("K", "sweep", 10),
            )),
            Self::Weak => Some(row(&[Key::Char('W')], "", "", ("W", "weak-*", 10))),
            Self::Body => Some(row(&[Key::Char('B')], "", "", ("B", "body", 10))),
            Self::Compare => Some(row(
                &[Key::Char('C')],
                "C",
                "compare with a partner on one time axis",
                ("C", "compare", 9),
            )),
            Self::Map => Some(row(&[Key::Char('M')], "", "", ("M", "map", 10))),
            Self::Params | Self::Portrait | Self::Lesson => None,
        }
    }

    /// Share of the right-hand column's height (the parameter panel has its own column).
    #[must_use]
    pub fn weight(self) -> u16 {
        match self {
            Self::Params => 0,
            Self::Portrait => 65,
            Self::Series | Self::Sweep | Self::Weak => 35,
            Self::Map => 50,
            Self::Lesson => 30,
            Self::Body => 45,
            Self::Compare => 55,
        }
    }

    /// The pane a lesson step names (`portrait`, `series`, `sweep`, `weak`, `map`, `body`,
    /// `compare`): the portrait or a pane a key shows, by its recorded name.
    #[must_use]
    pub fn named(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|p| (p.toggle_action().is_some() || *p == Self::Portrait) && p.key() == name)
    }

    /// Its name in files (a recorded layout, a lesson's `pane`).
    #[must_use]
    pub fn key(self) -> String {
        serde_json::to_value(self)
            .ok()
            .and_then(|v| v.as_str().map(str::to_owned))
            .unwrap_or_default()
    }

    /// The action that shows or hides this pane, when a key does.
    #[must_use]
    pub fn toggle_action(self) -> Option<super::Action> {
        self.toggle_name().map(|_| super::Action::Toggle(self))
    }

    /// The name of its toggle in `[keys]` (a user's config file: never rename one), when a key
    /// shows and hides it.
    #[must_use]
    pub fn toggle_name(self) -> Option<&'static str> {
        match self {
            Self::Series => Some("toggle_series"),
            Self::Sweep => Some("toggle_sweep"),
            Self::Weak => Some("toggle_weak"),
            Self::Map => Some("toggle_map"),
            Self::Body => Some("toggle_body"),
            Self::Compare => Some("toggle_compare"),
            Self::Params | Self::Portrait | Self::Lesson => None,
        }
    }

    /// Whether `model`'s scene offers what the pane shows (its studies; the sweep needs a
    /// small parameter).
    #[must_use]
    pub fn offered_by(self, model: crate::physics::ModelKind) -> bool {
        let studies = model.studies();
        match self {
            // Every scene draws its body (the pendulum on its shaken pivot since issue 59) and
            // has a chart (`study::chart::Chart`), so `Studies` has no flag for either.
            Self::Params
            | Self::Portrait
            | Self::Series
            | Self::Lesson
            | Self::Compare
            | Self::Body
            | Self::Map => true,
            Self::Sweep => model.small().is_some(),
            Self::Weak => studies.weak.is_some(),
        }
    }

    /// The pane's name in messages.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Params => "parameter",
            Self::Portrait => "portrait",
            Self::Series => "time-series",
            Self::Sweep => "sweep",
            Self::Weak => "weak-*",
            Self::Map => "regime-map",
            Self::Lesson => "lesson",
            Self::Body => "body",
            Self::Compare => "compare",
        }
    }

    /// Whether the user may hide it.
    #[must_use]
    pub fn optional(self) -> bool {
        matches!(
            self,
            Self::Series
                | Self::Sweep
                | Self::Weak
                | Self::Map
                | Self::Lesson
                | Self::Body
                | Self::Compare
        )
    }
}

/// The visible panes: one bit per [`Pane`], in a word wide enough for every pane (a new pane
/// past the width fails to compile, not at run time); and when each was last brought to the
/// front, so a column too short for every pane shows the most recent ones first and lists the
/// rest (`Tab` cycles them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panes {
    shown: u32,
    /// Per pane, the order it was brought to the front in (higher: more recent).
    stamp: [u16; Pane::ALL.len()],
    /// The last stamp given.
    clock: u16,
}

const _: () = assert!(
    Pane::ALL.len() <= u32::BITS as usize,
    "Panes holds one bit per pane: widen it"
);

impl Default for Panes {
    fn default() -> Self {
        Self::of(&[Pane::Params, Pane::Portrait])
    }
}

impl Panes {
    fn bit(pane: Pane) -> u32 {
        1 << pane as u32
    }

    /// A set of panes, brought to the front in the order listed.
    #[must_use]
    pub fn of(panes: &[Pane]) -> Self {
        let mut p = Self {
            shown: 0,
            stamp: [0; Pane::ALL.len()],
            clock: 0,
        };
        for pane in panes {
            p.set(*pane, true);
        }
        p
    }

    /// Whether `pane` is shown.
    #[must_use]
    pub fn shows(self, pane: Pane) -> bool {
        self.shown & Self::bit(pane) != 0
    }

    /// Shows (bringing it to the front) or hides `pane` (only optional panes can be hidden).
    pub fn set(&mut self, pane: Pane, on: bool) {
        if on {
            if !self.shows(pane) {
                self.front(pane);
            }
            self.shown |= Self::bit(pane);
        } else if pane.optional() {
            self.shown &= !Self::bit(pane);
        }
    }

    /// Brings `pane` to the front (the most recent).
    fn front(&mut self, pane: Pane) {
        if self.clock == u16::MAX {
            // Renumber, keeping the order.
            let mut order: Vec<usize> = (0..self.stamp.len()).collect();
            order.sort_by_key(|&i| self.stamp[i]);
            for (rank, i) in order.into_iter().enumerate() {
                self.stamp[i] = rank as u16;
            }
            self.clock = self.stamp.len() as u16;
        }
        self.clock += 1;
        self.stamp[pane as usize] = self.clock;
    }

    /// Toggles `pane`.
    pub fn toggle(&mut self, pane: Pane) {
        self.set(pane, !self.shows(pane));
    }

    /// The shown panes a key toggles, the most recent last (what a recorded layout lists; a
    /// replay brings them to the front in that order).
    #[must_use]
    pub fn toggled(self) -> Vec<Pane> {
        let mut panes: Vec<Pane> = Pane::ALL
            .into_iter()
            .filter(|p| p.toggle_action().is_some() && self.shows(*p))
            .collect();
        panes.sort_by_key(|p| self.stamp[*p as usize]);
        panes
    }

    /// The order a recording keeps: the panes a key toggles and, once Tab has brought it in
    /// front of one of them, the portrait; least recent first. (A portrait behind every other
    /// says nothing, and is left out as files before issue 68 had it.)
    #[must_use]
    pub fn ordered(self) -> Vec<Pane> {
        let mut panes = self.toggled();
        if self.shows(Pane::Portrait) {
            panes.push(Pane::Portrait);
            panes.sort_by_key(|p| self.stamp[*p as usize]);
            if panes.first() == Some(&Pane::Portrait) {
                panes.remove(0);
            }
        }
        panes
    }

    /// Brings the shown panes to the front in the order of `recent` (the most recent last), as
    /// a recorded layout lists them.
    pub fn order_as(&mut self, recent: &[Pane]) {
        for pane in recent {
            if self.shows(*pane) {
                self.front(*pane);
            }
        }
    }

    /// Sends the most recent optional pane to the back (`Tab`: the next one comes to the
    /// front); whether there was one to cycle (two or more shown).
    pub fn cycle(&mut self) -> bool {
        // The portrait takes its turn too: at 80×24 a pane opened beside it (B) takes its
        // place, and Tab gives it back (issue 68).
        let mut recent = self.toggled();
        if self.shows(Pane::Portrait) {
            recent.push(Pane::Portrait);
            recent.sort_by_key(|p| self.stamp[*p as usize]);
        }
        if recent.len() < 2 {
            return false;
        }
        let Some(last) = recent.pop() else {
            return false;
        };
        // The front goes behind every other: the others keep their order above it.
        recent.insert(0, last);
        self.order_as(&recent);
        true
    }

    /// The visible panes of the right-hand column, with their weights, in layout order.
    #[must_use]
    pub fn column(self) -> Vec<(Pane, u16)> {
        Pane::ALL
            .into_iter()
            .filter(|p| *p != Pane::Params && self.shows(*p))
            .map(|p| (p, p.weight()))
            .collect()
    }

    /// How recently `pane` was brought to the front (higher: more recent).
    #[must_use]
    pub fn recency(self, pane: Pane) -> u16 {
        self.stamp[pane as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pane_a_key_shows_has_its_row_its_toggle_name_and_its_place_in_the_keymap() {
        for p in Pane::ALL {
            let row = super::super::keys::pane_binding(p);
            assert_eq!(row.is_some(), p.toggle_name().is_some(), "{p:?}");
            let listed = Pane::KEYED.iter().filter(|k| **k == p).count();
            assert_eq!(listed, usize::from(row.is_some()), "{p:?} in KEYED");
            if let Some(row) = row {
                assert_eq!(row.action, super::super::keys::Action::Toggle(p));
            }
        }
    }

    #[test]
    fn the_column_lists_the_visible_panes_in_order() {
        let mut p = Panes::default();
        assert_eq!(p.column(), vec![(Pane::Portrait, 65)]);
        p.toggle(Pane::Series);
        assert_eq!(p.column(), vec![(Pane::Portrait, 65), (Pane::Series, 35)]);
        p.set(Pane::Portrait, false);
        assert!(p.shows(Pane::Portrait), "the portrait cannot be hidden");
    }

    #[test]
    fn a_pane_a_key_shows_is_named_by_its_key() {
        for p in Pane::ALL {
            let named = p.toggle_action().is_some() || p == Pane::Portrait;
            assert_eq!(
                Pane::named(&p.key()),
                named.then_some(p),
                "{p:?} as {}",
                p.key()
            );
        }
        assert_eq!(Pane::Compare.key(), "compare");
        assert_eq!(Pane::Series.key(), "series");
    }

    #[test]
    fn the_most_recent_pane_is_in_front_and_tab_cycles() {
        let mut p = Panes::default();
        p.set(Pane::Series, true);
        p.set(Pane::Sweep, true);
        p.set(Pane::Weak, true);
        assert_eq!(p.toggled(), [Pane::Series, Pane::Sweep, Pane::Weak]);
        // The portrait behind every other is left out of the recorded order.
        assert_eq!(p.ordered(), [Pane::Series, Pane::Sweep, Pane::Weak]);
        assert!(p.cycle());
        assert_eq!(p.toggled(), [Pane::Weak, Pane::Series, Pane::Sweep]);
        assert_eq!(
            p.ordered(),
            [Pane::Weak, Pane::Portrait, Pane::Series, Pane::Sweep]
        );
        assert!(p.cycle());
        assert!(p.cycle());
        // The portrait's turn (issue 68): in front of every other.
        assert_eq!(p.ordered().last(), Some(&Pane::Portrait));
        assert!(p.cycle());
        assert_eq!(
            p.ordered(),
            [Pane::Series, Pane::Sweep, Pane::Weak],
            "round"
        );
        // A recorded order is restored.
        let mut q = Panes::of(&[
            Pane::Params,
            Pane::Portrait,
            Pane::Weak,
            Pane::Series,
            Pane::Sweep,
        ]);
        q.order_as(&[Pane::Series, Pane::Sweep, Pane::Weak]);
        assert_eq!(q.toggled(), p.toggled());
        let mut one = Panes::default();
        assert!(!one.cycle(), "the portrait alone: nothing to cycle");
        one.set(Pane::Map, true);
        assert!(one.cycle(), "a pane and the portrait take turns");
        assert_eq!(one.ordered(), [Pane::Map, Pane::Portrait]);
        let mut none = Panes::of(&[Pane::Params]);
        assert!(!none.cycle(), "no pane: nothing to cycle");
    }

    #[test]
    fn every_pane_has_its_own_bit() {
        for a in Pane::ALL {
            let mut p = Panes::of(&[]);
            p.set(a, true);
            for b in Pane::ALL {
                assert_eq!(p.shows(b), a == b, "{a:?} set, {b:?} read");
            }
        }
    }
}

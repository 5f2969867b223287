//! The status bar: time, state, speed, reversals (full and limit), energy error, method and
//! `auto`'s verdict, integration rate. Reverse video, so it reads without colour. When it is
//! narrow, whole fields are dropped by priority; a number is never cut.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Paragraph, Widget};

use super::Look;
use super::marks::{Facts, Section};
use crate::app::fields::Settings;
use crate::app::{PlanState, ReplayInfo, RunState};
use crate::physics::scene::Monitor;

/// The status bar: what it shows, borrowed.
pub struct StatusBar<'a> {
    /// The run and its clock.
    pub run: &'a RunState,
    /// The settings (end time, method, tolerance).
    pub settings: &'a Settings,
    /// The replay's state, when replaying.
    pub replay: Option<ReplayInfo>,
    /// A recording is on.
    pub recording: bool,
    /// The limit is shown.
    pub overlay: bool,
}

/// A segment's horizon: whole as a whole number, else to the hundredth as the time is shown.
fn horizon(t: f64) -> String {
    if t.fract() == 0.0 && t.abs() < 1e15 {
        format!("{t:.0}")
    } else {
        format!("{t:.2}")
    }
}

/// A field of the status bar and its priority (0 is kept first), with a shorter form for a
/// narrow bar.
struct Field {
    text: String,
    short: Option<String>,
    priority: u8,
}

fn field(text: String, priority: u8) -> Field {
    Field {
        text,
        short: None,
        priority,
    }
}

impl Field {
    /// The same field, shortened to `short` where the whole text would push out another field.
    fn or_short(self, short: &str) -> Self {
        Self {
            short: Some(short.to_owned()),
            ..self
        }
    }

    fn shortest(&self) -> &str {
        self.short.as_deref().unwrap_or(&self.text)
    }
}

/// The status fields in display order.
fn fields(bar: &StatusBar<'_>) -> Vec<Field> {
    let run = bar.run;
    let s = bar.settings;
    let mut out = Vec::new();
    if bar.recording {
        out.push(field("● REC".to_owned(), 0));
    }
    out.push(field(
        format!("t {:.2}/{}", run.shown, crate::physics::Number(s.t_end)),
        0,
    ));
    let verified = run.verified();
    // The display has caught up with the verification ahead and waits for it.
    let waits = !run.segments.is_empty()
        && verified < s.t_end
        && run.shown >= run.reached
        && run.reached + run.sample_dt > verified;
    let state = match run.plan {
        _ if run.failed.is_some() => "failed".to_owned(),
        PlanState::Verifying { run: 0, .. } => "verifying auto…".to_owned(),
        PlanState::Verifying { run, percent } => format!("verifying auto… run {run} at {percent}%"),
        _ if run.done() => "done".to_owned(),
        _ if waits && run.playing => match run.ahead {
            Some(a) if a.run > 0 => {
                format!("verifying ahead… run {} at {}%", a.run, a.percent)
            }
            _ => "verifying ahead…".to_owned(),
        },
        // A replay (or a followed lecture) that has ended moves no more: not `▶` beside
        // "lecture ended" (issue 81).
        _ if run.playing && bar.replay.is_some_and(replay_over) => "stopped".to_owned(),
        _ if run.playing => "▶".to_owned(),
        _ => "paused".to_owned(),
    };
    out.push(field(state, 0));
    match bar.replay {
        Some(r) => out.extend(replay_fields(r)),
        None => out.push(field(format!("×{}", run.speed), 1)),
    }
    let kind = s.model.kind();
    // A scene without a limit (the celt) has no limit's events to count.
    let limit = if bar.overlay && kind.small().is_some() {
        format!(" limit {}", run.effective_reversals_shown())
    } else {
        String::new()
    };
    out.push(field(
        format!("{} {}{limit}", kind.words().events, run.reversals_shown()),
        0,
    ));
    if let (Some(n), Some(second)) = (run.second_shown(), kind.words().second_events) {
        out.push(field(format!("{} {n}", second.name), 1));
    }
    if let Some(f) = monitor_field(kind.words().monitor, run.current().map(|p| p.energy_error)) {
        out.push(f);
    }
    let method = match run.plan {
        PlanState::Running { plan, .. } if plan.method != s.method => {
            format!("{}→{}", s.method, plan.method)
        }
        _ => s.method.to_string(),
    };
    out.push(field(method, 4));
    if let PlanState::Running {
        estimate: Some(e), ..
    } = run.plan
    {
        // A missed tolerance is kept before anything but the time: the numbers on screen are
        // not as accurate as asked, and the user must see it. A met one before the energy
        // monitor and the method: it says how accurate the numbers on screen are, which the
        // others only hint at (at 80 columns, recording, there is room for one of the three).
        if e <= s.tolerance {
            out.push(field(format!("est {e:.0e} ✓"), 2));
        } else {
            out.push(field(format!("est {e:.0e} ✗ tol missed"), 1));
        }
    }
    if let Some(at) = run.stops.filter(|_| run.failed.is_none()) {
        out.push(field(format!("✗ stops at t {}", horizon(at)), 1));
    } else if !run.segments.is_empty() && verified < s.t_end && run.failed.is_none() {
        out.push(field(format!("verified to {}", horizon(verified)), 2));
    }
    if let Some(from) = run.missed_ahead(s.tolerance) {
        // Known before it is shown: said at once.
        out.push(field(format!("✗ tol missed after t {}", horizon(from)), 1));
    }
    // The rate only while something runs (paused, it would be a stale number).
    if run.playing && !run.done() {
        let rate = human(run.rate);
        let unit = if rate == "1" { "step/s" } else { "steps/s" };
        out.push(field(format!("{rate} {unit}"), 5));
    }
    out
}

/// What the bar shows, for the legend: the fields `fields` writes, in the scene's words.
#[must_use]
pub fn legend(f: &Facts<'_>, _look: &Look<'_>) -> Section {
    let words = f.kind.words();
    let mut s = Section::new("status bar")
        .note("t shown/end · ▶ playing, paused, done, verifying…, stopped (a replay at its end) · ×speed")
        .note("replay ×pace, paused, ended · chapter n/N · following live, f forks");
    let events = match f.kind.small() {
        Some(small) => format!(
            "{} N limit M: the full motion's and the limit's ({}), up to t shown; one is {}",
            words.events, small.limit, words.event_meaning
        ),
        None => format!(
            "{} N: up to t shown; one is {}",
            words.events, words.event_meaning
        ),
    };
    s = s.note(events);
    if let Some(second) = words.second_events {
        s = s.note(format!(
            "{} N: up to t shown; one is {}",
            second.name, second.meaning
        ));
    }
    s.note(monitor_note(words.monitor))
        .note("method, or auto→the method auto chose")
        .note("est E ✓: auto's verified error, within the tolerance (✗: missed)")
        .note("N steps/s: the integration rate, while playing · ● REC: recording")
}

/// The monitor's field at the displayed point's error (none for a scene that monitors nothing).
fn monitor_field(monitor: Option<Monitor>, error: Option<f64>) -> Option<Field> {
    Some(field(format!("{} {:.1e}", monitor?.label, error?), 3))
}

/// The legend's line of the monitor, in the scene's words.
fn monitor_note(monitor: Option<Monitor>) -> String {
    match monitor {
        Some(m) => format!("{}: {}, at the displayed point", m.label, m.meaning),
        None => "no monitor: the scene has no conserved quantity to watch".to_owned(),
    }
}

/// Whether a replay has shown all there is: its recording's end, or a followed lecture that has
/// ended and been shown to its end.
fn replay_over(r: ReplayInfo) -> bool {
    r.ended && r.live != Some(false)
}

/// A replay's or a follower's fields: its state, the lecture's clock, the chapter or the fork.
fn replay_fields(r: ReplayInfo) -> Vec<Field> {
    let mut out = Vec::new();
    if r.live.is_some() {
        let state = if r.live == Some(true) {
            field("lecturer's recording ended".to_owned(), 0).or_short("lecture ended")
        } else if r.paused {
            // The follower paused itself (the lecture goes on): shortened where the
            // estimate would not fit beside it.
            field("following, paused".to_owned(), 0).or_short("you paused")
        } else {
            field("● following live".to_owned(), 0).or_short("● live")
        };
        out.push(state);
        // The fork's hint, then the verified estimate (the lecturer's, at 80 columns too),
        // then the lecture's wall time.
        out.push(field(format!("{:.0} s", r.at), 3));
        out.push(field("f forks".to_owned(), 1));
    } else {
        let state = if r.ended {
            "replay ended".to_owned()
        } else if r.paused {
            "replay paused".to_owned()
        } else {
            format!("replay ×{}", r.pace)
        };
        out.push(field(state, 0));
        // After the verified estimate: at 80 columns with chapters there is room for one.
        out.push(field(format!("{:.0}/{:.0} s", r.at, r.length), 3));
        // A session without chapters has nothing to count (and at 80 columns the field
        // would push out the verified estimate).
        if r.chapters > 0 {
            out.push(field(format!("chapter {}/{}", r.chapter, r.chapters), 1));
        }
    }
    out
}

/// The highest priority a field is shortened for: a field keeps its whole text rather than make
/// room for a field of lower priority (the energy error, the method, the rate, positions).
const SHORTENED_FOR: u8 = 2;

/// The fields that fit in `width`, in display order: the fields of priority up to
/// [`SHORTENED_FOR`] that fit in their shortest forms, by priority; then each of them in its
/// whole text where the room left allows; then the others where they fit.
fn fit(fields: &[Field], width: usize) -> String {
    let sep = " │ ";
    let chars = |s: &str| s.chars().count();
    let mut keep: Vec<Option<&str>> = vec![None; fields.len()];
    let mut used = 1;
    let mut order: Vec<usize> = (0..fields.len()).collect();
    order.sort_by_key(|&i| (fields[i].priority, i));
    let (first, rest): (Vec<usize>, Vec<usize>) = order
        .into_iter()
        .partition(|&i| fields[i].priority <= SHORTENED_FOR);
    for &i in &first {
        let shortest = fields[i].shortest();
        let w = chars(shortest) + if used > 1 { chars(sep) } else { 0 };
        if used + w <= width {
            keep[i] = Some(shortest);
            used += w;
        }
    }
    for &i in &first {
        if let Some(shown) = keep[i] {
            let more = chars(&fields[i].text).saturating_sub(chars(shown));
            if more > 0 && used + more <= width {
                keep[i] = Some(&fields[i].text);
                used += more;
            }
        }
    }
    for &i in &rest {
        for text in [fields[i].text.as_str(), fields[i].shortest()] {
            let w = chars(text) + if used > 1 { chars(sep) } else { 0 };
            if used + w <= width {
                keep[i] = Some(text);
                used += w;
                break;
            }
        }
    }
    let kept: Vec<&str> = keep.into_iter().flatten().collect();
    format!(" {}", kept.join(sep))
}

impl Widget for StatusBar<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let text = fit(&fields(&self), area.width as usize);
        Paragraph::new(text)
            .style(Style::default().add_modifier(Modifier::REVERSED))
            .render(area, buf);
    }
}

fn human(v: f64) -> String {
    if v >= 1e6 {
        format!("{:.1}M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1}k", v / 1e3)
    } else {
        format!("{v:.0}")
    }
}

#[cfg(test)]
mod tests {

    /// Issue 83: the monitor is the scene's; a scene with no conserved quantity shows none,
    /// and the legend says so.
    #[test]
    fn a_scene_without_a_monitor_shows_none_and_says_so() {
        let m = crate::physics::ModelKind::Kapitza.words().monitor;
        let shown = monitor_field(m, Some(2.5e-9)).map(|f| f.text);
        assert_eq!(shown.as_deref(), Some("ΔE_eff 2.5e-9"));
        assert!(monitor_note(m).starts_with("ΔE_eff: the drift of the limit's energy"));
        assert!(monitor_field(None, Some(2.5e-9)).is_none());
        assert!(monitor_field(m, None).is_none());
        assert!(monitor_note(None).contains("no conserved quantity"));
    }
    use super::*;

    #[test]
    fn narrow_bars_drop_whole_fields_by_priority() {
        let f = vec![
            field("t 1.00/30".to_owned(), 0),
            field("ΔE/E -5.6e-10".to_owned(), 2),
            field("a-rather-long-method-name".to_owned(), 3),
            field("reversals 2".to_owned(), 0),
        ];
        let text = fit(&f, 40);
        assert_eq!(text, " t 1.00/30 │ ΔE/E -5.6e-10 │ reversals 2");
        assert!(text.chars().count() <= 40);
    }

    #[test]
    fn a_field_is_shortened_before_another_is_dropped() {
        let f = vec![
            field("t 1.00/30".to_owned(), 0),
            field("● following live".to_owned(), 0).or_short("● live"),
            field("est 5e-11 ✓".to_owned(), 2),
        ];
        // Room for all three only with the short form; then for the whole text.
        assert_eq!(fit(&f, 40), " t 1.00/30 │ ● live │ est 5e-11 ✓");
        assert_eq!(fit(&f, 50), " t 1.00/30 │ ● following live │ est 5e-11 ✓");
        // Too narrow for the estimate: the kept field takes its whole text.
        assert_eq!(fit(&f, 30), " t 1.00/30 │ ● following live");
    }
}

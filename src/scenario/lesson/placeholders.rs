//! A step's placeholders written from its condition and its scene (split from
//! `lesson/mod.rs`): `{time}`, `{reversals}`, `{at_least}`, `{at_most}`, `{section.key}` and
//! `{panel.LABEL}`, so what the student reads is what the step uses.

use super::Until;
use crate::scenario::preset::Preset;

/// A condition's number as the step's text and its "not yet" line both write it: one writer,
/// so the two never disagree (issue 55: "≥ 0.911" beside a threshold of 0.910).
#[must_use]
pub fn condition_value(v: f64) -> String {
    // Every digit the value has (the threshold a student must pass is exactly it), in
    // exponent form when long (`1e10`, not `10000000000`).
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// A scene's value as the panel shows it: 6 decimals at most with trailing zeros dropped, or
/// 7 significant digits in exponent form when very large or small (`1e-7`, `2.5e6`).
fn shown_value(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        let s = format!("{v:.6e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    } else {
        crate::scenario::text::format_number(v)
    }
}

/// The step's text (or prompt) with its placeholders written: `{at_least}`, `{at_most}`,
/// `{time}` and `{reversals}` from its condition, `{section.key}` from its scenario
/// ([`condition_value`] writes both); a placeholder without its value is a problem.
pub(super) fn with_placeholders(
    text: &str,
    until: &Until,
    scene: Option<&Preset>,
    path: &str,
    at: &mut dyn FnMut(&str, String),
) -> String {
    let bound = until.parameter.as_ref();
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let Some(close) = rest[open..].find('}').map(|c| open + c) else {
            out.push_str(&rest[open..]);
            rest = "";
            break;
        };
        let name = &rest[open + 1..close];
        let value = match name {
            "at_least" => bound.and_then(|b| b.at_least),
            "at_most" => bound.and_then(|b| b.at_most),
            "time" => until.time,
            "reversals" => until.reversals.map(|n| n as f64),
            key if key.starts_with("panel.") => {
                // What the panel's row shows, written as the panel writes it.
                if let Some(v) = scene.and_then(|p| panel_value(p, &key["panel.".len()..])) {
                    out.push_str(&v);
                    rest = &rest[close + 1..];
                    continue;
                }
                None
            }
            key if key.contains('.') => {
                // A scene's value as a student reads it beside the panel: 6 decimals at most,
                // `1.378405`, not `1.378404875209022` (issue 81, D-11).
                if let Some(v) = scene.and_then(|p| scene_value(p, key)) {
                    out.push_str(&shown_value(v));
                    rest = &rest[close + 1..];
                    continue;
                }
                None
            }
            _ => None,
        };
        if let Some(v) = value {
            out.push_str(&condition_value(v));
        } else {
            let why = match name {
                "at_least" | "at_most" | "time" | "reversals" => {
                    "the step's [step.until] has no such value".to_owned()
                }
                key if key.starts_with("panel.") => format!(
                    "the panel of the step's scene has no number `{}`; it has {}",
                    &key["panel.".len()..],
                    scene.map_or_else(String::new, |p| p
                        .model
                        .summary()
                        .iter()
                        .filter(|l| matches!(l.value, crate::physics::scene::Shown::Number(_)))
                        .map(|l| format!("{{panel.{}}}", l.label))
                        .collect::<Vec<_>>()
                        .join(", "))
                ),
                key if key.contains('.') => format!(
                    "the step's scene ({}) has no parameter `{key}`",
                    scene.map_or("none", |p| p.model.kind().name())
                ),
                _ => "allowed: {time}, {reversals}, {at_least}, {at_most}, {section.key} \
                          (a parameter of the step's scene, as `--set` names it), {panel.LABEL} \
                          (a number the panel shows)"
                    .to_owned(),
            };
            at(
                path,
                format!("{{{name}}} is written in the text, but {why}"),
            );
            out.push_str(&rest[open..=close]);
        }
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    out
}

/// The panel's number `label` for `preset` (`critical`, `b^2-2a`, `skew δ°`), as the panel
/// writes it.
fn panel_value(preset: &Preset, label: &str) -> Option<String> {
    preset
        .model
        .summary()
        .into_iter()
        .find(|l| l.label == label)
        .and_then(|l| match l.value {
            crate::physics::scene::Shown::Number(Some(v)) => {
                Some(crate::scenario::text::format_number(v))
            }
            _ => None,
        })
}

/// The value of `section.key` in `preset` (a model parameter or `run.t_end`/`run.tolerance`).
fn scene_value(preset: &Preset, key: &str) -> Option<f64> {
    match key {
        "run.t_end" => Some(preset.run.t_end),
        "run.tolerance" => preset.run.tolerance,
        _ => {
            let (section, name) = key.split_once('.')?;
            let kind = preset.model.kind();
            kind.params()
                .iter()
                .any(|p| p.section == section && p.key == name)
                .then(|| preset.model.value(name))
                .flatten()
        }
    }
}

//! Issue 25: each model's scene is complete and agrees with itself: its parameter table, its
//! values, its small parameter, its studies and its shipped presets.

use rattleback::physics::{Method, ModelKind};
use rattleback::scenario::Preset;
use rattleback::scenario::shipped::{SHIPPED, base_preset};

fn shipped_of(kind: ModelKind) -> Vec<Preset> {
    SHIPPED
        .iter()
        .map(|(name, text)| Preset::parse(text, name, name, &[]).unwrap())
        .filter(|p| p.model.kind() == kind)
        .collect()
}

#[test]
fn every_scene_is_complete_and_agrees_with_itself() {
    for kind in ModelKind::ALL {
        let scene = kind.scene();
        let params = scene.params;
        assert_eq!(scene.name, kind.name());
        // Keys are unique: a panel row, a preset key and a `--set` name each.
        for (i, p) in params.iter().enumerate() {
            assert!(
                params[i + 1..].iter().all(|q| q.key != p.key),
                "{}: {} twice",
                kind.name(),
                p.key
            );
            assert!(!p.doc.is_empty(), "{}: {} undocumented", kind.name(), p.key);
        }
        let presets = shipped_of(kind);
        assert!(!presets.is_empty(), "{} ships no preset", kind.name());
        let base = base_preset(kind);
        let (_, text) = SHIPPED.iter().find(|(n, _)| *n == base).unwrap();
        assert_eq!(
            Preset::parse(text, base, base, &[]).unwrap().model.kind(),
            kind,
            "{}: base preset {base} is of another scene",
            kind.name()
        );
        for preset in &presets {
            let values = preset.model.values();
            assert_eq!(values.len(), params.len(), "{}", preset.name);
            // The table's values build the same problem back.
            assert_eq!(
                kind.problem(&values).unwrap(),
                preset.model,
                "{}",
                preset.name
            );
            assert!(!preset.model.summary().is_empty(), "{}", preset.name);
            let (q, q_dot) = preset.model.slow_start();
            let words = scene.words;
            // A slow coordinate that is a parameter (the rattleback's α, the pendulum's θ)
            // starts at its value; one that is not (the celt's turn and spin) is checked below.
            if kind.params().iter().any(|p| p.key == words.q_name) {
                assert_eq!(preset.model.value(words.q_name), Some(q), "{}", preset.name);
                assert_eq!(
                    preset.model.value(words.q_dot_name),
                    Some(q_dot),
                    "{}",
                    preset.name
                );
            } else {
                assert!(
                    q.abs() < f64::MIN_POSITIVE,
                    "{}: a derived slow coordinate starts at 0",
                    preset.name
                );
                assert!(q_dot.is_finite(), "{}", preset.name);
            }
            // The weak-* view is there exactly when the scene says so (a stopped run answers
            // at once).
            let weak = preset.model.weak();
            assert_eq!(
                weak.is_some(),
                scene.studies.weak.is_some(),
                "{}",
                preset.name
            );
            if let Some(weak) = weak {
                // Its price is a real one (a job is admitted by it), and a stopped view answers
                // at once.
                let seconds = weak.seconds(preset.run.t_end);
                assert!(
                    seconds.is_finite() && seconds > 0.0,
                    "{}: {seconds}",
                    preset.name
                );
                drop(weak.view(1.0, &mut |_| false));
            }
        }
        if let Some(small) = scene.small {
            let spec = params
                .iter()
                .find(|p| p.key == small.key)
                .expect("the small parameter is a parameter");
            assert!(
                small.ladder.iter().all(|x| spec.allowed.contains(*x)),
                "{}: a rung out of range",
                kind.name()
            );
            let model = presets[0].model;
            let rung = model.with_value(small.key, small.ladder[0]).unwrap();
            assert_eq!(rung.value(small.key), Some(small.ladder[0]));
        }
        assert_eq!(scene.methods[0], Method::Auto, "{}", kind.name());
    }
}

#[test]
fn a_value_outside_the_table_is_refused_with_its_key_and_range() {
    for kind in ModelKind::ALL {
        let model = shipped_of(kind)[0].model;
        for p in kind.params() {
            let err = model.with_value(p.key, f64::NAN).unwrap_err();
            assert_eq!(err.field(), p.key);
            assert!(err.to_string().contains(p.allowed.text()), "{err}");
        }
        assert!(model.with_value("no-such-key", 1.0).is_err());
    }
}

/// Issue 83: every part the registry generates leads back to the scene: its presets' problems,
/// their charts, a chart refusing another scene's problem.
#[test]
fn every_generated_part_leads_back_to_its_scene() {
    use rattleback::physics::models::Chart;
    use rattleback::study::chart::PaneAsk;
    for (i, kind) in ModelKind::ALL.into_iter().enumerate() {
        let model = shipped_of(kind)[0].model;
        assert_eq!(model.kind(), kind);
        assert_eq!(kind.problem(&model.values()).unwrap(), model);
        let ask = PaneAsk {
            t_end: 1.0,
            tolerance: 1e-6,
            full: false,
            axes_from: (0.0, 0.0),
        };
        let chart = Chart::for_pane(&model, ask);
        assert_eq!(chart.model(), kind);
        let other = ModelKind::ALL[(i + 1) % ModelKind::ALL.len()];
        let theirs = shipped_of(other)[0].model;
        assert!(chart.load(&theirs, (0.0, 0.0)).is_err(), "{kind:?}");
    }
}

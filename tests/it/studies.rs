//! The limit's studies (issue 12): the stiffness sweep's convergence rate, the regime map
//! against the paper's theorems, and weak-* convergence.

use crate::common;

use rattleback::scenario::shipped::resolve;
use rattleback::study::map::{Grid, Source, regime_map};
use rattleback::study::sweep::{ladder, sweep};
use rattleback::study::weak::weak_star;

#[test]
fn the_sweep_converges_like_one_over_k_on_the_default_preset() {
    let preset = resolve("subcritical", &[]).unwrap();
    let s = sweep(
        &preset.model,
        ladder(rattleback::physics::ModelKind::Rattleback),
        preset.run.t_end,
        1e-8,
        &|_| true,
        &|| {},
    )
    .unwrap();
    eprintln!("{:?} slope {:?}", s.sup_error(), s.slope);
    let slope = s.slope.expect("a slope");
    assert!((slope + 1.0).abs() <= 0.2, "slope {slope}");
    // Every rung is closer to the limit than the one before it, from k = 1e2 on.
    for w in s.rungs.windows(2).skip(1) {
        assert!(
            w[1].sup_error < w[0].sup_error,
            "{} then {}",
            w[0].sup_error,
            w[1].sup_error
        );
    }
    assert_eq!(s.t.len(), s.limit.len());
    assert!(s.rungs.iter().all(|r| r.alpha.len() == s.t.len()));
}

#[test]
fn every_map_cell_away_from_the_critical_curve_obeys_the_theorems() {
    let grid = Grid::new(120, 60, 2.0, 1.0, 1.0, 30.0);
    let map = regime_map(&grid, Source::Limit, &|_| true).unwrap();
    assert_eq!(map.cells.len(), 120 * 60);
    let dr = grid.ratio_max / 120.0;
    let mut checked = 0;
    for (n, c) in map.cells.iter().enumerate() {
        let j = n / 120;
        // One cell away in both directions: this row's neighbours' critical ratios too.
        let neighbours: Vec<Option<f64>> = [j.saturating_sub(1), j, (j + 1).min(59)]
            .iter()
            .map(|&r| grid.critical(grid.inertia_ratio(r)))
            .collect();
        if neighbours.iter().all(Option::is_none) {
            assert_eq!(
                c.reversals, 0,
                "iy/ix = {} ≥ 1 never reverses",
                c.inertia_ratio
            );
            checked += 1;
        } else if neighbours.iter().all(Option::is_some) {
            let lo = neighbours
                .iter()
                .map(|x| x.unwrap())
                .fold(f64::INFINITY, f64::min);
            let hi = neighbours.iter().map(|x| x.unwrap()).fold(0.0, f64::max);
            if c.ratio < lo - dr {
                assert!(c.reversals > 0, "below the critical ratio: {c:?}");
                checked += 1;
            } else if c.ratio > hi + dr {
                assert_eq!(c.reversals, 0, "above the critical ratio: {c:?}");
                checked += 1;
            }
        }
    }
    assert!(checked > 6000, "{checked} cells checked");
    assert!(!map.critical.is_empty());
}

#[test]
fn weak_star_averages_settle_while_pointwise_values_swing() {
    let preset = resolve("subcritical", &["spring.k=1e6".parse().unwrap()]).unwrap();
    for window in [1.0, 3.0] {
        let w = weak_star(preset.problem().unwrap(), 30.0, window, &mut |_| true).unwrap();
        let (lo, hi) = w.pointwise_range();
        let dev = w.worst_average_deviation();
        eprintln!(
            "w = {window}: θ {} pointwise [{lo}, {hi}], worst average {dev:e}",
            w.theta
        );
        assert!(dev < 0.01, "w = {window}: the averages stray by {dev}");
        assert!(
            lo < 0.01 * w.theta && hi > 1.98 * w.theta,
            "[{lo}, {hi}] vs θ {}",
            w.theta
        );
    }
    // A window shorter than the fast period does not settle: the test can tell.
    let short = weak_star(preset.problem().unwrap(), 30.0, 1e-3, &mut |_| true).unwrap();
    assert!(short.worst_average_deviation() > 0.1);
}

#[test]
fn study_commands_keep_their_json_contract_and_write_their_files() {
    let dir = std::env::temp_dir().join(format!("rattleback-study-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().unwrap();
    let (code, json, err) = common::bin(&["study", "sweep", "--format", "json", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["stiffness"].as_array().unwrap().len(), 8);
    assert_eq!(v["sup_error"].as_array().unwrap().len(), 8);
    let slope = v["slope"].as_f64().unwrap();
    assert!((slope + 1.0).abs() < 0.2, "{slope}");
    for f in ["sweep.csv", "sweep_curves.csv", "sweep.svg"] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    assert!(csv.starts_with("stiffness,sup_error,method,estimate\n"));
    assert_eq!(csv.lines().count(), 9);

    let (code, json, err) = common::bin(&[
        "study", "map", "--grid", "20x10", "--format", "json", "--out", out,
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 200);
    for key in ["ratio", "inertia_ratio", "reversals"] {
        assert!(cells[0].get(key).is_some(), "{key}");
    }
    assert!(!v["critical"].as_array().unwrap().is_empty());
    assert!(dir.join("map.svg").is_file() && dir.join("map.csv").is_file());
    // Files are never replaced silently.
    let (code, _, err) = common::bin(&["study", "map", "--grid", "20x10", "--out", out]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--force"), "{err}");
    let (code, _, err) = common::bin(&["study", "map", "--grid", "20x10", "--out", out, "--force"]);
    assert_eq!(code, 0, "{err}");
    // Bad input: one line, exit 2.
    let (code, _, err) = common::bin(&["study", "map", "--inertia-min", "3", "--inertia-max", "2"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--inertia-min"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 28: a study that takes more than a second shows an indicatif bar on stderr only when
/// stderr is a terminal (checked by hand in tmux: `study map: 306 of 1200 cells [====>  ] 26%`,
/// erased at the end); through a pipe, as here, stderr stays empty and stdout is the data.
#[test]
fn a_long_study_prints_no_progress_into_a_pipe() {
    let started = std::time::Instant::now();
    let (code, out, err) = crate::common::bin(&[
        "study", "map", "--grid", "32x16", "--k", "1e4", "--force", "--format", "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "progress leaked into a pipe: {err:?}");
    assert_eq!(out.lines().count(), 1 + 32 * 16);
    // The check means something only if a terminal would have seen a bar: the run outlasted
    // the quiet first second (a floor on a shared machine, never a speed target).
    let took = started.elapsed().as_secs_f64();
    assert!(
        took > 1.0,
        "the run took {took:.2} s: too short for the bar to show; enlarge it"
    );
}

/// Issue 70: in a terminal, a chart's progress line says how many cells are done and the time
/// left, from the cost model at first and the pace as cells finish (seen in tmux at 80×24:
/// `study map: 1101 of 5000 cells, 12 s left [===>            ]  22%`). Run in a
/// pseudo-terminal of its own (`script`), with stdout to a file: the line is on stderr.
#[test]
fn a_charts_progress_in_a_terminal_says_the_time_left() {
    let dir = std::env::temp_dir().join(format!("rb-progress-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (log, out) = (dir.join("pty.out"), dir.join("map.json"));
    let command = format!(
        "stty rows 24 cols 80; exec {} study map --preset celt-clockwise --grid 80x40 --force --format json > {}",
        crate::common::program(),
        out.display()
    );
    let status = crate::common::in_pty(&command, &log)
        .stdin(std::process::Stdio::null())
        .status()
        .expect("`script` (util-linux) gives the study a pseudo-terminal");
    assert!(status.success());
    let seen = String::from_utf8_lossy(&std::fs::read(&log).unwrap()).into_owned();
    let chart: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let wall = chart["wall_seconds"].as_f64().unwrap();
    // The check means something only if the bar had time to show (a floor on a shared
    // machine, never a speed target).
    assert!(
        wall > 1.3,
        "the chart took {wall:.2} s: too short for the bar to show; enlarge it"
    );
    assert!(seen.contains(" of 3200 cells computed, "), "{seen:?}");
    assert!(seen.contains(" s left"), "{seen:?}");
    assert!(chart["predicted_seconds"].as_f64().unwrap() > 0.0);
    let _ = std::fs::remove_dir_all(&dir);
}

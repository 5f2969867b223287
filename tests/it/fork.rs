//! `auto`'s independent computations on two cores (issue 27: `physics::fork`, `parallel`): the
//! answer is the one computed on one core, bit for bit; a cancellation reaches the pool thread;
//! a panic there reaches the caller; inside the pool the two run on the calling thread.
//!
//! The pool is installed for the rest of this test process: every other test that reaches
//! `auto` afterwards runs the two-core way too, and must (and does) get the same answers.

// Stiffnesses are picked by the fixture's exact values.
#![allow(clippy::float_cmp)]

use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::common;

use rattleback::parallel;
use rattleback::physics::fork::{both, sequentially};
use rattleback::physics::rattleback::auto::run_auto;

fn installed() {
    parallel::install();
    assert!(rattleback::physics::fork::installed());
}

#[test]
fn auto_on_two_cores_answers_as_on_one_bit_for_bit() {
    installed();
    let cases = common::averaged_cases();
    let before = parallel::ran_elsewhere();
    let mut compared = 0;
    for case in &cases {
        // Both starts, each method auto picks (taylor, averaged3, averaged2), a first auto
        // (probes run) and one with them kept.
        if !["A", "B"].contains(&case.start.as_str())
            || ![1e2, 1e3, 1e4, 1e6, 1e8].contains(&case.k)
        {
            continue;
        }
        for tolerance in [1e-8, 1e-10] {
            let two = run_auto(&case.problem, tolerance, case.t_end, 17, true)
                .map(|v| format!("{v:?}"))
                .map_err(|e| e.to_string());
            let one = sequentially(|| {
                run_auto(&case.problem, tolerance, case.t_end, 17, true)
                    .map(|v| format!("{v:?}"))
                    .map_err(|e| e.to_string())
            });
            assert_eq!(two, one, "{} at tolerance {tolerance:e}", case.name);
            compared += 1;
        }
    }
    assert!(compared >= 16, "only {compared} cases compared");
    if rayon::current_num_threads() >= 2 {
        // Not vacuous: a pool thread took part of the work (a run's companion or a probe).
        assert!(
            parallel::ran_elsewhere() > before,
            "no computation ran on the pool"
        );
    }
}

#[test]
fn a_cancellation_reaches_the_pool_thread_and_a_panic_the_caller() {
    installed();
    if rayon::current_num_threads() < 2 {
        return;
    }
    // `here` ends at once; `there` runs until told to stop (or 20 s, a failure). The caller's
    // go_on says stop on its third question, asked while the caller waits.
    let stopped = Arc::new(AtomicBool::new(false));
    let asked = AtomicU32::new(0);
    let start = Instant::now();
    let flag = Arc::clone(&stopped);
    let ((), ran_for) = both(
        &mut |_| asked.fetch_add(1, Ordering::Relaxed) < 2,
        |_| {},
        move |go_on| {
            let began = Instant::now();
            while began.elapsed() < Duration::from_secs(20) {
                if !go_on(0.0) {
                    flag.store(true, Ordering::Relaxed);
                    break;
                }
                std::thread::sleep(Duration::from_millis(1));
            }
            began.elapsed()
        },
    );
    assert!(stopped.load(Ordering::Relaxed), "there ran {ran_for:?}");
    assert!(asked.load(Ordering::Relaxed) >= 3);
    assert!(start.elapsed() < Duration::from_secs(10));

    let caught = std::panic::catch_unwind(|| {
        both(
            &mut |_| true,
            |_| std::thread::sleep(Duration::from_millis(50)),
            |_| panic!("a failure on the pool"),
        )
    });
    assert!(
        caught.is_err(),
        "the pool thread's panic reached the caller"
    );
}

#[test]
fn inside_the_pool_both_run_on_the_calling_thread() {
    installed();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .expect("a pool");
    let threads = Mutex::new(Vec::new());
    pool.install(|| {
        let me = std::thread::current().id();
        let (here, there) = both(
            &mut |_| true,
            |_| std::thread::current().id(),
            |_| std::thread::current().id(),
        );
        threads.lock().unwrap().extend([me, here, there]);
    });
    let t = threads.into_inner().unwrap();
    assert_eq!((t[1], t[2]), (t[0], t[0]));
}

#[test]
fn cancelling_a_two_core_auto_stops_it() {
    installed();
    let case = common::averaged_cases()
        .into_iter()
        .find(|c| c.start == "B" && c.k == 1e4)
        .expect("rotating start at k = 1e4");
    let problem = case.problem;
    // Cancelled on the 20th question: mid-run, with the verification on the pool.
    let asked = AtomicU32::new(0);
    let r = rattleback::physics::rattleback::auto::run_auto_cancellable(
        &problem,
        &rattleback::physics::method::RunSpec {
            method: rattleback::physics::Method::Auto,
            tolerance: 1e-10,
            step: None,
            t_end: 300.0,
            samples: 0,
            monitor_energy: false,
        },
        f64::INFINITY,
        &mut |_| asked.fetch_add(1, Ordering::Relaxed) < 20,
    );
    assert!(
        matches!(r, Err(rattleback::physics::StepError::Cancelled { .. })),
        "{r:?}"
    );
}

//! The worker thread around an [`Engine`]: idle, it blocks on its command channel; busy, it
//! works in slices bounded in wall time and checks for commands between them, so a pause, a
//! restart or a quit takes effect within a frame. `auto`'s planning is cancelled as soon as a
//! restart or a quit is waiting. Events of a slice are coalesced before they are sent; the sink
//! is bounded, so when the UI is slow, `send` blocks.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::{Command, Engine, PlanBook, SimEvent};

/// Steps between two looks at the clock and the channel.
const CHUNK_STEPS: usize = 256;
/// Longest slice of work between two sends.
const SLICE: Duration = Duration::from_millis(8);
/// How long an idle worker waits for a command before looking at the verification ahead.
const WAIT: Duration = Duration::from_millis(5);

/// A running worker; dropping it without [`Worker::join`] leaves the thread to stop by itself
/// when its sink closes.
pub struct Worker {
    commands: Sender<Command>,
    handle: Option<JoinHandle<()>>,
}

impl Worker {
    /// Spawns the worker; `sink` delivers events and returns `false` once nobody listens,
    /// which stops the worker.
    ///
    /// # Panics
    /// When the OS cannot spawn a thread.
    pub fn spawn(sink: impl FnMut(SimEvent) -> bool + Send + 'static) -> Self {
        Self::spawn_with(PlanBook::default(), sink)
    }

    /// [`Worker::spawn`] resolving `auto` with `book` (replays pass the recorded plans).
    ///
    /// # Panics
    /// When the OS cannot spawn a thread.
    pub fn spawn_with(book: PlanBook, sink: impl FnMut(SimEvent) -> bool + Send + 'static) -> Self {
        let (commands, rx) = mpsc::channel();
        let handle = std::thread::Builder::new()
            .name("rattleback-sim".to_owned())
            .spawn(move || run(&rx, Engine::new(book), sink))
            .expect("spawn the integration worker");
        Self {
            commands,
            handle: Some(handle),
        }
    }

    /// Sends a command (ignored if the worker has stopped).
    pub fn send(&self, command: Command) {
        let _ = self.commands.send(command);
    }

    /// Asks the worker to stop and waits at most `limit` for it; a worker still busy then is
    /// left to end with the process (quitting never waits on a long step).
    pub fn join_within(mut self, limit: Duration) {
        let _ = self.commands.send(Command::Quit);
        let Some(h) = self.handle.take() else {
            return;
        };
        let end = Instant::now() + limit;
        while !h.is_finished() && Instant::now() < end {
            std::thread::sleep(Duration::from_millis(2));
        }
        if h.is_finished() {
            let _ = h.join();
        }
    }

    /// Asks the worker to stop and waits for it (at most one slice: planning is cancelled by
    /// the quit).
    pub fn join(mut self) {
        let _ = self.commands.send(Command::Quit);
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

/// Moves every waiting command into `queue`; a closed channel becomes a quit.
fn drain(rx: &Receiver<Command>, queue: &mut VecDeque<Command>) {
    loop {
        match rx.try_recv() {
            Ok(c) => queue.push_back(c),
            Err(TryRecvError::Empty) => return,
            Err(TryRecvError::Disconnected) => {
                queue.push_back(Command::Quit);
                return;
            }
        }
    }
}

/// Merges consecutive sample batches of one run and overlay life into one event.
fn coalesce(events: Vec<SimEvent>) -> Vec<SimEvent> {
    let mut out: Vec<SimEvent> = Vec::with_capacity(events.len());
    for e in events {
        if let (
            Some(SimEvent::Samples {
                generation: g0,
                epoch: e0,
                full: f0,
                effective: v0,
                t: t0,
                steps: s0,
            }),
            SimEvent::Samples {
                generation,
                epoch,
                full,
                effective,
                t,
                steps,
            },
        ) = (out.last_mut(), &e)
            && *g0 == *generation
            && *e0 == *epoch
        {
            f0.extend_from_slice(full);
            v0.extend_from_slice(effective);
            *t0 = t.or(*t0);
            *s0 = *steps;
            continue;
        }
        out.push(e);
    }
    out.retain(|e| {
        !matches!(e, SimEvent::Samples { full, effective, .. } if full.is_empty() && effective.is_empty())
    });
    out
}

fn run(rx: &Receiver<Command>, mut engine: Engine, mut sink: impl FnMut(SimEvent) -> bool) {
    let shared = RefCell::new(VecDeque::new());
    loop {
        let mut queue_now = shared.borrow_mut();
        let queue = &mut *queue_now;
        if queue.is_empty() {
            if engine.waiting() {
                // Only the verification ahead is going on: look at its reports a few times a
                // frame, and at commands as they come.
                match rx.recv_timeout(WAIT) {
                    Ok(c) => queue.push_back(c),
                    Err(RecvTimeoutError::Timeout) => {}
                    Err(RecvTimeoutError::Disconnected) => return,
                }
            } else if engine.busy() {
                drain(rx, queue);
            } else {
                match rx.recv() {
                    Ok(c) => queue.push_back(c),
                    Err(_) => return,
                }
            }
        }
        if let Some(c) = queue.pop_front() {
            if !engine.handle(&c, &mut sink) {
                return;
            }
            continue;
        }
        drop(queue_now);
        // A slice: chunks of steps until the slice's time is up or a command waits.
        let end = Instant::now() + SLICE;
        let mut events = Vec::new();
        let mut stop = false;
        {
            // Planning's progress goes out at once (planning is one slice, which may be long);
            // the rest is gathered and coalesced.
            let mut collect = |e| match e {
                SimEvent::PlanProgress { .. } => sink(e),
                e => {
                    events.push(e);
                    true
                }
            };
            // Planning is cancelled only by what makes it moot: a restart or a quit.
            let mut go_on = |_t: f64| {
                let mut q = shared.borrow_mut();
                drain(rx, &mut q);
                !q.iter()
                    .any(|c| matches!(c, Command::Restart { .. } | Command::Quit))
            };
            // Waiting for the verification ahead: one look at its reports.
            while engine.busy() || engine.waiting() {
                if !engine.work(CHUNK_STEPS, &mut go_on, &mut collect) {
                    stop = true;
                    break;
                }
                if engine.waiting() {
                    break;
                }
                if Instant::now() >= end {
                    break;
                }
                let mut q = shared.borrow_mut();
                drain(rx, &mut q);
                if !q.is_empty() {
                    break;
                }
            }
        }
        let mut sent = Vec::new();
        std::mem::swap(&mut sent, &mut events);
        for e in coalesce(sent) {
            if !sink(e) {
                return;
            }
        }
        if stop {
            return;
        }
    }
}

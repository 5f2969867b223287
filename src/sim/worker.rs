//! The worker thread around a [`Session`]: idle, it blocks on its command channel; busy, it
//! works in chunks of steps and checks for commands between chunks, so a restart cancels
//! in-flight work at once. Its sink is bounded: when the UI is slow, `send` blocks.

use std::collections::VecDeque;
use std::sync::mpsc::{self, Receiver, Sender, TryRecvError};
use std::thread::JoinHandle;

use super::{Command, Session, SimEvent};

/// Steps per chunk between command checks.
const CHUNK_STEPS: usize = 2_000;

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
        let (commands, rx) = mpsc::channel();
        let handle = std::thread::Builder::new()
            .name("rattleback-sim".to_owned())
            .spawn(move || run(&rx, sink))
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

    /// Asks the worker to stop and waits for it.
    pub fn join(mut self) {
        let _ = self.commands.send(Command::Quit);
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

struct Pending {
    generation: u64,
    target: f64,
    sample_dt: f64,
}

/// The worker's state between commands.
struct Loop {
    session: Option<Session>,
    pending: Option<Pending>,
    /// Checkpoints wait until the run reaches their time; the run stops there first so the
    /// step containing the time is the last one (the trajectory is the same either way).
    checkpoints: VecDeque<(u64, f64)>,
    /// Sample spacing of the last advance, kept for checkpoint-only advances.
    last_dt: f64,
}

impl Loop {
    fn busy(&self) -> bool {
        self.pending.is_some() || !self.checkpoints.is_empty()
    }

    /// Takes a command; `false` means stop.
    fn handle(&mut self, command: &Command, sink: &mut impl FnMut(SimEvent) -> bool) -> bool {
        match *command {
            Command::Quit => return false,
            Command::Restart { generation, spec } => {
                let s = Session::new(generation, spec);
                let started = SimEvent::Started {
                    generation,
                    method: s.method(),
                };
                self.session = Some(s);
                self.pending = None;
                self.checkpoints.clear();
                return sink(started);
            }
            Command::AdvanceTo {
                generation,
                t,
                sample_dt,
            } => {
                if self
                    .session
                    .as_ref()
                    .is_some_and(|s| s.generation() == generation)
                {
                    self.pending = Some(Pending {
                        generation,
                        target: t,
                        sample_dt,
                    });
                }
            }
            Command::Checkpoint { generation, t } => self.checkpoints.push_back((generation, t)),
            Command::SetEffective(on) => {
                if let Some(s) = self.session.as_mut() {
                    s.set_effective(on);
                }
            }
        }
        true
    }

    /// Works one chunk towards the next target or checkpoint; `false` means stop.
    fn work(&mut self, sink: &mut impl FnMut(SimEvent) -> bool) -> bool {
        let Some(s) = self.session.as_mut() else {
            self.pending = None;
            self.checkpoints.clear();
            return true;
        };
        self.checkpoints.retain(|(g, _)| *g == s.generation());
        if self
            .pending
            .as_ref()
            .is_some_and(|p| p.generation != s.generation())
        {
            self.pending = None;
        }
        let due = self.checkpoints.front().map(|c| c.1);
        let target = match (self.pending.as_ref(), due) {
            (Some(p), Some(c)) => p.target.min(c),
            (Some(p), None) => p.target,
            (None, Some(c)) => c,
            (None, None) => return true,
        };
        if let Some(p) = self.pending.as_ref() {
            self.last_dt = p.sample_dt;
        }
        let (events, reached) = s.advance(target, self.last_dt, CHUNK_STEPS);
        for e in events {
            if !sink(e) {
                return false;
            }
        }
        if !reached {
            return true;
        }
        if let Some(c) = due.filter(|c| *c <= target) {
            self.checkpoints.pop_front();
            let generation = s.generation();
            if let Some((state, reversals)) = s.checkpoint(c)
                && !sink(SimEvent::Checkpoint {
                    generation,
                    t: c,
                    state,
                    reversals,
                })
            {
                return false;
            }
        }
        if self.pending.as_ref().is_some_and(|p| target >= p.target) {
            self.pending = None;
        }
        true
    }
}

fn run(rx: &Receiver<Command>, mut sink: impl FnMut(SimEvent) -> bool) {
    let mut state = Loop {
        session: None,
        pending: None,
        checkpoints: VecDeque::new(),
        last_dt: 0.1,
    };
    loop {
        // Block when idle, poll when busy: commands are checked between chunks, so a restart
        // cancels in-flight work at once.
        let command = if state.busy() {
            match rx.try_recv() {
                Ok(c) => Some(c),
                Err(TryRecvError::Empty) => None,
                Err(TryRecvError::Disconnected) => return,
            }
        } else {
            match rx.recv() {
                Ok(c) => Some(c),
                Err(_) => return,
            }
        };
        let go_on = match command {
            Some(c) => state.handle(&c, &mut sink),
            None => state.work(&mut sink),
        };
        if !go_on {
            return;
        }
    }
}

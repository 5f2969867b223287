//! The worker thread around a [`Session`]: idle, it blocks on its command channel; busy, it
//! works in chunks of steps and checks for commands between chunks, so a restart cancels
//! in-flight work at once. Its sink is bounded: when the UI is slow, `send` blocks.

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

fn run(rx: &Receiver<Command>, mut sink: impl FnMut(SimEvent) -> bool) {
    let mut session: Option<Session> = None;
    let mut pending: Option<Pending> = None;
    loop {
        // Block when idle, poll when busy.
        let command = if pending.is_some() {
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
        match command {
            Some(Command::Quit) => return,
            Some(Command::Restart { generation, spec }) => {
                let s = Session::new(generation, spec);
                let started = SimEvent::Started {
                    generation,
                    method: s.method(),
                };
                session = Some(s);
                pending = None;
                if !sink(started) {
                    return;
                }
                continue;
            }
            Some(Command::AdvanceTo {
                generation,
                t,
                sample_dt,
            }) => {
                if session
                    .as_ref()
                    .is_some_and(|s| s.generation() == generation)
                {
                    pending = Some(Pending {
                        generation,
                        target: t,
                        sample_dt,
                    });
                }
                continue;
            }
            Some(Command::SetEffective(on)) => {
                if let Some(s) = session.as_mut() {
                    s.set_effective(on);
                }
                continue;
            }
            None => {}
        }
        let (Some(s), Some(p)) = (session.as_mut(), pending.as_ref()) else {
            pending = None;
            continue;
        };
        if s.generation() != p.generation {
            pending = None;
            continue;
        }
        let (events, reached) = s.advance(p.target, p.sample_dt, CHUNK_STEPS);
        for e in events {
            if !sink(e) {
                return;
            }
        }
        if reached {
            pending = None;
        }
    }
}

//! The recording in progress: its file (or, in the browser, its bytes), periodic checkpoints,
//! and closing it once the final checkpoint is written. The clock is the caller's (the
//! terminal's explorer reads the system's; the browser's page gives its frames' times), so the
//! same code records in both.

use crate::app::journal::Event;
use crate::app::{App, Effect, Outcome};
use crate::record::{Header, Line, Recorder, Size};

/// Wall seconds between checkpoints while recording.
pub const CHECKPOINT_EVERY: f64 = 2.0;

/// A recording in progress.
pub struct ActiveRecording {
    recorder: Recorder,
    /// The caller's clock when it started (seconds).
    started: f64,
    /// The caller's clock at the last periodic checkpoint.
    last_checkpoint: f64,
    /// Close once the final checkpoint is written.
    pub stopping: bool,
}

/// The header of a recording of `app` now.
#[must_use]
pub fn header(app: &App, size: (u16, u16), fps: f64) -> Header {
    Header {
        format: crate::record::FORMAT.to_owned(),
        version: crate::record::VERSION,
        program: env!("CARGO_PKG_VERSION").to_owned(),
        preset: app.to_preset(&app.scenario.name).to_toml(),
        method: app.scenario.settings.method.name().to_owned(),
        tolerance: app.scenario.settings.tolerance,
        terminal: Size {
            width: size.0,
            height: size.1,
        },
        theme: crate::record::ThemeRef::Name(
            app.options
                .theme_names
                .get(app.view.theme)
                .cloned()
                .unwrap_or_else(|| "default".to_owned()),
        ),
        fps,
        lesson: app.lesson.as_ref().map(|l| l.lesson.recorded()),
    }
}

impl ActiveRecording {
    /// Opens `path` (never replacing a file) with the header of `app`, at `now` on the
    /// caller's clock (seconds).
    ///
    /// # Errors
    /// The file exists or cannot be written.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn start(
        app: &App,
        path: &std::path::Path,
        size: (u16, u16),
        fps: f64,
        sign: Option<&std::path::Path>,
        now: f64,
    ) -> Result<Self, Box<dyn std::error::Error + Send + Sync>> {
        let signer = sign.map(crate::record::sign::Signer::read).transpose()?;
        let recorder = Recorder::create(path, &header(app, size, fps), signer)?;
        Ok(Self::around(recorder, now))
    }

    /// A recording of `app` kept in memory under the name `name` (the browser's, which hands
    /// the bytes to the page to download), at `now` on the caller's clock.
    ///
    /// # Errors
    /// The header cannot be written (never in practice).
    pub fn in_memory(
        app: &App,
        name: &str,
        size: (u16, u16),
        fps: f64,
        now: f64,
    ) -> Result<Self, crate::record::RecordError> {
        let recorder = Recorder::in_memory(name, &header(app, size, fps))?;
        Ok(Self::around(recorder, now))
    }

    fn around(recorder: Recorder, now: f64) -> Self {
        Self {
            recorder,
            started: now,
            last_checkpoint: now,
            stopping: false,
        }
    }

    /// The file (or the name of the recording in memory).
    #[must_use]
    pub fn path(&self) -> String {
        self.recorder.path().to_owned()
    }

    /// What was written, for a recording in memory.
    #[must_use]
    pub fn bytes(&self) -> Option<&[u8]> {
        self.recorder.bytes()
    }

    /// A periodic checkpoint, when one is due at `now`.
    pub fn due(&mut self, app: &App, now: f64) -> Option<Effect> {
        (now - self.last_checkpoint >= CHECKPOINT_EVERY).then(|| {
            self.last_checkpoint = now;
            app.checkpoint()
        })
    }

    /// Writes the journal, stamped `now` on the caller's clock. `Ok(Some(outcome))` when the
    /// recording is over (closed after its final checkpoint); `Err` when writing failed (it
    /// stopped).
    pub fn flush(&mut self, app: &mut App, now: f64) -> Result<Option<Outcome>, Outcome> {
        let wall = (now - self.started).max(0.0);
        let mut checkpoint = false;
        let mut last = (app.run.shown, app.run.generation);
        for (t, generation, event) in app.take_journal() {
            checkpoint |= matches!(event, Event::Checkpoint { .. });
            last = (t, generation);
            self.write(wall, t, generation, event)?;
        }
        if checkpoint && self.stopping {
            // The last line says the recording is over (a follower shows it).
            self.write(wall, last.0, last.1, Event::end())?;
            return Ok(Some(Outcome::RecordingSaved(self.path())));
        }
        Ok(None)
    }

    fn write(&mut self, wall: f64, t: f64, generation: u64, event: Event) -> Result<(), Outcome> {
        self.recorder
            .write(&Line {
                wall,
                t,
                generation,
                chain: None,
                event,
            })
            .map_err(|e| Outcome::RecordingFailed(e.to_string()))
    }
}

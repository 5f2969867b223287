//! Where `serve`'s two halves meet (issue 71): the [`Hub`] keeps the current screen (a reader
//! who joins late is sent it whole at once) and a bounded ring of frames, so memory does not
//! grow with the lecture's length; [`Config`] says what is served and how.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use bytes::Bytes;
use tokio::sync::broadcast;

/// Readers of `/events` at most, unless `--max-readers` says otherwise.
pub const DEFAULT_MAX_READERS: usize = 500;
/// Readers of `/events` from one address at most, unless `--max-per-address` says otherwise
/// (issue 80, N10: one client took every reader's place; a hall behind one NAT address raises
/// it).
pub const DEFAULT_MAX_PER_ADDRESS: usize = 20;
/// Frames kept for readers who are behind (then they are dropped and reconnect): about 25 s
/// at 10 frames a second, a few megabytes at most.
const RING: usize = 256;

/// What `serve` serves, and how.
#[derive(Clone, Debug)]
pub struct Config {
    /// The session file (it may not exist yet: the page waits for it).
    pub file: PathBuf,
    /// The token every request must carry (`?token=`), or none (loopback only).
    pub token: Option<String>,
    /// Readers of `/events` at most.
    pub max_readers: usize,
    /// Readers of `/events` from one address at most; loopback's too when asked (`Some`): by
    /// default a loopback peer is not counted, since every reader through an SSH tunnel or a
    /// reverse proxy comes from 127.0.0.1.
    pub max_per_address: (usize, bool),
    /// Frames a second drawn for the readers.
    pub fps: f64,
    /// How the frames are drawn (as `--export-cast`: no key footer).
    pub ui: crate::ui::UiOptions,
    /// The browser explorer's module (`--site`), read once: forks compute in the readers'
    /// browsers, and this is all the server gives them.
    pub module: Option<Bytes>,
}

/// Whether `serve` may listen at `addr` without a token: loopback only (a reader there is a
/// user of this machine, or comes through an SSH tunnel).
#[must_use]
pub fn tokenless_allowed(addr: &SocketAddr) -> bool {
    addr.ip().is_loopback()
}

/// A fresh random token: 128 bits from the system's generator, in hex.
///
/// # Errors
/// When the system's generator fails.
pub fn new_token() -> Result<String, getrandom::Error> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes)?;
    Ok(hex::encode(bytes))
}

/// The address a reader opens: the listening address (for an unspecified one, `0.0.0.0` or
/// `::`, this machine's address on its default route, so a hall can reach it), and the token.
#[must_use]
pub fn url(local: SocketAddr, token: Option<&str>) -> String {
    let mut shown = local;
    if local.ip().is_unspecified()
        && let Some(ip) = outward_address(local.is_ipv6())
    {
        shown.set_ip(ip);
    }
    let query = token.map_or_else(String::new, |t| format!("?token={t}"));
    format!("http://{shown}/{query}")
}

/// This machine's address on its default route (a UDP socket "connected" to a documentation
/// address: nothing is sent).
fn outward_address(v6: bool) -> Option<std::net::IpAddr> {
    let (bind, peer) = if v6 {
        ("[::]:0", "[2001:db8::1]:9")
    } else {
        ("0.0.0.0:0", "192.0.2.1:9")
    };
    let socket = std::net::UdpSocket::bind(bind).ok()?;
    socket.connect(peer).ok()?;
    let ip = socket.local_addr().ok()?.ip();
    (!ip.is_unspecified()).then_some(ip)
}

/// What the page and the stream show: the renderer writes it, the readers read it.
pub struct Hub {
    frames: broadcast::Sender<Bytes>,
    state: Mutex<State>,
    started: Instant,
}

/// The hub's current screen and phase.
struct State {
    /// The lecture's screen now (its size is the recorded terminal's), or a waiting message.
    screen: Screen,
    /// The recording ended: the page of the whole session, in a temporary file (removed when
    /// another lecture begins and its last reader is done, or when `serve` ends).
    finished: Option<Arc<tempfile::TempPath>>,
}

enum Screen {
    Waiting(String),
    Drawn(ratatui::buffer::Buffer),
}

/// One Server-Sent Events message of `data` (JSON: one line).
fn message(data: &str) -> Bytes {
    Bytes::from(format!("data: {data}\n\n"))
}

/// The message that ends a stream: asciinema-player's eventsource driver closes on it and
/// says the stream ended.
pub const DONE: &[u8] = b"event: done\ndata: ended\n\n";
/// A comment that keeps a quiet connection open through proxies.
pub const KEEPALIVE: &[u8] = b": keepalive\n\n";
/// The first line of every stream: how long a browser waits before reconnecting.
const RETRY: &str = "retry: 2000\n";

impl Default for Hub {
    fn default() -> Self {
        Self::new()
    }
}

impl Hub {
    /// A hub waiting for the lecture.
    #[must_use]
    pub fn new() -> Self {
        Self {
            frames: broadcast::channel(RING).0,
            state: Mutex::new(State {
                screen: Screen::Waiting("waiting for the lecture".to_owned()),
                finished: None,
            }),
            started: Instant::now(),
        }
    }

    fn state(&self) -> std::sync::MutexGuard<'_, State> {
        self.state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Seconds since the hub started: the streams' clock.
    fn time(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// The message that sets a reader's terminal to `screen` at once.
    fn reset_message(&self, screen: &Screen) -> Bytes {
        let (cols, rows, init) = match screen {
            Screen::Waiting(text) => (
                80,
                24,
                format!(
                    "\x1b[2J\x1b[H{}",
                    crate::scenario::text::clean(text).replace('\n', "\r\n")
                ),
            ),
            Screen::Drawn(buffer) => (
                buffer.area.width,
                buffer.area.height,
                String::from_utf8_lossy(&crate::cast::whole(buffer)).into_owned(),
            ),
        };
        let json = serde_json::json!({
            "cols": cols,
            "rows": rows,
            "time": self.time(),
            "init": init,
        });
        message(&json.to_string())
    }

    /// Nothing to show yet (no file, or not a session yet): every reader sees `text`.
    pub fn waiting(&self, text: &str) {
        let mut state = self.state();
        if matches!(&state.screen, Screen::Waiting(t) if t == text) {
            return;
        }
        state.screen = Screen::Waiting(text.to_owned());
        state.finished = None;
        let _ = self.frames.send(self.reset_message(&state.screen));
    }

    /// A new lecture (the file appeared, or was truncated or replaced): every reader's
    /// terminal is set to `screen`, whatever its size.
    pub fn restart(&self, screen: &ratatui::buffer::Buffer) {
        let mut state = self.state();
        state.screen = Screen::Drawn(screen.clone());
        state.finished = None;
        let _ = self.frames.send(self.reset_message(&state.screen));
    }

    /// A frame: the bytes that turn the last screen into `screen`.
    pub fn frame(&self, bytes: &[u8], screen: &ratatui::buffer::Buffer) {
        let mut state = self.state();
        match &mut state.screen {
            Screen::Drawn(b) if b.area == screen.area => b.clone_from(screen),
            _ => {
                drop(state);
                self.restart(screen);
                return;
            }
        }
        let json = serde_json::json!([self.time(), "o", String::from_utf8_lossy(bytes)]);
        let _ = self.frames.send(message(&json.to_string()));
    }

    /// The recording ended: its whole page is at `page`; every stream ends (the page then
    /// loads the recording to replay with its chapters).
    pub fn finish(&self, page: tempfile::TempPath) {
        let mut state = self.state();
        state.finished = Some(Arc::new(page));
        let _ = self.frames.send(Bytes::from_static(DONE));
    }

    /// The finished lecture's page, once the recording ended.
    #[must_use]
    pub fn finished(&self) -> Option<Arc<tempfile::TempPath>> {
        self.state().finished.clone()
    }

    /// A new reader: what it is sent first (the current screen whole, and the end if the
    /// recording ended) and its subscription to what follows, taken together so that no frame
    /// falls between them.
    #[must_use]
    pub fn join(&self) -> (Bytes, broadcast::Receiver<Bytes>) {
        let state = self.state();
        let mut first = RETRY.as_bytes().to_vec();
        first.extend_from_slice(&self.reset_message(&state.screen));
        if state.finished.is_some() {
            first.extend_from_slice(DONE);
        }
        (Bytes::from(first), self.frames.subscribe())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_address_carries_the_token_and_a_reachable_host() {
        let loopback: SocketAddr = "127.0.0.1:8080".parse().unwrap();
        assert_eq!(url(loopback, None), "http://127.0.0.1:8080/");
        assert_eq!(
            url(loopback, Some("ab12")),
            "http://127.0.0.1:8080/?token=ab12"
        );
        let any: SocketAddr = "0.0.0.0:8080".parse().unwrap();
        assert!(!url(any, None).contains("0.0.0.0"), "{}", url(any, None));
        assert!(tokenless_allowed(&loopback));
        assert!(tokenless_allowed(&"[::1]:80".parse().unwrap()));
        assert!(!tokenless_allowed(&any));
        assert!(!tokenless_allowed(&"192.168.1.5:80".parse().unwrap()));
        let t = new_token().unwrap();
        assert_eq!(t.len(), 32);
        assert_ne!(t, new_token().unwrap());
    }

    #[test]
    fn a_late_reader_gets_the_screen_whole_then_the_frames() {
        let hub = Hub::new();
        let (first, _) = hub.join();
        let text = String::from_utf8_lossy(&first).into_owned();
        assert!(text.starts_with("retry: "), "{text}");
        assert!(text.contains("waiting for the lecture"), "{text}");
        let area = ratatui::layout::Rect::new(0, 0, 20, 3);
        let mut screen = ratatui::buffer::Buffer::empty(area);
        screen.set_string(0, 1, "t 1.00/30 │ paused", ratatui::style::Style::default());
        hub.restart(&screen);
        let (first, mut rx) = hub.join();
        let text = String::from_utf8_lossy(&first).into_owned();
        assert!(
            text.contains("\"cols\":20") && text.contains("\"rows\":3"),
            "{text}"
        );
        // Blank cells are skipped by moving the cursor.
        assert!(
            text.contains("1.00/30") && text.contains("│") && text.contains("paused"),
            "{text}"
        );
        hub.frame(b"x", &screen);
        let next = rx.try_recv().unwrap();
        assert!(next.starts_with(b"data: ["), "{next:?}");
        hub.finish(tempfile::NamedTempFile::new().unwrap().into_temp_path());
        assert_eq!(&rx.try_recv().unwrap()[..], DONE);
        let (first, _) = hub.join();
        assert!(
            first.ends_with(DONE),
            "a reader after the end is told at once"
        );
    }
}

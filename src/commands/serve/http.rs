//! The HTTP side of `serve`: hyper's HTTP/1.1 on a tokio runtime of two threads, read-only.
//!
//! Routes: `/` the page (live while the lecture is recorded, then the whole session's),
//! `/events` the frames as Server-Sent Events, `/session.jsonl` the file's complete lines so
//! far. Anything else is 404, a method other than GET or HEAD 405; no path is ever joined to a
//! folder. Limits: the token (403), the request's headers (16 KiB, 431 by hyper), the time to
//! send them (5 s, then hyper closes the connection: a thousand idle or half-open connections
//! leave), readers of `/events` (503 past the most), each reader's queue (a reader that falls
//! behind is disconnected, and its browser reconnects to the current screen), connections in
//! all (bounded by the process's file descriptors).

use std::convert::Infallible;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::task::{Context, Poll};
use std::time::Duration;

use bytes::Bytes;
use hyper::body::{Frame, Incoming};
use hyper::header::{self, HeaderValue};
use hyper::{Method, Request, Response, StatusCode};
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::sync::{Notify, OwnedSemaphorePermit, Semaphore, mpsc};

use super::hub::{Config, DONE, Hub, KEEPALIVE};

/// The most bytes of a request's line and headers (then 431).
pub const MAX_HEADER_BYTES: usize = 16 * 1024;
/// How long a connection may take to send a request's headers (then it is closed).
pub const HEADER_TIME: Duration = Duration::from_secs(5);
/// Messages waiting for one reader (about six seconds of frames): a reader further behind is
/// disconnected.
const READER_QUEUE: usize = 64;
/// A quiet stream says something this often (proxies close silent connections).
const KEEPALIVE_EVERY: Duration = Duration::from_secs(15);
/// Bytes read from a file per chunk sent.
const CHUNK: usize = 64 * 1024;
/// File descriptors kept for everything but connections (the file, the runtime, the page).
const SPARE_FDS: usize = 64;
/// How long opening the session file and finding its complete lines may take (a regular file
/// only, opened without blocking: this bounds a slow disk).
const FILE_TIME: Duration = Duration::from_secs(2);

/// Where the session file's complete lines ended when last looked at: the file (device and
/// inode), its length then, and the end of its last complete line. A request scans only what
/// was appended since (issue 80, N6: a huge unfinished line was scanned on every request).
type Prefix = ((u64, u64), u64, u64);

/// A reader's place among its address's readers, given back when its stream ends.
pub struct Slot {
    counts: Arc<std::sync::Mutex<std::collections::HashMap<std::net::IpAddr, usize>>>,
    address: std::net::IpAddr,
}

impl Drop for Slot {
    fn drop(&mut self) {
        let mut counts = self
            .counts
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(n) = counts.get_mut(&self.address) {
            *n -= 1;
            if *n == 0 {
                counts.remove(&self.address);
            }
        }
    }
}

/// The server's shared state.
pub struct Server {
    hub: Arc<Hub>,
    config: Config,
    readers: Arc<Semaphore>,
    /// Readers of `/events` by address.
    per_address: Arc<std::sync::Mutex<std::collections::HashMap<std::net::IpAddr, usize>>>,
    /// The session file's complete lines when last looked at.
    prefix: std::sync::Mutex<Option<Prefix>>,
    live_page: Bytes,
    max_connections: usize,
    /// Connections open now.
    open: AtomicUsize,
}

/// A response's body: a whole text, a stream of events, or a file read chunk by chunk.
pub enum Reply {
    /// Bytes given at once (`None` once sent).
    Whole(Option<Bytes>),
    /// A reader's events, and its places among the readers and among its address's.
    Events(mpsc::Receiver<Bytes>, OwnedSemaphorePermit, Slot),
    /// `left` bytes of a file; `_page` keeps a finished page's file while it is read.
    File {
        /// The file, read from where it is.
        file: tokio::fs::File,
        /// Bytes still to send.
        left: u64,
        /// A finished page's temporary file, kept while it is read.
        _page: Option<Arc<tempfile::TempPath>>,
    },
}

impl hyper::body::Body for Reply {
    type Data = Bytes;
    type Error = std::io::Error;

    fn poll_frame(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, std::io::Error>>> {
        match self.get_mut() {
            Reply::Whole(bytes) => Poll::Ready(bytes.take().map(|b| Ok(Frame::data(b)))),
            Reply::Events(rx, ..) => rx.poll_recv(cx).map(|m| m.map(|b| Ok(Frame::data(b)))),
            Reply::File { file, left, .. } => {
                if *left == 0 {
                    return Poll::Ready(None);
                }
                let n = CHUNK.min(usize::try_from(*left).unwrap_or(CHUNK));
                let mut buf = vec![0u8; n];
                let mut read = tokio::io::ReadBuf::new(&mut buf);
                match tokio::io::AsyncRead::poll_read(Pin::new(file), cx, &mut read) {
                    Poll::Pending => Poll::Pending,
                    Poll::Ready(Err(e)) => Poll::Ready(Some(Err(e))),
                    Poll::Ready(Ok(())) => {
                        let got = read.filled().len();
                        if got == 0 {
                            // The file is shorter than it was: what was sent is all.
                            *left = 0;
                            return Poll::Ready(None);
                        }
                        *left -= got as u64;
                        buf.truncate(got);
                        Poll::Ready(Some(Ok(Frame::data(Bytes::from(buf)))))
                    }
                }
            }
        }
    }

    fn size_hint(&self) -> hyper::body::SizeHint {
        match self {
            Reply::Whole(bytes) => {
                hyper::body::SizeHint::with_exact(bytes.as_ref().map_or(0, |b| b.len() as u64))
            }
            Reply::File { left, .. } => hyper::body::SizeHint::with_exact(*left),
            Reply::Events(..) => hyper::body::SizeHint::default(),
        }
    }

    fn is_end_stream(&self) -> bool {
        matches!(self, Reply::Whole(None) | Reply::File { left: 0, .. })
    }
}

/// `r` with `headers` set.
fn with(mut r: Response<Reply>, headers: &[(header::HeaderName, &'static str)]) -> Response<Reply> {
    for (name, value) in headers {
        r.headers_mut()
            .insert(name.clone(), HeaderValue::from_static(value));
    }
    r
}

/// A plain-text response (a refusal says why).
fn text(status: StatusCode, message: &str) -> Response<Reply> {
    let mut r = Response::new(Reply::Whole(Some(Bytes::from(format!("{message}\n")))));
    *r.status_mut() = status;
    with(r, &[(header::CONTENT_TYPE, "text/plain; charset=utf-8")])
}

/// Headers every response carries: nothing cached (the token is in the address), nothing
/// sniffed, no address sent elsewhere.
fn guard(r: Response<Reply>) -> Response<Reply> {
    with(
        r,
        &[
            (header::CACHE_CONTROL, "no-store"),
            (header::X_CONTENT_TYPE_OPTIONS, "nosniff"),
            (header::REFERRER_POLICY, "no-referrer"),
            (header::X_FRAME_OPTIONS, "DENY"),
        ],
    )
}

/// Whether `query` carries `token` (compared in constant time).
fn has_token(query: Option<&str>, token: &str) -> bool {
    query.unwrap_or("").split('&').any(|pair| {
        pair.strip_prefix("token=").is_some_and(|given| {
            given.len() == token.len()
                && given
                    .bytes()
                    .zip(token.bytes())
                    .fold(0u8, |acc, (a, b)| acc | (a ^ b))
                    == 0
        })
    })
}

/// Whether a request's `Host` names this machine's loopback (a page elsewhere that renamed
/// its own host to 127.0.0.1, "DNS rebinding", sends its own name and is refused). The port
/// is not compared: an SSH tunnel forwards from another.
fn loopback_host(host: Option<&HeaderValue>) -> bool {
    let Some(host) = host.and_then(|h| h.to_str().ok()) else {
        return host.is_none();
    };
    let name = if let Some(rest) = host.strip_prefix('[') {
        rest.split(']').next().unwrap_or("")
    } else {
        host.rsplit_once(':').map_or(host, |(name, _)| name)
    };
    name.eq_ignore_ascii_case("localhost")
        || name
            .parse::<std::net::IpAddr>()
            .is_ok_and(|ip| ip.is_loopback())
}

impl Server {
    /// A server of `hub` as `config` says, for `max_connections` connections at most.
    #[must_use]
    pub fn new(hub: Arc<Hub>, config: Config, max_connections: usize) -> Self {
        let live_page = Bytes::from(crate::commands::page::live_page(
            "rattleback: a live lecture",
            config.token.as_deref(),
        ));
        Self {
            readers: Arc::new(Semaphore::new(config.max_readers)),
            per_address: Arc::default(),
            prefix: std::sync::Mutex::new(None),
            hub,
            config,
            live_page,
            max_connections,
            open: AtomicUsize::new(0),
        }
    }

    /// The response to `req` from `peer` (`kill` closes its connection: a reader too far
    /// behind).
    async fn respond(
        &self,
        req: Request<Incoming>,
        peer: std::net::IpAddr,
        kill: &Arc<Notify>,
    ) -> Response<Reply> {
        guard(self.route(&req, peer, kill).await)
    }

    async fn route(
        &self,
        req: &Request<Incoming>,
        peer: std::net::IpAddr,
        kill: &Arc<Notify>,
    ) -> Response<Reply> {
        if req.method() != Method::GET && req.method() != Method::HEAD {
            return with(
                text(
                    StatusCode::METHOD_NOT_ALLOWED,
                    "read-only: GET and HEAD only",
                ),
                &[(header::ALLOW, "GET, HEAD")],
            );
        }
        match &self.config.token {
            Some(token) if !has_token(req.uri().query(), token) => {
                return text(
                    StatusCode::FORBIDDEN,
                    "a wrong or missing token: open the address rattleback serve printed, whole",
                );
            }
            None if !loopback_host(req.headers().get(header::HOST)) => {
                return text(
                    StatusCode::FORBIDDEN,
                    "this server answers only to localhost (it has no token)",
                );
            }
            _ => {}
        }
        let head = req.method() == Method::HEAD;
        match req.uri().path() {
            "/" => self.page().await,
            "/events" if head => event_stream(Response::new(Reply::Whole(None))),
            "/events" => self.events(peer, kill),
            "/session.jsonl" => self.session().await,
            "/rattleback.wasm" => self.module(),
            _ => text(
                StatusCode::NOT_FOUND,
                "not found: this server has /, /events, /session.jsonl and /rattleback.wasm",
            ),
        }
    }

    /// The page: live, or the whole session's once the recording ended.
    async fn page(&self) -> Response<Reply> {
        let r = match self.hub.finished() {
            Some(page) => match tokio::fs::File::open(&**page).await {
                Ok(file) => {
                    let left = file.metadata().await.map_or(0, |m| m.len());
                    Response::new(Reply::File {
                        file,
                        left,
                        _page: Some(page),
                    })
                }
                Err(_) => Response::new(Reply::Whole(Some(self.live_page.clone()))),
            },
            None => Response::new(Reply::Whole(Some(self.live_page.clone()))),
        };
        with(
            r,
            &[
                (header::CONTENT_TYPE, "text/html; charset=utf-8"),
                // Inline script and style only; the stream and the file from this server alone.
                (
                    header::CONTENT_SECURITY_POLICY,
                    "default-src 'none'; script-src 'unsafe-inline' 'wasm-unsafe-eval'; style-src 'unsafe-inline'; \
                     worker-src blob:; connect-src 'self'; img-src data:; font-src data:; base-uri 'none'; form-action 'none'",
                ),
            ],
        )
    }

    /// A reader's place among `address`'s readers, if it has one left (a loopback reader is
    /// counted only when `--max-per-address` was given: through a tunnel or a proxy every
    /// reader comes from there).
    fn slot(&self, address: std::net::IpAddr) -> Option<Slot> {
        let (most, asked) = self.config.max_per_address;
        let mut counts = self
            .per_address
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let n = counts.entry(address).or_insert(0);
        if *n >= most && (asked || !address.is_loopback()) {
            return None;
        }
        *n += 1;
        Some(Slot {
            counts: Arc::clone(&self.per_address),
            address,
        })
    }

    /// A reader's stream: the screen now, then every frame, until the recording ends.
    fn events(&self, peer: std::net::IpAddr, kill: &Arc<Notify>) -> Response<Reply> {
        let Some(slot) = self.slot(peer) else {
            return with(
                text(
                    StatusCode::SERVICE_UNAVAILABLE,
                    &format!(
                        "this address has {} readers of this lecture already (serve --max-per-address)",
                        self.config.max_per_address.0
                    ),
                ),
                &[(header::RETRY_AFTER, "10")],
            );
        };
        let Ok(permit) = Arc::clone(&self.readers).try_acquire_owned() else {
            return with(
                text(
                    StatusCode::SERVICE_UNAVAILABLE,
                    &format!(
                        "this lecture has {} readers already (serve --max-readers)",
                        self.config.max_readers
                    ),
                ),
                &[(header::RETRY_AFTER, "10")],
            );
        };
        let (first, mut frames) = self.hub.join();
        let (tx, rx) = mpsc::channel(READER_QUEUE);
        let _ = tx.try_send(first);
        let kill = Arc::clone(kill);
        tokio::spawn(async move {
            loop {
                let message = match tokio::time::timeout(KEEPALIVE_EVERY, frames.recv()).await {
                    Err(_) => Bytes::from_static(KEEPALIVE),
                    Ok(Ok(m)) => m,
                    Ok(Err(tokio::sync::broadcast::error::RecvError::Lagged(_))) => {
                        kill.notify_one();
                        return;
                    }
                    Ok(Err(tokio::sync::broadcast::error::RecvError::Closed)) => return,
                };
                let done = message[..] == *DONE;
                match tx.try_send(message) {
                    Ok(()) => {}
                    // Behind by a whole queue: disconnected (its browser reconnects to the
                    // screen as it is then); the others and the lecturer never wait for it.
                    Err(mpsc::error::TrySendError::Full(_)) => {
                        kill.notify_one();
                        return;
                    }
                    Err(mpsc::error::TrySendError::Closed(_)) => return,
                }
                if done {
                    return;
                }
            }
        });
        event_stream(Response::new(Reply::Events(rx, permit, slot)))
    }

    /// The browser explorer's module, for forks (`--site`); without it, why not.
    fn module(&self) -> Response<Reply> {
        let Some(module) = &self.config.module else {
            return text(
                StatusCode::NOT_FOUND,
                "this lecture is served without the explorer's module, so it cannot be forked in the browser: the lecturer adds --site DIR to serve (rattleback web DIR writes it); rattleback follow and f fork it in a terminal",
            );
        };
        with(
            Response::new(Reply::Whole(Some(module.clone()))),
            &[
                (header::CONTENT_TYPE, "application/wasm"),
                (header::CACHE_CONTROL, "private, max-age=3600"),
            ],
        )
    }

    /// The session file's complete lines so far: only a regular file, by its name, opened
    /// without blocking and within [`FILE_TIME`] (issue 80, N4: a FIFO at the path parked a
    /// thread of the shared pool per request, for good).
    async fn session(&self) -> Response<Reply> {
        let path = self.config.file.clone();
        let known = *self
            .prefix
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let opened = tokio::time::timeout(
            FILE_TIME,
            tokio::task::spawn_blocking(move || complete_lines(&path, known)),
        )
        .await;
        let Ok(Ok(Ok((file, prefix)))) = opened else {
            return text(
                StatusCode::NOT_FOUND,
                "the lecturer has not started recording yet",
            );
        };
        *self
            .prefix
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner) = Some(prefix);
        let r = Response::new(Reply::File {
            file: tokio::fs::File::from_std(file),
            left: prefix.2,
            _page: None,
        });
        with(
            r,
            &[
                (header::CONTENT_TYPE, "application/x-ndjson; charset=utf-8"),
                (
                    header::CONTENT_DISPOSITION,
                    "attachment; filename=\"session.jsonl\"",
                ),
            ],
        )
    }
}

/// The session file at `path` (a regular file, never through a link), opened, and where its
/// complete lines end, from where they ended when last looked at (`known`, when the same file
/// has not shrunk since): only the bytes appended since are scanned.
fn complete_lines(
    path: &std::path::Path,
    known: Option<Prefix>,
) -> std::io::Result<(std::fs::File, Prefix)> {
    let mut file =
        crate::scenario::write::open_regular(path, crate::scenario::write::Links::Refuse)?;
    let meta = file.metadata()?;
    #[cfg(unix)]
    let id = {
        use std::os::unix::fs::MetadataExt as _;
        (meta.dev(), meta.ino())
    };
    #[cfg(not(unix))]
    let id = (0, 0);
    let len = meta.len();
    let (scanned, known_end) = match known {
        Some((was, was_len, end)) if was == id && was_len <= len => (was_len, end),
        _ => (0, 0),
    };
    let end = crate::record::tail::complete_prefix_of(&mut file, len, scanned, known_end);
    std::io::Seek::seek(&mut file, std::io::SeekFrom::Start(0))?;
    Ok((file, (id, len, end)))
}

/// The headers of an event stream.
fn event_stream(r: Response<Reply>) -> Response<Reply> {
    with(
        r,
        &[
            (header::CONTENT_TYPE, "text/event-stream"),
            // nginx and others pass the stream on at once.
            (header::HeaderName::from_static("x-accel-buffering"), "no"),
        ],
    )
}

/// One connection, until it ends, is idle too long, or is killed (a reader too far behind).
async fn connection(server: Arc<Server>, stream: tokio::net::TcpStream) {
    let _ = stream.set_nodelay(true);
    let peer = stream
        .peer_addr()
        .map_or(std::net::IpAddr::V4(std::net::Ipv4Addr::UNSPECIFIED), |a| {
            a.ip()
        });
    let kill = Arc::new(Notify::new());
    let service = {
        let server = Arc::clone(&server);
        let kill = Arc::clone(&kill);
        hyper::service::service_fn(move |req| {
            let server = Arc::clone(&server);
            let kill = Arc::clone(&kill);
            async move { Ok::<_, Infallible>(server.respond(req, peer, &kill).await) }
        })
    };
    let mut builder = hyper::server::conn::http1::Builder::new();
    builder
        .timer(TokioTimer::new())
        .header_read_timeout(HEADER_TIME)
        .max_buf_size(MAX_HEADER_BYTES);
    let conn = builder.serve_connection(TokioIo::new(stream), service);
    let mut conn = std::pin::pin!(conn);
    let killed = kill.notified();
    let mut killed = std::pin::pin!(killed);
    std::future::poll_fn(|cx| {
        if conn.as_mut().poll(cx).is_ready() || killed.as_mut().poll(cx).is_ready() {
            Poll::Ready(())
        } else {
            Poll::Pending
        }
    })
    .await;
    server.open.fetch_sub(1, Ordering::Relaxed);
}

/// Connections at most: the file descriptors this process may open (raised to the system's
/// limit first), less a few for everything else.
#[must_use]
pub fn connection_limit() -> usize {
    let limit = rlimit::increase_nofile_limit(u64::MAX).unwrap_or(1024);
    usize::try_from(limit)
        .unwrap_or(usize::MAX)
        .saturating_sub(SPARE_FDS)
        .max(16)
}

/// Accepts connections on `listener` until `stop` (or a signal).
///
/// # Errors
/// When the runtime cannot start or the listener cannot be handed to it.
pub fn run(
    server: &Arc<Server>,
    listener: std::net::TcpListener,
    stop: &AtomicBool,
) -> std::io::Result<()> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("rattleback-serve")
        .enable_all()
        .build()?;
    runtime.block_on(async {
        listener.set_nonblocking(true)?;
        let listener = tokio::net::TcpListener::from_std(listener)?;
        while !stop.load(Ordering::Relaxed) {
            if crate::interrupt::requested().is_some() {
                // Stopping on its own, well within the watchdog's grace: it leaves the
                // cleaning up (the page's file) to this.
                crate::interrupt::ending_now();
                break;
            }
            let accepted = tokio::time::timeout(Duration::from_millis(20), listener.accept()).await;
            match accepted {
                Err(_) => {}
                // Out of descriptors, or a connection reset before it was taken: a moment's
                // pause, then on.
                Ok(Err(_)) => tokio::time::sleep(Duration::from_millis(20)).await,
                Ok(Ok((stream, _))) => {
                    if server.open.load(Ordering::Relaxed) >= server.max_connections {
                        drop(stream);
                        continue;
                    }
                    server.open.fetch_add(1, Ordering::Relaxed);
                    tokio::spawn(connection(Arc::clone(server), stream));
                }
            }
        }
        Ok::<(), std::io::Error>(())
    })?;

    runtime.shutdown_timeout(Duration::from_millis(200));
    Ok(())
}

/// The address actually listened at (a port of 0 becomes the one given).
///
/// # Errors
/// When the address cannot be bound.
pub fn bind(addr: SocketAddr) -> std::io::Result<(std::net::TcpListener, SocketAddr)> {
    let listener = std::net::TcpListener::bind(addr)?;
    let local = listener.local_addr()?;
    Ok((listener, local))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_token_must_be_whole_and_exact() {
        assert!(has_token(Some("token=abc"), "abc"));
        assert!(has_token(Some("x=1&token=abc"), "abc"));
        assert!(!has_token(Some("token=abcd"), "abc"));
        assert!(!has_token(Some("token=ab"), "abc"));
        assert!(!has_token(Some("xtoken=abc"), "abc"));
        assert!(!has_token(None, "abc"));
        assert!(!has_token(Some("token="), "abc"));
    }

    #[test]
    fn only_loopback_names_pass_without_a_token() {
        let h = |s: &'static str| Some(HeaderValue::from_static(s));
        assert!(loopback_host(h("127.0.0.1:8080").as_ref()));
        assert!(loopback_host(h("localhost:9").as_ref()));
        assert!(loopback_host(h("[::1]:80").as_ref()));
        assert!(loopback_host(h("127.0.0.1").as_ref()));
        assert!(!loopback_host(h("evil.example:8080").as_ref()));
        assert!(!loopback_host(h("192.168.1.2:8080").as_ref()));
        assert!(!loopback_host(h("localhost.evil.example").as_ref()));
        assert!(loopback_host(None), "HTTP/1.0 sends no Host");
    }
}

//! The explorer's web server (hyper on tokio), built so that no client can stop it or freeze it:
//!
//! - at most [`max_connections`] connections at once (fewer under a low limit of open files);
//!   when they are all taken, the one quiet the longest is closed to make room (never one
//!   answering, writing an answer or holding part of a request), and if none is quiet new ones
//!   wait in the listening backlog. An error accepting one (no file descriptor
//!   left, say) is waited out, never fatal, and lowers the number kept to what the process can
//!   really open;
//! - every connection is bounded in time (a request's head within [`HEAD_TIMEOUT`], each write
//!   taken within [`guard::WRITE_TIMEOUT`]) and in size (a request line within
//!   [`guard::MAX_REQUEST_LINE`], else 414; a head within [`MAX_HEAD`], else 431), answered by its
//!   own task: the accepting loop writes nothing;
//! - the heavy requests go to a small pool of workers ([`work`]), 503 with
//!   `Retry-After` when its queue is full, and are abandoned when their client leaves or is
//!   superseded; everything else (the page, its files, the scene list, a scene's sketch, refusals)
//!   is answered at once;
//! - answers are sent a chunk at a time, held in memory within a budget and beyond it from
//!   temporary files ([`answer`](super::answer)), so slow readers cannot grow the server;
//! - a scene file is sent once (`POST /api/keep`) and named by a key afterwards
//!   ([`kept`](super::kept)), so that addresses stay short;
//! - only this machine's pages are served ([`origin`](super::origin)): a foreign `Host` or
//!   `Origin` gets 403, and so does a request without the token when one is asked for.

use std::collections::BTreeMap;
use std::convert::Infallible;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

use hyper::body::Incoming;
use hyper::header::{self, HeaderValue};
use hyper::{Method, Request, Response};
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{Notify, Semaphore};

use bentstraw_explore::{self as api, Reply, MAX_URL};
use bentstraw_optics::frame::Frame;
use bentstraw_optics::setup::MAX_SCENE_FILE_BYTES;
use http_body_util::BodyExt;

use super::answer::AnswerBody;
use super::guard::{self, Activity, Guarded};
use super::kept::Kept;
use super::origin::{Access, Local};
use super::work::{self, Pool};

/// Where the page sends a scene file's text once, to name it by a key afterwards.
const KEEP: &str = "/api/keep";

/// Most connections open at once, when the limit of open files allows it.
pub const MAX_CONNECTIONS: usize = 256;
/// File descriptors left for everything but connections (standard streams, the listener, the
/// runtime's own, a browser being started).
const SPARE_FILES: u64 = 32;
/// Time a client has to send a request's head; also how long a connection may stay idle.
pub const HEAD_TIMEOUT: Duration = Duration::from_secs(15);
/// Longest request head (request line and headers); hyper answers 431 beyond it.
pub const MAX_HEAD: usize = 48 * 1024;
/// Most header lines in a request.
const MAX_HEADERS: usize = 64;
/// Pause after an error accepting a connection (no descriptor left, say), so as not to spin.
const ACCEPT_PAUSE: Duration = Duration::from_millis(20);
/// Fewest connections kept however often descriptors run out.
const MIN_CONNECTIONS: usize = 8;
/// After a refusal the client may still be sending: what comes is read and dropped for this
/// long (at most [`LINGER_BYTES`]), so that it reads the refusal rather than a reset.
const LINGER: Duration = Duration::from_secs(2);
const LINGER_BYTES: usize = 4 << 20;
/// How often a request being computed is checked against [`work::MAX_COMPUTE`].
const OVERTIME_CHECK: Duration = Duration::from_millis(250);

/// The refusal of a scene file longer than the command line takes (by its length, or as it comes).
fn scene_too_large() -> Reply {
    Reply::text(
        413,
        format!("a scene file is at most {MAX_SCENE_FILE_BYTES} bytes (1 MB)"),
    )
}

/// The answer to a request computed for longer than [`work::MAX_COMPUTE`] (then stopped).
fn overtime() -> Reply {
    Reply::text(
        422,
        format!(
            "this view took more than {} s of the explorer's time and was stopped: ask for fewer \
             pixels, samples, points or events (the command line has no such limit)",
            work::MAX_COMPUTE.as_secs()
        ),
    )
}

/// Most connections this process can keep open: [`MAX_CONNECTIONS`], or fewer when the limit of
/// open files is low (each connection is one).
pub fn max_connections() -> usize {
    #[cfg(unix)]
    {
        let mut limit = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit writes the struct it is given, nothing else.
        if unsafe { libc::getrlimit(libc::RLIMIT_NOFILE, &mut limit) } == 0
            && limit.rlim_cur != libc::RLIM_INFINITY
        {
            let room = limit.rlim_cur.saturating_sub(SPARE_FILES as libc::rlim_t);
            return (room.min(MAX_CONNECTIONS as libc::rlim_t) as usize).max(MIN_CONNECTIONS);
        }
    }
    MAX_CONNECTIONS
}

/// One open connection, as the accepting loop and the connection's requests see it.
struct Conn {
    /// Requests being answered (0: idle, between requests or in a head).
    busy: AtomicUsize,
    /// Set to close the connection now.
    evict: Notify,
    evicted: AtomicBool,
    /// Set when its request line was too long (answered 414, then closed).
    too_long: Arc<AtomicBool>,
    /// What it is doing, and when it last did something.
    activity: Arc<Activity>,
}

/// The open connections, oldest first.
#[derive(Default)]
struct Conns {
    next: AtomicU64,
    open: Mutex<BTreeMap<u64, Arc<Conn>>>,
}

impl Conns {
    fn add(&self) -> (u64, Arc<Conn>) {
        let id = self.next.fetch_add(1, Ordering::Relaxed);
        let conn = Arc::new(Conn {
            busy: AtomicUsize::new(0),
            evict: Notify::new(),
            evicted: AtomicBool::new(false),
            too_long: Arc::new(AtomicBool::new(false)),
            activity: Arc::default(),
        });
        conn.activity.touch();
        let mut open = self.open.lock().unwrap_or_else(|e| e.into_inner());
        open.insert(id, Arc::clone(&conn));
        (id, conn)
    }

    fn remove(&self, id: u64) {
        self.open
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .remove(&id);
    }

    /// Closes the connection quiet the longest (no request under way, nothing being written,
    /// no part of a request held); whether there was one.
    fn evict_least_active(&self) -> bool {
        let open = self.open.lock().unwrap_or_else(|e| e.into_inner());
        let quietest = open
            .values()
            .filter(|c| {
                c.busy.load(Ordering::Relaxed) == 0
                    && c.activity.quiet()
                    && !c.evicted.load(Ordering::Relaxed)
            })
            .min_by_key(|c| c.activity.last());
        match quietest {
            Some(conn) => {
                conn.evicted.store(true, Ordering::Relaxed);
                conn.evict.notify_one();
                true
            }
            None => false,
        }
    }
}

/// Marks a connection busy while a request of it is answered.
struct Busy(Arc<Conn>);

impl Busy {
    fn new(conn: &Arc<Conn>) -> Busy {
        conn.busy.fetch_add(1, Ordering::Relaxed);
        conn.activity.touch();
        Busy(Arc::clone(conn))
    }
}

impl Drop for Busy {
    fn drop(&mut self) {
        self.0.activity.touch();
        self.0.busy.fetch_sub(1, Ordering::Relaxed);
    }
}

/// What every request's answer needs.
struct App {
    /// The page's HTML, its starting view filled in.
    page: String,
    local: Local,
    pool: Arc<Pool>,
    /// The scene files pages have sent.
    kept: Kept,
}

/// Serves the explorer on `listener` until the process ends; `initial` is the query of the view
/// the page starts with (when its address holds none); `access` the other names it answers to and
/// the token it asks for. An error only if it cannot start.
pub fn serve(
    listener: std::net::TcpListener,
    initial: &str,
    access: Access,
) -> std::io::Result<()> {
    let local = Local::with_access(listener.local_addr()?, access);
    listener.set_nonblocking(true)?;
    let app = Arc::new(App {
        page: api::page::index_html(initial, api::page::Engine::Server),
        local,
        pool: Pool::start()?,
        kept: Kept::default(),
    });
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("explore-io")
        .enable_io()
        .enable_time()
        .build()?;
    runtime.block_on(async move {
        let listener = TcpListener::from_std(listener)?;
        accept_loop(listener, app).await;
        Ok(())
    })
}

/// Accepts connections for ever, each answered by a task of its own.
async fn accept_loop(listener: TcpListener, app: Arc<App>) {
    let mut limit = max_connections();
    let slots = Arc::new(Semaphore::new(limit));
    let conns = Arc::new(Conns::default());
    loop {
        let slot = match Arc::clone(&slots).try_acquire_owned() {
            Ok(slot) => slot,
            Err(_) => {
                // All taken: make room by closing an idle one; if none is, wait for one to end
                // (new connections wait in the backlog meanwhile).
                conns.evict_least_active();
                match Arc::clone(&slots).acquire_owned().await {
                    Ok(slot) => slot,
                    Err(_) => return,
                }
            }
        };
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            // A connection reset before it was accepted: the next one.
            Err(e) if is_connection_error(&e) => continue,
            // Out of descriptors (or memory): the connections open are all this process can
            // have, so one fewer is kept from now on (and the one idle the longest makes room).
            Err(_) => {
                if limit > MIN_CONNECTIONS {
                    slot.forget();
                    limit -= 1;
                }
                conns.evict_least_active();
                tokio::time::sleep(ACCEPT_PAUSE).await;
                continue;
            }
        };
        let (id, conn) = conns.add();
        let app = Arc::clone(&app);
        let conns = Arc::clone(&conns);
        tokio::spawn(async move {
            connection(stream, &app, conn).await;
            // Out of the list before the slot is free: it is not chosen to make room again.
            conns.remove(id);
            drop(slot);
        });
    }
}

fn is_connection_error(e: &std::io::Error) -> bool {
    use std::io::ErrorKind::*;
    matches!(
        e.kind(),
        ConnectionRefused | ConnectionAborted | ConnectionReset | Interrupted | WouldBlock
    )
}

/// Answers the requests of one connection until it closes, times out or is evicted.
async fn connection(stream: TcpStream, app: &Arc<App>, conn: Arc<Conn>) {
    // Frames go out as soon as they are written: without this, a frame's last pieces wait for
    // the browser's delayed acknowledgement (Nagle's algorithm), up to 40 ms a frame.
    let _ = stream.set_nodelay(true);
    let mut io =
        Guarded::new(stream, Arc::clone(&conn.too_long)).watched(Arc::clone(&conn.activity));
    let refused = {
        let service = hyper::service::service_fn(|request| {
            let app = Arc::clone(app);
            let busy = Busy::new(&conn);
            async move {
                let response = app.answer(request, &busy.0).await;
                drop(busy);
                Ok::<_, Infallible>(response)
            }
        });
        let serving = hyper::server::conn::http1::Builder::new()
            .timer(TokioTimer::new())
            .header_read_timeout(HEAD_TIMEOUT)
            .max_header_size(MAX_HEAD)
            .max_buf_size(MAX_HEAD + 16 * 1024)
            .max_headers(MAX_HEADERS)
            .serve_connection(TokioIo::new(&mut io), service);
        tokio::select! {
            done = serving => match done {
                Ok(()) => conn.too_long.load(Ordering::Relaxed),
                Err(e) => e.is_parse() || e.is_parse_too_large(),
            },
            _ = conn.evict.notified() => false,
        }
    };
    if refused {
        // Answered and closed on our side; what the client still sends is read and dropped for
        // a moment, unless the room is needed first.
        conn.activity.refused();
        tokio::select! {
            _ = linger(io.get_mut()) => {}
            _ = conn.evict.notified() => {}
        }
    }
}

/// Closes our side, then reads and drops what the client still sends, for a moment.
async fn linger(stream: &mut TcpStream) {
    let _ = stream.shutdown().await;
    let drain = async {
        let mut buf = [0u8; 8192];
        let mut total = 0;
        while total < LINGER_BYTES {
            match stream.read(&mut buf).await {
                Ok(0) | Err(_) => break,
                Ok(n) => total += n,
            }
        }
    };
    let _ = tokio::time::timeout(LINGER, drain).await;
}

impl App {
    /// The answer to one request.
    async fn answer(&self, request: Request<Incoming>, conn: &Conn) -> Response<AnswerBody> {
        if conn.too_long.load(Ordering::Relaxed) {
            return closing(Reply::text(
                414,
                format!("request line longer than {} bytes", guard::MAX_REQUEST_LINE),
            ));
        }
        let (request, body) = request.into_parts();
        // The one request with a body: a scene file's text sent to be kept.
        let keep = request.method == Method::POST && request.uri.path() == KEEP;
        if !keep && !matches!(request.method, Method::GET | Method::HEAD) {
            let mut response = closing(Reply::text(
                405,
                format!("only GET is served (and POST to {KEEP})"),
            ));
            response
                .headers_mut()
                .insert(header::ALLOW, HeaderValue::from_static("GET, HEAD"));
            return response;
        }
        let headers = &request.headers;
        let text = |name: header::HeaderName| headers.get(name).and_then(|v| v.to_str().ok());
        let length = headers.get(header::CONTENT_LENGTH);
        if keep {
            if headers.contains_key(header::TRANSFER_ENCODING) || length.is_none() {
                return closing(Reply::text(
                    411,
                    "a scene file is sent with its length (Content-Length)",
                ));
            }
            let too_long = length
                .and_then(|v| v.to_str().ok())
                .and_then(|v| v.parse::<u64>().ok())
                .is_none_or(|n| n > MAX_SCENE_FILE_BYTES);
            if too_long {
                return closing(scene_too_large());
            }
        } else if length.is_some() || headers.contains_key(header::TRANSFER_ENCODING) {
            return closing(Reply::text(400, "a GET request has no body"));
        }
        // HTTP names one server a request: with two, which one was meant cannot be known.
        if headers.get_all(header::HOST).iter().nth(1).is_some() {
            return closing(Reply::text(
                400,
                "two Host headers: a request names its server once",
            ));
        }
        let uri = &request.uri;
        let path = uri.path();
        let api = path.starts_with("/api/");
        let mut host = text(header::HOST);
        // An absolute address ("GET http://host/…") names its server itself.
        if let Some(authority) = uri.authority() {
            if host.is_some_and(|h| !h.eq_ignore_ascii_case(authority.as_str())) {
                host = None;
            }
        }
        if let Err(why) = self.local.check(
            host,
            text(header::ORIGIN),
            headers.get("sec-fetch-site").and_then(|v| v.to_str().ok()),
            api,
        ) {
            return respond(Reply::text(403, why));
        }
        let query = uri.query().unwrap_or("");
        // Reachable from other machines: only with the token it printed.
        let Some(token_in_query) = self.local.token_given(query, text(header::COOKIE)) else {
            return respond(Reply::text(
                403,
                "this explorer asks for its token: open the whole address it printed \
                 (http://…/?token=…)",
            ));
        };
        let length = path.len()
            + if uri.query().is_some() {
                1 + query.len()
            } else {
                0
            };
        if length > MAX_URL {
            return respond(Reply::text(
                414,
                format!("address longer than {MAX_URL} bytes"),
            ));
        }
        if keep {
            return self.keep(body).await;
        }
        let page = match path {
            "/" | "/index.html" => asset("text/html; charset=utf-8", &self.page),
            _ if api => return self.api(path, query).await,
            p => match (api::page::PAGE_FILES.iter()).find(|f| p.strip_prefix('/') == Some(f.name))
            {
                Some(f) => asset(f.content_type, f.text),
                None => Reply::text(
                    404,
                    format!("no such page: {}", bentstraw_optics::text::clip_text(p, 60)),
                ),
            },
        };
        let mut response = respond(page);
        // The token given in the address is kept by the browser for the page's own requests.
        if token_in_query {
            let cookie = format!(
                "{}={}; Path=/; HttpOnly; SameSite=Strict",
                self.local.cookie_name(),
                self.local.token().unwrap_or_default()
            );
            if let Ok(value) = HeaderValue::from_str(&cookie) {
                response.headers_mut().insert(header::SET_COOKIE, value);
            }
        }
        response
    }

    /// `POST /api/keep`: keeps the scene file's text sent (within its length, read within
    /// [`HEAD_TIMEOUT`]); its key as JSON, `{"key": KEY}`. The connection closes after it.
    async fn keep(&self, body: Incoming) -> Response<AnswerBody> {
        let limited = http_body_util::Limited::new(body, MAX_SCENE_FILE_BYTES as usize);
        let bytes = match tokio::time::timeout(HEAD_TIMEOUT, limited.collect()).await {
            Ok(Ok(collected)) => collected.to_bytes(),
            Ok(Err(_)) => return closing(scene_too_large()),
            Err(_) => {
                return closing(Reply::text(
                    408,
                    format!(
                        "the scene file did not arrive within {} s",
                        HEAD_TIMEOUT.as_secs()
                    ),
                ))
            }
        };
        let Ok(text) = std::str::from_utf8(&bytes) else {
            return closing(Reply::text(400, "a scene file is UTF-8 text"));
        };
        let key = self.kept.keep(text);
        closing(Reply::bytes(
            "application/json",
            format!("{{\"key\":\"{key}\"}}").into_bytes(),
        ))
    }

    /// `query` with its `scene-key=KEY` replaced by the text kept under that key
    /// (`scene-file=TEXT`); `None` when it names none; 410 when the key is no longer kept.
    fn resolve(&self, query: &str) -> Result<Option<String>, Reply> {
        if !query.contains("scene-key=") {
            return Ok(None);
        }
        let mut q = api::parse_query(query).map_err(|e| Reply::text(400, e))?;
        let Some(key) = q.remove("scene-key") else {
            return Ok(None);
        };
        if q.contains_key("scene-file") {
            return Err(Reply::text(
                400,
                "give either 'scene-key' (a scene file sent before) or 'scene-file', not both",
            ));
        }
        let Some(text) = self.kept.get(&key) else {
            return Err(Reply::text(
                410,
                "this scene file is no longer kept by the explorer: send it again (POST /api/keep)",
            ));
        };
        q.insert("scene-file".into(), text.to_string());
        let mut pairs: Vec<String> = q
            .iter()
            .map(|(k, v)| format!("{}={}", api::query_value(k), api::query_value(v)))
            .collect();
        pairs.sort();
        Ok(Some(pairs.join("&")))
    }

    /// The answer to an API request: the heavy ones through the workers' queue, the others
    /// (and any refusal of a query) at once.
    async fn api(&self, path: &str, query: &str) -> Response<AnswerBody> {
        if path == "/api/scenes" {
            static SCENES: OnceLock<Reply> = OnceLock::new();
            return respond(SCENES.get_or_init(api::scenes_reply).clone());
        }
        let resolved = match self.resolve(query) {
            Ok(resolved) => resolved,
            Err(refusal) => return respond(refusal),
        };
        let query = resolved.as_deref().unwrap_or(query);
        let heavy = matches!(
            path,
            "/api/frame" | "/api/model" | "/api/ray" | "/api/aim" | "/api/export"
        ) || path == "/api/sweep";
        if !heavy {
            // Light routes remember nothing: a memory of their own, empty.
            let memory = api::Memory::default();
            return respond(api::handle(path, query, &mut Frame::default(), &memory));
        }
        // A query that breaks a rule is refused here, without waiting for a worker.
        // (A scene's broken rules go as data, as the page's own engine sends them.)
        let parsed = api::parse_query(query)
            .map_err(api::Refused::from)
            .and_then(|q| api::View::checked(&q).map(|view| (q, view.work())));
        let (q, work) = match parsed {
            Ok(checked) => checked,
            Err(e) => return respond(e.reply()),
        };
        let chan = q
            .get("chan")
            .zip(q.get("seq").and_then(|s| s.parse::<u64>().ok()))
            .map(|(chan, seq)| (bentstraw_optics::text::clip_text(chan, 64), seq));
        let mut waiting = match self.pool.submit(path, query, chan, work > api::HEAVY_WORK) {
            Ok(waiting) => waiting,
            Err(refusal) => return respond(refusal),
        };
        loop {
            tokio::select! {
                answer = &mut waiting.answer => return match answer {
                    Ok(answer) => timed(respond_with(answer.reply, answer.body), answer.engine_ms),
                    Err(_) => respond(Reply::text(500, "the request was lost")),
                },
                _ = tokio::time::sleep(OVERTIME_CHECK) => {
                    // Given up (and its work stopped) when `waiting` is dropped.
                    if waiting.overtime(work::MAX_COMPUTE) {
                        return respond(overtime());
                    }
                }
            }
        }
    }
}

fn asset(content_type: &'static str, text: &str) -> Reply {
    Reply::bytes(content_type, text.as_bytes().to_vec())
}

/// `reply` as an HTTP response, sent with its length (hyper writes `Content-Length` for a
/// body of known size: no chunks, which stall for the peer's delayed acknowledgement).
fn respond(mut reply: Reply) -> Response<AnswerBody> {
    let body = AnswerBody::small(std::mem::take(&mut reply.body));
    respond_with(reply, body)
}

/// `reply`'s status and headers with `body` (held within the answers' budgets).
fn respond_with(reply: Reply, body: AnswerBody) -> Response<AnswerBody> {
    let mut response = Response::new(body);
    *response.status_mut() = hyper::StatusCode::from_u16(reply.status)
        .unwrap_or(hyper::StatusCode::INTERNAL_SERVER_ERROR);
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static(reply.content_type),
    );
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    headers.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    if reply.status == 503 {
        headers.insert(header::RETRY_AFTER, HeaderValue::from_static("1"));
    }
    if let Some(name) = reply.file_name {
        if let Ok(value) = HeaderValue::from_str(&format!("attachment; filename=\"{name}\"")) {
            headers.insert(header::CONTENT_DISPOSITION, value);
        }
    }
    // A model's answer that started from the last frame's points says so (as the page's own
    // engine does), for the page and its tests.
    if reply.reused_points {
        headers.insert("x-points", HeaderValue::from_static("reused"));
    }
    response
}

/// `response` with the engine's time for it, as `Server-Timing: engine;dur=MS` (what a browser's
/// developer tools show, and what the page measures the native engine by).
fn timed(mut response: Response<AnswerBody>, engine_ms: f64) -> Response<AnswerBody> {
    if let Ok(value) = HeaderValue::from_str(&format!("engine;dur={engine_ms:.3}")) {
        response.headers_mut().insert("server-timing", value);
    }
    response
}

/// [`respond`], closing the connection after it (what follows on it is not read).
fn closing(reply: Reply) -> Response<AnswerBody> {
    let mut response = respond(reply);
    response
        .headers_mut()
        .insert(header::CONNECTION, HeaderValue::from_static("close"));
    response
}

/// The address `addr` as a URL's host: IPv6 in brackets.
pub fn url_host(addr: SocketAddr) -> String {
    match addr {
        SocketAddr::V4(a) => a.ip().to_string(),
        SocketAddr::V6(a) => format!("[{}]", a.ip()),
    }
}

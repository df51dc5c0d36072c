//! The explorer's web server: one thread takes requests and answers the cheap ones (the page, its
//! script, refusals); a fixed pool of workers computes frames from a short queue. A full queue
//! answers 503 at once, and work superseded by a newer request of the same page (its sequence
//! number) answers 409 without being computed; a frame already being drawn when it is superseded
//! is abandoned, so a fast drag never piles up work nor waits for a view it has left.

use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, TrySendError};
use std::sync::{Arc, Mutex};

use bentstraw_optics::frame::Frame;
use tiny_http::{Header, Method, Request, Response, Server};

use bentstraw_explore::{self as api, Reply, MAX_URL};

/// Frames computed at once (each is itself parallel over the cores).
pub const WORKERS: usize = 2;
/// Requests waiting for a worker, beyond which the server answers 503.
pub const QUEUE: usize = 4;
/// Most channels (page × kind of request) whose latest sequence number is remembered.
const MAX_CHANNELS: usize = 256;

/// Per channel: the latest sequence number seen, and the job being computed (its number and its
/// frame's stop flag).
#[derive(Default)]
struct Channel {
    newest: u64,
    running: Option<(u64, Arc<AtomicBool>)>,
}

/// The channels, by name.
type Latest = Arc<Mutex<HashMap<String, Channel>>>;

struct Job {
    request: Request,
    path: String,
    query: String,
    ticket: Option<(String, u64)>,
}

/// Serves the explorer on `server` until the process ends; `initial` is the query of the view the
/// page starts with (when its address holds none).
pub fn serve(server: Server, initial: &str) {
    let page = api::page::index_html(initial, api::page::Engine::Server);
    let latest: Latest = Arc::default();
    let (tx, rx) = sync_channel::<Job>(QUEUE);
    let rx = Arc::new(Mutex::new(rx));
    for _ in 0..WORKERS {
        let rx = Arc::clone(&rx);
        let latest = Arc::clone(&latest);
        std::thread::spawn(move || worker(&rx, &latest));
    }
    for request in server.incoming_requests() {
        let url = request.url().to_string();
        if url.len() > MAX_URL {
            respond(
                request,
                Reply::text(414, format!("address longer than {MAX_URL} bytes")),
            );
            continue;
        }
        if !matches!(request.method(), Method::Get | Method::Head) {
            respond(request, Reply::text(405, "only GET is served"));
            continue;
        }
        let (path, query) = url.split_once('?').unwrap_or((&url, ""));
        let reply = match path {
            "/" | "/index.html" => Some(asset("text/html; charset=utf-8", &page)),
            p if p.starts_with("/api/") => None,
            p => Some(
                match api::page::PAGE_FILES.iter().find(|f| p[1..] == *f.name) {
                    Some(f) => asset(f.content_type, f.text),
                    None => Reply::text(
                        404,
                        format!(
                            "no such page: {}",
                            bentstraw_optics::scene::clip_text(p, 60)
                        ),
                    ),
                },
            ),
        };
        if let Some(reply) = reply {
            respond(request, reply);
            continue;
        }
        let ticket = ticket_of(query);
        if let Some((chan, seq)) = &ticket {
            let mut map = latest.lock().unwrap_or_else(|e| e.into_inner());
            if map.len() >= MAX_CHANNELS && !map.contains_key(chan) {
                map.clear();
            }
            let entry = map.entry(chan.clone()).or_default();
            entry.newest = entry.newest.max(*seq);
            // The view being drawn for this page is no longer wanted: stop drawing it.
            if let Some((running, stop)) = &entry.running {
                if *running < entry.newest {
                    stop.store(true, Ordering::Relaxed);
                }
            }
        }
        let job = Job {
            request,
            path: path.to_string(),
            query: query.to_string(),
            ticket,
        };
        match tx.try_send(job) {
            Ok(()) => {}
            Err(TrySendError::Full(job)) | Err(TrySendError::Disconnected(job)) => respond(
                job.request,
                Reply::text(503, "the explorer is busy: try again in a moment"),
            ),
        }
    }
}

/// The channel and sequence number of an API request (`chan=…&seq=N`), if it has both.
fn ticket_of(query: &str) -> Option<(String, u64)> {
    let q = api::parse_query(query).ok()?;
    let chan = q.get("chan")?;
    let seq = q.get("seq")?.parse().ok()?;
    Some((bentstraw_optics::scene::clip_text(chan, 64), seq))
}

fn worker(rx: &Mutex<Receiver<Job>>, latest: &Latest) {
    let mut frame = Frame::default();
    loop {
        let job = {
            let rx = rx.lock().unwrap_or_else(|e| e.into_inner());
            match rx.recv() {
                Ok(job) => job,
                Err(_) => return,
            }
        };
        let stop = frame.stop_flag();
        if let Some((chan, seq)) = &job.ticket {
            let mut map = latest.lock().unwrap_or_else(|e| e.into_inner());
            let entry = map.entry(chan.clone()).or_default();
            if entry.newest > *seq {
                drop(map);
                respond(job.request, stale());
                continue;
            }
            // Cleared under the lock: a newer request can only set it from now on.
            stop.store(false, Ordering::Relaxed);
            entry.running = Some((*seq, Arc::clone(&stop)));
        }
        let reply = catch_unwind(AssertUnwindSafe(|| {
            api::handle(&job.path, &job.query, &mut frame)
        }))
        .unwrap_or_else(|_| {
            frame = Frame::default();
            Reply::text(500, "internal error while computing this view")
        });
        if let Some((chan, seq)) = &job.ticket {
            let mut map = latest.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(entry) = map.get_mut(chan) {
                if entry.running.as_ref().is_some_and(|r| r.0 == *seq) {
                    entry.running = None;
                }
            }
        }
        // Abandoned half-way: what was drawn is not the view asked for.
        let reply = if stop.swap(false, Ordering::Relaxed) {
            stale()
        } else {
            reply
        };
        respond(job.request, reply);
    }
}

/// The answer to a request a newer one from the same page has replaced.
fn stale() -> Reply {
    Reply::text(409, "stale: a newer request replaced this one")
}

fn asset(content_type: &'static str, text: &str) -> Reply {
    Reply {
        status: 200,
        content_type,
        body: text.as_bytes().to_vec(),
        file_name: None,
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}

fn respond(request: Request, reply: Reply) {
    // Sent whole with its length: tiny_http's chunked encoding (its default above 32 KB) writes
    // small pieces, which stall for the peer's delayed acknowledgement (tens of ms a frame).
    let length = reply.body.len();
    let mut response = Response::from_data(reply.body)
        .with_chunked_threshold(length + 1)
        .with_status_code(reply.status)
        .with_header(header("Content-Type", reply.content_type))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Content-Type-Options", "nosniff"));
    if let Some(name) = reply.file_name {
        response = response.with_header(header(
            "Content-Disposition",
            &format!("attachment; filename=\"{name}\""),
        ));
    }
    // The page may have gone (a cancelled request): nothing to do about it.
    let _ = request.respond(response);
}

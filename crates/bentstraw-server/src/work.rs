//! The explorer's heavy work (frames, models, rays, exports): [`WORKERS`] threads, each with its
//! own frame buffers, take requests from a queue of at most [`QUEUE`]; beyond it the server
//! answers 503 at once. Requests whose work is large ([`bentstraw_explore::HEAVY_WORK`]) wait in a
//! queue of their own ([`HEAVY_QUEUE`]) and are computed one at a time, the other worker kept for
//! the rest, so that a 4K export never makes a page's frames wait; a request computed for longer
//! than [`MAX_COMPUTE`] is stopped and refused. A request stops being worked on when nobody waits for it any more: its
//! client left (the connection closed) or the same page asked for something newer on the same
//! channel (`chan=…&seq=N`), which is then answered 409 ("stale"), as the page expects. Work
//! already under way is abandoned through its frame's stop flag, so a fast drag never piles up
//! work and a client that hangs up frees its worker at once.

use std::collections::{HashMap, VecDeque};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::sync::{Arc, Condvar, Mutex, Weak};
use std::time::Instant;

use bentstraw_explore::{self as api, Reply};
use bentstraw_optics::frame::Frame;
use tokio::sync::oneshot;

use super::answer::{AnswerBody, Budgets};

/// Requests computed at once (each is itself parallel over the cores).
pub const WORKERS: usize = 2;
/// Requests waiting for a worker, beyond which the server answers 503.
pub const QUEUE: usize = 4;
/// Heavy requests waiting, beyond which the server answers 503.
pub const HEAVY_QUEUE: usize = 2;
/// Heavy requests computed at once: the other workers are kept for the light ones.
const HEAVY_RUNNING: usize = WORKERS - 1;
/// Longest a request is computed before it is stopped and refused.
pub const MAX_COMPUTE: std::time::Duration = std::time::Duration::from_secs(30);
/// Most channels (page × kind of request) whose latest sequence number is remembered.
const MAX_CHANNELS: usize = 256;

/// Still wanted.
const WANTED: u8 = 0;
/// Its client left: nobody reads the answer.
const GONE: u8 = 1;
/// Replaced by a newer request of the same page: answered 409.
const STALE: u8 = 2;

/// A request's fate, shared by its waiting client, its channel and its worker.
#[derive(Default)]
struct Ticket {
    /// [`WANTED`], [`GONE`] or [`STALE`].
    fate: AtomicU8,
    /// While a worker computes it: that worker's stop flag. Guarded, so that a request given up
    /// just as a worker takes it is stopped all the same.
    running: Mutex<Option<Arc<AtomicBool>>>,
    /// When a worker started computing it.
    started: Mutex<Option<Instant>>,
}

impl Ticket {
    /// Gives the request up (`why`: [`GONE`] or [`STALE`]), stopping the work under way.
    fn give_up(&self, why: u8) {
        let running = self.running.lock().unwrap_or_else(|e| e.into_inner());
        let _ = self
            .fate
            .compare_exchange(WANTED, why, Ordering::Relaxed, Ordering::Relaxed);
        if let Some(stop) = running.as_ref() {
            stop.store(true, Ordering::Relaxed);
        }
    }

    fn fate(&self) -> u8 {
        self.fate.load(Ordering::Relaxed)
    }
}

/// A request waiting for a worker.
struct Job {
    path: String,
    query: String,
    heavy: bool,
    ticket: Arc<Ticket>,
    answer: oneshot::Sender<Answer>,
}

/// A worker's answer: the reply, and how long the engine took to compute it (sent to the page as
/// `Server-Timing`, so that it can be set beside the WebAssembly engine's own time).
pub struct Answer {
    /// The reply, its body taken out into `body`.
    pub reply: Reply,
    /// The reply's body, held within the answers' budgets.
    pub body: AnswerBody,
    /// The engine's time, in milliseconds.
    pub engine_ms: f64,
}

/// Per channel: the newest sequence number seen, and the requests not yet answered.
#[derive(Default)]
struct Channel {
    newest: u64,
    pending: Vec<(u64, Weak<Ticket>)>,
}

/// The requests waiting, and how many are being worked on.
#[derive(Default)]
struct Queue {
    jobs: VecDeque<Job>,
    /// Heavy requests waiting.
    heavy: VecDeque<Job>,
    /// Requests a worker has taken and not yet answered: the queue is full when these and
    /// those waiting make [`WORKERS`] + [`QUEUE`] (whether or not the workers have woken yet).
    running: usize,
    /// Of those, the heavy ones.
    running_heavy: usize,
}

impl Queue {
    /// The next request a free worker takes: a light one first; a heavy one only while fewer
    /// than [`HEAVY_RUNNING`] are computed.
    fn next(&mut self) -> Option<Job> {
        if let Some(job) = self.jobs.pop_front() {
            return Some(job);
        }
        if self.running_heavy < HEAVY_RUNNING {
            return self.heavy.pop_front();
        }
        None
    }
}

/// The workers and their queue.
pub struct Pool {
    /// What the workers remember between requests (a frame's points for the models that follow).
    memory: api::Memory,
    /// Room for the answers waiting to be sent.
    budgets: Budgets,
    queue: Mutex<Queue>,
    ready: Condvar,
    channels: Mutex<HashMap<String, Channel>>,
}

/// A request handed to the pool: its answer to come, and what gives it up when dropped (its
/// client gone: hyper drops a request's future when its connection closes).
pub struct Waiting {
    /// The answer.
    pub answer: oneshot::Receiver<Answer>,
    ticket: Arc<Ticket>,
}

impl Waiting {
    /// Whether a worker has computed it for longer than `limit`.
    pub fn overtime(&self, limit: std::time::Duration) -> bool {
        let started = *self
            .ticket
            .started
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        started.is_some_and(|t| t.elapsed() > limit)
    }
}

impl Drop for Waiting {
    fn drop(&mut self) {
        // After the answer, nothing is running: this changes nothing.
        self.ticket.give_up(GONE);
    }
}

/// The answer to a request a newer one from the same page has replaced.
pub fn stale() -> Reply {
    Reply::text(409, "stale: a newer request replaced this one")
}

/// The answer when the queue is full (sent with `Retry-After`).
pub fn busy() -> Reply {
    Reply::text(503, "the explorer is busy: try again in a moment")
}

impl Pool {
    /// The pool, its workers started.
    pub fn start() -> std::io::Result<Arc<Pool>> {
        let pool = Arc::new(Pool {
            memory: api::Memory::default(),
            budgets: Budgets::default(),
            queue: Mutex::new(Queue::default()),
            ready: Condvar::new(),
            channels: Mutex::new(HashMap::new()),
        });
        for k in 0..WORKERS {
            let pool = Arc::clone(&pool);
            std::thread::Builder::new()
                .name(format!("explore-worker-{k}"))
                .spawn(move || pool.work())?;
        }
        Ok(pool)
    }

    /// Queues `path?query` (`chan`: its channel and sequence number, if it has them; `heavy`:
    /// whether its work is beyond [`bentstraw_explore::HEAVY_WORK`]); the answer to wait for, or
    /// the refusal to send at once (409 when already replaced, 503 when full).
    pub fn submit(
        &self,
        path: &str,
        query: &str,
        chan: Option<(String, u64)>,
        heavy: bool,
    ) -> Result<Waiting, Reply> {
        let ticket = Arc::new(Ticket::default());
        if let Some((name, seq)) = chan {
            let mut channels = self.channels.lock().unwrap_or_else(|e| e.into_inner());
            if channels.len() >= MAX_CHANNELS && !channels.contains_key(&name) {
                channels.clear();
            }
            let channel = channels.entry(name).or_default();
            if seq < channel.newest {
                return Err(stale());
            }
            channel.newest = seq;
            // What this page asked before on this channel is no longer wanted.
            channel.pending.retain(|(s, t)| match t.upgrade() {
                Some(t) if *s < seq => {
                    t.give_up(STALE);
                    false
                }
                Some(t) => t.fate() == WANTED,
                None => false,
            });
            channel.pending.push((seq, Arc::downgrade(&ticket)));
        }
        let (tx, rx) = oneshot::channel();
        let mut queue = self.queue.lock().unwrap_or_else(|e| e.into_inner());
        // Requests given up leave the queue now, not when a worker comes to them.
        queue.jobs.retain(|job| job.ticket.fate() == WANTED);
        queue.heavy.retain(|job| job.ticket.fate() == WANTED);
        let full = if heavy {
            queue.heavy.len() + queue.running_heavy >= HEAVY_QUEUE + HEAVY_RUNNING
        } else {
            queue.jobs.len() + queue.running - queue.running_heavy >= QUEUE + WORKERS
        };
        if full {
            return Err(busy());
        }
        let job = Job {
            path: path.to_string(),
            query: query.to_string(),
            heavy,
            ticket: Arc::clone(&ticket),
            answer: tx,
        };
        if heavy {
            queue.heavy.push_back(job);
        } else {
            queue.jobs.push_back(job);
        }
        drop(queue);
        // Every worker looks: the one woken may be kept for light work.
        self.ready.notify_all();
        Ok(Waiting { answer: rx, ticket })
    }

    /// A worker: takes requests and answers them, until the process ends.
    fn work(&self) {
        let mut frame = Frame::default();
        loop {
            let job = {
                let mut queue = self.queue.lock().unwrap_or_else(|e| e.into_inner());
                loop {
                    match queue.next() {
                        Some(job) => {
                            queue.running += 1;
                            queue.running_heavy += usize::from(job.heavy);
                            break job;
                        }
                        None => queue = self.ready.wait(queue).unwrap_or_else(|e| e.into_inner()),
                    }
                }
            };
            let Job {
                path,
                query,
                heavy,
                ticket,
                answer,
            } = job;
            let started = Instant::now();
            let reply = compute(&path, &query, &ticket, &mut frame, &self.memory);
            let engine_ms = started.elapsed().as_secs_f64() * 1e3;
            // Free before answering: the client's next request finds room.
            {
                let mut queue = self.queue.lock().unwrap_or_else(|e| e.into_inner());
                queue.running -= 1;
                queue.running_heavy -= usize::from(heavy);
            }
            // A heavy one done: a waiting heavy one may start.
            if heavy {
                self.ready.notify_all();
            }
            // A client that left reads nothing: that is fine.
            if let Some(mut reply) = reply {
                // Its client left meanwhile: no room taken for an answer nobody reads.
                if ticket.fate() == GONE {
                    continue;
                }
                let body = match self.budgets.hold(std::mem::take(&mut reply.body)) {
                    Some(body) => body,
                    None => {
                        reply = busy();
                        AnswerBody::small(std::mem::take(&mut reply.body))
                    }
                };
                let _ = answer.send(Answer {
                    reply,
                    body,
                    engine_ms,
                });
            }
        }
    }
}

/// The answer to `path?query` computed with `frame`'s buffers and the workers' `memory`, or none
/// if its client left; 409 if it was superseded, before or while it was computed.
fn compute(
    path: &str,
    query: &str,
    ticket: &Ticket,
    frame: &mut Frame,
    memory: &api::Memory,
) -> Option<Reply> {
    let stop = frame.stop_flag();
    {
        let mut running = ticket.running.lock().unwrap_or_else(|e| e.into_inner());
        match ticket.fate() {
            WANTED => {}
            STALE => return Some(stale()),
            _ => return None,
        }
        // Cleared under the lock: giving the request up can only set it from now on.
        stop.store(false, Ordering::Relaxed);
        *running = Some(Arc::clone(&stop));
        *ticket.started.lock().unwrap_or_else(|e| e.into_inner()) = Some(Instant::now());
    }
    let reply = catch_unwind(AssertUnwindSafe(|| api::handle(path, query, frame, memory)))
        .unwrap_or_else(|_| {
            *frame = Frame::default();
            Reply::text(500, "internal error while computing this view")
        });
    *ticket.running.lock().unwrap_or_else(|e| e.into_inner()) = None;
    // Abandoned half-way: what was computed is not what was asked for.
    if stop.swap(false, Ordering::Relaxed) {
        return (ticket.fate() == STALE).then(stale);
    }
    Some(reply)
}

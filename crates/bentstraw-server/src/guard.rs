//! A connection's socket as hyper sees it, with two limits hyper lacks: a request line longer
//! than [`MAX_REQUEST_LINE`] is refused (414) as soon as that many bytes have come, never read
//! whole; and a write that the client does not take within [`WRITE_TIMEOUT`] fails, so a client
//! that stops reading cannot hold a response (and its connection) forever.

use std::future::Future;
use std::io;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::task::{Context, Poll};
use std::time::{Duration, Instant};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::time::Sleep;

use bentstraw_explore::MAX_URL;

/// Longest request line taken: the longest address the explorer serves, its method and version.
pub const MAX_REQUEST_LINE: usize = MAX_URL + 64;
/// How long a response may wait for the client to take any of its bytes.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(10);

/// What hyper is given in place of a request line that is too long: a request the server
/// answers 414 (it knows from [`Guarded::too_long`]'s flag), after which the connection closes.
const STAND_IN: &[u8] = b"GET / HTTP/1.1\r\nhost: stand-in\r\nconnection: close\r\n\r\n";

/// Where the bytes read stand in the requests.
enum Reading {
    /// Before a request line: its bytes are held back until its end shows it is short enough.
    RequestLine,
    /// In a request's header lines, passed on at once (hyper bounds them): `line` counts the
    /// current line's bytes, `start` holds its first ones (lowercase), `body` whether a header
    /// announced a body.
    Headers {
        line: usize,
        start: [u8; 18],
        body: bool,
    },
    /// After a request with a body, or with a method the server refuses (it then closes the
    /// connection): passed on unexamined.
    Through,
    /// The request line was too long: hyper gets [`STAND_IN`], then nothing more is read.
    TooLong,
}

/// A socket with the request-line limit and the write timeout (module documentation).
pub struct Guarded<S> {
    io: S,
    reading: Reading,
    /// The request line read so far (at most [`MAX_REQUEST_LINE`] bytes).
    line: Vec<u8>,
    /// Bytes ready for hyper, from `ready_at` on.
    ready: Vec<u8>,
    ready_at: usize,
    /// Set when a request line was too long.
    too_long: Arc<AtomicBool>,
    /// When the write waiting for the client gives up.
    write_deadline: Option<Pin<Box<Sleep>>>,
    /// What the connection is doing, for the server's choice of one to close.
    activity: Arc<Activity>,
}

/// What a connection is doing, as the server sees it when it must close one to make room: the
/// one quiet the longest goes, never one writing an answer or in the middle of a request's head.
#[derive(Debug, Default)]
pub struct Activity {
    /// When bytes last came or went, in milliseconds from the server's start.
    last: AtomicU64,
    /// Whether a write waits for the client to take what was sent (an answer under way).
    writing: AtomicBool,
    /// Whether part of a request's head has come and not the whole of it.
    in_head: AtomicBool,
}

impl Activity {
    /// Notes that something happened now.
    pub fn touch(&self) {
        let now = START.get_or_init(Instant::now).elapsed().as_millis() as u64;
        self.last.store(now, Ordering::Relaxed);
    }

    /// When something last happened (ms from the server's start).
    pub fn last(&self) -> u64 {
        self.last.load(Ordering::Relaxed)
    }

    /// Notes that the connection was refused and closed on the server's side: it is the first
    /// to go when room is needed.
    pub fn refused(&self) {
        self.writing.store(false, Ordering::Relaxed);
        self.in_head.store(false, Ordering::Relaxed);
        self.last.store(0, Ordering::Relaxed);
    }

    /// Whether the connection may be closed to make room: it is writing nothing and holds no
    /// part of a request.
    pub fn quiet(&self) -> bool {
        !self.writing.load(Ordering::Relaxed) && !self.in_head.load(Ordering::Relaxed)
    }
}

/// The server's start, the origin of [`Activity`]'s times.
static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();

impl<S> Guarded<S> {
    /// `io` guarded; `too_long` is set when a request line is refused.
    pub fn new(io: S, too_long: Arc<AtomicBool>) -> Guarded<S> {
        Guarded {
            io,
            reading: Reading::RequestLine,
            line: Vec::new(),
            ready: Vec::new(),
            ready_at: 0,
            too_long,
            write_deadline: None,
            activity: Arc::default(),
        }
    }

    /// The socket, its doings noted in `activity`.
    pub fn watched(mut self, activity: Arc<Activity>) -> Guarded<S> {
        activity.touch();
        self.activity = activity;
        self
    }

    /// The socket.
    pub fn get_mut(&mut self) -> &mut S {
        &mut self.io
    }

    /// Sorts `bytes` just read: passed on (`ready`), held back (`line`), or dropped once the
    /// request line is too long.
    fn take(&mut self, bytes: &[u8]) {
        let mut rest = bytes;
        while let Some((&b, after)) = rest.split_first() {
            match &mut self.reading {
                Reading::RequestLine => {
                    self.line.push(b);
                    if b == b'\n' {
                        let text = self.line.trim_ascii_end();
                        let method = text.split(|&c| c == b' ').next().unwrap_or(b"");
                        let next = if text.is_empty() {
                            // A blank line before a request is allowed.
                            Reading::RequestLine
                        } else if method == b"GET" || method == b"HEAD" {
                            Reading::Headers {
                                line: 0,
                                start: [0; 18],
                                body: false,
                            }
                        } else {
                            Reading::Through
                        };
                        self.ready.append(&mut self.line);
                        self.reading = next;
                    } else if self.line.len() > MAX_REQUEST_LINE {
                        self.line = Vec::new();
                        self.ready.extend_from_slice(STAND_IN);
                        self.too_long.store(true, Ordering::Relaxed);
                        self.reading = Reading::TooLong;
                        return;
                    }
                }
                Reading::Headers { line, start, body } => {
                    self.ready.push(b);
                    if b == b'\n' {
                        let blank = *line == 0 || (*line == 1 && start[0] == b'\r');
                        if blank {
                            self.reading = if *body {
                                Reading::Through
                            } else {
                                Reading::RequestLine
                            };
                        } else {
                            let name = &start[..(*line).min(start.len())];
                            if name.starts_with(b"content-length:")
                                || name.starts_with(b"transfer-encoding:")
                            {
                                *body = true;
                            }
                            *line = 0;
                        }
                    } else {
                        if *line < start.len() {
                            start[*line] = b.to_ascii_lowercase();
                        }
                        *line += 1;
                    }
                }
                Reading::Through => {
                    self.ready.extend_from_slice(rest);
                    return;
                }
                Reading::TooLong => return,
            }
            rest = after;
        }
    }

    /// Copies what is ready into `buf`; whether anything was.
    fn give(&mut self, buf: &mut ReadBuf<'_>) -> bool {
        let ready = &self.ready[self.ready_at..];
        if ready.is_empty() {
            return false;
        }
        let n = ready.len().min(buf.remaining());
        buf.put_slice(&ready[..n]);
        self.ready_at += n;
        if self.ready_at == self.ready.len() {
            self.ready.clear();
            self.ready_at = 0;
        }
        true
    }
}

impl<S: AsyncRead + Unpin> AsyncRead for Guarded<S> {
    fn poll_read(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        let this = self.get_mut();
        loop {
            if this.give(buf) {
                return Poll::Ready(Ok(()));
            }
            if let Reading::TooLong = this.reading {
                // Nothing more is read: the refusal is written, then the connection closes.
                return Poll::Pending;
            }
            let mut chunk = [0u8; 4096];
            let mut into = ReadBuf::new(&mut chunk);
            match Pin::new(&mut this.io).poll_read(cx, &mut into) {
                Poll::Ready(Ok(())) if into.filled().is_empty() => {
                    // The end: a request line cut short goes to hyper, which refuses it.
                    let mut line = std::mem::take(&mut this.line);
                    this.ready.append(&mut line);
                    this.give(buf);
                    return Poll::Ready(Ok(()));
                }
                Poll::Ready(Ok(())) => {
                    let n = into.filled().len();
                    this.take(&chunk[..n]);
                    this.activity.touch();
                    let in_head =
                        !this.line.is_empty() || matches!(this.reading, Reading::Headers { .. });
                    this.activity.in_head.store(in_head, Ordering::Relaxed);
                }
                other => return other,
            }
        }
    }
}

impl<S: AsyncWrite + Unpin> Guarded<S> {
    /// Runs a write of the socket, failing it when the client has taken nothing for
    /// [`WRITE_TIMEOUT`].
    fn timed<T>(
        &mut self,
        cx: &mut Context<'_>,
        write: impl FnOnce(Pin<&mut S>, &mut Context<'_>) -> Poll<io::Result<T>>,
    ) -> Poll<io::Result<T>> {
        match write(Pin::new(&mut self.io), cx) {
            Poll::Pending => {
                self.activity.writing.store(true, Ordering::Relaxed);
                let deadline = self
                    .write_deadline
                    .get_or_insert_with(|| Box::pin(tokio::time::sleep(WRITE_TIMEOUT)));
                if deadline.as_mut().poll(cx).is_ready() {
                    return Poll::Ready(Err(io::Error::new(
                        io::ErrorKind::TimedOut,
                        "the client took no data",
                    )));
                }
                Poll::Pending
            }
            done => {
                self.write_deadline = None;
                self.activity.writing.store(false, Ordering::Relaxed);
                self.activity.touch();
                done
            }
        }
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for Guarded<S> {
    fn poll_write(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        self.get_mut().timed(cx, |io, cx| io.poll_write(cx, buf))
    }

    fn poll_write_vectored(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        self.get_mut()
            .timed(cx, |io, cx| io.poll_write_vectored(cx, bufs))
    }

    fn is_write_vectored(&self) -> bool {
        self.io.is_write_vectored()
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        self.get_mut().timed(cx, |io, cx| io.poll_flush(cx))
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        self.get_mut().timed(cx, |io, cx| io.poll_shutdown(cx))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What hyper would read of `input`, given in pieces of `piece` bytes.
    fn passed(input: &[u8], piece: usize) -> (Vec<u8>, bool) {
        let flag = Arc::new(AtomicBool::new(false));
        let mut g = Guarded::new((), Arc::clone(&flag));
        for chunk in input.chunks(piece) {
            g.take(chunk);
        }
        (g.ready[g.ready_at..].to_vec(), flag.load(Ordering::Relaxed))
    }

    #[test]
    fn requests_pass_whole_and_in_order() {
        let two = b"GET /a HTTP/1.1\r\nHost: x\r\n\r\nGET /b?c=d HTTP/1.1\r\nHost: x\r\n\r\n";
        for piece in [1, 3, 7, 4096] {
            assert_eq!(passed(two, piece), (two.to_vec(), false), "{piece}");
        }
        // A request line not yet ended is held back.
        let (got, _) = passed(b"GET /a HTTP/1.1\r\nHost: x\r\n\r\nGET /b HT", 5);
        assert_eq!(got, b"GET /a HTTP/1.1\r\nHost: x\r\n\r\n");
    }

    #[test]
    fn a_long_request_line_becomes_the_stand_in() {
        let mut long = b"GET /".to_vec();
        long.extend_from_slice(&vec![b'a'; MAX_REQUEST_LINE + 10_000]);
        for piece in [1000, 4096] {
            let (got, flag) = passed(&long, piece);
            assert_eq!(got, STAND_IN);
            assert!(flag);
        }
        // After a first request, on the same connection.
        let mut two = b"GET / HTTP/1.1\r\nHost: x\r\n\r\n".to_vec();
        let first = two.len();
        two.extend_from_slice(&long);
        let (got, flag) = passed(&two, 4096);
        assert_eq!(&got[..first], &two[..first]);
        assert_eq!(&got[first..], STAND_IN);
        assert!(flag);
        // A line just under the limit passes.
        let mut fits = b"GET /".to_vec();
        fits.extend_from_slice(&vec![b'a'; MAX_URL]);
        fits.extend_from_slice(b" HTTP/1.1\r\n\r\n");
        assert_eq!(passed(&fits, 4096), (fits.clone(), false));
    }

    #[test]
    fn bodies_are_not_taken_for_request_lines() {
        let mut post = b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 30000\r\n\r\n".to_vec();
        post.extend_from_slice(&[b'a'; 30_000]);
        assert_eq!(passed(&post, 4096), (post.clone(), false));
        let mut get = b"GET / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n".to_vec();
        get.extend_from_slice(&[b'a'; 30_000]);
        assert_eq!(passed(&get, 4096), (get.clone(), false));
    }
}

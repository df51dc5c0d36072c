//! Answers' bodies, bounded in memory however slowly clients read them. Answers computed by the
//! workers are held in memory up to [`MEMORY_FOR_ANSWERS`] in all; one that does not fit there
//! (a 4K picture for a slow client, say) is written to an unnamed temporary file and sent from it a
//! chunk at a time as the client takes it, so that the server's memory is that budget plus a
//! chunk per connection whatever the clients do. The files hold at most [`DISK_FOR_ANSWERS`] in
//! all; beyond it the request is answered 503. Nothing stays on disk: a file has no name and is
//! gone when its answer is sent or dropped.

use std::io::{self, Seek, Write};
use std::pin::Pin;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::task::{Context, Poll};

use bytes::Bytes;
use hyper::body::{Body, Frame, SizeHint};
use tokio::io::{AsyncRead, ReadBuf};

/// Most bytes of computed answers held in memory at once, over all connections.
pub const MEMORY_FOR_ANSWERS: u64 = 128 << 20;
/// Most bytes of computed answers waiting in temporary files at once.
pub const DISK_FOR_ANSWERS: u64 = 4 << 30;
/// Bytes read from a file per piece of an answer sent.
pub const CHUNK: usize = 64 << 10;

/// Bytes taken from a budget, given back when dropped.
pub struct Taken {
    budget: Arc<AtomicU64>,
    bytes: u64,
}

impl Drop for Taken {
    fn drop(&mut self) {
        self.budget.fetch_sub(self.bytes, Ordering::Relaxed);
    }
}

/// Takes `bytes` from `budget` (bytes in use, at most `limit`), if they fit.
fn take(budget: &Arc<AtomicU64>, bytes: u64, limit: u64) -> Option<Taken> {
    budget
        .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |used| {
            (used + bytes <= limit).then_some(used + bytes)
        })
        .ok()
        .map(|_| Taken {
            budget: Arc::clone(budget),
            bytes,
        })
}

/// A computed answer's bytes with their room in memory: given back only when the last piece of
/// them has been written (pieces of it wait in the connection's buffer after the body is done).
struct Owned {
    body: Vec<u8>,
    _taken: Taken,
}

impl AsRef<[u8]> for Owned {
    fn as_ref(&self) -> &[u8] {
        &self.body
    }
}

/// The memory and disk the answers waiting to be sent take.
#[derive(Default)]
pub struct Budgets {
    memory: Arc<AtomicU64>,
    disk: Arc<AtomicU64>,
}

impl Budgets {
    /// A computed answer's body, in memory if it fits there, else in a temporary file; `None`
    /// when neither has room (or the file cannot be written).
    pub fn hold(&self, body: Vec<u8>) -> Option<AnswerBody> {
        let n = body.len() as u64;
        if let Some(taken) = take(&self.memory, n, MEMORY_FOR_ANSWERS) {
            return Some(AnswerBody::Memory(Bytes::from_owner(Owned {
                body,
                _taken: taken,
            })));
        }
        let taken = take(&self.disk, n, DISK_FOR_ANSWERS)?;
        let mut file = tempfile::tempfile().ok()?;
        file.write_all(&body).ok()?;
        file.rewind().ok()?;
        drop(body);
        Some(AnswerBody::File {
            file: tokio::fs::File::from_std(file),
            left: n,
            buf: Vec::new(),
            _taken: taken,
        })
    }
}

/// An answer's body: bytes in memory, or a temporary file read a chunk at a time.
pub enum AnswerBody {
    /// The bytes not yet sent (a computed answer's own their room in memory).
    Memory(Bytes),
    /// A file, the bytes of it still to send, and a chunk's buffer.
    File {
        /// The unnamed file.
        file: tokio::fs::File,
        /// Bytes not yet sent.
        left: u64,
        /// The chunk being read.
        buf: Vec<u8>,
        /// Its room on disk, given back when the answer is sent or dropped.
        _taken: Taken,
    },
}

impl AnswerBody {
    /// A body of `bytes` that counts against no budget (the page's files, refusals).
    pub fn small(bytes: impl Into<Bytes>) -> AnswerBody {
        AnswerBody::Memory(bytes.into())
    }
}

impl Body for AnswerBody {
    type Data = Bytes;
    type Error = io::Error;

    fn poll_frame(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, io::Error>>> {
        match self.get_mut() {
            AnswerBody::Memory(bytes) => {
                // A chunk at a time: the connection's buffer holds a few, never the whole answer
                // once the body is done.
                let n = bytes.len().min(CHUNK);
                Poll::Ready((n > 0).then(|| Ok(Frame::data(bytes.split_to(n)))))
            }
            AnswerBody::File {
                file, left, buf, ..
            } => {
                if *left == 0 {
                    return Poll::Ready(None);
                }
                let want = (*left).min(CHUNK as u64) as usize;
                buf.resize(want, 0);
                let mut read = ReadBuf::new(&mut buf[..want]);
                match Pin::new(file).poll_read(cx, &mut read) {
                    Poll::Pending => Poll::Pending,
                    Poll::Ready(Err(e)) => Poll::Ready(Some(Err(e))),
                    Poll::Ready(Ok(())) => {
                        let got = read.filled().len();
                        if got == 0 {
                            return Poll::Ready(Some(Err(io::ErrorKind::UnexpectedEof.into())));
                        }
                        *left -= got as u64;
                        Poll::Ready(Some(Ok(Frame::data(Bytes::copy_from_slice(&buf[..got])))))
                    }
                }
            }
        }
    }

    fn is_end_stream(&self) -> bool {
        match self {
            AnswerBody::Memory(bytes) => bytes.is_empty(),
            AnswerBody::File { left, .. } => *left == 0,
        }
    }

    fn size_hint(&self) -> SizeHint {
        // Exact: hyper sends it as `Content-Length` (no chunked encoding).
        SizeHint::with_exact(match self {
            AnswerBody::Memory(bytes) => bytes.len() as u64,
            AnswerBody::File { left, .. } => *left,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use http_body_util::BodyExt;

    async fn collect(body: AnswerBody) -> Vec<u8> {
        body.collect().await.unwrap().to_bytes().to_vec()
    }

    #[tokio::test]
    async fn answers_beyond_memory_go_through_a_file_whole() {
        let budgets = Budgets::default();
        // Fill the memory budget but for a little.
        let filler = budgets
            .hold(vec![0; (MEMORY_FOR_ANSWERS - 10) as usize])
            .unwrap();
        assert!(matches!(filler, AnswerBody::Memory(_)));
        // A small one still fits in memory; a larger one goes to a file, and comes out whole.
        let small = budgets.hold(vec![1; 10]).unwrap();
        assert!(matches!(small, AnswerBody::Memory(_)));
        let big: Vec<u8> = (0..3 * CHUNK + 17).map(|k| (k % 251) as u8).collect();
        let held = budgets.hold(big.clone()).unwrap();
        assert!(matches!(held, AnswerBody::File { .. }));
        assert_eq!(held.size_hint().exact(), Some(big.len() as u64));
        assert_eq!(budgets.disk.load(Ordering::Relaxed), big.len() as u64);
        assert_eq!(collect(held).await, big);
        // Sent or dropped, an answer gives its room back.
        assert_eq!(budgets.disk.load(Ordering::Relaxed), 0);
        drop(filler);
        assert_eq!(budgets.memory.load(Ordering::Relaxed), 10);
        assert_eq!(collect(small).await, vec![1; 10]);
        assert_eq!(budgets.memory.load(Ordering::Relaxed), 0);
    }

    #[test]
    fn budgets_refuse_what_does_not_fit() {
        let used = Arc::new(AtomicU64::new(0));
        let a = take(&used, 60, 100).unwrap();
        assert!(take(&used, 41, 100).is_none());
        let b = take(&used, 40, 100).unwrap();
        drop(a);
        assert_eq!(used.load(Ordering::Relaxed), 40);
        drop(b);
        assert_eq!(used.load(Ordering::Relaxed), 0);
    }
}

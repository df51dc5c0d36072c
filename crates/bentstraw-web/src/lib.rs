//! The explorer's engine in the page: the same [`bentstraw_explore::handle`] that
//! `bentstraw explore` serves over HTTP, compiled to WebAssembly and called by a Web Worker with
//! the same path and query. One API, two carriers: the page cannot tell them apart, and the
//! numbers are the same to the bit (see `docs/physics.md` for the physics itself).

#![warn(missing_docs)]

use std::cell::RefCell;

use bentstraw_optics::frame::Frame;
use wasm_bindgen::prelude::*;

// Built with threads: `initThreadPool(n)` starts rayon's pool of `n` Web Workers sharing this
// instance's memory, over which each frame's rows are split as on the native program's cores.
#[cfg(target_feature = "atomics")]
pub use wasm_bindgen_rayon::init_thread_pool;

thread_local! {
    /// The worker's picture buffers, kept from one frame to the next (a worker is one thread).
    static FRAME: RefCell<Frame> = RefCell::new(Frame::default());
    /// What this worker's engine remembers between requests (a frame's points for its models).
    static MEMORY: bentstraw_explore::Memory = bentstraw_explore::Memory::default();
}

/// A finished answer, as the page reads an HTTP response: status, type, body, download name.
#[wasm_bindgen]
pub struct Reply {
    status: u16,
    content_type: String,
    body: Vec<u8>,
    file_name: Option<String>,
    reused_points: bool,
}

#[wasm_bindgen]
impl Reply {
    /// The HTTP status the server would send (200, or 400 with the rule broken as text).
    #[wasm_bindgen(getter)]
    pub fn status(&self) -> u16 {
        self.status
    }

    /// The `Content-Type` the server would send.
    #[wasm_bindgen(getter, js_name = contentType)]
    pub fn content_type(&self) -> String {
        self.content_type.clone()
    }

    /// The body (taken: a second call gives nothing).
    #[wasm_bindgen(js_name = takeBody)]
    pub fn take_body(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.body)
    }

    /// The file name of a download, if the answer is one.
    #[wasm_bindgen(getter, js_name = fileName)]
    pub fn file_name(&self) -> Option<String> {
        self.file_name.clone()
    }

    /// Whether a model's answer started from this worker's last frame's points (the server sends
    /// `X-Points: reused`).
    #[wasm_bindgen(getter, js_name = reusedPoints)]
    pub fn reused_points(&self) -> bool {
        self.reused_points
    }
}

/// How many threads this engine splits a frame over (rayon's pool: 1 without threads).
#[wasm_bindgen]
pub fn threads() -> usize {
    bentstraw_optics::parallel::current_num_threads()
}

/// Where this worker's stop flag lies in the engine's memory (a byte: 0 go on, 1 stop). With
/// threads the memory is shared, so the page abandons a frame by setting it, and every thread
/// stops at its next row; the worker clears it before each request.
#[wasm_bindgen(js_name = stopFlag)]
pub fn stop_flag() -> usize {
    FRAME.with(|frame| std::sync::Arc::as_ptr(&frame.borrow().stop_flag()) as usize)
}

/// The answer to the API request `path?query` (for example `/api/frame`, `observer=0.1,0,0.1&…`).
#[wasm_bindgen]
pub fn handle(path: &str, query: &str) -> Reply {
    let reply = FRAME.with(|frame| {
        let mut frame = frame.borrow_mut();
        MEMORY.with(|memory| bentstraw_explore::handle(path, query, &mut frame, memory))
    });
    Reply {
        status: reply.status,
        content_type: reply.content_type.to_string(),
        body: reply.body,
        file_name: reply.file_name,
        reused_points: reply.reused_points,
    }
}

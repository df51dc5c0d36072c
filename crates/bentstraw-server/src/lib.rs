//! `bentstraw-server`: the live explorer served by bentstraw itself on this machine. The page
//! (embedded, no network needed) asks for frames, models, rays and exports; the server checks
//! where requests come from, queues the heavy ones for a small pool of workers, and answers each
//! with the explorer's API ([`bentstraw_explore::handle`]): it only carries requests and answers.

#![warn(missing_docs)]

mod answer;
mod guard;
mod kept;
mod origin;
mod server;
mod work;

pub use origin::{new_token, Access};
pub use server::{serve, url_host};

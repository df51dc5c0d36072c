//! Shared test helpers: an independent high-precision tracer.
pub mod reference;

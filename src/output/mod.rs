//! Exporters: CSV tables and terminal tables, written into any `io::Write`, and the atomic
//! file writer that puts them on disk whole or not at all.

pub mod atomic;
pub mod diagnose;
pub mod identify;
pub mod study;
pub mod table;

pub use atomic::write_atomically;

//! whitted compiled to WebAssembly: the page's calls into the same library as the command line.
//!
//! The page writes a JSON request into the inbox, calls [`abi::whitted_call`], and reads the JSON
//! answer (and, for `render`, the RGBA bytes) back; `web/README.md` is the contract. Every request
//! is validated by the library functions the command line uses (`whitted::request`), so errors
//! are worded alike, and every path returns an error instead of panicking: a panic would abort
//! the module (`panic = "abort"`), so none may be reachable from a request.
//!
//! The only code the `unsafe_code` lint reports is the `#[no_mangle]` on the exports of [`abi`]
//! (a WebAssembly module can be called only through exported, unmangled names): there is no
//! `unsafe` block, and no raw pointer is dereferenced; the lint is therefore denied, not
//! forbidden, and allowed on those items alone.
#![deny(unsafe_code)]

pub mod abi;
mod ask;
pub mod ops;

pub use ops::{call, Answer};

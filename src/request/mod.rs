//! What a command does between reading its arguments and printing its answer, shared by the
//! command line (`src/cli/`) and the WebAssembly binding (`web/`): both only turn their input
//! (clap's arguments, a JSON request) into these types, call the same functions and print or
//! return what comes back, so the page and the terminal give the same numbers and word every error
//! alike.
//!
//! - [`parse`]: the options' values as the command line writes them (`I,J`, `WxH`, …), checked;
//! - [`options`]: `--depth`, `--size`, `--aa`/`--threshold`/`--max-level`, `--accel`/`--bounds`/
//!   `--grid` validated into the library's types, with the notes for ignored options;
//! - [`target`]: `--pixel`/`--ray` → the primary ray, checked against the image;
//! - [`check`]: what a valid scene models (`whitted check`);
//! - [`trace`]: one pixel's or ray's trace document and narration (`whitted trace`);
//! - [`render`]: an image and its statistics (`whitted render --json`);
//! - [`figure`]: one diagram (`whitted figure`), with the pixel it picked;
//! - [`grade`]: a student's trace document checked (`whitted grade`);
//! - [`exercises`]: one pixel's exercise sheet and answers (`whitted exercises`).

pub mod check;
pub mod exercises;
pub mod figure;
pub mod grade;
pub mod options;
pub mod parse;
pub mod render;
pub mod target;
pub mod trace;

use std::fmt;

/// An error for the reader: bad input (a scene, an option, a pixel; exit code 2) or anything else
/// (exit code 1). The message names the option or JSON path, one line per problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failure {
    /// The message, one line per problem.
    pub message: String,
    /// True for bad input.
    pub input: bool,
}

/// The exit code (and the binding's return code) of bad input.
pub const INPUT_CODE: u8 = 2;
/// The exit code (and the binding's return code) of any other failure.
pub const OTHER_CODE: u8 = 1;

impl Failure {
    /// Bad input: exit code 2.
    pub fn input(message: impl Into<String>) -> Self {
        Self { message: message.into(), input: true }
    }
    /// Anything else (writing a file failed): exit code 1.
    pub fn other(message: impl Into<String>) -> Self {
        Self { message: message.into(), input: false }
    }
    /// [`INPUT_CODE`] or [`OTHER_CODE`].
    #[must_use]
    pub fn code(&self) -> u8 {
        if self.input {
            INPUT_CODE
        } else {
            OTHER_CODE
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Failure {}

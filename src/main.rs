//! The `whitted` binary: parse the command line, run the command, print the error, exit
//! (0 success, 1 failure, 2 bad input). A broken pipe on stdout counts as success.
#![forbid(unsafe_code)]

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    let code = cli::main();
    ExitCode::from(code)
}

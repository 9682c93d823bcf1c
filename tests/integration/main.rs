//! The one integration-test binary (one build, shared helpers): scenes, traces, numerics, figures, the CLI.
#![allow(clippy::float_cmp)] // The tests pin exact IEEE results on purpose (numerics.md).

mod accel;
mod claims;
mod cli;
mod figures;
mod grade;
mod hardening;
mod layout;
mod narration;
mod numerics;
mod outputs;
mod properties;
mod sampling;
mod scripts;
mod states;
mod support;
mod tidy;
mod traces;
mod web;

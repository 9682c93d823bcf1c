//! The one integration-test binary (design.md habit 7): scenes, traces, numerics, figures and the CLI.
#![allow(clippy::float_cmp)] // The tests pin exact IEEE results on purpose (numerics.md).

mod accel;
mod cli;
mod figures;
mod numerics;
mod properties;
mod sampling;
mod support;
mod tidy;
mod traces;
mod web;

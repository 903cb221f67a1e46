//! Integration tests of noether-constraints, one binary with a module per topic.

mod bad_input;
mod chain;
mod continuous;
mod gibbs_appell;
mod impulse;
mod models;
mod nonholonomic;
mod rattle;
mod time_resolution;

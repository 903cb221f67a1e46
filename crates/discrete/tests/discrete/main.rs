//! Tests of noether-discrete, one binary with a module per kind of truth: closed forms and orders,
//! conservation laws, regressions against hand-written equations, bad input.

mod bad_input;
mod boundary;
mod bounded_control;
mod conserves;
mod degenerate;
mod forced;
mod mechanical;
mod models;
mod optimal_control;
mod order;
mod regress;
mod tangent;

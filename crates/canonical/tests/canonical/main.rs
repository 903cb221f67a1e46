//! Integration tests of noether-canonical: one test binary, one module per topic.

mod action_angle;
mod routh;
mod section;

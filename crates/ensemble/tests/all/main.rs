//! noether-ensemble's integration tests in one test binary (one link; what the files share is compiled
//! once): one module per file of tests/.

#[path = "../ensemble.rs"]
mod ensemble;
#[path = "../issue29.rs"]
mod issue29;

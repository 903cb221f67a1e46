//! noether-compile's integration tests, one binary (each test binary links core and the testkit: one
//! instead of five keeps the workspace's cold build shorter).

mod agreement;
mod generated;
mod legendre;
mod native;
mod natural;

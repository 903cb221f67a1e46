//! noether-rigid's integration tests in one test binary (one link; what the files share is compiled
//! once): one module per file of tests/.

#[path = "../errors.rs"]
mod errors;
#[path = "../free_body.rs"]
mod free_body;
#[path = "../heavy_top.rs"]
mod heavy_top;
#[path = "../properties.rs"]
mod properties;
#[path = "../rattle.rs"]
mod rattle;
#[path = "../time_resolution.rs"]
mod time_resolution;

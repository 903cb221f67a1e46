//! noether-particles's integration tests in one test binary (one link; what the files share is compiled
//! once): one module per file of tests/.

#[path = "../forces.rs"]
mod forces;
#[path = "../particles.rs"]
mod particles;
#[path = "../properties.rs"]
mod properties;

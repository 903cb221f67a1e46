//! noether-analysis's integration tests in one test binary (one link; what the files share is compiled
//! once): one module per file of tests/.

#[path = "../chaos.rs"]
mod chaos;
#[path = "../constrained.rs"]
mod constrained;
#[path = "../control.rs"]
mod control;
#[path = "../families.rs"]
mod families;
#[path = "../lyapunov.rs"]
mod lyapunov;
#[path = "../periodic.rs"]
mod periodic;
#[path = "../sensitivity.rs"]
mod sensitivity;
#[path = "../small_oscillations.rs"]
mod small_oscillations;

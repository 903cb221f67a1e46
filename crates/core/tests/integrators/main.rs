//! Integration tests of the continuous integrators: observed convergence orders (`order_*`), long-run
//! energy behaviour (`conserves_*`), bad input (`bad_input_*`), regressions (`regress_*`) and the
//! adaptive methods pinned to Hairer's codes (`pin_*`). One test binary, one module each.

mod adaptive;
mod bad_input;
mod conserves;
mod events;
mod fixed;
mod ias15;
mod ias15_forces;
mod implicit;
mod nystrom;
mod order;
mod pin;
mod problems;
mod regress;
mod soak;

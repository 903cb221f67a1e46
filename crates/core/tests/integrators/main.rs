//! Integration tests of the continuous integrators: observed convergence orders (`order_*`), long-run
//! energy behaviour (`conserves_*`) and bad input (`bad_input_*`). One test binary, one module each.

mod adaptive;
mod bad_input;
mod conserves;
mod implicit;
mod order;
mod problems;
mod soak;

//! Lennard-Jones cluster of 100 atoms (particles): bounded energy error over 1e5 steps.
//! The model and the checks live in `src/gallery/lj_cluster.rs`.
//!
//! Run: `cargo run --release --example lj_cluster`
fn main() {
    noether::gallery::main_for("lj_cluster");
}

//! Runs the `coupled_chains` example of the gallery: momentum and energy transfer between two coupled
//! mass-spring chains with the midpoint variational integrator (noether-discrete).
//!
//! The model, the experiments and the checks are in `src/gallery/coupled_chains.rs`; the chains'
//! potential is `noether_discrete::chains::CoupledChains`.
//! Run: `cargo run --release --example coupled_chains` (SVG pictures go to `gallery-out/`).

fn main() {
    noether::gallery::main_for("coupled_chains");
}

//! A bead on a hoop rotating about its vertical diameter, simulated in Cartesian coordinates with a
//! time-dependent constraint: equilibria, small-oscillation frequencies, the hoop's force on the bead.
//! The model and the checks live in `src/gallery/bead_rotating_hoop.rs`.
//!
//! Run: `cargo run --release --example bead_rotating_hoop`
fn main() {
    noether::gallery::main_for("bead_rotating_hoop");
}

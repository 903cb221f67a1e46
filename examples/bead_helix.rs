//! A bead on a helical wire under gravity: constant vertical acceleration −g a²/(a²+b²) and the wire's force.
//! The model and the checks live in `src/gallery/bead_helix.rs`.
//!
//! Run: `cargo run --release --example bead_helix`
fn main() {
    noether::gallery::main_for("bead_helix");
}

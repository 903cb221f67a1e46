//! billiard collision of equal balls (particles): momentum, energy, velocity exchange.
//! The model and the checks live in `src/gallery/billiard.rs`.
//!
//! Run: `cargo run --release --example billiard`
fn main() {
    noether::gallery::main_for("billiard");
}

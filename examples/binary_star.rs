//! binary star under gravity (particles): two-body Kepler orbit, centre of mass at rest.
//! The model and the checks live in `src/gallery/binary_star.rs`.
//!
//! Run: `cargo run --release --example binary_star`
fn main() {
    noether::gallery::main_for("binary_star");
}

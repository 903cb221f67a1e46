//! random internal interactions (particles): momentum and angular momentum to 1e-13.
//! The model and the checks live in `src/gallery/third_law.rs`.
//!
//! Run: `cargo run --release --example third_law`
fn main() {
    noether::gallery::main_for("third_law");
}

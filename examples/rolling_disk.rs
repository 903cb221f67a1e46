//! A vertical disk rolling without slipping (nonholonomic constraints): a circle of radius R θ̇/φ̇.
//! The model and the checks live in `src/gallery/rolling_disk.rs`.
//!
//! Run: `cargo run --release --example rolling_disk`
fn main() {
    noether::gallery::main_for("rolling_disk");
}

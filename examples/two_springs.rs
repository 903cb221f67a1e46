//! wall - m1 - m2 with two springs (particles): normal modes and the modal solution.
//! The model and the checks live in `src/gallery/two_springs.rs`.
//!
//! Run: `cargo run --release --example two_springs`
fn main() {
    noether::gallery::main_for("two_springs");
}

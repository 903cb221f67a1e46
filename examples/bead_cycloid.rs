//! The tautochrone: a bead on a cycloid returns in 4π sqrt(a/g) from every release height.
//! The model and the checks live in `src/gallery/bead_cycloid.rs`.
//!
//! Run: `cargo run --release --example bead_cycloid`
fn main() {
    noether::gallery::main_for("bead_cycloid");
}

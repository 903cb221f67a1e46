//! The heavy symmetric top: `cargo run --release --example heavy_top`.
//!
//! The model (L in Euler angles, and the same top in Cardan angles for the sleeping top) and every
//! check live in `src/gallery/heavy_top.rs`; this program prints the check lines.
fn main() {
    noether::gallery::main_for("heavy_top");
}

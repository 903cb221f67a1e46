//! Runs the `pendulum` example of the gallery and prints its checks against closed forms.
//!
//! The model and the checks are in `src/gallery/pendulum.rs` (open it to read or copy the model).
//! Run: `cargo run --release --example pendulum` (pictures go to `gallery-out/`).

fn main() {
    noether::gallery::main_for("pendulum");
}

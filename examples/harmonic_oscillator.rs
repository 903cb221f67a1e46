//! Runs the `harmonic_oscillator` example of the gallery and prints its checks against closed forms.
//!
//! The model and the checks are in `src/gallery/harmonic_oscillator.rs` (open it to read or copy the model).
//! Run: `cargo run --release --example harmonic_oscillator` (pictures go to `gallery-out/`).

fn main() {
    noether::gallery::main_for("harmonic_oscillator");
}

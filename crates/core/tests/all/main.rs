//! noether-core's integration tests, in one test binary: the AD kernels against hand-derived
//! mechanics (`ad`), the continuous integrators (`integrators`), the tangents of the flow (`tangent`)
//! and the property tests of the error contract (`properties`). One binary, not four: the models and
//! integrators they share are compiled and linked once (docs/benchmarks.md, "Compile time").

#[path = "../ad/main.rs"]
mod ad;
#[path = "../integrators/main.rs"]
mod integrators;
#[path = "../properties.rs"]
mod properties;
#[path = "../tangent/main.rs"]
mod tangent;

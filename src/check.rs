//! A check of a computed quantity against its closed form, with the tolerance it must meet.

use std::fmt;

/// How a computed value is compared with the expected one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// |computed − expected| / |expected| ≤ tol.
    Relative(f64),
    /// |computed − expected| ≤ tol (for quantities whose expected value is 0, such as a drift).
    Absolute(f64),
}

/// One check of a computed quantity against its closed form.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// Example name, e.g. "pendulum".
    pub example: &'static str,
    /// Quantity, e.g. "period(θ0=1)".
    pub quantity: String,
    /// Value noether computed.
    pub computed: f64,
    /// Closed-form value.
    pub expected: f64,
    /// Allowed error.
    pub tolerance: Tolerance,
}

impl Check {
    /// A check with a relative tolerance.
    pub fn rel(
        example: &'static str,
        quantity: impl Into<String>,
        computed: f64,
        expected: f64,
        tol: f64,
    ) -> Self {
        Self::new(example, quantity, computed, expected, Tolerance::Relative(tol))
    }

    /// A check with an absolute tolerance.
    pub fn abs(
        example: &'static str,
        quantity: impl Into<String>,
        computed: f64,
        expected: f64,
        tol: f64,
    ) -> Self {
        Self::new(example, quantity, computed, expected, Tolerance::Absolute(tol))
    }

    fn new(
        example: &'static str,
        quantity: impl Into<String>,
        computed: f64,
        expected: f64,
        tolerance: Tolerance,
    ) -> Self {
        Check {
            example,
            quantity: quantity.into(),
            computed,
            expected,
            tolerance,
        }
    }

    /// The error measured in the check's own norm (relative or absolute).
    pub fn error(&self) -> f64 {
        let d = (self.computed - self.expected).abs();
        match self.tolerance {
            Tolerance::Relative(_) => d / self.expected.abs(),
            Tolerance::Absolute(_) => d,
        }
    }

    /// The tolerance value.
    pub fn tol(&self) -> f64 {
        match self.tolerance {
            Tolerance::Relative(t) | Tolerance::Absolute(t) => t,
        }
    }

    /// `true` when the error is finite and within tolerance.
    pub fn passed(&self) -> bool {
        let e = self.error();
        e.is_finite() && e <= self.tol()
    }
}

impl fmt::Display for Check {
    /// `check <example>/<quantity>: computed=<v> expected=<v> rel_err=<v> tol=<v> PASS|FAIL`
    /// (`abs_err` in place of `rel_err` for absolute checks).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.tolerance {
            Tolerance::Relative(_) => "rel_err",
            Tolerance::Absolute(_) => "abs_err",
        };
        write!(
            f,
            "check {}/{}: computed={:.12e} expected={:.12e} {}={:.3e} tol={:.1e} {}",
            self.example,
            self.quantity,
            self.computed,
            self.expected,
            kind,
            self.error(),
            self.tol(),
            if self.passed() { "PASS" } else { "FAIL" }
        )
    }
}

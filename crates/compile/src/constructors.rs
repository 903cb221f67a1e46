//! The constructor set every compiled system has (`new`, `at`, `interpreted`, `backend`, and
//! [`Compile`](crate::Compile) for its dual-number system), written once around each type's own
//! private `build(system, point, backend)`.

/// Generates `new`, `at`, `interpreted` and `backend` for a compiled system, and `Compile` for the
/// system it compiles:
///
/// ```text
/// compiled_constructors! {
///     Type<P: Bound>(System<P>), "F" recorded by `build`, programs run by field `program`;
///     default "the default point in words", (q, v) => point built from default_point's pair;
///     at "(the point in words)" (args: of at) => point passed to build
/// }
/// ```
///
/// `new` and `interpreted` record F at the default point (`default_point`, in
/// [`euler_lagrange`](crate::euler_lagrange)), `at` at the caller's point; `backend` tells what runs
/// the program in `program`; `compile` is `new`.
macro_rules! compiled_constructors {
    (
        $ty:ident<$p:ident: $bound:path>($system:ty), $f:literal, $program:ident;
        default $default_doc:literal, $default_pat:pat => $default:expr;
        at $at_doc:literal ($($arg:ident: $arg_ty:ty),*) => $at:expr
    ) => {
        impl<$p: $bound> $ty<$p> {
            #[doc = concat!(
                "Compiles `system`, recording ", $f, " at a point chosen only for the branches ", $f,
                " takes there (", $default_doc, "); see [`at`](Self::at) to choose it."
            )]
            pub fn new(system: $system) -> $crate::Result<Self> {
                let $default_pat = $crate::euler_lagrange::default_point(system.dof());
                Self::build(system, $default, $crate::Backend::Native)
            }

            #[doc = concat!(
                "Compiles `system`, recording ", $f, " at ", $at_doc, ": where ", $f,
                " branches (compares values), the compiled code follows the branches taken there and",
                " falls back to dual numbers elsewhere."
            )]
            pub fn at(system: $system, $($arg: $arg_ty),*) -> $crate::Result<Self> {
                Self::build(system, $at, $crate::Backend::Native)
            }

            /// Compiles `system` as [`new`](Self::new) does, its programs run by the interpreter even
            /// with the feature `jit` (no time spent in Cranelift; the same results bit for bit).
            pub fn interpreted(system: $system) -> $crate::Result<Self> {
                let $default_pat = $crate::euler_lagrange::default_point(system.dof());
                Self::build(system, $default, $crate::Backend::Interpreter)
            }

            /// What runs the programs ([`Backend::Native`](crate::Backend::Native) with the feature
            /// `jit`, unless built by [`interpreted`](Self::interpreted) or Cranelift failed).
            pub fn backend(&self) -> $crate::Backend {
                self.$program.backend()
            }
        }

        impl<$p: $bound> $crate::Compile for $system {
            type Compiled = $ty<$p>;
            fn compile(self) -> $crate::Result<$ty<$p>> {
                $ty::new(self)
            }
        }
    };
}

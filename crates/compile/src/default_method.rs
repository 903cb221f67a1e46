//! The method noether picks for a compiled system when none is named: the same as for the system it
//! was compiled from (see [`DefaultMethod`]), on the compiled system.

use crate::{CompiledEulerLagrange, CompiledHamiltonEquations, CompiledNatural};
use noether_core::integrators::{Composition, DefaultMethod, Dop853, Gauss, StormerVerlet};
use noether_core::{Hamiltonian, Lagrangian, Potential};

/// Implements [`DefaultMethod`] for a compiled system and for a reference to it.
macro_rules! default_method {
    ($system:ident<$p:ident: $bound:ident>, $method:ident, $make:expr) => {
        impl<$p: $bound> DefaultMethod for $system<$p> {
            type Method = default_method!(@ty $method, $system<$p>);
            fn default_method(self) -> Self::Method {
                $make(self)
            }
        }
        impl<'a, $p: $bound> DefaultMethod for &'a $system<$p> {
            type Method = default_method!(@ty $method, &'a $system<$p>);
            fn default_method(self) -> Self::Method {
                $make(self)
            }
        }
    };
    (@ty Composition, $s:ty) => { Composition<StormerVerlet<$s>> };
    (@ty Gauss, $s:ty) => { Gauss<$s> };
    (@ty Dop853, $s:ty) => { Dop853<$s> };
}

// Natural: Kahan-Li 8 (explicit, symplectic, order 8), the kick the compiled force.
default_method!(CompiledNatural<P: Potential>, Composition, Composition::kahan_li8);
// Any H: Gauss-Legendre of order 6, its Newton iteration on the compiled Jacobian.
default_method!(CompiledHamiltonEquations<H: Hamiltonian>, Gauss, Gauss::gauss6);
// Any L: DOP853 at its default tolerances.
default_method!(CompiledEulerLagrange<L: Lagrangian>, Dop853, Dop853::new);

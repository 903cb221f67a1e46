//! noether-constraints (under construction).

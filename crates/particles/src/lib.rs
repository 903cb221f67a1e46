//! noether-particles (under construction).

//! noether-discrete (under construction).

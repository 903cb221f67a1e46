//! noether-analysis (under construction).

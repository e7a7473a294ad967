//! Topological editing operators: checked, all-or-nothing, attribute-aware.

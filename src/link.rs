//! Low-level reflecting setters, for people writing their own operators.

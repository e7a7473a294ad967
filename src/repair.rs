//! Repair of dirty input: import policies and a report of what was done.

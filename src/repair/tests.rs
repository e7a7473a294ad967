//! Each policy on a tiny soup.

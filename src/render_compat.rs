//! The raw `u32` accessors that `src/render/` was written against, kept
//! only so it compiles unchanged while it moves to the CLI crate (where it
//! will use the public API). Delete this file and its `mod` line in
//! `lib.rs` with `src/render/`. Nothing else may use these.

use crate::layout::{Fid, Hid};
use crate::mesh::Mesh;

impl Mesh {
    /// Whether face slot `f` is a hole.
    #[inline]
    pub(crate) fn is_hole_raw(&self, f: u32) -> bool {
        self.is_hole(Fid::new(f))
    }

    /// Whether half-edge slot `h` lies in a hole.
    #[inline]
    pub(crate) fn in_hole_raw(&self, h: u32) -> bool {
        self.in_hole(Hid::new(h))
    }

    /// The vertex slot half-edge slot `h` leaves.
    #[inline]
    pub(crate) fn origin_of(&self, h: u32) -> u32 {
        self.origin(Hid::new(h)).raw()
    }

    /// The half-edge slots of face slot `f`.
    #[inline]
    pub(crate) fn face_loop_raw(&self, f: u32) -> impl Iterator<Item = u32> + Clone + '_ {
        self.face_loop(Fid::new(f)).map(Hid::raw)
    }
}

//! A small software renderer: shaded orthographic pictures of a mesh as PNG.

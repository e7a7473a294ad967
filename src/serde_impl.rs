//! Serde support (feature `serde`): meshes round-trip and are checked on the way in.

//! `quickcheck::Arbitrary` for valid random meshes (feature `quickcheck`).

//! Fuzz target `gltf`: see `meshloom_fuzz::gltf`. Under `cargo afl build`
//! this is an AFL++ harness; otherwise it replays the files named on the
//! command line (a crash found by AFL, say).

#[cfg(fuzzing)]
fn main() {
    afl::fuzz!(|data: &[u8]| meshloom_fuzz::gltf(data));
}

#[cfg(not(fuzzing))]
fn main() {
    meshloom_fuzz::replay_args(meshloom_fuzz::gltf);
}

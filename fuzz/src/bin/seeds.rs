//! Write the synthetic seeds (buffers, repair, serde, ops) into
//! `corpus/<target>/`: `cargo run -p meshloom-fuzz --bin seeds -- corpus`.
//! The file seeds come from `seeds.sh`.

use std::path::Path;

fn main() {
    let root = std::env::args().nth(1).unwrap_or_else(|| "corpus".into());
    let root = Path::new(&root);
    for (target, name, bytes) in meshloom_fuzz::synthetic_seeds() {
        let dir = root.join(target);
        std::fs::create_dir_all(&dir).expect("a writable corpus directory");
        std::fs::write(dir.join(name), bytes).expect("a writable seed");
    }
}

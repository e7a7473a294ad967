//! Damaged input never panics: small real files, cut short, with bytes
//! changed, dropped or repeated, go through every reader strictly and with
//! every repair; each gives a mesh that validates or an error.

use meshloom::io::{self, Format, ReadOptions};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/meshes");

/// xorshift: deterministic damage.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn damage(bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for _ in 0..1 + rng.below(4) {
        if b.is_empty() {
            break;
        }
        let i = rng.below(b.len());
        match rng.below(6) {
            0 => b.truncate(i),
            1 => b[i] = b"0123456789 -.e\n/#"[rng.below(17)],
            2 => b[i] = rng.next() as u8,
            3 => {
                b.remove(i);
            }
            4 => {
                let j = (i + 1 + rng.below(16)).min(b.len());
                let piece = b[i..j].to_vec();
                b.splice(i..i, piece);
            }
            _ => b.insert(i, b"9"[0]),
        }
    }
    b
}

fn check(format: Format, bytes: &[u8]) {
    for options in [ReadOptions::strict(), ReadOptions::repair_all()] {
        if let Ok((mesh, _)) = io::read_bytes(format, bytes, &options) {
            mesh.validate().unwrap();
        }
    }
}

#[test]
fn damaged_files_give_errors_not_panics() {
    let files = [
        ("closed/cgal_cube.off", Format::Off),
        ("polygons/geomview_abstr.off", Format::Off),
        ("dirty/geomview_hypercube.off", Format::Off),
        ("polygons/compas_faces.obj", Format::Obj),
        ("dirty/openmesh_cube-minimal-degenerated.obj", Format::Obj),
        ("polygons/openmesh_cube-minimal.ply", Format::Ply),
        (
            "closed/openmesh_cube-minimal-custom_props-binary.ply",
            Format::Ply,
        ),
        ("stl/openscad_issue1580-back-to-back.stl", Format::Stl),
        ("stl/compas_cube_binary.stl", Format::Stl),
    ];
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for (name, format) in files {
        let bytes = std::fs::read(format!("{DATA}/{name}")).unwrap();
        check(format, &bytes);
        for _ in 0..1000 {
            check(format, &damage(&bytes, &mut rng_fork(&mut rng)));
        }
    }
}

fn rng_fork(rng: &mut Rng) -> Rng {
    Rng(rng.next() | 1)
}

#[test]
fn written_files_damaged_too() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mesh = meshloom::shapes::cube();
    let mut outputs = Vec::new();
    let mut obj = Vec::new();
    io::write_obj(&mesh, &mut obj).unwrap();
    outputs.push((Format::Obj, obj));
    for enc in [
        io::PlyEncoding::Ascii,
        io::PlyEncoding::BinaryLittleEndian,
        io::PlyEncoding::BinaryBigEndian,
    ] {
        let mut ply = Vec::new();
        io::write_ply(&mesh, &mut ply, enc).unwrap();
        outputs.push((Format::Ply, ply));
    }
    let mut stl = Vec::new();
    io::write_stl(&mesh, &mut stl, io::StlEncoding::Ascii).unwrap();
    outputs.push((Format::Stl, stl));
    for (format, bytes) in outputs {
        for _ in 0..1000 {
            check(format, &damage(&bytes, &mut rng_fork(&mut rng)));
        }
    }
}

//! The constraint flags shared by decimate, fair, lod, remesh and smooth, in the
//! library's words (`--boundary free|slide|lock`, `--seams`,
//! `--feature-angle`, `--features COLUMN`, `--pinned COLUMN`); the old
//! flags mapped to the one meaning with a warning; and the columns they
//! name read into temporary boolean columns (from a `bool` column or any
//! number column: non-zero is true), removed again before writing.

use meshloom::algo::Constraints;
use meshloom::attr::{EdgeAttr, Element, Value, VertexAttr};
use meshloom::{EdgeKey, Mesh, VertexKey};

use crate::cli::ConstraintArgs;
use crate::Failure;

/// The temporary column behind `--pinned` (or the old `--mask-column`).
const PINNED: &str = "meshloom-cli pinned";
/// The temporary column behind `--features`.
const FEATURES: &str = "meshloom-cli features";
/// The temporary column behind `fair --region`.
const REGION: &str = "meshloom-cli region";

/// The temporary columns a command added; [`Temps::remove`] takes them off
/// the mesh.
#[derive(Clone, Default)]
pub struct Temps {
    pinned: Option<VertexAttr<bool>>,
    features: Option<EdgeAttr<bool>>,
    region: Option<VertexAttr<bool>>,
}

impl Temps {
    /// Remove the temporary columns (ours, just added: this cannot fail).
    pub fn remove(self, mesh: &mut Mesh) {
        if let Some(h) = self.pinned {
            let _ = mesh.remove_attr(&h);
        }
        if let Some(h) = self.features {
            let _ = mesh.remove_attr(&h);
        }
        if let Some(h) = self.region {
            let _ = mesh.remove_attr(&h);
        }
    }

    /// The vertex column `name` (`bool`, or any number: non-zero is true)
    /// read into a temporary boolean column, removed with the others;
    /// `flag` names the flag in messages.
    pub fn region(
        &mut self,
        mesh: &mut Mesh,
        name: &str,
        flag: &str,
    ) -> Result<VertexAttr<bool>, Failure> {
        let keys: Vec<VertexKey> = mesh.vertices().collect();
        let on = flags(mesh, &keys, name, flag, false)?;
        let h = mesh
            .add_vertex_attr::<bool>(REGION)
            .map_err(Failure::input)?;
        write(mesh, &h, &keys, &on)?;
        self.region = Some(h.clone());
        Ok(h)
    }
}

/// Say on standard error that `old` is deprecated in favour of `new`.
pub fn deprecated(old: &str, new: &str) {
    eprintln!("meshloom: warning: {old} is deprecated; use {new}");
}

/// The constraints the flags name, over the command's `defaults` (the
/// library's), with the columns they name read from `mesh` (`pinned`:
/// the old `--mask-column NAME`, whose complement is pinned, when given).
pub fn resolve(
    mesh: &mut Mesh,
    args: &ConstraintArgs,
    defaults: Constraints,
    mask_column: Option<&str>,
) -> Result<(Constraints, Temps), Failure> {
    let mut c = defaults;
    if let Some(k) = args.boundary {
        c.boundary = k;
    }
    if let Some(k) = args.seams {
        c.seams = k;
    }
    if let Some(deg) = args.feature_angle {
        c.feature_angle = Some(deg.to_radians());
    }
    let mut temps = Temps::default();
    let pinned = match (&args.pinned, mask_column) {
        (Some(name), _) => Some(("--pinned", name.as_str(), false)),
        (None, Some(name)) => Some(("--mask-column", name, true)),
        (None, None) => None,
    };
    if let Some((flag, name, invert)) = pinned {
        let keys: Vec<VertexKey> = mesh.vertices().collect();
        let on = flags(mesh, &keys, name, flag, invert)?;
        let h = mesh
            .add_vertex_attr::<bool>(PINNED)
            .map_err(Failure::input)?;
        write(mesh, &h, &keys, &on)?;
        c.pinned = Some(h.clone());
        temps.pinned = Some(h);
    }
    if let Some(name) = &args.features {
        let keys: Vec<EdgeKey> = mesh.edges().collect();
        let on = flags(mesh, &keys, name, "--features", false)?;
        let h = mesh
            .add_edge_attr::<bool>(FEATURES)
            .map_err(Failure::input)?;
        write(mesh, &h, &keys, &on)?;
        c.features = Some(h.clone());
        temps.features = Some(h);
    }
    Ok((c, temps))
}

/// Whether the column `name` is true (a `bool`, or a non-zero number) at
/// each of `keys`, negated with `invert`.
fn flags<K: Element>(
    mesh: &Mesh,
    keys: &[K],
    name: &str,
    flag: &str,
    invert: bool,
) -> Result<Vec<bool>, Failure> {
    let mut on = Vec::with_capacity(keys.len());
    for &k in keys {
        let value = mesh
            .attr_value(name, k)
            .map_err(|e| Failure::input(format!("{flag}: {e}")))?;
        let b = match value {
            None => false,
            Some(Value::Bool(b)) => b,
            Some(Value::Text(t)) => {
                return Err(Failure::input(format!(
                    "{flag}: {name:?} holds text ({t:?}), not flags or numbers"
                )))
            }
            Some(Value::List(_)) => {
                return Err(Failure::input(format!(
                    "{flag}: {name:?} holds lists, not flags or numbers"
                )))
            }
            Some(number) => number_of(&number) != 0.0,
        };
        on.push(b != invert);
    }
    Ok(on)
}

/// Write `on` to the new column `h` at `keys`.
fn write<K: Element>(
    mesh: &mut Mesh,
    h: &meshloom::attr::Attr<K, bool>,
    keys: &[K],
    on: &[bool],
) -> Result<(), Failure> {
    for (&k, &b) in keys.iter().zip(on) {
        mesh.set_attr(h, k, b).map_err(Failure::input)?;
    }
    Ok(())
}

fn number_of(v: &Value) -> f64 {
    match *v {
        Value::I8(x) => f64::from(x),
        Value::U8(x) => f64::from(x),
        Value::I16(x) => f64::from(x),
        Value::U16(x) => f64::from(x),
        Value::I32(x) => f64::from(x),
        Value::U32(x) => f64::from(x),
        Value::I64(x) => x as f64,
        Value::U64(x) => x as f64,
        Value::F32(x) => f64::from(x),
        Value::F64(x) => x,
        _ => 0.0,
    }
}

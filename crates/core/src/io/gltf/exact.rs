//! Far glTF scenes (see `io::origin`): accessor data is f32 by the specification, but the
//! JSON's node translations and matrices are numbers of any precision, and georeferenced
//! files put their far coordinates there (or in `CESIUM_RTC`'s centre, added to every
//! position). Each node's local transform is read here from the JSON in f64, so the walk can
//! compose world transforms in f64 beside the gltf crate's f32 ones, and the node tree
//! keeps them (`mesh::LocalTransform`) for a glTF output to write back in full.

use glam::{DMat4, DQuat, DVec3};
use serde_json::Value;

use crate::mesh::LocalTransform;

/// Every node's local transform in f64, by index, and the `CESIUM_RTC` centre as a
/// translation applied after them (identity when the file has none).
#[derive(Debug, Clone, Default)]
pub struct Exact {
    pub locals: Vec<DMat4>,
    pub rtc: DMat4,
}

impl Exact {
    /// The transforms of the file's JSON `root` (already checked by the gltf crate: a node
    /// has a matrix or TRS of the right lengths); an entry that is not a number counts as
    /// absent.
    pub fn of(root: &Value) -> Self {
        let locals = match root.get("nodes").and_then(Value::as_array) {
            Some(nodes) => nodes.iter().map(local).collect(),
            None => Vec::new(),
        };
        let center = root
            .pointer("/extensions/CESIUM_RTC/center")
            .and_then(|c| numbers::<3>(Some(c)));
        Self {
            locals,
            rtc: center.map_or(DMat4::IDENTITY, |c| {
                DMat4::from_translation(DVec3::from_array(c))
            }),
        }
    }

    /// Node `index`'s local transform (identity for an index the JSON lacks).
    pub fn local(&self, index: usize) -> DMat4 {
        self.locals.get(index).copied().unwrap_or(DMat4::IDENTITY)
    }
}

/// `N` numbers of a JSON array, if it is one of that length.
fn numbers<const N: usize>(v: Option<&Value>) -> Option<[f64; N]> {
    let a = v?.as_array()?;
    if a.len() != N {
        return None;
    }
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(a) {
        *o = x.as_f64()?;
    }
    Some(out)
}

/// A node's local transform as a matrix.
fn local(node: &Value) -> DMat4 {
    local_transform(node).matrix()
}

/// A node's local transform in the form the file gives it: its matrix (column-major), else
/// translation, rotation and scale (each its default where absent).
pub fn local_transform(node: &Value) -> LocalTransform {
    if let Some(m) = numbers::<16>(node.get("matrix")) {
        return LocalTransform::Matrix(DMat4::from_cols_array(&m));
    }
    LocalTransform::Trs {
        translation: numbers::<3>(node.get("translation")).map_or(DVec3::ZERO, DVec3::from_array),
        rotation: numbers::<4>(node.get("rotation")).map_or(DQuat::IDENTITY, DQuat::from_array),
        scale: numbers::<3>(node.get("scale")).map_or(DVec3::ONE, DVec3::from_array),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn translations_keep_the_digits_f32_loses() {
        let root = serde_json::json!({
            "nodes": [
                { "translation": [300000.25, 1200000.35, 50.0] },
                { "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 512345.678,0,0,1] },
                {}
            ],
            "extensions": { "CESIUM_RTC": { "center": [6378137.125, 0, 0] } }
        });
        let e = Exact::of(&root);
        assert_eq!(e.local(0).w_axis.y, 1200000.35);
        assert_eq!(e.local(1).w_axis.x, 512345.678);
        assert_eq!(e.local(2), DMat4::IDENTITY);
        assert_eq!(e.local(7), DMat4::IDENTITY);
        assert_eq!(e.rtc.w_axis.x, 6378137.125);
    }
}

//! `manifest.json` of a tiling work folder: the input, its origin, bounds and counts, the
//! final target, and per tile its box, triangle count, target share and file names. Written with
//! serde_json's `json!` and read back with its parser, so a malformed or foreign file is
//! refused with the JSON error's line and column.

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use super::TileError;

/// Name of the manifest inside the work folder.
pub const FILE: &str = "manifest.json";
/// What `format` says in every manifest we write.
pub const FORMAT: &str = "decimate-tiles";
/// Bumped whenever a field changes meaning; older manifests are refused.
pub const VERSION: u64 = 1;

/// One tile of the plan.
#[derive(Debug, Clone, PartialEq)]
pub struct Tile {
    /// Box of the centroids this tile took (its triangles may reach beyond it).
    pub min: [f64; 3],
    pub max: [f64; 3],
    /// Triangles in this tile.
    pub triangles: usize,
    /// Triangles `run` keeps (its share of the target, with the seam slack of `plan`).
    pub target: usize,
}

/// The whole plan.
#[derive(Debug, Clone, PartialEq)]
pub struct Manifest {
    /// The input file the tiles were cut from.
    pub input: PathBuf,
    /// Triangles in the input.
    pub triangles: usize,
    /// Final triangle count `merge` decimates to, unless it is given another.
    pub target_triangles: usize,
    /// Where the tiles' frame stands in the input's coordinates (`Model::origin`): zero
    /// unless the input is far from zero. Bounds, boxes and tile files are relative to it.
    pub origin: [f64; 3],
    /// The input's bounding box, lower corner.
    pub min: [f32; 3],
    /// The input's bounding box, upper corner.
    pub max: [f32; 3],
    /// The tiles, in index order.
    pub tiles: Vec<Tile>,
}

impl Manifest {
    /// The input PLY of tile `i` inside the work folder.
    pub fn tile_input(dir: &Path, i: usize) -> PathBuf {
        dir.join(format!("tile-{i:05}.ply"))
    }

    /// The decimated PLY `run` writes for tile `i`.
    pub fn tile_output(dir: &Path, i: usize) -> PathBuf {
        dir.join(format!("tile-{i:05}.out.ply"))
    }

    /// The manifest as `manifest.json` holds it.
    pub fn to_json(&self) -> String {
        let tiles: Vec<Value> = self
            .tiles
            .iter()
            .enumerate()
            .map(|(i, t)| {
                json!({
                    "index": i,
                    "min": t.min,
                    "max": t.max,
                    "triangles": t.triangles,
                    "target": t.target,
                    "input": format!("tile-{i:05}.ply"),
                    "output": format!("tile-{i:05}.out.ply"),
                })
            })
            .collect();
        let v = json!({
            "format": FORMAT,
            "version": VERSION,
            "input": self.input.to_string_lossy(),
            "triangles": self.triangles,
            "target_triangles": self.target_triangles,
            "origin": self.origin,
            "bounds": { "min": self.min, "max": self.max },
            "tiles": tiles,
        });
        let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
        s.push('\n');
        s
    }

    /// Reads the manifest of work folder `dir`.
    pub fn read(dir: &Path) -> Result<Self, TileError> {
        let file = dir.join(FILE);
        let text = std::fs::read_to_string(&file).map_err(|e| TileError::io(&file, e))?;
        Self::parse(&text).map_err(|message| TileError::Manifest { file, message })
    }

    fn parse(text: &str) -> Result<Self, String> {
        let v: Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
        if v["format"] != FORMAT {
            return Err(format!(
                "not a tiling manifest (no \"format\": \"{FORMAT}\")"
            ));
        }
        if v["version"] != VERSION {
            return Err(format!(
                "manifest version {} is not {VERSION}: plan again with this decimate",
                v["version"]
            ));
        }
        let count = |v: &Value, key: &str| {
            v[key]
                .as_u64()
                .map(|n| n as usize)
                .ok_or_else(|| format!("\"{key}\" must be a non-negative integer"))
        };
        let triple = |v: &Value, key: &str| -> Result<[f64; 3], String> {
            let a = v[key].as_array().filter(|a| a.len() == 3);
            let a = a.ok_or_else(|| format!("\"{key}\" must be three numbers"))?;
            let mut out = [0.0; 3];
            for (o, x) in out.iter_mut().zip(a) {
                *o = x
                    .as_f64()
                    .ok_or_else(|| format!("\"{key}\" must be three numbers"))?;
            }
            Ok(out)
        };
        let tiles = v["tiles"]
            .as_array()
            .ok_or("\"tiles\" must be a list")?
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let at = |m: String| format!("tile {i}: {m}");
                Ok(Tile {
                    min: triple(t, "min").map_err(at)?,
                    max: triple(t, "max").map_err(at)?,
                    triangles: count(t, "triangles").map_err(at)?,
                    target: count(t, "target").map_err(at)?,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        let f32s = |a: [f64; 3]| a.map(|x| x as f32);
        Ok(Self {
            input: PathBuf::from(v["input"].as_str().unwrap_or("")),
            triangles: count(&v, "triangles")?,
            target_triangles: count(&v, "target_triangles")?,
            // Absent from manifests written before far inputs were tiled: zero.
            origin: match v.get("origin") {
                Some(_) => triple(&v, "origin")?,
                None => [0.0; 3],
            },
            min: f32s(triple(&v["bounds"], "min")?),
            max: f32s(triple(&v["bounds"], "max")?),
            tiles,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_refuses_foreign_files() {
        let m = Manifest {
            input: PathBuf::from("in.ply"),
            triangles: 10,
            target_triangles: 4,
            origin: [300000.0, 1200000.0, -51.0],
            min: [0.0, -1.5, 2.0],
            max: [1.0, 1.0, 3.25],
            tiles: vec![Tile {
                min: [0.0, -1.5, 2.0],
                max: [0.5, 1.0, 3.25],
                triangles: 10,
                target: 8,
            }],
        };
        assert_eq!(Manifest::parse(&m.to_json()), Ok(m.clone()));
        let e = Manifest::parse("{\"format\": \"x\"}").unwrap_err();
        assert!(e.contains("not a tiling manifest"), "{e}");
        let e = Manifest::parse("{ nope").unwrap_err();
        assert!(e.contains("line 1"), "{e}");
        let old = m.to_json().replace("\"version\": 1", "\"version\": 0");
        assert!(Manifest::parse(&old).unwrap_err().contains("version 0"));
    }
}

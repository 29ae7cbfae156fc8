//! The library's entry point for programs: decimate a triangle mesh given as plain arrays
//! ([`simplify`]; [`simplify_f64`] for coordinates far from zero), a [`Scene`] already in memory ([`simplify_scene`]), or a file into
//! another file in any format the `decimate` program reads and writes ([`simplify_file`]:
//! VRML 1.0/2.0, Open Inventor, PLY, OBJ, STL, OFF, glTF 2.0). [`with_threads`] runs any of
//! them on a given number of threads (one: no other thread); the result is the same for
//! every number.
//!
//! ```
//! use decimate_core::api::{simplify, Algorithm, Params, Target};
//!
//! // A 10 × 10 grid of squares, two triangles each.
//! let n = 10;
//! let positions: Vec<[f32; 3]> = (0..=n)
//!     .flat_map(|j| (0..=n).map(move |i| [i as f32, j as f32, 0.0]))
//!     .collect();
//! let mut indices = Vec::new();
//! for j in 0..n {
//!     for i in 0..n {
//!         let a = j * (n + 1) + i;
//!         indices.extend([a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]);
//!     }
//! }
//! let params = Params {
//!     target: Target::KeepTriangles(50),
//!     algorithm: Algorithm::Qem,
//!     ..Params::default()
//! };
//! let (mesh, report) = simplify(&positions, &indices, &params)?;
//! assert!(mesh.indices.len() / 3 <= 50);
//! assert_eq!(report.models[0].triangles_before, 200);
//! # Ok::<(), decimate_core::api::Error>(())
//! ```

use std::path::{Path, PathBuf};

use glam::Vec3;

pub use crate::decimate::{Algorithm, ErrorBound, ModelReport, Params, Report, Target};
use crate::io;
pub use crate::io::{read_scene, write_scene, ReadError, WriteError};
pub use crate::mesh::{Model, Scene};
pub use crate::threads::with_threads;

/// A triangle mesh as plain arrays: positions, and three indices into them per triangle
/// (counter-clockwise seen from the front). Positions are f32, relative to `origin`: a
/// mesh far from zero (georeferenced, coordinates of 1e5 and more) given to
/// [`simplify_f64`] comes back with the origin it was moved to (see `io::origin`), and
/// [`Mesh::points`] gives its coordinates in f64.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, relative to `origin`.
    pub positions: Vec<[f32; 3]>,
    /// Three indices into `positions` per triangle.
    pub indices: Vec<u32>,
    /// Where the positions' frame stands: zero unless the mesh was far from zero.
    pub origin: [f64; 3],
}

impl Mesh {
    /// The positions in the input's coordinates, in f64: `origin + position`.
    pub fn points(&self) -> Vec<[f64; 3]> {
        let o = self.origin;
        (self.positions.iter())
            .map(|p| std::array::from_fn(|k| o[k] + f64::from(p[k])))
            .collect()
    }
}

/// What stops a simplification: a file that cannot be read or written, or arrays that do
/// not make a mesh.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The input file could not be read.
    #[error("{0}")]
    Read(#[from] ReadError),
    /// The output file could not be written.
    #[error("{0}")]
    Write(#[from] WriteError),
    /// The arrays do not make a mesh (an index out of range, a count not a multiple of 3, ...).
    #[error("{0}")]
    InvalidMesh(String),
    /// The output path names the input file.
    #[error("{}: is the input file: refusing to write over it", .0.display())]
    SameFile(PathBuf),
}

/// What [`simplify_file`] did: the decimation's report, and the warnings met reading the
/// input (parts it skipped) and writing the output (what its format cannot hold).
#[derive(Debug, Clone, Default)]
pub struct FileReport {
    /// What the decimation did.
    pub report: Report,
    /// Warnings from reading the input and writing the output.
    pub warnings: Vec<String>,
}

/// Decimates the mesh of `positions` and `indices` (three per triangle) as `params` says and
/// returns the result as arrays, with the report. The mesh is prepared as the `decimate`
/// program prepares a file's (bit-equal positions merged, triangles with no area or
/// repeated removed: [`crate::mesh::build`]), so the same arrays give the program's
/// result. Unused positions are left out of the result. A mesh decimated below four
/// vertices comes back empty (`report.models[0].dropped`).
pub fn simplify(
    positions: &[[f32; 3]],
    indices: &[u32],
    params: &Params,
) -> Result<(Mesh, Report), Error> {
    let model = model_from_arrays(positions, indices)?;
    let scene = Scene {
        models: vec![model],
    };
    let mut scene = crate::mesh::build::build_scene(scene, true);
    let report = simplify_scene(&mut scene, params);
    let mesh = scene
        .models
        .first()
        .map(|m| Mesh {
            positions: m.positions.iter().map(|p| p.to_array()).collect(),
            indices: m.triangles.iter().flatten().copied().collect(),
            origin: [0.0; 3],
        })
        .unwrap_or_default();
    Ok((mesh, report))
}

/// As [`simplify`], for f64 coordinates: when the first position is far from zero, the
/// mesh is decimated relative to it rounded (`io::origin`, as the file readers do), so it
/// keeps the shape f32 coordinates would lose, and the result carries that `origin`.
pub fn simplify_f64(
    positions: &[[f64; 3]],
    indices: &[u32],
    params: &Params,
) -> Result<(Mesh, Report), Error> {
    let mut recentre = io::origin::Recentre::default();
    let relative: Vec<[f32; 3]> = positions.iter().map(|&p| recentre.relative(p)).collect();
    let (mut mesh, report) = simplify(&relative, indices, params)?;
    mesh.origin = recentre.origin().to_array();
    Ok((mesh, report))
}

/// The one-model mesh of `positions` and `indices` (three per triangle), checked: a whole
/// number of triangles, finite coordinates, every index naming a position. [`simplify`]
/// starts here; bindings that add attributes or a cancel flag (the Python package) too.
pub fn model_from_arrays(positions: &[[f32; 3]], indices: &[u32]) -> Result<Model, Error> {
    if !indices.len().is_multiple_of(3) {
        return Err(Error::InvalidMesh(format!(
            "{} indices: not a whole number of triangles",
            indices.len()
        )));
    }
    if let Some(k) = positions
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(Error::InvalidMesh(format!(
            "position {k} is not a finite number"
        )));
    }
    let n = positions.len();
    if let Some((k, i)) = indices.iter().enumerate().find(|(_, &i)| i as usize >= n) {
        return Err(Error::InvalidMesh(format!(
            "index {k} is {i}, but there are {n} positions"
        )));
    }
    Ok(Model {
        name: "mesh".into(),
        positions: positions.iter().map(|&p| Vec3::from(p)).collect(),
        triangles: indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        ..Model::default()
    })
}

/// Decimates every model of `scene` in place (see [`crate::decimate::simplify_scene`]).
pub fn simplify_scene(scene: &mut Scene, params: &Params) -> Report {
    crate::decimate::simplify_scene(scene, params, &mut |_| {})
}

/// Reads `input`, prepares it as the `decimate` program does ([`crate::mesh::build`]),
/// decimates it as `params` says and writes it to `output`, in the format the output's
/// extension names (texture names re-expressed for the output's folder, files replaced
/// atomically). Refuses to write over the input.
pub fn simplify_file(input: &Path, output: &Path, params: &Params) -> Result<FileReport, Error> {
    if let (Ok(a), Ok(b)) = (input.canonicalize(), output.canonicalize()) {
        if a == b {
            return Err(Error::SameFile(output.to_path_buf()));
        }
    }
    let io::ReadOutcome {
        mut scene,
        warnings,
        ..
    } = read_scene(input)?;
    scene = crate::mesh::build::build_scene(scene, true);
    let mut warnings: Vec<String> = io::warning::grouped(&warnings)
        .into_iter()
        .map(ToString::to_string)
        .collect();
    let report = simplify_scene(&mut scene, params);
    let folder = io::texture_path::folder_of;
    io::rebase_textures(&mut scene, folder(input), folder(output));
    warnings.extend(io::losses::losses_at(&scene, output));
    write_scene(&scene, output)?;
    Ok(FileReport { report, warnings })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_soup_is_welded_as_the_program_welds_a_file() {
        // The same sphere indexed, and as a soup (each triangle its own three positions).
        let sphere = crate::mesh::shapes::uv_sphere(12, 24);
        let positions: Vec<[f32; 3]> = sphere.positions.iter().map(|p| p.to_array()).collect();
        let indices: Vec<u32> = sphere.triangles.iter().flatten().copied().collect();
        let soup: Vec<[f32; 3]> = indices.iter().map(|&i| positions[i as usize]).collect();
        let soup_indices: Vec<u32> = (0..soup.len() as u32).collect();
        let params = Params {
            target: Target::KeepTriangles(100),
            algorithm: Algorithm::Qem,
            ..Params::default()
        };
        let (indexed, _) = simplify(&positions, &indices, &params).expect("the sphere");
        let (welded, report) = simplify(&soup, &soup_indices, &params).expect("the soup");
        assert_eq!(report.models[0].vertices_before, sphere.positions.len());
        assert_eq!(welded.indices.len(), 300);
        // The same triangles, numbered in another order.
        assert_eq!(
            triangles_by_position(&welded),
            triangles_by_position(&indexed)
        );
    }

    /// Each triangle as its corners' bits, rotated to start at the least: comparable
    /// whatever the vertices' numbering.
    fn triangles_by_position(mesh: &Mesh) -> Vec<[[u32; 3]; 3]> {
        let mut all: Vec<[[u32; 3]; 3]> = (mesh.indices.chunks_exact(3))
            .map(|t| {
                let mut c = [0, 1, 2].map(|k| mesh.positions[t[k] as usize].map(f32::to_bits));
                let first = (0..3).min_by_key(|&k| c[k]).unwrap_or(0);
                c.rotate_left(first);
                c
            })
            .collect();
        all.sort_unstable();
        all
    }

    #[test]
    fn a_far_mesh_in_f64_decimates_as_it_does_at_the_origin() {
        let mut sphere = crate::mesh::shapes::bumpy_sphere(24, 48);
        // On a grid of 2⁻²⁰, so that every coordinate plus the far offset is exact in f64
        // (a coordinate below 1/64 would not be): both runs then decimate the same numbers.
        for p in &mut sphere.positions {
            *p = (*p * 1048576.0).round() / 1048576.0;
        }
        let indices: Vec<u32> = sphere.triangles.iter().flatten().copied().collect();
        let at = |t: [f64; 3]| -> Vec<[f64; 3]> {
            (sphere.positions.iter())
                .map(|p| std::array::from_fn(|k| f64::from(p[k]) + t[k]))
                .collect()
        };
        let params = Params {
            target: Target::KeepTriangles(500),
            algorithm: Algorithm::Qem,
            ..Params::default()
        };
        // The far run's frame is its first position rounded: the origin run in that frame
        // (all numbers exact in f64) is what it must give back, moved by the origin.
        let o = sphere.positions[0].as_dvec3().round().to_array();
        let (near, _) = simplify_f64(&at(o.map(|x| -x)), &indices, &params).expect("near");
        assert_eq!(near.origin, [0.0; 3]);
        let t = [300000.0, 1200000.0, -10000000.0];
        let (far, _) = simplify_f64(&at(t), &indices, &params).expect("far");
        assert_eq!(far.indices, near.indices);
        assert_eq!(far.origin, std::array::from_fn(|k| o[k] + t[k]));
        for (p, q) in far.points().iter().zip(near.points()) {
            let d: f64 = (0..3).map(|k| (p[k] - t[k] - o[k] - q[k]).powi(2)).sum();
            assert!(d.sqrt() < 1e-9, "{p:?} against {q:?}");
        }
    }

    #[test]
    fn arrays_that_are_not_a_mesh_are_refused_with_the_reason() {
        let p = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let params = Params::default();
        let e = simplify(&p, &[0, 1], &params).unwrap_err().to_string();
        assert!(e.contains("whole number of triangles"), "{e}");
        let e = simplify(&p, &[0, 1, 3], &params).unwrap_err().to_string();
        assert!(e.contains("index 2 is 3"), "{e}");
        let nan = [[f32::NAN, 0.0, 0.0], p[1], p[2]];
        let e = simplify(&nan, &[0, 1, 2], &params).unwrap_err().to_string();
        assert!(e.contains("position 0"), "{e}");
    }
}

//! `read` and `write`: scenes as lists of model dictionaries (numpy arrays for positions,
//! triangles, colours, normals and texture coordinates; a 4 × 4 transform in numpy's row
//! convention; the texture path, diffuse colour and name; the f64 `origin` that far,
//! georeferenced files' positions are relative to), every format the core reads and writes.

use std::path::{Path, PathBuf};

use decimate_core::api::{Model, Scene};
use decimate_core::cancel::Cancel;
use decimate_core::io::{self, ReadError as CoreReadError, ReadOutcome};
use decimate_core::mesh::Attribute;
use glam::{DVec3, Mat4};
use numpy::PyReadonlyArray2;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::arrays::{rows, to_numpy, to_vec3s, vec3s};
use crate::run::interruptible;
use crate::ReadError;

/// Reads `path` off the GIL: a missing file is FileNotFoundError, anything else that stops
/// the reader `decimate.ReadError` with the reader's message (file, line, what).
pub fn read_outcome(py: Python<'_>, path: &Path, cancel: &Cancel) -> PyResult<ReadOutcome> {
    let p = path.to_path_buf();
    match interruptible(py, cancel, move || io::read_scene(&p))? {
        Ok(outcome) => Ok(outcome),
        Err(e @ CoreReadError::Io { .. }) if !path.exists() => {
            Err(PyFileNotFoundError::new_err(e.to_string()))
        }
        Err(e) => Err(ReadError::new_err(e.to_string())),
    }
}

/// Writes `scene` to `path` off the GIL (the format from the extension).
pub fn write_scene(py: Python<'_>, scene: &Scene, path: &Path, cancel: &Cancel) -> PyResult<()> {
    if io::Format::from_path(path).is_none() {
        return Err(PyValueError::new_err(format!(
            "{}: unknown output format (use .wrl, .ply, .obj, .stl, .off, .gltf or .glb)",
            path.display()
        )));
    }
    interruptible(py, cancel, || io::write_scene(scene, path))?
        .map_err(|e| PyOSError::new_err(e.to_string()))
}

/// Reads a mesh file into `(models, warnings)` (see `decimate.read`).
#[pyfunction]
pub fn read<'py>(py: Python<'py>, path: PathBuf) -> PyResult<(Bound<'py, PyList>, Vec<String>)> {
    let outcome = read_outcome(py, &path, &Cancel::new())?;
    let models = PyList::empty(py);
    for m in &outcome.scene.models {
        models.append(model_dict(py, m)?)?;
    }
    let warnings = decimate_core::io::warning::grouped(&outcome.warnings)
        .into_iter()
        .map(ToString::to_string)
        .collect();
    Ok((models, warnings))
}

/// Writes model dictionaries to `path` (see `decimate.write`).
#[pyfunction]
pub fn write(py: Python<'_>, models: Vec<Bound<'_, PyDict>>, path: PathBuf) -> PyResult<()> {
    let scene = Scene {
        models: models.iter().map(dict_model).collect::<PyResult<_>>()?,
    };
    write_scene(py, &scene, &path, &Cancel::new())
}

fn model_dict<'py>(py: Python<'py>, m: &Model) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", &m.name)?;
    d.set_item("vertices", vec3s(py, &m.positions)?)?;
    d.set_item("faces", to_numpy(py, m.triangles.clone())?)?;
    d.set_item(
        "transform",
        to_numpy(py, m.transform.transpose().to_cols_array_2d().to_vec())?,
    )?;
    d.set_item("origin", m.origin.to_array().to_vec())?;
    if let Some(c) = &m.colors {
        d.set_item("colors", to_numpy(py, c.values().to_vec())?)?;
        d.set_item("colors_per", binding(c))?;
    }
    if let Some(n) = &m.normals {
        d.set_item("normals", vec3s(py, n.values())?)?;
        d.set_item("normals_per", binding(n))?;
    }
    if let Some(t) = &m.texcoords {
        d.set_item("uvs", to_numpy(py, t.clone())?)?;
    }
    d.set_item("texture", &m.texture)?;
    d.set_item("diffuse", m.diffuse.to_vec())?;
    d.set_item("solid", m.solid)?;
    Ok(d)
}

fn binding<T>(a: &Attribute<T>) -> &'static str {
    match a {
        Attribute::PerVertex(_) => "vertex",
        Attribute::PerFace(_) => "face",
    }
}

/// A per-vertex or per-face attribute from its rows and its `*_per` key.
fn attribute<T>(
    values: Vec<T>,
    per: Option<String>,
    what: &str,
    counts: (usize, usize),
) -> PyResult<Attribute<T>> {
    let (n, expected) = match per.as_deref() {
        None | Some("vertex") => (counts.0, "vertices"),
        Some("face") => (counts.1, "faces"),
        Some(other) => {
            return Err(PyValueError::new_err(format!(
                "{what}_per: expected 'vertex' or 'face', got {other:?}"
            )))
        }
    };
    if values.len() != n {
        return Err(PyValueError::new_err(format!(
            "{what}: {} rows, but there are {n} {expected}",
            values.len()
        )));
    }
    Ok(if expected == "faces" {
        Attribute::PerFace(values)
    } else {
        Attribute::PerVertex(values)
    })
}

fn dict_model(d: &Bound<'_, PyDict>) -> PyResult<Model> {
    let get = |k: &str| d.get_item(k).map(|v| v.filter(|v| !v.is_none()));
    let need =
        |k: &str| get(k)?.ok_or_else(|| PyValueError::new_err(format!("model without {k:?}")));
    let v: PyReadonlyArray2<'_, f32> = need("vertices")?.extract()?;
    let f: PyReadonlyArray2<'_, u32> = need("faces")?.extract()?;
    let positions = rows::<f32, 3>(&v, "vertices")?;
    let mut m = decimate_core::api::model_from_arrays(
        positions,
        rows::<u32, 3>(&f, "faces")?.as_flattened(),
    )
    .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let counts = (m.positions.len(), m.triangles.len());
    if let Some(name) = get("name")? {
        m.name = name.extract()?;
    }
    if let Some(t) = get("transform")? {
        let t: PyReadonlyArray2<'_, f32> = t.extract()?;
        let r = rows::<f32, 4>(&t, "transform")?;
        let r: [[f32; 4]; 4] = r
            .try_into()
            .map_err(|_| PyValueError::new_err("transform: expected a 4 x 4 array"))?;
        m.transform = Mat4::from_cols_array_2d(&r).transpose();
    }
    if let Some(o) = get("origin")? {
        let o: [f64; 3] = o.extract()?;
        if !o.iter().all(|c| c.is_finite()) {
            return Err(PyValueError::new_err("origin: not finite"));
        }
        m.origin = DVec3::from(o);
    }
    if let Some(c) = get("colors")? {
        let c: PyReadonlyArray2<'_, f32> = c.extract()?;
        let per = get("colors_per")?.map(|p| p.extract()).transpose()?;
        m.colors = Some(attribute(
            rows::<f32, 3>(&c, "colors")?.to_vec(),
            per,
            "colors",
            counts,
        )?);
    }
    if let Some(n) = get("normals")? {
        let n: PyReadonlyArray2<'_, f32> = n.extract()?;
        let per = get("normals_per")?.map(|p| p.extract()).transpose()?;
        m.normals = Some(attribute(
            to_vec3s(rows::<f32, 3>(&n, "normals")?),
            per,
            "normals",
            counts,
        )?);
    }
    if let Some(t) = get("uvs")? {
        let t: PyReadonlyArray2<'_, f32> = t.extract()?;
        let t = rows::<f32, 2>(&t, "uvs")?;
        attribute(t.to_vec(), None, "uvs", counts)?;
        m.texcoords = Some(t.to_vec());
    }
    m.texture = get("texture")?.map(|t| t.extract()).transpose()?;
    if let Some(c) = get("diffuse")? {
        m.diffuse = c.extract()?;
    }
    if let Some(s) = get("solid")? {
        m.solid = s.extract()?;
    }
    Ok(m)
}

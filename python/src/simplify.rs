//! `simplify` (arrays) and `simplify_file` (file to file): the Python keywords turned into
//! the core's [`Params`], the run made interruptible, and the result handed back as numpy
//! arrays and a report dictionary.

use std::path::PathBuf;

use decimate_core::api::{self, Algorithm, ErrorBound, Model, Params, Report, Scene, Target};
use decimate_core::decimate::{simplify_scene_cancellable, simplify_scene_progressive_cancellable};
use decimate_core::io;
use decimate_core::mesh::build::{build_scene_with, BuildOptions};
use decimate_core::mesh::Attribute;
use numpy::PyReadonlyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{rows, to_numpy, to_vec3s, vec3s};
use crate::progressive::Progressive;
use crate::run::{interruptible, on_threads};
use crate::{scene, Cancel, Cancelled};

/// The target keywords, before the triangle count is known.
#[derive(Clone, Copy)]
pub struct Goal {
    pub ratio: Option<f64>,
    pub keep_triangles: Option<usize>,
    pub keep_vertices: Option<usize>,
    pub max_error: Option<f64>,
}

/// The keywords as Python passes them: (ratio, keep_triangles, keep_vertices, max_error).
impl From<(Option<f64>, Option<usize>, Option<usize>, Option<f64>)> for Goal {
    fn from(
        (ratio, keep_triangles, keep_vertices, max_error): (
            Option<f64>,
            Option<usize>,
            Option<usize>,
            Option<f64>,
        ),
    ) -> Self {
        Self {
            ratio,
            keep_triangles,
            keep_vertices,
            max_error,
        }
    }
}

impl Goal {
    /// The core's target for a mesh of `triangles` triangles: `ratio` is the fraction of
    /// triangles kept (rounded to the nearest count), as in trimesh and Open3D.
    fn target(&self, triangles: usize) -> Target {
        match (self.ratio, self.keep_triangles, self.keep_vertices) {
            (Some(r), _, _) => Target::KeepTriangles((r * triangles as f64).round() as usize),
            (_, Some(t), _) => Target::KeepTriangles(t),
            (_, _, Some(v)) => Target::KeepVertices(v),
            _ => Target::ErrorOnly,
        }
    }
}

/// Parameters for a mesh of `triangles` triangles.
pub fn params(
    goal: Goal,
    triangles: usize,
    algorithm: &str,
    keep_border: bool,
    feature_angle: f64,
) -> PyResult<Params> {
    let algorithm = match algorithm {
        "qem" => Algorithm::Qem,
        "schroeder" => Algorithm::Schroeder,
        other => {
            return Err(PyValueError::new_err(format!(
                "algorithm: expected 'qem' or 'schroeder', got {other:?}"
            )))
        }
    };
    Ok(Params {
        target: goal.target(triangles),
        max_error: goal.max_error.map(ErrorBound::Absolute),
        feature_angle_deg: feature_angle,
        keep_border,
        algorithm,
        ..Params::default()
    })
}

/// The report as a dictionary (one model's figures for arrays, the totals for a file).
pub fn report_dict<'py>(
    py: Python<'py>,
    report: &Report,
    target: Target,
    warnings: &[String],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let sum = |f: fn(&api::ModelReport) -> usize| -> usize {
        report
            .models
            .iter()
            .filter(|m| m.instance_of.is_none())
            .map(f)
            .sum()
    };
    d.set_item("vertices_before", sum(|m| m.vertices_before))?;
    d.set_item("vertices_after", sum(|m| m.vertices_after))?;
    d.set_item("triangles_before", sum(|m| m.triangles_before))?;
    d.set_item("triangles_after", sum(|m| m.triangles_after))?;
    let max_error = report
        .models
        .iter()
        .map(|m| m.max_error)
        .fold(0.0, f64::max);
    d.set_item("max_error", max_error)?;
    d.set_item("seconds", report.seconds)?;
    d.set_item("fully_decimated", report.fully_decimated())?;
    let angle = report
        .models
        .iter()
        .map(|m| m.feature_angle_deg)
        .fold(report.feature_angle_deg, f64::max);
    d.set_item("feature_angle", angle)?;
    let mut all: Vec<String> = warnings.to_vec();
    if angle > report.feature_angle_deg {
        all.push(format!(
            "the feature angle was relaxed from {} to {angle} degrees to reach the target",
            report.feature_angle_deg
        ));
    }
    let short = match target {
        Target::KeepTriangles(k) => Some((sum(|m| m.triangles_after), k, "triangles")),
        Target::KeepVertices(k) => Some((sum(|m| m.vertices_after), k, "vertices")),
        _ => None,
    };
    if let Some((left, asked, what)) = short.filter(|&(left, asked, _)| left > asked + 1) {
        all.push(format!(
            "the target was not reached: {left} {what} left, {asked} asked (the error bound, \
             the feature angle or the pieces' shapes held the rest)"
        ));
    }
    if report.models.iter().any(|m| m.dropped) {
        all.push("a model fell under four vertices and was dropped".into());
    }
    d.set_item("warnings", all)?;
    Ok(d)
}

/// What the `decimate` program does to a file's meshes before decimating them: merge
/// bit-equal vertices (unless `weld` is false), remove triangles with no area and duplicate
/// triangles, orient them alike, drop unused vertices. Returns what it changed, as warnings.
fn prepare(scene: Scene, weld: bool) -> (Scene, Vec<String>) {
    let options = BuildOptions {
        weld,
        weld_tolerance: None,
    };
    let (scene, repairs) = build_scene_with(scene, &options);
    let warnings = repairs.summary().map(|s| s.trim_end().to_string());
    (scene, warnings.into_iter().collect())
}

/// The mesh to decimate, with its optional per-vertex attributes, checked.
fn model(
    vertices: &PyReadonlyArray2<'_, f32>,
    faces: &PyReadonlyArray2<'_, u32>,
    colors: Option<&PyReadonlyArray2<'_, f32>>,
    uvs: Option<&PyReadonlyArray2<'_, f32>>,
    normals: Option<&PyReadonlyArray2<'_, f32>>,
) -> PyResult<Model> {
    let positions = rows::<f32, 3>(vertices, "vertices")?;
    let triangles = rows::<u32, 3>(faces, "faces")?;
    let mut m = api::model_from_arrays(positions, triangles.as_flattened())
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let n = positions.len();
    let count = |what: &str, k: usize| -> PyResult<()> {
        if k == n {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "{what}: {k} rows, but there are {n} vertices"
            )))
        }
    };
    if let Some(c) = colors {
        let c = rows::<f32, 3>(c, "colors")?;
        count("colors", c.len())?;
        m.colors = Some(Attribute::PerVertex(c.to_vec()));
    }
    if let Some(t) = uvs {
        let t = rows::<f32, 2>(t, "uvs")?;
        count("uvs", t.len())?;
        m.texcoords = Some(t.to_vec());
    }
    if let Some(v) = normals {
        let v = rows::<f32, 3>(v, "normals")?;
        count("normals", v.len())?;
        m.normals = Some(Attribute::PerVertex(to_vec3s(v)));
    }
    Ok(m)
}

/// Decimates one mesh given as arrays (see `decimate.simplify`, which checks and converts
/// its arguments and calls this).
#[pyfunction]
#[pyo3(signature = (vertices, faces, goal, algorithm, keep_border, feature_angle, colors, uvs, normals, record, weld, cancel, threads))]
#[allow(clippy::too_many_arguments)]
pub fn simplify<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f32>,
    faces: PyReadonlyArray2<'py, u32>,
    goal: (Option<f64>, Option<usize>, Option<usize>, Option<f64>),
    algorithm: &str,
    keep_border: bool,
    feature_angle: f64,
    colors: Option<PyReadonlyArray2<'py, f32>>,
    uvs: Option<PyReadonlyArray2<'py, f32>>,
    normals: Option<PyReadonlyArray2<'py, f32>>,
    record: bool,
    weld: bool,
    cancel: Option<PyRef<'py, Cancel>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let goal = Goal::from(goal);
    let m = model(
        &vertices,
        &faces,
        colors.as_ref(),
        uvs.as_ref(),
        normals.as_ref(),
    )?;
    let params = params(
        goal,
        m.triangles.len(),
        algorithm,
        keep_border,
        feature_angle,
    )?;
    let cancel = cancel.map_or_else(decimate_core::cancel::Cancel::new, |c| c.0.clone());
    let scene = Scene { models: vec![m] };
    let flag = cancel.clone();
    let (scene, outcome, repairs) = interruptible(py, &cancel, move || {
        on_threads(threads, || {
            decimate_prepared(scene, weld, record, &params, &flag)
        })
    })?;
    let Some((report, progressive)) = outcome else {
        return Err(Cancelled::new_err("simplify was cancelled"));
    };
    let out = PyDict::new(py);
    let m = scene.models.into_iter().next().unwrap_or_default();
    out.set_item("vertices", vec3s(py, &m.positions)?)?;
    out.set_item("faces", to_numpy(py, m.triangles)?)?;
    if let Some(Attribute::PerVertex(c)) = m.colors {
        out.set_item("colors", to_numpy(py, c)?)?;
    }
    if let Some(t) = m.texcoords {
        out.set_item("uvs", to_numpy(py, t)?)?;
    }
    if let Some(Attribute::PerVertex(v)) = m.normals {
        out.set_item("normals", vec3s(py, &v)?)?;
    }
    out.set_item("report", report_dict(py, &report, params.target, &repairs)?)?;
    out.set_item("progressive", progressive.map(Progressive::new))?;
    Ok(out)
}

/// What one `simplify` call hands back from its worker: the scene, the report with the
/// progressive record (`None` when cancelled) and the repairs made before decimating.
type Prepared = (
    Scene,
    Option<(
        Report,
        Option<decimate_core::mesh::progressive::ProgressiveModel>,
    )>,
    Vec<String>,
);

/// Prepares `scene` as the program does (welded unless `weld` is false) and decimates it,
/// recording a progressive mesh when `record`.
fn decimate_prepared(
    scene: Scene,
    weld: bool,
    record: bool,
    params: &Params,
    flag: &decimate_core::cancel::Cancel,
) -> Prepared {
    let (mut scene, repairs) = prepare(scene, weld);
    let outcome = if record {
        simplify_scene_progressive_cancellable(&mut scene, params, &mut |_| {}, flag)
            .map(|(r, p)| (r, p.models.into_iter().next()))
    } else {
        simplify_scene_cancellable(&mut scene, params, &mut |_| {}, flag).map(|r| (r, None))
    };
    (scene, outcome, repairs)
}

/// Reads `src`, decimates it and writes `dst` in the format its extension names (see
/// `decimate.simplify_file`). Refuses to write over the input.
#[pyfunction]
#[pyo3(signature = (src, dst, goal, algorithm, keep_border, feature_angle, cancel, threads))]
#[allow(clippy::too_many_arguments)]
pub fn simplify_file<'py>(
    py: Python<'py>,
    src: PathBuf,
    dst: PathBuf,
    goal: (Option<f64>, Option<usize>, Option<usize>, Option<f64>),
    algorithm: &str,
    keep_border: bool,
    feature_angle: f64,
    cancel: Option<PyRef<'py, Cancel>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let goal = Goal::from(goal);
    if let (Ok(a), Ok(b)) = (src.canonicalize(), dst.canonicalize()) {
        if a == b {
            return Err(PyValueError::new_err(api::Error::SameFile(dst).to_string()));
        }
    }
    let cancel = cancel.map_or_else(decimate_core::cancel::Cancel::new, |c| c.0.clone());
    let outcome = scene::read_outcome(py, &src, &cancel)?;
    let s = outcome.scene;
    let params = params(
        goal,
        s.triangle_count(),
        algorithm,
        keep_border,
        feature_angle,
    )?;
    let flag = cancel.clone();
    let (s, report, repairs) = interruptible(py, &cancel, move || {
        on_threads(threads, move || {
            let (mut s, repairs) = prepare(s, true);
            let r = simplify_scene_cancellable(&mut s, &params, &mut |_| {}, &flag);
            (s, r, repairs)
        })
    })?;
    let Some(report) = report else {
        return Err(Cancelled::new_err("simplify_file was cancelled"));
    };
    let mut s = s;
    let folder = io::texture_path::folder_of;
    io::texture_path::rebase_textures(&mut s, folder(&src), folder(&dst));
    let mut warnings: Vec<String> = io::warning::grouped(&outcome.warnings)
        .into_iter()
        .map(ToString::to_string)
        .collect();
    warnings.extend(repairs);
    warnings.extend(io::losses::losses_at(&s, &dst));
    scene::write_scene(py, &s, &dst, &cancel)?;
    report_dict(py, &report, params.target, &warnings)
}

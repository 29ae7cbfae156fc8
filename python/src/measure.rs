//! `metro`: the surface distance between two meshes (both directions sampled, see
//! `decimate_core::metro`), off the GIL and interruptible.

use decimate_core::cancel::Cancel as CoreCancel;
use decimate_core::metro::{compare_cancellable, MetroError, Options, Surface};
use glam::DVec3;
use numpy::PyReadonlyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::rows;
use crate::run::interruptible;
use crate::{Cancel, Cancelled};

fn surface(
    v: &PyReadonlyArray2<'_, f64>,
    f: &PyReadonlyArray2<'_, u32>,
    side: &str,
) -> PyResult<Surface> {
    let positions: Vec<DVec3> = rows::<f64, 3>(v, side)?
        .iter()
        .map(|&p| DVec3::from(p))
        .collect();
    let triangles = rows::<u32, 3>(f, side)?;
    Ok(Surface::new(&positions, triangles))
}

/// Measures mesh A against mesh B (see `decimate.metro`).
#[pyfunction]
#[pyo3(signature = (va, fa, vb, fb, samples, seed, cancel))]
#[allow(clippy::too_many_arguments)]
pub fn metro<'py>(
    py: Python<'py>,
    va: PyReadonlyArray2<'py, f64>,
    fa: PyReadonlyArray2<'py, u32>,
    vb: PyReadonlyArray2<'py, f64>,
    fb: PyReadonlyArray2<'py, u32>,
    samples: Option<usize>,
    seed: u64,
    cancel: Option<PyRef<'py, Cancel>>,
) -> PyResult<Bound<'py, PyDict>> {
    let a = surface(&va, &fa, "a")?;
    let b = surface(&vb, &fb, "b")?;
    let options = Options {
        samples,
        seed,
        ..Options::default()
    };
    let cancel = cancel.map_or_else(CoreCancel::new, |c| c.0.clone());
    let flag = cancel.clone();
    let result = interruptible(py, &cancel, move || {
        compare_cancellable(&a, &b, &options, &flag)
    })?;
    let c = match result {
        Ok(c) => c,
        Err(MetroError::Cancelled) => return Err(Cancelled::new_err("metro was cancelled")),
        Err(e) => return Err(PyValueError::new_err(e.to_string())),
    };
    let d = PyDict::new(py);
    let s = c.symmetric();
    d.set_item("max", s.max)?;
    d.set_item("mean", s.mean)?;
    d.set_item("rms", s.rms)?;
    d.set_item("diagonal", c.diagonal)?;
    for (key, side) in [("a_to_b", &c.a_to_b), ("b_to_a", &c.b_to_a)] {
        let one = PyDict::new(py);
        one.set_item("max", side.max)?;
        one.set_item("mean", side.mean)?;
        one.set_item("rms", side.rms)?;
        one.set_item("samples", side.samples())?;
        d.set_item(key, one)?;
    }
    d.set_item("nonmanifold_edges_b", c.b.nonmanifold_edges)?;
    d.set_item("boundary_edges_b", c.b.boundary_edges)?;
    Ok(d)
}

//! `Progressive`: the record of a quadric decimation (`simplify(..., record=True)`), from
//! which every level of detail between the result and the input is rebuilt exactly.

use std::sync::Mutex;

use decimate_core::mesh::progressive::{Lod, ProgressiveModel};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{to_numpy, vec3s};

/// Every level of detail between a decimated mesh and its input. `level(n)` gives the
/// mesh with `n` vertices (clamped to `min_vertices..=max_vertices`) as `(vertices,
/// faces)` arrays; moving between nearby levels is cheap.
#[pyclass(module = "decimate")]
pub struct Progressive {
    lod: Mutex<Lod<ProgressiveModel>>,
    base: usize,
    full: usize,
}

impl Progressive {
    pub fn new(pm: ProgressiveModel) -> Self {
        let base = pm.base.positions.len();
        let full = pm.full_vertex_count();
        Self {
            lod: Mutex::new(Lod::new(pm)),
            base,
            full,
        }
    }
}

#[pymethods]
impl Progressive {
    /// Vertices of the coarsest level (the decimated mesh).
    #[getter]
    fn min_vertices(&self) -> usize {
        self.base
    }

    /// Vertices of the finest level (the input, unused vertices left out).
    #[getter]
    fn max_vertices(&self) -> usize {
        self.full
    }

    /// The mesh with `n_vertices` vertices (clamped to the levels there are; one fewer where
    /// the level would open a texture seam) as `(vertices, faces)`: float32 `(n, 3)` and
    /// uint32 `(m, 3)` arrays.
    #[allow(clippy::type_complexity)]
    fn level<'py>(
        &self,
        py: Python<'py>,
        n_vertices: usize,
    ) -> PyResult<(Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<u32>>)> {
        let mut lod = self
            .lod
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let level = n_vertices.clamp(self.base, self.full) - self.base;
        let level = lod.progressive().whole_level(level);
        lod.set_level(level);
        let m = lod.model();
        Ok((vec3s(py, &m.positions)?, to_numpy(py, m.triangles.clone())?))
    }

    fn __repr__(&self) -> String {
        format!(
            "<decimate.Progressive {}..{} vertices>",
            self.base, self.full
        )
    }
}

//! numpy arrays in and out. Inputs arrive from the Python half as C-contiguous float32 /
//! uint32 arrays of the right width (it converts and checks shapes); here they are viewed as
//! rows and copied into the core's vectors while the GIL is held, so that no Python thread
//! can change them under a running decimation.

use glam::Vec3;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The rows of an `(n, N)` C-contiguous array.
pub fn rows<'a, T: numpy::Element, const N: usize>(
    array: &'a PyReadonlyArray2<'_, T>,
    what: &str,
) -> PyResult<&'a [[T; N]]> {
    let shape = array.shape();
    if shape[1] != N {
        return Err(PyValueError::new_err(format!(
            "{what}: expected shape (n, {N}), got ({}, {})",
            shape[0], shape[1]
        )));
    }
    let flat = array
        .as_slice()
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))?;
    Ok(flat.as_chunks::<N>().0)
}

/// An `(n, N)` array of rows.
pub fn to_numpy<'py, T: numpy::Element, const N: usize>(
    py: Python<'py>,
    rows: Vec<[T; N]>,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let n = rows.len();
    let flat: Vec<T> = rows.into_iter().flatten().collect();
    flat.into_pyarray(py).reshape([n, N])
}

/// Positions as an `(n, 3)` float32 array.
pub fn vec3s<'py>(py: Python<'py>, v: &[Vec3]) -> PyResult<Bound<'py, PyArray2<f32>>> {
    to_numpy(py, v.iter().map(|p| p.to_array()).collect())
}

/// `(n, 3)` float32 rows as vectors.
pub fn to_vec3s(rows: &[[f32; 3]]) -> Vec<Vec3> {
    rows.iter().map(|&p| Vec3::from(p)).collect()
}

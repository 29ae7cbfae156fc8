//! `decimate._decimate`: the compiled half of the Python package. It turns numpy arrays into
//! `decimate-core` models and back, runs the core's decimation, metro and readers/writers
//! with the GIL released, and stops them when Python raises KeyboardInterrupt (Ctrl-C) or a
//! [`Cancel`] is requested. Argument checking, defaults and the duck-typed adapters live in
//! the pure-Python half (`decimate/__init__.py`), which is what users call.

mod arrays;
mod measure;
mod progressive;
mod run;
mod scene;
mod simplify;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    _decimate,
    ReadError,
    PyValueError,
    "A file that cannot be read as a mesh: the message names the file and what is wrong."
);
create_exception!(
    _decimate,
    Cancelled,
    pyo3::exceptions::PyException,
    "A run stopped because its `Cancel` was requested."
);

/// A stop request that another thread can make while `simplify`, `simplify_file` or
/// `metro` runs: pass it as `cancel=`, call `request()` from elsewhere, and the run raises
/// `decimate.Cancelled` within a fraction of a second.
#[pyclass(module = "decimate", frozen)]
#[derive(Clone, Default)]
pub struct Cancel(pub decimate_core::cancel::Cancel);

#[pymethods]
impl Cancel {
    #[new]
    fn new() -> Self {
        Self(decimate_core::cancel::Cancel::new())
    }

    /// Asks every run given this token to stop.
    fn request(&self) {
        self.0.request();
    }

    /// True once `request()` was called.
    #[getter]
    fn requested(&self) -> bool {
        self.0.requested()
    }
}

#[pymodule]
fn _decimate(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ReadError", m.py().get_type::<ReadError>())?;
    m.add("Cancelled", m.py().get_type::<Cancelled>())?;
    m.add_class::<Cancel>()?;
    m.add_class::<progressive::Progressive>()?;
    m.add_function(wrap_pyfunction!(simplify::simplify, m)?)?;
    m.add_function(wrap_pyfunction!(simplify::simplify_file, m)?)?;
    m.add_function(wrap_pyfunction!(scene::read, m)?)?;
    m.add_function(wrap_pyfunction!(scene::write, m)?)?;
    m.add_function(wrap_pyfunction!(measure::metro, m)?)?;
    Ok(())
}

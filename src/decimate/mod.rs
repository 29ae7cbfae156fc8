//! Decimation algorithms, one module per algorithm, over `mesh` arrays.

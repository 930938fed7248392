//! Integration tests of tumble-studies: one binary, one module per feature.

mod work_precision;

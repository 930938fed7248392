//! Integration tests of tumble-studies: one binary, one module per feature.

mod default_accuracy;
mod work_precision;

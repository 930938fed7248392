//! Integration tests of tumble-studies: one binary, one module per feature.

mod coriolis_landing;
mod default_accuracy;
mod error_estimate;
mod fuzz;
mod hard_cases;
mod max_tilt_reference;
mod method_agreement;
mod recommendations;
mod records;
mod reduced_model;
mod refinement;
mod results_table;
mod work_precision;

//! Integration tests of tumble-integrators: one binary, one module per feature.

mod rigid_support;
mod support;

mod composition_of_any_state;
mod coupled_bead_on_hoop;
mod dense_output_and_events;
mod driver_contract;
mod error_control_rigid_body;
mod exact_free_rigid_body;
mod heavy_top_simo_wong;
mod lgvi_long_run;
mod lie_gauss_variational;
mod lie_group_methods_stay_on_so3;
mod long_run_brouwer;
mod observed_order;
mod pair_orders_rigid_body;
mod product_group_methods;
mod quadratic_invariants;
mod registry_lists_every_method;
mod rigid_body_hard_cases;
mod rigid_body_orders;
mod rigid_body_problems;
mod special_functions;
mod tables_as_data;
mod taylor_double_double;
mod taylor_method;

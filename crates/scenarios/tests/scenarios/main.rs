//! Integration tests of tumble-scenarios: one binary, one module per feature; each test is named
//! after what it proves, against closed forms, conserved quantities or textbook equations.

mod support;

mod body_scenes;
mod compositions;
mod coriolis_drop;
mod driven_hoop;
mod free_hoop;
mod free_hoop_euler;
mod fuzz;
mod heavy_top_euler;
mod lagrangian_ad;
mod rigid_scenes;
mod scene_runs;
mod separable_hoops;
mod spinning_hoop;

//! Tests of tumble-model: the expression graph, the mechanics, the shipped models against their
//! built-in twins and against independent closed forms, and the model parser under mutation.

mod carried;
mod double_double;
mod drawing;
mod expr;
mod fuzz;
mod lie;
mod models;
mod multi_so3;
mod multi_so3_lie;
mod multi_so3_variational;
mod native;
mod so3;
mod support;
mod taylor;
mod twins;
mod units;

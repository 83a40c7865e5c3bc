//! Butcher tableaux of the embedded Runge–Kutta pairs, one file each, as numbers only
//! (the steps that use them live in [`crate::ode::pair`]).

pub mod dop853;
pub mod dp5;
pub mod vern9;

#[cfg(test)]
mod order_conditions;

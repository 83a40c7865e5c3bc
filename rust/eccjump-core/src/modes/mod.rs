//! The modes of motion, each a constraint on Newton–Euler ([`crate::mechanics`]) with its
//! equations as an ODE system, its fast closed forms and its runs. Today: pure rolling.
//! Slipping, flight and impact join here.

pub mod rolling;

//! Maps over many independent points: the bit-reproducible parallel driver, JARM maps over
//! point lists and grids, and the region's boundaries by bisection.

pub mod boundary;
pub mod parallel;
pub mod region;

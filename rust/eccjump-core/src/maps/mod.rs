//! Maps over many independent points: the bit-reproducible parallel driver, JARM maps over
//! point lists and grids written as columns, the region's boundaries by bisection, and maps
//! of the full motion over grids and over lists of points.

pub mod boundary;
pub mod columns;
pub mod motion;
pub mod motion_points;
pub mod parallel;
pub mod region;

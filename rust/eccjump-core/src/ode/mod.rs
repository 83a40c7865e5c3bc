//! Dormand–Prince 5(4) integrator (to be written).

//! The Dormand–Prince 5(4) Butcher tableau and dense-output matrix (to be written).

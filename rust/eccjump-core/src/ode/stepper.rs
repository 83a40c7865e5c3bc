//! One adaptive Dormand–Prince step: error norm and step-size control (to be written).

"""Writes rust/eccjump-core/src/ode/tableau/dop853.rs from scipy's DOP853 coefficients.

Run from the repository root, then `cargo fmt`:

    python scripts/gen_dop853.py > rust/eccjump-core/src/ode/tableau/dop853.rs

Every entry is printed as the shortest decimal that round-trips to scipy's float64, so the
Rust constants are bit-identical to scipy's.
"""

from rust_literals import const, mat, row
from scipy.integrate._ivp import dop853_coefficients as c

HEADER = """\
//! The Dormand–Prince 8(5,3) tableau of DOP853 (Hairer, Nørsett & Wanner, Solving ODEs I,
//! Sec. II.10), as scipy's `dop853_coefficients.py`.
//!
//! GENERATED from scipy's file by `scripts/gen_dop853.py`: every entry is the correctly
//! rounded f64 of scipy's decimal literal, written in its shortest round-trip form, so the
//! numbers are bit-identical to scipy's (a hand-copied coefficient is the typo this
//! project fears most; `ode::pair::dop853`'s tests check the orders as well).

#![allow(clippy::excessive_precision, clippy::unreadable_literal)]
"""


S = c.N_STAGES
ITEMS = [
    (f"Stages of one step (the FSAL derivative at the step end is stored as stage {S}).",
     "N_STAGES", "usize", str(S)),
    ("Stages including the three extra ones of the 7th-degree dense output.",
     "N_STAGES_EXTENDED", "usize", str(c.N_STAGES_EXTENDED)),
    ("Order of the propagated solution.", "ORDER", "i32", "8"),
    ("Order of the error estimator; step control uses the exponent −1/(7 + 1).",
     "ERROR_ESTIMATOR_ORDER", "i32", "7"),
    ("Step-size exponent −1/(error_estimator_order + 1), as scipy's `error_exponent`.",
     "ERROR_EXPONENT", "f64", "-1.0 / (ERROR_ESTIMATOR_ORDER as f64 + 1.0)"),
    ("Nodes c_i of the 12 main stages.", "C", "[f64; N_STAGES]", row(c.C[:S])),
    ("Stage coupling a_ij of the main stages (row i, columns j < i; zero-padded).",
     "A", "[[f64; N_STAGES]; N_STAGES]", mat(c.A[:S, :S])),
    ("Weights of the 8th-order solution.", "B", "[f64; N_STAGES]", row(c.B)),
    ("The 5th-order error weights over the 13 stages (including FSAL).",
     "E5", "[f64; N_STAGES + 1]", row(c.E5)),
    ("The 3rd-order error weights over the 13 stages (including FSAL).",
     "E3", "[f64; N_STAGES + 1]", row(c.E3)),
    ("Nodes of the three extra stages of the dense output.",
     "C_EXTRA", "[f64; 3]", row(c.C[S + 1 :])),
    ("Coupling of the three extra stages to the 13 before them (and to each other).",
     "A_EXTRA", "[[f64; N_STAGES_EXTENDED]; 3]", mat(c.A[S + 1 :])),
    ("The dense output's F_3..F_6 = h D K (F_0..F_2 come from y and f at the step ends).",
     "D", "[[f64; N_STAGES_EXTENDED]; 4]", mat(c.D)),
]  # fmt: skip

if __name__ == "__main__":
    print(HEADER)
    print("\n".join(const(*item) for item in ITEMS))

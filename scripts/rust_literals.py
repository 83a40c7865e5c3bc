"""Rust source for the tableau generators (`gen_dop853.py`, `gen_vern9.py`):
each number as the shortest decimal that round-trips to its float64, rows, matrices and
documented consts."""


def lit(x: float) -> str:
    r = repr(float(x))
    return r if ("e" in r or "." in r) else r + ".0"


def row(v) -> str:
    return "[" + ", ".join(lit(x) for x in v) + "]"


def mat(m) -> str:
    return "[\n" + "".join(f"    {row(r)},\n" for r in m) + "]"


def const(doc: str, name: str, ty: str, value: str) -> str:
    return f"/// {doc}\npub const {name}: {ty} = {value};\n"

"""The body: a cylinder whose centre of mass is offset from its axis.

Its motion depends only on two numbers (paper, Sec. 2.4):

* ``chi`` = d/R in [0, 1], the offset of the centre of mass (CM) from the geometric centre C;
* ``km`` = m_C/M in [0, 1 - chi], the mass fraction of the uniform thin shell of the paper's
  shell-plus-line-mass model.

Derived, in units of M R²: ``Ic`` = km + chi²/(1 - km) (about C), ``Icm`` = Ic - chi² (about the
CM), and the paper's ``gamma`` = (Ic + 1 + 2 chi)/(4 pi chi) (Eq. dega2; infinite for chi = 0).
Validation is done by the Rust core, so Python and Rust agree on every boundary.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from eccjump import _core
from eccjump._checks import real
from eccjump._html import card


@dataclass(frozen=True, slots=True)
class Cylinder:
    """A validated eccentric cylinder, immutable and hashable.

    Parameters
    ----------
    chi : float
        d/R, offset of the centre of mass from the axis, in [0, 1].
    km : float
        Shell mass fraction m_C/M, in [0, 1 - chi].

    Raises
    ------
    ValueError
        If a parameter is NaN, infinite or out of its range (the message names it).
    TypeError
        If a parameter is not a real number (bools, strings, None, complex, arrays).
    """

    chi: float
    km: float
    Ic: float = field(init=False, repr=False, compare=False)
    Icm: float = field(init=False, repr=False, compare=False)
    gamma: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        chi, km = real("chi", self.chi), real("km", self.km)
        ic, icm, gamma = _core.body_derived(chi, km)
        for name, value in (("chi", chi), ("km", km), ("Ic", ic), ("Icm", icm), ("gamma", gamma)):
            object.__setattr__(self, name, value)

    def __getstate__(self) -> tuple[float, float]:
        return (self.chi, self.km)

    def __setstate__(self, state: tuple[float, float]) -> None:
        object.__setattr__(self, "chi", state[0])
        object.__setattr__(self, "km", state[1])
        self.__post_init__()

    def __repr__(self) -> str:
        return f"Cylinder(chi={self.chi!r}, km={self.km!r})"

    def __str__(self) -> str:
        """The body with its derived inertias."""
        return f"{self!r}: Ic={self.Ic:.6g}, Icm={self.Icm:.6g}, gamma={self.gamma:.6g}"

    def _repr_html_(self) -> str:
        return card(
            "Cylinder",
            [
                ("chi", f"{self.chi:.6g} (CM offset d/R)"),
                ("km", f"{self.km:.6g} (shell mass fraction)"),
                ("Ic, Icm", f"{self.Ic:.6g}, {self.Icm:.6g} [M R^2] (about C, about the CM)"),
                ("gamma", f"{self.gamma:.6g}"),
            ],
        )

    @classmethod
    def from_inertia(cls, M: float, R: float, d: float, I_C: float) -> Cylinder:
        """A body of mass ``M`` [kg], radius ``R`` [m], CM offset ``d`` [m] and moment of
        inertia ``I_C`` [kg m²] about the geometric axis; valid iff 0 <= d <= R and
        M d² <= I_C <= M R²."""
        chi, km = _core.body_from_inertia(
            real("M", M), real("R", R), real("d", d), real("I_C", I_C)
        )
        return cls(chi, km)

    @classmethod
    def from_shell_and_line(cls, m_C: float, m_P: float, R: float, d: float) -> Cylinder:
        """The paper's model: a uniform thin shell of mass ``m_C`` and radius ``R`` plus a line
        mass ``m_P`` parallel to the axis, placed so that the CM is at distance ``d`` from the
        axis (the line then sits at d/(1 - km) <= R)."""
        chi, km = _core.body_from_shell_and_line(
            real("m_C", m_C), real("m_P", m_P), real("R", R), real("d", d)
        )
        return cls(chi, km)

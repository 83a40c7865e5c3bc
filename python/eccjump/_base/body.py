"""The body: a cylinder whose centre of mass is offset from its axis.

Its motion depends only on two numbers (paper, Sec. 2.4):

* ``chi`` = d/R in [0, 1], the offset of the centre of mass (CM) from the geometric centre C;
* ``km`` = m_C/M in [0, 1 - χ], the mass fraction of the uniform thin shell of the paper's
  shell-plus-line-mass model.

Derived, in units of M R²: ``Ic`` = km + chi²/(1 - km) (about C), ``Icm`` = Ic - chi² (about the
CM), and the paper's ``gamma`` = (Ic + 1 + 2 χ)/(4π χ) (Eq. dega2; infinite for χ = 0).
Validation is done by the Rust core, so Python and Rust agree on every boundary.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from eccjump import _core
from eccjump._base.checks import real
from eccjump._base.html import card

#: How far k_m may pass 1 - chi and still be a body: the core's slack for the rounding of
#: 1 - chi (a rod at the rim, chi = 1 - k_m computed, gives k_m an ulp above it).
KM_ROUNDING = 4.0 * 2.0**-52


@dataclass(frozen=True, slots=True)
class Cylinder:
    """A validated eccentric cylinder, immutable and hashable.

    The motion depends on the body only through ``chi`` and ``km`` (units g = R = M = 1).

    Parameters
    ----------
    chi : float
        d/R, the offset of the centre of mass from the geometric axis, in [0, 1]
        (dimensionless).
    km : float
        The shell mass fraction m_C/M of the paper's shell-plus-line-mass model, in
        [0, 1 - χ] (dimensionless).

    Attributes
    ----------
    chi : float
        As given.
    km : float
        As given.
    Ic : float
        Moment of inertia about the geometric axis, km + chi²/(1 - km) [M R²].
    Icm : float
        Moment of inertia about the centre of mass, Ic - chi² [M R²].
    gamma : float
        The paper's γ = (Ic + 1 + 2 χ)/(4π χ) (Eq. dega2); inf for χ = 0.

    Raises
    ------
    ValueError
        If a parameter is NaN, infinite or out of its range (the message names it).
    TypeError
        If a parameter is not a real number (bools, strings, None, complex, arrays).

    See Also
    --------
    from_inertia : the body of a given mass, radius, offset and moment of inertia.
    from_shell_and_line : the paper's shell plus line mass.
    eccjump.build : the inverse, a body as a shell plus a rod of given radius and mass.

    Examples
    --------
    >>> import eccjump
    >>> body = eccjump.Cylinder(chi=0.15, km=0.02)
    >>> print(f"Ic = {body.Ic:.6f}, Icm = {body.Icm:.6f} M R^2")
    Ic = 0.042959, Icm = 0.020459 M R^2
    >>> eccjump.Cylinder(chi=0.5, km=0.6)
    Traceback (most recent call last):
    ...
    ValueError: km = 0.6 is outside the allowed range [0, 1 - chi] = [0, 0.5]
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
        """The body of mass ``M``, radius ``R``, centre-of-mass offset ``d`` and moment of
        inertia ``I_C`` about the geometric axis (any consistent units, e.g. SI).

        Parameters
        ----------
        M : float
            Mass [kg], finite and > 0.
        R : float
            Radius [m], finite and > 0.
        d : float
            Distance of the centre of mass from the geometric axis [m], in [0, R].
        I_C : float
            Moment of inertia about the geometric axis [kg m²], in [M d², M R²].

        Returns
        -------
        Cylinder
            χ = d/R and the km of the shell-plus-line-mass body with I_C/(M R²).

        Raises
        ------
        ValueError
            If a value is out of its range (the message names it).
        TypeError
            If a value is not a real number.

        Examples
        --------
        >>> import eccjump
        >>> body = eccjump.Cylinder.from_inertia(M=1.5, R=0.2, d=0.03, I_C=0.0026)
        >>> print(f"chi = {body.chi:.4f}, km = {body.km:.6f}")
        chi = 0.1500, km = 0.020366
        """
        chi, km = _core.body_from_inertia(
            real("M", M), real("R", R), real("d", d), real("I_C", I_C)
        )
        return cls(chi, km)

    @classmethod
    def from_shell_and_line(cls, m_C: float, m_P: float, R: float, d: float) -> Cylinder:
        """The paper's model: a uniform thin shell of mass ``m_C`` and radius ``R`` plus a line
        mass ``m_P`` parallel to the axis, placed so that the centre of mass is at distance
        ``d`` from the axis (the line then sits at d/(1 - km) ≤ R from it).

        Parameters
        ----------
        m_C : float
            Mass of the shell [kg], ≥ 0.
        m_P : float
            Mass of the line (a rod) [kg], ≥ 0; m_C + m_P > 0.
        R : float
            Radius of the shell [m], > 0.
        d : float
            Distance of the centre of mass from the axis [m], in [0, R m_P/(m_C + m_P)].

        Returns
        -------
        Cylinder
            χ = d/R, km = m_C/(m_C + m_P).

        Raises
        ------
        ValueError
            If a value is out of its range (the message names it).
        TypeError
            If a value is not a real number.

        Examples
        --------
        >>> import eccjump
        >>> body = eccjump.Cylinder.from_shell_and_line(m_C=0.03, m_P=1.47, R=0.2, d=0.03)
        >>> print(f"chi = {body.chi:.4f}, km = {body.km:.4f}")
        chi = 0.1500, km = 0.0200
        """
        chi, km = _core.body_from_shell_and_line(
            real("m_C", m_C), real("m_P", m_P), real("R", R), real("d", d)
        )
        return cls(chi, km)

"""Elastic couplings from catalogue data (domain).

A highly elastic coupling (rubber or steel-spring element) enters the lumped model as a shaft
between its primary and secondary inertias (:class:`crankdyn.torsion.elements.Shaft` with a
:class:`Coupling`). The makers' catalogues give, for torsional vibration calculations:

- the **dynamic torsional stiffness** C_Tdyn (N m/rad), which for rubber depends on the mean
  torque carried (a table of C_Tdyn against the mean torque, or one value at the nominal torque
  T_KN), on the temperature of the rubber (a temperature factor) and, more weakly, on the
  frequency and the vibratory amplitude (not modelled);
- the **relative damping** psi, the ratio of the damping work per vibration cycle A_D (the area
  of the hysteresis loop) to the elastic strain energy A_el at the amplitude, psi = A_D / A_el
  (DIN 740-2:1986, "Nachgiebige Wellenkupplungen; Begriffe und Berechnungsgrundlagen"; the
  definitions sheets of the catalogues of Centa, Vulkan and Renold). Rubber damping is
  practically independent of the frequency, so the coupling is hysteretic: its torque is
  C (1 + i eta) times the twist with the loss factor eta = tan(delta), and then
  A_D = pi eta C theta^2 and A_el = C theta^2 / 2 give

      psi = 2 pi eta = 2 pi tan(delta),     eta = psi / (2 pi),

  the relation printed by Renold (psi = A_D / A_f = 2 pi / M with the dynamic magnifier
  M = 1 / tan(delta)); the resonance factor of the catalogues V_R = 2 pi / psi = 1 / eta is the
  magnification at resonance of a single mass on the coupling. A single mass on a hysteretic
  spring has at resonance the magnification of a viscous one with damping ratio zeta = eta / 2,
  so a damping ratio given instead of psi is converted by psi = 4 pi zeta;
- the **permissible torques** for the rule checks (DIN 740-2): the nominal torque T_KN (mean
  torque carried continuously), the maximum torque T_Kmax (transient, e.g. passing a resonance),
  the permissible continuous vibratory torque T_KW (amplitude) and the permissible power loss
  P_KV (the heat the element can dissipate continuously, W); where the maker's catalogue
  gives them, the maximum torques T_Kmax1 for normal transient conditions (starts, stops,
  clutch engagements, passing resonances: many times in the coupling's life) and T_Kmax2 for
  exceptional ones (a generator's short circuit, an emergency stop: a few times), as the
  marine coupling catalogues print them beside T_Kmax (e.g. Vulkan's and Centa's data sheets;
  T_Kmax2 >= T_Kmax1). They are kept here, unchecked by the vibration analysis itself.

Temperature. The catalogues give factors for the stiffness and the relative damping at the
rubber's operating temperature (e.g. C_T(theta) = C_T,ref S_t in Renold's and Poona's tables;
psi reduced by a factor in Centa's): ``temperature_factor`` multiplies C_Tdyn and
``damping_temperature_factor`` multiplies psi.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError
from crankdyn.results import freeze

__all__ = ["PSI_MAX", "Coupling", "loss_factor_from_psi", "psi_from_damping_ratio"]

PSI_MAX = 2.0 * math.pi
"""Largest relative damping accepted (psi = 2 pi: loss factor 1, the damping work per cycle
2 pi times the strain energy). Catalogue values of rubber and spring couplings lie between about
0.1 and 2."""


def loss_factor_from_psi(psi: float) -> float:
    """Loss factor eta = tan(delta) = psi / (2 pi) of a relative damping psi.

    From psi = A_D / A_el = 2 pi eta for a hysteretic element (DIN 740-2:1986; Renold's
    definitions sheet, psi = 2 pi / M with M = 1 / tan(delta); module docstring).

    Parameters
    ----------
    psi : float
        Relative damping psi (dimensionless), the damping work per cycle over the elastic
        strain energy.

    Returns
    -------
    float
        Loss factor eta (dimensionless).

    Examples
    --------
    >>> round(loss_factor_from_psi(2.0 * math.pi), 12)
    1.0
    >>> f"{loss_factor_from_psi(1.0):.6g}"
    '0.159155'
    """
    return psi / (2.0 * math.pi)


def psi_from_damping_ratio(zeta: float) -> float:
    """Relative damping psi = 4 pi zeta equivalent to a damping ratio zeta at resonance.

    A single mass on a hysteretic spring of loss factor eta has at resonance the magnification
    1 / eta of a viscous one with damping ratio zeta = eta / 2, so psi = 2 pi eta = 4 pi zeta
    (DIN 740-2:1986; module docstring).

    Parameters
    ----------
    zeta : float
        Damping ratio zeta (dimensionless, fraction of critical).

    Returns
    -------
    float
        Relative damping psi (dimensionless).

    Examples
    --------
    >>> f"{psi_from_damping_ratio(0.05):.6g}"
    '0.628319'
    >>> round(loss_factor_from_psi(psi_from_damping_ratio(0.05)), 12)
    0.1
    """
    return 4.0 * math.pi * zeta


def _optional_positive(name: str, value: object, what: str) -> float | None:
    """``value`` checked positive (:func:`~crankdyn.crank.geometry.check_positive`), or None."""
    if value is None:
        return None
    return check_positive(name, value, what)


@dataclass(frozen=True, eq=False)
class Coupling:
    """Catalogue data of an elastic coupling (module docstring).

    Parameters
    ----------
    stiffness : float or None
        C_Tdyn (N m/rad) at the reference torque, > 0; or None with a table.
    table_torque, table_stiffness : sequence of float or None
        C_Tdyn (N m/rad) against the mean torque (N m): a table, torques >= 0 increasing
        strictly, interpolated linearly and never extrapolated; stored as read-only arrays,
        shape (rows,).
    relative_damping : float or None
        psi (dimensionless), 0 < psi <= 2 pi; or None with ``damping_ratio``.
    damping_ratio : float or None
        zeta (dimensionless) instead of psi (psi = 4 pi zeta), 0 < zeta <= 0.5.
    temperature_factor : float
        Factor on C_Tdyn at the operating temperature (dimensionless), > 0 (default 1).
    damping_temperature_factor : float
        Factor on psi at the operating temperature (dimensionless), > 0 (default 1).
    reference_torque : float or None
        Mean torque (N m) at which the table gives the stiffness of the model (its natural
        frequencies and, unless a load law gives the mean torque at each speed, the forced
        response); default the nominal torque T_KN, else the table's largest torque.
    nominal_torque, maximum_torque, vibratory_torque : float or None
        T_KN, T_Kmax, T_KW (N m), for the rule checks; each > 0, T_Kmax >= T_KN >= T_KW.
    maximum_torque_1, maximum_torque_2 : float or None
        T_Kmax1 and T_Kmax2 (N m): the maximum torques for normal and for exceptional
        transient conditions, where the catalogue gives them; each > 0, T_Kmax2 >= T_Kmax1.
    power_loss : float or None
        P_KV, the permissible power loss (W), for the rule checks.
    designation : str or None
        Maker and type, for reports.

    Raises
    ------
    crankdyn.errors.InputError
        On a missing, doubled or impossible value, naming its key (``dynamic_stiffness``,
        ``stiffness_table``, ``stiffness_table_torque``, ``relative_damping``,
        ``damping_ratio``, the torque or factor's own name) and the value given.

    Examples
    --------
    >>> c = Coupling(stiffness=50e3, relative_damping=1.0, nominal_torque=2000.0)
    >>> f"{c.model_stiffness:.6g} N·m/rad, eta {c.loss_factor:.4f}, V_R {c.resonance_factor:.4f}"
    '50000 N·m/rad, eta 0.1592, V_R 6.2832'
    >>> t = Coupling(table_torque=[0.0, 1000.0, 2000.0], table_stiffness=[40e3, 50e3, 70e3],
    ...              damping_ratio=0.05, nominal_torque=1500.0)
    >>> t.model_torque, float(t.model_stiffness), t.stiffness_at([500.0, -2000.0]).tolist()
    (1500.0, 60000.0, [45000.0, 70000.0])
    """

    stiffness: float | None = None
    table_torque: tuple[float, ...] | np.ndarray | None = None
    table_stiffness: tuple[float, ...] | np.ndarray | None = None
    relative_damping: float | None = None
    damping_ratio: float | None = None
    temperature_factor: float = 1.0
    damping_temperature_factor: float = 1.0
    reference_torque: float | None = None
    nominal_torque: float | None = None
    maximum_torque: float | None = None
    vibratory_torque: float | None = None
    power_loss: float | None = None
    designation: str | None = None
    maximum_torque_1: float | None = None
    maximum_torque_2: float | None = None

    def __post_init__(self) -> None:
        table = self.table_torque is not None or self.table_stiffness is not None
        if table and self.stiffness is not None:
            raise InputError(
                "give the dynamic stiffness or its table against the mean torque, not both",
                key="dynamic_stiffness",
                value=self.stiffness,
            )
        if not table and self.stiffness is None:
            raise InputError(
                "missing; give the coupling's dynamic torsional stiffness C_Tdyn (or a table "
                "against the mean torque)",
                key="dynamic_stiffness",
            )
        for name, what in (
            ("nominal_torque", "the nominal torque T_KN"),
            ("maximum_torque", "the maximum torque T_Kmax"),
            ("vibratory_torque", "the permissible vibratory torque T_KW"),
            ("power_loss", "the permissible power loss P_KV"),
            ("maximum_torque_1", "the maximum torque T_Kmax1"),
            ("maximum_torque_2", "the maximum torque T_Kmax2"),
        ):
            object.__setattr__(self, name, _optional_positive(name, getattr(self, name), what))
        t_kn, t_max, t_kw = self.nominal_torque, self.maximum_torque, self.vibratory_torque
        if t_kn is not None and t_max is not None and t_max < t_kn:
            raise InputError(
                f"the maximum torque T_Kmax lies below the nominal torque T_KN ({t_kn:.6g} N·m); "
                "no catalogue rates a coupling so",
                key="maximum_torque",
                value=t_max,
            )
        t1, t2 = self.maximum_torque_1, self.maximum_torque_2
        if t1 is not None and t2 is not None and t2 < t1:
            raise InputError(
                f"T_Kmax2 (exceptional transient conditions) lies below T_Kmax1 ({t1:.6g} N·m, "
                "normal ones); no catalogue rates a coupling so",
                key="maximum_torque_2",
                value=t2,
            )
        if t_kn is not None and t_kw is not None and t_kw > t_kn:
            raise InputError(
                f"the permissible vibratory torque T_KW exceeds the nominal torque T_KN "
                f"({t_kn:.6g} N·m), out of any catalogue's range; check the value",
                key="vibratory_torque",
                value=t_kw,
            )
        if self.stiffness is not None:
            object.__setattr__(
                self,
                "stiffness",
                check_positive("dynamic_stiffness", self.stiffness, "the dynamic stiffness"),
            )
        else:
            self._check_table()
        self._check_damping()
        for name in ("temperature_factor", "damping_temperature_factor"):
            object.__setattr__(
                self, name, check_positive(name, getattr(self, name), "the temperature factor")
            )
        if self.reference_torque is not None:
            value = check_finite("reference_torque", self.reference_torque)
            if value < 0.0:
                raise InputError(
                    "the reference torque must not be negative", key="reference_torque", value=value
                )
            object.__setattr__(self, "reference_torque", value)
            if self.table_torque is not None:
                self._in_table(value, "reference_torque")

    def _check_table(self) -> None:
        if self.table_torque is None or self.table_stiffness is None:
            missing = "stiffness_table_torque" if self.table_torque is None else "stiffness_table"
            raise InputError("a stiffness table needs its torques and its stiffnesses", key=missing)
        t = np.asarray(self.table_torque, dtype=float)
        c = np.asarray(self.table_stiffness, dtype=float)
        if t.ndim != 1 or t.shape != c.shape or t.size < 1:
            raise InputError(
                "the stiffness table needs as many torques as stiffnesses",
                key="stiffness_table",
                value=[len(np.atleast_1d(t)), len(np.atleast_1d(c))],
            )
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(c))):
            raise InputError("the stiffness table holds values that are not finite numbers")
        if np.any(t < 0.0) or np.any(np.diff(t) <= 0.0):
            raise InputError(
                "the table's mean torques must be >= 0 and increase strictly",
                key="stiffness_table_torque",
                value=t.tolist(),
            )
        if np.any(c <= 0.0):
            raise InputError(
                "the table's stiffnesses must be positive",
                key="stiffness_table",
                value=c.tolist(),
            )
        if self.maximum_torque is not None and t[-1] > self.maximum_torque * (1 + 1e-12):
            raise InputError(
                f"the stiffness table reaches beyond the maximum torque T_Kmax "
                f"({self.maximum_torque:.6g} N·m), outside the coupling's catalogue range",
                key="stiffness_table_torque",
                value=t.tolist(),
            )
        object.__setattr__(self, "table_torque", freeze(t))
        object.__setattr__(self, "table_stiffness", freeze(c))

    def _check_damping(self) -> None:
        psi, zeta = self.relative_damping, self.damping_ratio
        if psi is not None and zeta is not None:
            raise InputError(
                "give the relative damping psi or the damping ratio, not both",
                key="damping_ratio",
                value=zeta,
            )
        if psi is None and zeta is None:
            raise InputError(
                "missing; give the coupling's relative damping psi (or its damping ratio)",
                key="relative_damping",
            )
        if psi is not None:
            value = check_finite("relative_damping", psi)
            if not 0.0 < value <= PSI_MAX:
                raise InputError(
                    "the relative damping psi = A_D/A_el lies between 0 and 2 pi (loss factor "
                    "psi/(2 pi) up to 1; catalogues give 0.1 to 2); was a percentage or "
                    "a damping ratio given?",
                    key="relative_damping",
                    value=psi,
                )
            object.__setattr__(self, "relative_damping", value)
        else:
            value = check_finite("damping_ratio", zeta)
            if not 0.0 < value <= PSI_MAX / (4.0 * math.pi):
                raise InputError(
                    "the damping ratio must lie between 0 and 0.5 (psi = 4 pi zeta up to 2 pi)",
                    key="damping_ratio",
                    value=zeta,
                )
            object.__setattr__(self, "damping_ratio", value)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Coupling):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def _key(self) -> tuple:
        table = None
        if self.table_torque is not None:
            assert self.table_stiffness is not None  # both or neither (__post_init__)
            table = (tuple(self.table_torque), tuple(self.table_stiffness))
        return (
            self.stiffness,
            table,
            self.relative_damping,
            self.damping_ratio,
            self.temperature_factor,
            self.damping_temperature_factor,
            self.reference_torque,
            self.nominal_torque,
            self.maximum_torque,
            self.vibratory_torque,
            self.power_loss,
            self.designation,
            self.maximum_torque_1,
            self.maximum_torque_2,
        )

    # ---- derived values -----------------------------------------------------------------------
    @property
    def psi(self) -> float:
        """Relative damping psi at the operating temperature (dimensionless)."""
        if self.relative_damping is not None:
            base = self.relative_damping
        else:
            assert self.damping_ratio is not None  # psi or zeta is given (__post_init__)
            base = psi_from_damping_ratio(self.damping_ratio)
        return base * self.damping_temperature_factor

    @property
    def loss_factor(self) -> float:
        """Loss factor eta = psi / (2 pi) (dimensionless)."""
        return loss_factor_from_psi(self.psi)

    @property
    def resonance_factor(self) -> float:
        """V_R = 2 pi / psi (dimensionless): the catalogues' magnification at resonance."""
        return 2.0 * math.pi / self.psi

    @property
    def load_dependent(self) -> bool:
        """Whether the stiffness depends on the mean torque (a table of more than one row)."""
        return self.table_torque is not None and len(self.table_torque) > 1

    @property
    def model_torque(self) -> float | None:
        """The mean torque (N m) at which the model's stiffness is taken (None without a
        table)."""
        if self.table_torque is None:
            return None
        if self.reference_torque is not None:
            return self.reference_torque
        if self.nominal_torque is not None and self._fits(self.nominal_torque):
            return self.nominal_torque
        return float(self.table_torque[-1])

    @property
    def model_stiffness(self) -> float:
        """C_Tdyn of the model (N m/rad): at :attr:`model_torque`, with the temperature
        factor."""
        torque = self.model_torque
        if torque is None:
            assert self.stiffness is not None  # a stiffness or a table (__post_init__)
            return self.stiffness * self.temperature_factor
        return float(self.stiffness_at(torque))

    def _fits(self, torque: float) -> bool:
        t = self.table_torque
        assert t is not None  # called with a table only
        return t[0] * (1 - 1e-9) - 1e-12 <= torque <= t[-1] * (1 + 1e-9)

    def _in_table(self, torque: float, key: str) -> None:
        if not self._fits(torque):
            t = self.table_torque
            assert t is not None  # _fits needs a table
            raise InputError(
                f"the mean torque lies outside the coupling's stiffness table ({t[0]:.6g} to "
                f"{t[-1]:.6g} N·m, not extrapolated)",
                key=key,
                value=torque,
            )

    def stiffness_at(self, mean_torque: ArrayLike) -> NDArray[np.float64]:
        """C_Tdyn at mean torques |T|: interpolated linearly in the table, times the
        temperature factor (module docstring).

        Parameters
        ----------
        mean_torque : array_like
            Mean torques carried by the coupling (N m), any shape; the sign is ignored.

        Returns
        -------
        numpy.ndarray
            Dynamic torsional stiffness (N m/rad), the shape of ``mean_torque``; constant
            without a table.

        Raises
        ------
        crankdyn.errors.InputError
            When a torque lies outside the table (never extrapolated): key ``mean_torque``,
            the first such torque as value.

        Examples
        --------
        >>> c = Coupling(table_torque=[0.0, 1000.0], table_stiffness=[40e3, 60e3],
        ...              relative_damping=1.0, temperature_factor=0.9)
        >>> c.stiffness_at([0.0, 250.0, -1000.0]).tolist()
        [36000.0, 40500.0, 54000.0]
        """
        t = np.abs(np.asarray(mean_torque, dtype=float))
        if self.table_torque is None:
            assert self.stiffness is not None  # a stiffness or a table (__post_init__)
            return np.full(t.shape, self.stiffness * self.temperature_factor)
        outside = ~(
            (t >= self.table_torque[0] * (1 - 1e-9) - 1e-12)
            & (t <= self.table_torque[-1] * (1 + 1e-9))
        )
        if np.any(outside):
            self._in_table(float(np.atleast_1d(t)[np.atleast_1d(outside)][0]), "mean_torque")
        assert self.table_stiffness is not None  # both or neither (__post_init__)
        return np.interp(t, self.table_torque, self.table_stiffness) * self.temperature_factor

    def limits(self) -> dict[str, float | None]:
        """The permissible values kept for the rule checks (DIN 740-2; SI).

        Returns
        -------
        dict of str to float or None
            ``nominal_torque_Nm``, ``maximum_torque_Nm``, ``vibratory_torque_Nm``,
            ``maximum_torque_1_Nm``, ``maximum_torque_2_Nm`` (N m) and ``power_loss_W`` (W);
            None where not given.

        Examples
        --------
        >>> c = Coupling(stiffness=1e4, relative_damping=1.0, nominal_torque=800.0, power_loss=90.0)
        >>> c.limits()
        {'nominal_torque_Nm': 800.0, 'maximum_torque_Nm': None, 'vibratory_torque_Nm': None,
         'maximum_torque_1_Nm': None, 'maximum_torque_2_Nm': None, 'power_loss_W': 90.0}
        """
        return {
            "nominal_torque_Nm": self.nominal_torque,
            "maximum_torque_Nm": self.maximum_torque,
            "vibratory_torque_Nm": self.vibratory_torque,
            "maximum_torque_1_Nm": self.maximum_torque_1,
            "maximum_torque_2_Nm": self.maximum_torque_2,
            "power_loss_W": self.power_loss,
        }

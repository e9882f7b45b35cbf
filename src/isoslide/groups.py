"""The Pi-group registry: every dimensionless group, defined once.

Buckingham's theorem with the repeating variables ``a_p`` (pulse acceleration
amplitude, m/s^2), ``T_p`` (pulse period, s) and ``M_b`` (isolated mass, kg)
turns the eleven physical parameters of the paper's model into one result
group and seven input groups, the five parameters of the general building
(hysteretic isolator, flexible superstructure; see :mod:`isoslide.engine.building`)
into five more, the second horizontal ground component into three and the vertical one into one:

=====  ===================  ==========================================  ================
group  definition           meaning                                     valid range
=====  ===================  ==========================================  ================
Pi1    u_max / (a_p T_p^2)  peak sliding displacement (the result)      >= 0
Pi2    mu_k g / a_p         kinetic friction strength                   0 < Pi2 < inf
Pi3    T_b / T_p            isolation-to-pulse period ratio, 0 = fixed  0 <= Pi3 <= 1e4
Pi4    xi_b                 isolation damping ratio (>= 1 overdamped)   0 <= Pi4 <= 1e3
Pi5    mu_k / mu_s          kinetic-to-static friction ratio            0 < Pi5 <= 1
Pi6    beta a_p T_p         Stribeck transition sharpness               0 <= Pi6 <= 1e12
Pi7    gamma g T_p          viscous contact group                       0 <= Pi7 <= 1e6
Pi8    m_EC / M_b           contents-to-isolated mass ratio             0 <= Pi8 <= 1e3
Pi9    Q / (M_b a_p)        isolator strength; 0 = linear isolator      0 <= Pi9 <= 1e6
Pi10   D_y / (a_p T_p^2)    isolator yield displacement; 0 = sliding    0 <= Pi10 <= 1e6
Pi11   m_st / M_b           superstructure mass fraction                0 <= Pi11 < 1
Pi12   T_s / T_p            superstructure period; 0 = rigid            0 <= Pi12 <= 1e4
Pi13   xi_s                 superstructure damping ratio                0 <= Pi13 <= 1e3
Pi14   a_py / a_p           transverse-to-main pulse amplitude ratio    0 <= Pi14 <= 1e3
Pi15   T_py / T_p           transverse-to-main pulse period ratio       0 < Pi15 <= 1e4
Pi16   t_y / T_p            transverse pulse time shift                 -1e4 <= Pi16 <= 1e4
Pi17   a_pz / g             vertical ground acceleration over gravity   0 <= Pi17 <= 1e3
Pi18   b / h                aspect ratio of a rocking block             0 < Pi18 <= 1e3
Pi19   p T_p                block frequency parameter over the pulse    0 < Pi19 <= 1e6
Pi20   e                    restitution of a rocking block at impact    0 < Pi20 <= 1
Pi21   a_p / (g tan alpha)  pulse amplitude over the uplift acceleration  0 < Pi21 <= 1e6
Pi22   mu_slow / mu_fast    bearing breakaway-to-fast friction ratio    0 < Pi22 <= 1
Pi23   a a_p T_p            bearing friction rate group                 0 <= Pi23 <= 1e12
Pi24   L1 / (L2 + L3)       inner radius ratio of a triple pendulum     0 <= Pi24 <= 1e3
Pi25   L2 / (L2 + L3)       lower radius share of a triple pendulum     0 < Pi25 < 1
Pi26   mu1 / mu2            inner friction ratio of a triple pendulum   0 < Pi26 <= 1
Pi27   mu3 / mu2            upper friction ratio of a triple pendulum   1 <= Pi27 <= 1e3
Pi28   d1 / (a_p T_p^2)     inner limit of a triple pendulum            0 <= Pi28 <= 1e6
Pi29   d2 / (a_p T_p^2)     lower outer limit of a triple pendulum      0 <= Pi29 <= 1e6
Pi30   d3 / (a_p T_p^2)     upper outer limit of a triple pendulum      0 <= Pi30 <= 1e6
Pi31   mu_slow1 / mu1       inner breakaway-to-fast friction ratio      0 < Pi31 < 1
Pi32   mu_slow3 / mu3       upper breakaway-to-fast friction ratio      0 < Pi32 < 1
Pi33   a1 a_p T_p           inner friction rate group                   0 < Pi33 <= 1e12
Pi34   a3 a_p T_p           upper friction rate group                   0 < Pi34 <= 1e12
=====  ===================  ==========================================  ================

``M_b = m_b + m_st`` is the whole isolated mass (base slab and superstructure,
the contents excluded) and ``T_b = 2 pi sqrt(M_b / k_d)`` the isolation
period with the isolator's post-yield (or linear) stiffness ``k_d``.  Pi11 is
read only with a flexible superstructure (``Pi12 > 0``), where ``0 < Pi11 < 1``
(checked by :class:`isoslide.Scene`).  Pi14 to Pi16 shape the second horizontal component,
``a_gy = Pi14 a_p p_y((tau - Pi16)/Pi15)`` of a scene's ``pulse_y`` (read only with one).  Pi17 scales the vertical ground acceleration
``a_gz = Pi17 g p_z(t/T_p)`` of a scene's ``pulse_z``; it acts through the normal forces.  Pi22 and
Pi23 give a sliding bearing (``Pi9 > 0``, ``Pi10 = 0``) the speed-dependent friction of PTFE-type
surfaces (Constantinou, Mokha and Reinhorn 1990), ``mu(v) = mu_fast - (mu_fast - mu_slow)
exp(-a |v|)`` with ``Pi9 = mu_fast g / a_p`` (read only with a sliding bearing).  Pi24 to Pi30
make a sliding bearing a triple friction pendulum (``Pi24 > 0``; OpenSees's
``TripleFrictionPendulum``: ``L1`` the effective radius of each inner surface, ``L2`` and ``L3`` the
lower and upper outer surfaces', ``mu1 <= mu2 <= mu3`` and ``d1, d2, d3`` their friction and
displacement limits); with them ``Pi3 = 2 pi sqrt((L2 + L3)/g) / T_p`` is the period of its outer
surfaces sliding together (regime III) and ``Pi9 = mu2 g / a_p`` (the bearing's weight ``M_b g``), so
that equal frictions give the single pendulum of radius ``L2 + L3``.  With ``Pi22 < 1`` and ``Pi23 > 0``
every surface of a triple pendulum follows that law of its own sliding speed: ``Pi22``, ``Pi23`` are
surface 1's (``mu2``), Pi31 to Pi34 (:data:`TFP_SPEED`, each optional: ``None`` takes surface 1's)
the inner surfaces' (``mu1``) and the upper one's (``mu3``).  Pi18 to Pi21 (:data:`ROCKING`)
make the contents a rigid rectangular block that can rock (half-width ``b``, half-height ``h``,
``alpha = atan(b/h)``, ``R = sqrt(b^2 + h^2)``, ``p = sqrt(3 g / (4 R))``): ``Pi18 = b/h``, ``Pi19 = p
T_p``, ``Pi20 = e`` the restitution of its angular velocity at impact and ``Pi21 = a_p/(g tan
alpha)``; each is optional (``None``: contents that only slide, the paper's model).

Scene validation, dataset attributes, figure labels, the similarity check's
definitions, study dimension names and the command-line help are all derived
from :data:`GROUPS`; adding a group here adds it everywhere.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .model.validation import check_range, range_text


@dataclass(frozen=True)
class Group:
    r"""One dimensionless group.

    Attributes
    ----------
    name : str
        Identifier (``"pi2"``); the keyword of :class:`isoslide.Scene` and the
        dataset dimension name.
    definition : str
        Plain-text definition in physical parameters (``"mu_k g / a_p"``).
    meaning : str
        Short meaning (``"kinetic friction strength"``).
    tex : str
        TeX symbol without dollars (``r"\Pi_2"``).
    tex_definition : str
        TeX definition without dollars (``r"\mu_k g / a_p"``).
    unicode : str
        Plain Unicode symbol (``"Π₂"``).
    lo, hi : float
        Bounds of the valid range.
    lo_in, hi_in : bool
        Whether the bounds are included.
    default : float or None
        Value a :class:`isoslide.Scene` takes when the group is not given;
        ``None`` when the group must be given.
    comment : str
        Longer note for dataset attributes.
    paper_definition : str
        The definition as the paper prints it (Eq. 5) when it differs.
    units : str
        CF units string; ``"1"`` for every dimensionless group.
    """

    name: str
    definition: str
    meaning: str
    tex: str
    tex_definition: str
    unicode: str
    lo: float = 0.0
    hi: float = math.inf
    lo_in: bool = True
    hi_in: bool = True
    default: float | None = None
    comment: str = ""
    paper_definition: str = ""
    units: str = "1"

    @property
    def label(self) -> str:
        r"""Axis label in TeX (with dollars): ``$\Pi_2 = \mu_k g / a_p$``."""
        return f"${self.tex} = {self.tex_definition}$"

    @property
    def long_name(self) -> str:
        """CF ``long_name``: ``"Pi2 = mu_k g / a_p: kinetic friction strength"``."""
        return f"{self.name.capitalize()} = {self.definition}: {self.meaning}"

    @property
    def range_text(self) -> str:
        """The valid range as text, e.g. ``0 < value <= 1``."""
        return range_text(self.lo, self.hi, self.lo_in, self.hi_in)

    @property
    def printed(self) -> str:
        """The definition as the paper prints it."""
        return self.paper_definition or self.definition

    def check(self, value) -> float:
        """``float(value)`` or ``ValueError`` naming the group, the value and the range."""
        return check_range(self.name, value, self.lo, self.hi, self.lo_in, self.hi_in)

    def attrs(self) -> dict:
        """CF attributes of a variable or coordinate holding this group."""
        out = {"long_name": self.long_name, "units": self.units}
        if self.comment:
            out["comment"] = self.comment
        return out


RESULT = Group(
    "pi1", "u_max / (a_p T_p^2)",
    "peak sliding displacement of the contents relative to the floor",
    r"\Pi_1", r"u_{max}\,/\,(a_p T_p^2)", "Π₁",
    comment="peak |u_s| over the whole response, in units of the pulse length scale a_p T_p^2")
"""The result group Pi1."""

INPUTS = (
    Group("pi2", "mu_k g / a_p", "kinetic friction strength", r"\Pi_2", r"\mu_k g\,/\,a_p", "Π₂",
          lo_in=False, hi_in=False,
          comment="kinetic friction coefficient times g over the pulse acceleration amplitude; "
                  "the abscissa of the master curves"),
    Group("pi3", "T_b / T_p", "isolation-to-pulse period ratio", r"\Pi_3", r"T_b/T_p", "Π₃",
          hi=1e4, comment="T_b = 2 pi sqrt(M_b / k_b) with the isolated mass M_b alone; 0 = fixed base"),
    Group("pi4", "xi_b", "isolation damping ratio", r"\Pi_4", r"\xi_b", "Π₄",
          hi=1e3, default=0.0, comment="xi_b = c_b / (2 sqrt(k_b M_b)); >= 1 is over-damped"),
    Group("pi5", "mu_k / mu_s", "kinetic-to-static friction ratio", r"\Pi_5", r"\mu_k/\mu_s", "Π₅",
          lo_in=False, hi=1.0, default=1.0, comment="1 = Coulomb friction"),
    Group("pi6", "beta a_p T_p", "Stribeck transition sharpness", r"\Pi_6", r"\beta a_p T_p", "Π₆",
          hi=1e12, default=0.0,
          comment="beta (s/m) sets the speed of the static-to-kinetic transition in mu(v); "
                  "0 = friction mu_s at every speed"),
    Group("pi7", "gamma g T_p", "viscous contact group", r"\Pi_7", r"\gamma g T_p", "Π₇",
          hi=1e6, default=0.0, paper_definition="gamma a_p T_p",
          comment="the paper prints gamma a_p T_p, which is a similarity group only when a_p = g; "
                  "see isoslide.scene"),
    Group("pi8", "m_EC / M_b", "contents-to-isolated mass ratio", r"\Pi_8", r"m_{EC}/M_b", "Π₈",
          hi=1e3, default=1e-5, comment="mass of the sliding contents over the isolated mass"),
    Group("pi9", "Q / (M_b a_p)", "isolator strength", r"\Pi_9", r"Q\,/\,(M_b a_p)", "Π₉",
          hi=1e6, default=0.0,
          comment="characteristic strength Q of a hysteretic isolator (bilinear bearing: yield force of "
                  "its elastic-perfectly-plastic part; sliding bearing: friction force mu_b M_b g) over "
                  "M_b a_p; 0 = the paper's linear isolator"),
    Group("pi10", "D_y / (a_p T_p^2)", "isolator yield displacement", r"\Pi_{10}", r"D_y\,/\,(a_p T_p^2)",
          "Π₁₀", hi=1e6, default=0.0,
          comment="yield displacement of the bilinear bearing's elastic-perfectly-plastic part "
                  "(initial stiffness k_d + Q/D_y); 0 with Pi9 > 0 = a sliding bearing with true stick"),
    Group("pi11", "m_st / M_b", "superstructure mass fraction", r"\Pi_{11}", r"m_{st}/M_b", "Π₁₁",
          hi=1.0, hi_in=False, default=0.0,
          comment="superstructure mass over the whole isolated mass M_b = m_b + m_st; read only when "
                  "Pi12 > 0, where 0 < Pi11 < 1"),
    Group("pi12", "T_s / T_p", "superstructure-to-pulse period ratio", r"\Pi_{12}", r"T_s/T_p", "Π₁₂",
          hi=1e4, default=0.0,
          comment="T_s = 2 pi sqrt(m_st / k_s), the fixed-base period of the superstructure on the slab; "
                  "0 = rigid superstructure (the paper's Fig. 1-b)"),
    Group("pi13", "xi_s", "superstructure damping ratio", r"\Pi_{13}", r"\xi_s", "Π₁₃",
          hi=1e3, default=0.0, comment="xi_s = c_s / (2 sqrt(k_s m_st))"),
    Group("pi14", "a_py / a_p", "transverse-to-main pulse amplitude ratio", r"\Pi_{14}", r"a_{py}/a_p", "Π₁₄",
          hi=1e3, default=1.0,
          comment="amplitude of the second horizontal ground acceleration a_gy = Pi14 a_p p_y((t - t_y)/T_py) "
                  "over the main one's; read only with a pulse_y (no pulse_y: no y motion)"),
    Group("pi15", "T_py / T_p", "transverse-to-main pulse period ratio", r"\Pi_{15}", r"T_{py}/T_p", "Π₁₅",
          lo_in=False, hi=1e4, default=1.0,
          comment="period of the second horizontal pulse over the main one's; read only with a pulse_y"),
    Group("pi16", "t_y / T_p", "transverse pulse time shift", r"\Pi_{16}", r"t_y/T_p", "Π₁₆",
          lo=-1e4, hi=1e4, default=0.0,
          comment="time by which the second horizontal pulse lags the main one, over T_p; read only with "
                  "a pulse_y"),
    Group("pi17", "a_pz / g", "vertical ground acceleration over gravity", r"\Pi_{17}", r"a_{pz}/g", "Π₁₇",
          hi=1e3, default=0.0,
          comment="amplitude of the vertical ground acceleration a_gz = Pi17 g p_z(t/T_p) over g; it acts "
                  "through the normal forces (contents, sliding bearing): N = m (g + a_gz); 0 = no vertical "
                  "motion"),
    Group("pi22", "mu_slow / mu_fast", "bearing breakaway-to-fast friction ratio", r"\Pi_{22}",
          r"\mu_{slow}/\mu_{fast}", "Π₂₂", lo_in=False, hi=1.0, default=1.0,
          comment="a sliding bearing's friction coefficient at breakaway (zero speed) over its value at high "
                  "speed, mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|), with Pi9 = mu_fast g / a_p; the "
                  "bearing sticks while the force that holds it is within mu_slow N; 1 = constant friction; "
                  "read only with a sliding bearing (Pi9 > 0, Pi10 = 0)"),
    Group("pi23", "a a_p T_p", "bearing friction rate group", r"\Pi_{23}", r"a\,a_p T_p", "Π₂₃",
          hi=1e12, default=0.0,
          comment="rate a (s/m) of the sliding bearing's friction law mu(v) = mu_fast - (mu_fast - mu_slow) "
                  "exp(-a |v|) times the pulse's velocity scale a_p T_p; 0 = mu_slow at every speed (constant "
                  "friction Pi9 Pi22); read only with a sliding bearing (Pi9 > 0, Pi10 = 0)"),
    Group("pi24", "L1 / (L2 + L3)", "inner radius ratio of a triple pendulum", r"\Pi_{24}", r"L_1/(L_2 + L_3)",
          "Π₂₄", hi=1e3, default=0.0,
          comment="effective radius of each inner surface of a triple friction pendulum over the sum of the outer "
                  "ones' (Pi3 = 2 pi sqrt((L2 + L3)/g)/T_p); 0 = a single friction pendulum; read only with a "
                  "sliding bearing (Pi9 > 0, Pi10 = 0)"),
    Group("pi25", "L2 / (L2 + L3)", "lower radius share of a triple pendulum", r"\Pi_{25}", r"L_2/(L_2 + L_3)",
          "Π₂₅", lo_in=False, hi=1.0, hi_in=False, default=0.5,
          comment="share of the lower outer surface (surface 1) in L2 + L3; read only with Pi24 > 0"),
    Group("pi26", "mu1 / mu2", "inner friction ratio of a triple pendulum", r"\Pi_{26}", r"\mu_1/\mu_2", "Π₂₆",
          lo_in=False, hi=1.0, default=1.0,
          comment="friction coefficient of the inner surfaces over the lower outer surface's (Pi9 = mu2 g/a_p); "
                  "read only with Pi24 > 0"),
    Group("pi27", "mu3 / mu2", "upper friction ratio of a triple pendulum", r"\Pi_{27}", r"\mu_3/\mu_2", "Π₂₇",
          lo=1.0, hi=1e3, default=1.0,
          comment="friction coefficient of the upper outer surface (surface 4) over the lower one's; read only "
                  "with Pi24 > 0"),
    Group("pi28", "d1 / (a_p T_p^2)", "inner limit of a triple pendulum", r"\Pi_{28}", r"d_1/(a_p T_p^2)", "Π₂₈",
          hi=1e6, default=0.0,
          comment="displacement limit of each inner surface (OpenSees's d1) over the pulse length scale; > 0 "
                  "with Pi24 > 0"),
    Group("pi29", "d2 / (a_p T_p^2)", "lower outer limit of a triple pendulum", r"\Pi_{29}", r"d_2/(a_p T_p^2)",
          "Π₂₉", hi=1e6, default=0.0,
          comment="displacement limit of the lower outer surface (OpenSees's d2); > 0 with Pi24 > 0"),
    Group("pi30", "d3 / (a_p T_p^2)", "upper outer limit of a triple pendulum", r"\Pi_{30}", r"d_3/(a_p T_p^2)",
          "Π₃₀", hi=1e6, default=0.0,
          comment="displacement limit of the upper outer surface (OpenSees's d3); > 0 with Pi24 > 0"),
)
"""The input groups, in the order of :class:`isoslide.Scene`'s arguments."""

ROCKING = (
    Group("pi18", "b / h", "aspect ratio of a rocking block", r"\Pi_{18}", r"b/h", "Π₁₈",
          lo_in=False, hi=1e3,
          comment="half-width over half-height of the contents as a rigid rectangular block, tan(alpha); the "
                  "block rocks about a bottom corner once the floor tips it; absent (None) = contents that "
                  "only slide"),
    Group("pi19", "p T_p", "block frequency parameter over the pulse", r"\Pi_{19}", r"p\,T_p", "Π₁₉",
          lo_in=False, hi=1e6,
          comment="p = sqrt(3 g / (4 R)) (rad/s), R = sqrt(b^2 + h^2) the corner-to-centre distance, times T_p; "
                  "given with Pi18"),
    Group("pi20", "e", "restitution of a rocking block at impact", r"\Pi_{20}", r"e", "Π₂₀",
          lo_in=False, hi=1.0,
          comment="ratio of the angular velocity after an impact to before it; absent (None) = Housner's "
                  "1 - 3/2 sin^2(alpha); allowed 0 < Pi20 <= that value; read only with Pi18"),
    Group("pi21", "a_p / (g tan alpha)", "pulse amplitude over the uplift acceleration", r"\Pi_{21}",
          r"a_p/(g \tan\alpha)", "Π₂₁", lo_in=False, hi=1e6,
          comment="the rocking literature's intensity group; with it g / a_p = 1/(Pi18 Pi21) and mu_s / tan(alpha) "
                  "= Pi2 Pi21 / Pi5; given with Pi18"),
)
"""The rocking block's groups, each optional (``None``: contents that only slide)."""

ROCKING_NAMES = tuple(g.name for g in ROCKING)
"""Names of the rocking block's groups (``("pi18", ..., "pi21")``)."""

TFP_SPEED = (
    Group("pi31", "mu_slow1 / mu1", "inner breakaway-to-fast friction ratio", r"\Pi_{31}", r"\mu_{slow,1}/\mu_1",
          "Π₃₁", lo_in=False, hi=1.0, hi_in=False,
          comment="breakaway friction of the inner surfaces of a triple friction pendulum over their fast value "
                  "(mu1 = Pi26 Pi9 a_p/g), their law mu(v) = mu1 - (mu1 - mu_slow1) exp(-a1 |v|) of their own sliding "
                  "speed; absent (None) = Pi22; read only with a triple pendulum whose friction rises with speed "
                  "(Pi24 > 0, Pi22 < 1, Pi23 > 0)"),
    Group("pi32", "mu_slow3 / mu3", "upper breakaway-to-fast friction ratio", r"\Pi_{32}", r"\mu_{slow,3}/\mu_3",
          "Π₃₂", lo_in=False, hi=1.0, hi_in=False,
          comment="breakaway friction of the upper outer surface (surface 4) of a triple friction pendulum over its "
                  "fast value; absent (None) = Pi22; read only as Pi31"),
    Group("pi33", "a1 a_p T_p", "inner friction rate group", r"\Pi_{33}", r"a_1\,a_p T_p", "Π₃₃",
          lo_in=False, hi=1e12,
          comment="rate a1 (s/m) of the inner surfaces' friction law times the pulse's velocity scale a_p T_p; "
                  "absent (None) = Pi23; read only as Pi31"),
    Group("pi34", "a3 a_p T_p", "upper friction rate group", r"\Pi_{34}", r"a_3\,a_p T_p", "Π₃₄",
          lo_in=False, hi=1e12,
          comment="rate a3 (s/m) of the upper outer surface's friction law times a_p T_p; absent (None) = Pi23; "
                  "read only as Pi31"),
)
"""The groups of a triple pendulum's inner and upper surfaces whose friction rises with speed, each
optional (``None``: surface 1's ``Pi22`` or ``Pi23``)."""

TFP_SPEED_NAMES = tuple(g.name for g in TFP_SPEED)
"""Names of those groups (``("pi31", ..., "pi34")``)."""

GROUPS = {g.name: g for g in (RESULT, *INPUTS, *ROCKING, *TFP_SPEED)}
"""Every group by name, the result first."""

INPUT_NAMES = tuple(g.name for g in INPUTS)
"""Names of the input groups, in order (``("pi2", ..., "pi13")``)."""

PAPER_NAMES = INPUT_NAMES[:7]
"""The paper's input groups ``("pi2", ..., "pi8")``: the model of its Fig. 1-b."""

BUILDING_NAMES = INPUT_NAMES[7:12]
"""The general building's groups ``("pi9", ..., "pi13")``: zero in the paper's model."""

EXCITATION_NAMES = ("pi14", "pi15", "pi16", "pi17")
"""The groups of the excitation beyond the main horizontal pulse (``("pi14", ..., "pi17")``): at their
defaults in the paper's model (without a ``pulse_y`` and a ``pulse_z`` they have no effect)."""

TFP_NAMES = ("pi24", "pi25", "pi26", "pi27", "pi28", "pi29", "pi30")
"""The triple friction pendulum's groups (``Pi24`` .. ``Pi30``): at their defaults (a single friction
pendulum) in the paper's model and read only with a sliding bearing."""

BEARING_FRICTION_NAMES = ("pi22", "pi23")
"""The sliding bearing's speed-dependent friction (``Pi22``, ``Pi23``): at their defaults (constant
friction) in the paper's model and read only with a sliding bearing."""


def group(name: str) -> Group:
    """The group called ``name``; ``KeyError`` naming the known groups otherwise."""
    try:
        return GROUPS[name]
    except KeyError:
        raise KeyError(f"unknown Pi-group {name!r}; known: {list(GROUPS)}") from None


def defaults() -> dict:
    """Default value of every input group that has one (``{"pi4": 0.0, ...}``)."""
    return {g.name: g.default for g in INPUTS if g.default is not None}

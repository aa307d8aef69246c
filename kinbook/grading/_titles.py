"""Titles of the constraint classes that do not carry their own ``title`` yet (until the registry gives
every class one): looked up by class, never by type name."""

from __future__ import annotations

__all__ = ["title_of"]

_TITLES = None


def _table():
    from .. import planar as P
    from .. import spatial as S

    return {
        P.Revolute: ("revolute joint", "par de revolución"),
        P.Translational: ("translational joint", "par de traslación"),
        P.RevoluteRevolute: ("revolute-revolute joint", "par revolución-revolución"),
        P.RevoluteTranslational: ("revolute-translational joint", "par revolución-traslación"),
        P.Gear: ("gear pair", "engranaje"),
        P.RackPinion: ("rack-and-pinion", "piñón-cremallera"),
        P.Driver: ("driver", "restricción motriz"),
        P.RelativeAngleDriver: ("relative-angle driver", "restricción motriz de ángulo relativo"),
        P.DistanceDriver: ("distance driver", "restricción motriz de distancia"),
        P.Ground: ("simple constraints of the fixed body", "restricciones simples del elemento fijo"),
        P.Simple: ("simple constraint", "restricción simple"),
        S.Normalization: ("Euler-parameter normalization", "normalización de los parámetros de Euler"),
        S.Ground: ("ground constraints", "restricciones del elemento fijo"),
        S.Spherical: ("spherical joint", "par esférico"),
        S.Universal: ("universal joint", "junta universal"),
        S.Revolute: ("revolute joint", "par de revolución"),
        S.Cylindrical: ("cylindrical joint", "par cilíndrico"),
        S.Translational: ("translational joint", "par de traslación"),
        S.SphericalSpherical: ("spherical-spherical joint", "par esférico-esférico"),
        S.Normal1: ("normal-1 constraint", "restricción normal-1"),
        S.Normal2: ("normal-2 constraint", "restricción normal-2"),
        S.Parallel1: ("parallel-1 constraint", "restricción paralela-1"),
        S.Parallel2: ("parallel-2 constraint", "restricción paralela-2"),
        S.RevoluteDriver: ("revolute driver", "restricción motriz de rotación"),
        S.DistanceDriver: ("distance driver", "restricción motriz de distancia"),
    }


def title_of(c, lang):
    """The title of constraint ``c``'s class in ``lang``; its type name for an unknown class."""
    global _TITLES
    if _TITLES is None:
        _TITLES = _table()
    for cls in type(c).__mro__:
        if cls in _TITLES:
            en, es = _TITLES[cls]
            return es if lang == "es" else en
    return str(getattr(c, "type_name", type(c).__name__))

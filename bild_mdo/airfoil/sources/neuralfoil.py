"""Make airfoil polars with NeuralFoil, a neural-network emulator of XFOIL.

NeuralFoil (``pip install bild-mdo[neuralfoil]``) is an optional alternative
to running XFOIL: it needs no system programs, ships its network weights in
the package (no download at run time) and always returns a value, so no point
is dropped.  It is an approximation of XFOIL (incompressible, Mach 0).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.airfoil.sources.coordinates import parse_airfoil, read_coordinates
from bild_mdo.airfoil.sources.polar_data import PolarData

__all__ = ["MODEL_SIZES", "run_neuralfoil"]

#: NeuralFoil network sizes, smallest (fastest) to largest (most accurate).
MODEL_SIZES = ("xxsmall", "xsmall", "small", "medium", "large", "xlarge", "xxlarge", "xxxlarge")


def _import_neuralfoil():
    try:
        import aerosandbox
        import neuralfoil
    except ImportError as exc:
        raise ImportError(
            "run_neuralfoil needs the optional package 'neuralfoil' (it brings 'aerosandbox'); "
            "install it with: pip install bild-mdo[neuralfoil]") from exc
    return neuralfoil, aerosandbox


def run_neuralfoil(airfoil, reynolds_list, alpha_deg, model_size="large", ncrit=9.0):
    """Compute polars with NeuralFoil at several Reynolds numbers.

    Parameters
    ----------
    airfoil : str or os.PathLike
        NACA 4-digit designation (``"NACA 4412"``, ``"naca4412"``, ``"4412"``)
        or the path of a Selig-format coordinates file.
    reynolds_list : sequence of float
        Chord Reynolds numbers (> 0).
    alpha_deg : array_like
        Angles of attack (deg); sorted, duplicates removed.
    model_size : str
        One of :data:`MODEL_SIZES`.
    ncrit : float
        e^N transition amplification factor, as in XFOIL.

    Returns
    -------
    list of PolarData
        One per Reynolds number, in the order of ``reynolds_list``, Mach 0.

    Raises
    ------
    ImportError
        NeuralFoil is not installed (the message gives the pip command).
    ValueError
        Invalid airfoil, Reynolds numbers, angles or model size.
    """
    if model_size not in MODEL_SIZES:
        raise ValueError(f"model_size must be one of {', '.join(MODEL_SIZES)}; got {model_size!r}")
    kind, spec = parse_airfoil(airfoil)
    reynolds = np.atleast_1d(np.asarray(reynolds_list, dtype=float))
    if reynolds.ndim != 1 or reynolds.size == 0 or not np.all(np.isfinite(reynolds) & (reynolds > 0.0)):
        raise ValueError(f"reynolds_list must hold finite Reynolds numbers > 0, got {reynolds_list!r}")
    alpha = np.unique(np.asarray(alpha_deg, dtype=float).ravel())
    if alpha.size == 0 or not np.all(np.isfinite(alpha)) or np.abs(alpha).max() > 90.0:
        raise ValueError("alpha_deg must be a non-empty set of finite angles in degrees within [-90, 90]")
    if not (np.isfinite(ncrit) and ncrit > 0.0):
        raise ValueError(f"ncrit must be > 0, got {ncrit!r}")
    nf, asb = _import_neuralfoil()

    if kind == "naca":
        label = f"NACA {spec}"
        section = asb.Airfoil(name=f"naca{spec}")
    else:
        name, xy = read_coordinates(spec)
        label = name or spec.stem
        section = asb.Airfoil(name=label, coordinates=xy)

    polars = []
    for r in reynolds:
        out = nf.get_aero_from_airfoil(section, alpha=alpha, Re=float(r), n_crit=float(ncrit),
                                       model_size=model_size)
        confidence = float(np.min(out["analysis_confidence"]))
        polars.append(PolarData(
            reynolds=float(r), mach=0.0, alpha_deg=alpha,
            cl=np.broadcast_to(np.asarray(out["CL"], dtype=float), alpha.shape),
            cd=np.broadcast_to(np.asarray(out["CD"], dtype=float), alpha.shape),
            ncrit=float(ncrit),
            source=f"NeuralFoil {nf.__version__} ({model_size}) {label} Re={r:g} Ncrit={ncrit:g} "
                   f"min confidence {confidence:.2f}"))
    return polars

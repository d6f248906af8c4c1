"""Random BEM analyses across flow states: exceptions, NaNs and unphysical metrics that no warning names.

Run: ``.venv/bin/python benchmarks/bem_robustness.py [--count 20000] [--seed 9] [--batch 1000]``.

Blade family (seeded): tip radius 0.3-1.5 m, hub 10-25 % of it, B = 2-5, linear chord 3-15 % of
R at root and tip, linear twist root U(0, 45) deg and tip U(-15, 20) deg, rpm 1000-6000;
a third hover (V_x = 0), a third V_x U(2, 40) m/s, a third V_x U(40, 120) m/s (windmill and
turbulent-wake states), NACA 4412 surrogate, 20 stations, altitude 0-3000 m.  Analysed in
batches with ``analyze_rotor(..., on_invalid='warn')``.

Counted per rotor:
* exceptions (per batch: a batch that raises counts all its rotors);
* any NaN or inf in any result field;
* ``FM > 1`` (hover) or ``eta > 1`` (forward), where ``T > 0`` and ``P > 0``, in a rotor that has no
  station flagged invalid (flow_state in INVALID_STATES), or whose batch issued no
  BEMStateWarning: "reported without a warning naming the stations".  The acceptance is 0 for all.
Also printed: the flow states met, rotors with a flagged station, and the same metrics with the
formula's value taken at face value (T or P <= 0), which tables print as "n/a".
"""
from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

from bild_mdo.airfoil import get_polar
from bild_mdo.bem import analyze_rotor
from bild_mdo.bem.flow_states import FLOW_STATE_NAMES, INVALID_STATES, BEMStateWarning


def random_rotors(count, seed, num_radial=20):
    """Seeded random rotors (see the module docstring)."""
    rng = np.random.default_rng(seed)
    x = (np.arange(num_radial) + 0.5) / num_radial
    radius = rng.uniform(0.3, 1.5, count)
    hub = radius * rng.uniform(0.10, 0.25, count)
    chord = radius[:, None] * (rng.uniform(0.03, 0.15, (count, 1)) * (1 - x) + rng.uniform(0.03, 0.15, (count, 1)) * x)
    twist = np.radians(rng.uniform(0, 45, (count, 1)) * (1 - x) + rng.uniform(-15, 20, (count, 1)) * x)
    kind = rng.integers(0, 3, count)
    v_axial = np.where(kind == 0, 0.0, np.where(kind == 1, rng.uniform(2, 40, count), rng.uniform(40, 120, count)))
    return dict(chord=chord, twist=twist, radius=radius, hub_radius=hub, rpm=rng.uniform(1000, 6000, count),
                v_axial=v_axial, num_blades=rng.integers(2, 6, count), altitude=rng.uniform(0, 3000, count))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=20_000)
    parser.add_argument("--seed", type=int, default=9)
    parser.add_argument("--batch", type=int, default=1000)
    args = parser.parse_args(argv)
    polar = get_polar("naca4412")
    rotors = random_rotors(args.count, args.seed)
    totals = dict(exceptions=0, nan=0, unflagged_fm=0, unflagged_eta=0, flagged_rotors=0, warned_batches=0,
                  fm_gt_1=0, eta_gt_1=0, raw_eta_gt_1=0, raw_fm_negative=0, t_pos_p_nonpos=0)
    states = np.zeros(6, dtype=int)
    start = time.perf_counter()
    for lo in range(0, args.count, args.batch):
        for blades in np.unique(rotors["num_blades"]):
            sel = np.flatnonzero(rotors["num_blades"][lo:lo + args.batch] == blades) + lo
            if sel.size == 0:
                continue
            kw = {k: v[sel] for k, v in rotors.items() if k != "num_blades"}
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("ignore", UserWarning)   # the polar's Reynolds-clamp note
                warnings.simplefilter("always", BEMStateWarning)   # (filters added later match first)
                try:
                    res = analyze_rotor(num_blades=int(blades), polar=polar, **kw)
                except Exception as err:  # noqa: BLE001 -- counted, the acceptance is zero
                    totals["exceptions"] += sel.size
                    print(f"exception in batch at {lo} (B = {blades}): {type(err).__name__}: {err}")
                    continue
            warned = [w for w in caught if issubclass(w.category, BEMStateWarning)]
            totals["warned_batches"] += bool(warned)
            fields = res.to_dict()
            totals["nan"] += int(np.count_nonzero(~np.all(
                np.stack([np.all(np.isfinite(np.reshape(v, (sel.size, -1))), axis=1) for v in fields.values()]),
                axis=0)))
            st = res.flow_state
            states += np.bincount(st.ravel(), minlength=6)
            flagged = np.isin(st, INVALID_STATES).any(axis=1)
            totals["flagged_rotors"] += int(flagged.sum())
            hover = kw["v_axial"] == 0.0
            ok = (res.thrust > 0) & (res.power > 0)
            fm_bad = ok & hover & (res.figure_of_merit > 1.0)
            eta_bad = ok & ~hover & (res.efficiency > 1.0)
            named = flagged & bool(warned)
            totals["fm_gt_1"] += int(fm_bad.sum())
            totals["eta_gt_1"] += int(eta_bad.sum())
            totals["unflagged_fm"] += int((fm_bad & ~named).sum())
            totals["unflagged_eta"] += int((eta_bad & ~named).sum())
            totals["raw_eta_gt_1"] += int((~hover & (res.efficiency > 1.0)).sum())
            totals["raw_fm_negative"] += int((hover & (res.figure_of_merit < 0.0)).sum())
            totals["t_pos_p_nonpos"] += int(((res.thrust > 0) & (res.power <= 0)).sum())
    elapsed = time.perf_counter() - start
    print(f"{args.count} random BEM analyses (seed {args.seed}, batches of {args.batch}) in {elapsed:.1f} s")
    print(f"  exceptions: {totals['exceptions']}")
    print(f"  rotors with a NaN/inf in any result field: {totals['nan']}")
    print(f"  FM > 1 (hover, T > 0, P > 0) without a warning naming the stations: {totals['unflagged_fm']}"
          f" (FM > 1 in all: {totals['fm_gt_1']})")
    print(f"  eta > 1 (forward, T > 0, P > 0) without a warning naming the stations: {totals['unflagged_eta']}"
          f" (eta > 1 in all: {totals['eta_gt_1']})")
    print(f"  T > 0 with P <= 0: {totals['t_pos_p_nonpos']}")
    print(f"  formula values where T or P <= 0 (tables print n/a): V T / P > 1 in {totals['raw_eta_gt_1']} "
          f"forward rotors, FM < 0 in {totals['raw_fm_negative']} hover rotors")
    print(f"  rotors with a flagged station: {totals['flagged_rotors']}; batches that warned: "
          f"{totals['warned_batches']}")
    print("  stations per flow state: " + ", ".join(f"{FLOW_STATE_NAMES[k]} {states[k]}" for k in range(6)))
    return 0 if (totals["exceptions"] + totals["nan"] + totals["unflagged_fm"] + totals["unflagged_eta"]) == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())

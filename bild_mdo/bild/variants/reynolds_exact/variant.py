"""ReynoldsExactVariant: the Reynolds-aware exact ideal loading (exact loading with the local section point)."""
from bild_mdo.bild.variants.local_point.variant import LocalPointVariant
from bild_mdo.bild.variants.reynolds_exact.chord_at_reference import ChordAtReferenceComp
from bild_mdo.bild.variants.reynolds_exact.station import ReynoldsStationComp


class ReynoldsExactVariant(LocalPointVariant):
    """Each annulus minimises ``F (e - lambda t)`` with its section point following its own load
    (:class:`~bild_mdo.bild.variants.reynolds_exact.station.ReynoldsStationComp`); lambda is that of the reference
    annulus, given by the reference component.

    With ``thrust_target=True`` lambda itself is solved for the thrust: the stations need nothing else of the
    reference station, whose chord names the design only piecewise (the thrust jumps where the reference
    station changes branch).  There is then no reference component; ``ref_chord`` and ``reynolds_ref`` are the
    design's at ``r_ref`` (:class:`~bild_mdo.bild.variants.reynolds_exact.chord_at_reference.ChordAtReferenceComp`).
    """

    ideal_loading = "exact"
    station_comp = ReynoldsStationComp

    @property
    def _solves_lambda(self):
        return self.wiring.group.options["thrust_target"]

    @property
    def thrust_target_state(self):
        return "ideal_loading_constant" if self._solves_lambda else "ref_chord"

    def add_reference(self):
        if not self._solves_lambda:
            super().add_reference()

    def add_loading(self):
        """lambda comes with the reference state (``LocalReferenceComp(ideal_loading='exact')``), or from the
        thrust-target balance."""

    def add(self):
        super().add()
        if self._solves_lambda:
            self.wiring.group.add_subsystem(
                "chord_at_reference", ChordAtReferenceComp(**self.wiring.size),
                promotes_inputs=["chord_raw", "radii", "ref_radius", "v_axial", "v_theta_ref", "rho", "mu"],
                promotes_outputs=["ref_chord", "reynolds_ref"])

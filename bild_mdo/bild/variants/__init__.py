"""The BILD family: one interface (:class:`~bild_mdo.bild.variants.base.BILDVariant`), four members.

=====================  =================  ===================================================
member                 ideal_loading      section_point
=====================  =================  ===================================================
PaperVariant           ``'paper'``        ``'reference'`` (the paper, Algorithm 1)
ExactVariant           ``'exact'``        ``'reference'``
LocalPaperVariant      ``'paper'``        ``'local'``
ReynoldsExactVariant   ``'exact'``        ``'local'`` (the Reynolds-aware exact loading)
=====================  =================  ===================================================

Each member lives in its own folder; ``reference_point/`` and ``local_point/``
hold what the members of one section point share.
"""
from bild_mdo.bild.variants.exact.variant import ExactVariant
from bild_mdo.bild.variants.local_paper.variant import LocalPaperVariant
from bild_mdo.bild.variants.paper.variant import PaperVariant
from bild_mdo.bild.variants.reynolds_exact.variant import ReynoldsExactVariant

#: The section points of BILDGroup's option ``section_point``.
SECTION_POINTS = ("reference", "local")
#: The members by ``(ideal_loading, section_point)``.
VARIANTS = {(v.ideal_loading, v.section_point): v
            for v in (PaperVariant, ExactVariant, LocalPaperVariant, ReynoldsExactVariant)}

__all__ = ["SECTION_POINTS", "VARIANTS", "ExactVariant", "LocalPaperVariant", "PaperVariant", "ReynoldsExactVariant"]

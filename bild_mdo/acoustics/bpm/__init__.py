"""BPM airfoil self-noise (Brooks, Pope & Marcolini, NASA RP-1218, 1989): one module per ingredient.

Pure, vectorised, complex-safe functions of a blade segment that also accept
:class:`~bild_mdo.utils.jet.Jet` values (exact first partials): boundary layer, directivity, TBL-TE and
separation, LBL-VS, tip vortex, trailing-edge bluntness, and :func:`segment_spectra` that combines the
first four for one segment.
"""
from bild_mdo.acoustics.bpm.bluntness import (NACA0012_TRAILING_EDGE_ANGLE, bluntness_pressure_squared,
                                              peak_strouhal_3, shape_g4, shape_g5, shape_g5_psi14)
from bild_mdo.acoustics.bpm.boundary_layer import (BoundaryLayer, boundary_layer, pressure_side_ratios,
                                                   suction_side_ratios, zero_angle_thickness)
from bild_mdo.acoustics.bpm.directivity import (high_frequency_directivity, high_frequency_directivity_from_cosines,
                                                low_frequency_directivity, low_frequency_directivity_from_cosines,
                                                moving_source_directivities)
from bild_mdo.acoustics.bpm.laminar_vortex_shedding import (lbl_vs_pressure_squared, peak_strouhal,
                                                            reference_reynolds, reference_strouhal, shape_g1,
                                                            shape_g2, shape_g3)
from bild_mdo.acoustics.bpm.segment import SEGMENT_SOURCES, segment_spectra
from bild_mdo.acoustics.bpm.tip_vortex import (TIP_ALPHA_CORRECTION, TIP_SHAPES, tip_extent_ratio,
                                               tip_vortex_pressure_squared)
from bild_mdo.acoustics.bpm.turbulent_trailing_edge import (amplitude_delta_k1, amplitude_k1, amplitude_k2,
                                                            amplitude_k2_minus_k1, peak_strouhal_1, peak_strouhal_2,
                                                            shape_a_max, shape_a_min, shape_b_max, shape_b_min,
                                                            spectral_shape_a, spectral_shape_b, stall_angle_deg,
                                                            tbl_te_pressure_squared)

__all__ = ["NACA0012_TRAILING_EDGE_ANGLE", "bluntness_pressure_squared", "peak_strouhal_3", "shape_g4", "shape_g5",
           "shape_g5_psi14", "BoundaryLayer", "boundary_layer", "pressure_side_ratios", "suction_side_ratios",
           "zero_angle_thickness",
           "high_frequency_directivity", "high_frequency_directivity_from_cosines", "low_frequency_directivity",
           "low_frequency_directivity_from_cosines", "moving_source_directivities", "lbl_vs_pressure_squared",
           "peak_strouhal", "reference_reynolds", "reference_strouhal", "shape_g1", "shape_g2", "shape_g3",
           "SEGMENT_SOURCES", "segment_spectra",
           "TIP_ALPHA_CORRECTION", "TIP_SHAPES", "tip_extent_ratio", "tip_vortex_pressure_squared",
           "amplitude_delta_k1", "amplitude_k1", "amplitude_k2", "amplitude_k2_minus_k1", "peak_strouhal_1",
           "peak_strouhal_2", "shape_a_max", "shape_a_min", "shape_b_max", "shape_b_min", "spectral_shape_a",
           "spectral_shape_b", "stall_angle_deg", "tbl_te_pressure_squared"]

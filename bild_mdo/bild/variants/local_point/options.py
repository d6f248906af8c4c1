"""What the station components of the two local-section-point variants share: options, failures, placeholders."""

from bild_mdo.airfoil.load_path_table import REYNOLDS_SPAN
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.bild.feasibility import declare_feasibility_option
from bild_mdo.utils.options import declare_size_options

#: Placeholder section point of a station without one (unloaded, or outside the table): finite, and the chord
#: is zero there anyway (no load).
PLACEHOLDER = {"alpha_star": 0.1, "cl_star": 1.0, "cd_star": 0.02}
#: Outputs of a station without a load: eta2 = 1, zero Reynolds numbers and the section point :data:`PLACEHOLDER`.
UNLOADED_OUTPUTS = {"eta2": 1.0, "reynolds": 0.0, "load_reynolds": 0.0, **PLACEHOLDER}


def declare_local_options(options, radial=True):
    """Options of a local-point station or reference component."""
    declare_size_options(options, radial=radial)
    options.declare("num_blades", types=int, default=3, desc="number of blades B")
    options.declare("loss_model", default="tip_hub", values=LOSS_MODELS, desc="Prandtl losses")
    options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                    desc="force coefficient of the chord formula: 'thrust' (C_x) or 'torque' (C_theta)")
    options.declare("polar", recordable=False, desc="airfoil Polar (Reynolds-dependent only)")
    declare_feasibility_option(options)


def station_failures(method):
    """Station status code -> (check key, reason) of a local-point station solve named ``method``."""
    return {
        3: ("overloaded", "lambda lies beyond the station's maximum annulus thrust before eta2 = 1/2; "
                          "reduce ref_chord"),
        4: ("solve", f"{method}: an input is outside its domain or the solve did not converge"),
        5: ("reynolds", f"{method}: a station's load Reynolds number lies more than {REYNOLDS_SPAN:g} times above "
                        "the polar's highest Reynolds number (give polar data at higher Reynolds numbers)"),
        6: ("angle", f"{method}: a station's inflow angle lies beyond the polar's load-path table (85 deg from "
                     "the thrust, 2 deg from the torque); lower the advance ratio or raise hub_radius_ratio"),
    }



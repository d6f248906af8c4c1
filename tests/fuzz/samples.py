"""Good input files for the fuzz tests: one blade in every geometry format, and polar files in both formats."""
import numpy as np

from bild_mdo.io.csv import write_csv
from bild_mdo.io.json import write_json
from bild_mdo.io.qprop import write_qprop

#: A small blade (hand-made, analytic airfoil) whose files are the seeds of the garbled inputs.
BLADE = dict(radii=[0.3, 0.5, 0.7, 0.9], chord=[0.12, 0.1, 0.08, 0.06], twist=np.radians([30.0, 20.0, 15.0, 12.0]),
             radius=1.0, hub_radius=0.2, num_blades=2, airfoil="analytic",
             design_point={"rpm": 1200.0, "v_axial": 5.0, "altitude": 0.0})

XFOIL_POLAR = """\
 Calculated polar for: NACA 4412

 1 1 Reynolds number fixed          Mach number fixed

 xtrf =   1.000 (top)        1.000 (bottom)
 Mach =   0.000     Re =     0.500 e 6     Ncrit =   9.000

  alpha    CL        CD       CDp       CM     Top_Xtr  Bot_Xtr
 ------ -------- --------- --------- -------- -------- --------
  -4.000  -0.0300   0.01080   0.00420  -0.0950   0.9000   0.0500
  -2.000   0.1800   0.00950   0.00330  -0.0980   0.8000   0.1000
   0.000   0.4000   0.00900   0.00290  -0.1000   0.7000   0.2000
   2.000   0.6200   0.00920   0.00300  -0.1010   0.6000   0.4000
   4.000   0.8400   0.01000   0.00350  -0.1020   0.5000   0.6000
   6.000   1.0500   0.01150   0.00450  -0.1020   0.4000   0.8000
   8.000   1.2300   0.01400   0.00650  -0.1000   0.3000   0.9000
"""

POLAR_TABLE = """\
# reynolds = 500000
# mach = 0
alpha_deg,cl,cd
-4,-0.03,0.0108
-2,0.18,0.0095
0,0.40,0.0090
2,0.62,0.0092
4,0.84,0.0100
6,1.05,0.0115
8,1.23,0.0140
"""


def geometry_texts(folder):
    """Text of the blade written as CSV, JSON and QPROP (written once into ``folder``)."""
    return {".csv": write_csv(folder / "blade.csv", BLADE).read_text(),
            ".json": write_json(folder / "blade.json", BLADE).read_text(),
            ".prop": write_qprop(folder / "blade.prop", BLADE).read_text()}

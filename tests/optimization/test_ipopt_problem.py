"""The Ipopt problem layout: importable without cyipopt, Ipopt's status codes."""
import os
import pathlib
import subprocess
import sys

import bild_mdo
from bild_mdo.optimization.ipopt_problem import IPOPT_STATUS_NAMES, SUCCESS_STATUSES

ROOT = pathlib.Path(bild_mdo.__file__).resolve().parents[1]


def test_driver_module_imports_without_cyipopt():
    # A None entry in sys.modules makes "import cyipopt" raise ImportError: the module still imports,
    # only making a driver needs cyipopt.
    code = ("import sys; sys.modules['cyipopt'] = None\n"
            "from bild_mdo.optimization.ipopt_driver import IpoptDriver\n"
            "try:\n    IpoptDriver()\nexcept ImportError as exc:\n    print('recipe' if 'apt-get' in str(exc) else exc)\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "recipe"


def test_status_names_follow_ipopt_return_codes():
    # IpReturnCodes_inc.h: 0 solved, 1 solved to the acceptable level (both success), -1 iteration limit.
    assert SUCCESS_STATUSES == (0, 1)
    assert IPOPT_STATUS_NAMES[0] == "Solve_Succeeded" and IPOPT_STATUS_NAMES[-1] == "Maximum_Iterations_Exceeded"

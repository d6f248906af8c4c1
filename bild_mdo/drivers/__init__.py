"""OpenMDAO drivers shipped with bild-mdo.

``IpoptDriver`` runs Ipopt through cyipopt (``pip install 'bild-mdo[ipopt]'``) for
installations without pyOptSparse.  Importing this package does not need cyipopt;
constructing the driver does.
"""
from bild_mdo.drivers.ipopt_driver import IpoptDriver

__all__ = ["IpoptDriver"]

"""Unit conversions and physical constants used across bild-mdo (one definition each)."""
import numpy as np

#: Rotational speed: rad/s per rpm (Omega = rpm * pi / 30).
RPM_TO_RAD_PER_S = np.pi / 30.0
#: Rotational speed: rev/s per rpm (n = rpm / 60).
RPM_TO_REV_PER_S = 1.0 / 60.0


def angular_velocity(rpm):
    """Angular velocity Omega (rad/s) of a rotor turning at ``rpm``."""
    return rpm * RPM_TO_RAD_PER_S

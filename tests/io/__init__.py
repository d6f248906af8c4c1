# Files carry 12 significant digits (bild_mdo.io.geometry.SIGNIFICANT_DIGITS): rounding error <= 0.5e-11
# relative, plus round-off of the deg/rad conversion of the twist.
FILE_RTOL = 5.1e-12

"""The turbine member of the BILD family: maximum power extracted for a given thrust (:mod:`.kernel`)."""

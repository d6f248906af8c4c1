"""Rotor noise: tonal (loading and thickness) and broadband (BPM self-noise) at far-field observers."""

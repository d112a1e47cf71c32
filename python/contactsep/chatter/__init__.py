"""Repeated impacts and circuit discontinuity: Appendix E, three-beam
nonsmooth dynamics (Moreau-Jean) and Hertz contact."""

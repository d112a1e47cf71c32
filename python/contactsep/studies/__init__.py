"""The thesis's design studies (Figures 5-8, 21, 23; Tables I-III),
sweeps and tolerance studies."""

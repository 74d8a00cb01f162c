"""Figures (PNG) of roller's outputs. matplotlib draws without a display (the Agg backend): every
figure module takes `plt` from here."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (the backend must be chosen first)

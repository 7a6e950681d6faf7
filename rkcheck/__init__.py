"""rkcheck: energy-preservation conditions of Runge-Kutta methods, checked exactly."""

__version__ = "0.1.0"

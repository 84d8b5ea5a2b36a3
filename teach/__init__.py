"""teach: teach a robot a high-level behaviour by demonstration."""

__version__ = "0.1.0"

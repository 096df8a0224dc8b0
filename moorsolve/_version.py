"""The package version (a leaf: the report and the command line read it)."""

__version__ = "0.1.0"

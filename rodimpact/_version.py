"""The package's version, in a module of its own so that modules inside the package never import the package
root (which imports every layer). ``pyproject.toml`` reads it from here (``[tool.setuptools.dynamic]``)."""

__version__ = "0.1.0"

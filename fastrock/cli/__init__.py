"""The ``fastrock`` command line (entry point ``fastrock.cli:main``)."""
from fastrock.cli.app import main

__all__ = ["main"]

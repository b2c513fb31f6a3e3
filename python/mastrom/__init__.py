"""mastrom from Python: the deployment dynamics and the modal ROM of a modular rover mast.

The same library as the ``mastrom`` command line, NumPy arrays in and out, SI units throughout
(degrees only in the ``*_deg`` configuration keys)::

    import mastrom
    cfg = mastrom.Config.load("configs/scheme3.toml", set={"interface.thickness": 1.5e-3})
    res = mastrom.simulate(cfg)                      # full order: res["time"], res["metrics"], ...
    modes = mastrom.modes(cfg)                       # modes["frequencies_hz"], modes["shapes"], ...
    db = mastrom.build_database(cfg, params={"interface.thickness": (1e-3, 2e-3, 3)}, modes=10)
    out = db.evaluate({"interface.thickness": 1.2e-3}, set={"drive.law": "cubic"})
    table = db.screen({"interface.thickness": numpy.linspace(1e-3, 2e-3, 100)})

Errors: ``InputError`` (a ValueError) for bad input, ``FileError`` (an OSError) for files,
``NumericalError`` (a RuntimeError) for numerical failure; the message is the library's one line,
the same the command line prints. Long calls release the GIL.
"""

from ._core import (  # noqa: F401  (the public API)
    Config,
    Error,
    FileError,
    InputError,
    NumericalError,
    RomDatabase,
    __version__,
    build_adaptive_database,
    build_database,
    modes,
    simulate,
)

__all__ = [
    "Config",
    "Error",
    "FileError",
    "InputError",
    "NumericalError",
    "RomDatabase",
    "__version__",
    "build_adaptive_database",
    "build_database",
    "modes",
    "simulate",
]

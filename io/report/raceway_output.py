"""The raceway output reader under its former module name: `from raceway_output import RacewayOutput`
with io/report (or the installed report folder) on sys.path. The reader is the `raceway` package
beside this file (raceway/output.py); new code should `import raceway`."""
from raceway.output import *  # noqa: F401,F403
from raceway.output import BUILD_ATTRIBUTES, LAYOUT_VERSION, Quantity, RacewayOutput  # noqa: F401

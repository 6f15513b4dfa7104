"""raceway: read the output files of the raceway bearing-dynamics simulator (docs/output_layout.md).

    import raceway
    with raceway.open_output("run.h5") as out:
        w = out.component("cage/angular_velocity", "about z")   # [T] rad/s, planar and spatial alike
        print(w.units, out.bearing["pitch_radius"], out.summary["cage_slip"])
        df = out.table().to_pandas()                             # pandas, where installed

Files of every layout version up to LAYOUT_VERSION are read under the names of the newest one
(raceway.output: OLD_NAMES). Needs numpy and h5py; pandas only for Table.to_pandas().

Where it is: installed with raceway (`cmake --install`) in the Python path of the prefix
(<prefix>/lib/python3.X/dist-packages), in the build tree under build/python, and in the sources
under io/report: put the folder that holds this package on sys.path (or PYTHONPATH).
"""
from raceway.output import (BEARING_ATTRIBUTES, BUILD_ATTRIBUTES, LAYOUT_VERSION, OLD_NAMES, Quantity,
                            RacewayOutput, open_output)
from raceway.table import Table

__all__ = ["BEARING_ATTRIBUTES", "BUILD_ATTRIBUTES", "LAYOUT_VERSION", "OLD_NAMES", "Quantity", "RacewayOutput",
           "Table", "open_output"]

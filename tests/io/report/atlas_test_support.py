"""What the atlas tests share: the stand-in atlas file and the error of a classifier's boundary on the
stand-in. Imported by the tests of this folder (their own folder is on sys.path when run as scripts),
after they have put io/report on sys.path."""
import numpy as np

import atlas_search as search

#: A two-parameter atlas over the 6205 scene (`{scene}`) that `--standin` evaluates by the stand-in model.
STANDIN_ATLAS = """[atlas]
name = "standin"
scene = "{scene}"
end_time = "20 ms"
settling_time = "10 ms"
classes = ["stable", "unstable"]
budget_points = 21
batch_size = 4

[certify]
realisation_key = "cage.initial_offset"
realisations = ["10 um", "20 um"]

[[parameter]]
key = "inner_ring.speed"
range = [1000, 8000]
unit = "rpm"

[[parameter]]
key = "inner_ring.load.fz"
name = "load"
range = [100, 2000]
unit = "N"
"""


def boundary_error(model, speeds=np.linspace(0, 1, 101), loads=np.linspace(0, 1, 401)):
    """Largest error over the speeds of the load at which the classifier's class turns stable (to the
    step of `loads`), against the stand-in's boundary."""
    grid = np.array([[a, b] for a in speeds for b in loads])
    stable = (model.predict(grid) == "stable").reshape(len(speeds), len(loads))
    est = np.array([loads[np.argmax(row)] if row.any() else 1.0 for row in stable])
    return float(np.max(np.abs(est - np.minimum(search.standin_boundary(speeds), 1.0))))

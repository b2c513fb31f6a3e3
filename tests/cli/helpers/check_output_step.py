"""The root attributes of a result whose output step was chosen (docs/theory.md §5.4a): the spacing
of /time is output_step_s, at least 20 samples per period of the resolved mode, not capped, and the
rule says it is the default. Usage: check_output_step.py FILE.h5"""
import sys

import h5py
import numpy as np

with h5py.File(sys.argv[1], "r") as f:
    t = f["time"][:]
    step = float(f.attrs["output_step_s"])
    rule = f.attrs["output_step_rule"]
    rule = rule.decode() if isinstance(rule, bytes) else str(rule)
    assert abs((t[1] - t[0]) - step) < 1e-9 * step, (t[1] - t[0], step)
    assert float(f.attrs["samples_per_period"]) >= 20, f.attrs["samples_per_period"]
    assert int(np.asarray(f.attrs["output_step_capped"]).reshape(-1)[0]) == 0
    assert "default" in rule, rule
print("ok")

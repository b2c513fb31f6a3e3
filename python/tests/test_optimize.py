"""RomDatabase.optimize: the same rounds as `mastrom optimize`, and its refusals."""
import pytest

import mastrom


def test_optimize_returns_the_rounds(database):
    r = database.optimize(minimize="mass",
                          subject_to=["peak_rel_end_angular_acceleration <= 50"], rounds=1)
    assert set(r) >= {"confirmed", "stop_reason", "variables", "metrics", "rounds"}
    assert len(r["rounds"]) == 1


def test_optimize_refuses_an_unknown_metric(database):
    with pytest.raises(Exception, match="no_such_metric"):
        database.optimize(minimize="no_such_metric")

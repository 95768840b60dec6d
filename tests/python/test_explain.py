"""explain(scene) returns, as a dict, what `lrigid explain` prints: every number and verdict of
the command's text is compared with the dict's."""
import os
import re

import pytest

import lrigid
from conftest import ROOT, cli


@pytest.mark.parametrize("scene", ["uniform_box.json", "plate_flutter.json"])
def test_dict_holds_what_the_command_prints(lrigid_bin, scene):
    path = os.path.join(ROOT, "scenes", scene)
    text = cli("explain", path).stdout
    d = lrigid.explain(path)
    assert d == lrigid.explain(lrigid.Scene.load(path))
    g = "%.3g"
    assert "flow (%s): |U| = %s m/s" % (d["flow"]["source"], g % d["flow"]["U"]) in text
    assert "integrator: %s, dt = %g s" % (d["integrator"], d["dt"]) in text
    blocks = text.split("\nbody type ")[1:]
    assert len(blocks) == len(d["body_types"]) >= 1
    for block, t in zip(blocks, d["body_types"]):
        assert block.startswith('%d "%s" (%s, %d bodies)' % (t["index"], t["name"], t["shape"],
                                                              t["count"]))
        for label, key in [("Re = ", "reynolds"), ("tau_p = ", "tau_p"),
                           ("St(k/eps) = ", "stokes_k_eps"), ("settling speed = ",
                                                              "terminal_speed")]:
            assert label + g % t[key] in block, (label, t[key])
        rows = re.findall(r"^  (\w+) +(\S+) +(keep|skip: .*)$", block, re.M)
        assert [(r[0], r[2]) for r in rows] == [
            (e["name"], "keep" if e["keep"] else "skip: " + e["reason"]) for e in t["effects"]]
        assert [r[1] for r in rows] == [g % e["size"] for e in t["effects"]]
        assert "simulated: %s" % (", ".join(t["simulated"]) or "(none)") in block
        assert "estimated cost: %.0f ns per body-step" % t["cost_ns"] in block
        assert ("step: batched" in block) == t["step"]["batched"]
        # the plain sentence comes first, the same in the dict
        assert block.split("\n")[1] == "  In plain words: " + t["plain_words"]
    assert "estimated total: %s body-steps" % (g % d["total"]["body_steps"]) in text


def test_explain_accepts_a_dict_and_reports_errors():
    import json
    with open(os.path.join(ROOT, "scenes", "uniform_box.json")) as f:
        s = json.load(f)
    d = lrigid.explain(s)
    assert d["scene"] == "<dict>" and [t["name"] for t in d["body_types"]] == [
        "paper_card", "polystyrene_bead"]
    s["bodies"][0]["density"] = 0
    with pytest.raises(lrigid.Error, match=r"bodies\[0\].density"):
        lrigid.explain(s)

"""Every column a table returns is described in the text its documentation page is generated
from (issue #16 item 3: the docs' column tables come from SPECTRUM_COLUMNS and BATCH_COLUMNS;
this keeps those texts and the DataFrames from drifting apart)."""
import re

import pytest

import fastrock as fr
from fastrock.analyses.spectrum import SPECTRUM_COLUMNS
from fastrock.model.foundation import TwoSpringFoundation
from fastrock.running.batch import BATCH_COLUMNS


def documented(text):
    names = set()
    for line in text.splitlines():
        if not line or line[0].isspace():
            continue
        head = re.split(r"\s{2,}", line.strip())[0]
        names.update(n.strip() for n in head.split(","))
    return names


BLOCK = fr.RigidBlock.rectangle(0.15, 0.6)
FLEX = fr.FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=8.0, zeta=0.05)
WEDGE = fr.RigidBody(mass=1.0, inertia=0.06, b1=0.25, h1=0.7, b2=0.12, h2=0.7)
SCENES = {
    "rigid": (BLOCK, {}),
    "rigid_body": (WEDGE, {}),
    "wall": (BLOCK, {"wall": fr.Wall(0.02)}),
    "friction": (BLOCK, {"friction": fr.Friction(0.3)}),
    "contact": (BLOCK, {"wall": fr.Wall(0.02), "friction": fr.Friction(0.4)}),
    "flexible": (FLEX, {}),
    "flexible_friction": (FLEX, {"friction": fr.Friction(0.5)}),
    "foundation": (BLOCK, {"foundation": TwoSpringFoundation.from_vibration(BLOCK, 40.0, 0.05, mass=50.0),
                           "mass": 50.0}),
    "flexible_foundation": (FLEX, {"foundation": TwoSpringFoundation.from_vibration(FLEX, 40.0, 0.05)}),
}


@pytest.mark.parametrize("case", sorted(SCENES))
def test_spectrum_columns_are_documented(case):
    body, kw = SCENES[case]
    df = fr.overturning_spectrum(body, [0.5, 3.0], [1.0], progress=False, boundary_check=case == "rigid", **kw)
    missing = set(df.columns) - documented(SPECTRUM_COLUMNS)
    assert not missing, f"{case}: columns without a line in SPECTRUM_COLUMNS: {sorted(missing)}"


def test_batch_columns_are_documented():
    scenes = [fr.Scene(body, fr.Pulse(0.3, 1.0), **kw) for body, kw in SCENES.values()]
    df = fr.run_batch(scenes, progress=False)
    missing = set(df.columns) - documented(BATCH_COLUMNS)
    assert not missing, f"columns without a line in BATCH_COLUMNS: {sorted(missing)}"
    assert len(df) == len(scenes)

"""The public API of issue #16 (item 5): top-level names, g defined once, full dimensions."""
import math
import pathlib
import re

import pytest

import fastrock
from fastrock import RigidBlock

PROMISED = ["fit_free_rocking", "half_cycles", "rocking_spectrum", "Scene", "Study", "run_study",
            "fit_fragility", "simulate_foundation", "TwoSpringFoundation", "SwitchingFoundation",
            "LinearVibration", "simulate", "overturning_spectrum", "RigidBlock", "FlexibleBody",
            "Wall", "Friction", "Pulse", "GroundMotion", "read_record", "Solver"]


def test_every_promised_name_is_exported_at_the_top_level():
    assert set(PROMISED) <= set(fastrock.__all__)
    assert len(set(fastrock.__all__)) == len(fastrock.__all__)
    for name in fastrock.__all__:
        assert getattr(fastrock, name) is not None, name


def test_top_level_names_are_the_modules_objects():
    from fastrock.analyses.freerocking.fitting import fit_free_rocking
    from fastrock.studies.definition import Study
    assert fastrock.fit_free_rocking is fit_free_rocking and fastrock.Study is Study


def test_g_is_defined_once():
    """No module of the front end or the kernels writes a literal standard gravity except
    fastrock/constants.py (published data keep their own g, marked as the paper's)."""
    root = pathlib.Path(fastrock.__file__).resolve().parent
    pattern = re.compile(r"(?<![\d.])9\.8(0665|1)?(?!\d)")
    offenders = []
    for path in sorted(root.rglob("*.py")) + sorted(root.parent.joinpath("kernels").glob("*.py")):
        if path.name == "constants.py":
            continue
        for i, line in enumerate(path.read_text().splitlines(), 1):
            code = line.split("#")[0]
            if pattern.search(code) and not re.search(r"published|paper", line):
                offenders.append(f"{path.name}:{i}: {line.strip()}")
    assert offenders == []
    assert fastrock.G_STANDARD == 9.80665
    assert RigidBlock(0.2, 2.0).g == fastrock.G_STANDARD


def test_rectangle_takes_full_dimensions_by_keyword():
    half = RigidBlock.rectangle(0.25, 1.0)
    full = RigidBlock.rectangle(width=0.5, height=2.0)
    assert full == half
    assert RigidBlock.rectangle(b=0.25, height=2.0) == half
    assert full.alpha == pytest.approx(math.atan(0.25))


@pytest.mark.parametrize("kw, field", [
    (dict(b=0.2, width=0.4, h=1.0), "width"),
    (dict(h=1.0), "width"),
    (dict(b=0.2), "height"),
    (dict(width=-1.0, h=1.0), "width"),
    (dict(b=0.2, height=float("nan")), "height"),
])
def test_rectangle_dimensions_are_validated_by_name(kw, field):
    with pytest.raises(ValueError, match=field):
        RigidBlock.rectangle(**kw)


def test_spectra_take_physical_axes_as_well_as_ratios():
    import numpy as np
    block = RigidBlock.rectangle(0.2, 1.0)
    amps_g, f_hz = np.array([0.1, 0.3, 0.6]), np.array([0.5, 1.0, 2.0])
    phys = fastrock.overturning_spectrum(block, amps_g, f_hz, amplitude_unit="g", frequency_unit="Hz",
                                         progress=False)
    ratios = fastrock.overturning_spectrum(block, amps_g * fastrock.G_STANDARD / (block.g * math.tan(block.alpha)),
                                           2 * math.pi * f_hz / block.p, progress=False)
    assert list(phys.outcome) == list(ratios.outcome)
    np.testing.assert_allclose(phys.max_rotation_ratio, ratios.max_rotation_ratio, rtol=1e-12)
    np.testing.assert_allclose(np.sort(phys.amplitude_g.unique()), amps_g, rtol=1e-14)
    np.testing.assert_allclose(np.sort(phys.frequency_hz.unique()), f_hz, rtol=1e-14)
    rad = fastrock.overturning_spectrum(block, amps_g * fastrock.G_STANDARD, 2 * math.pi * f_hz,
                                        amplitude_unit="m/s2", frequency_unit="rad/s", progress=False)
    assert list(rad.outcome) == list(ratios.outcome)
    with pytest.raises(ValueError, match="amplitude_unit"):
        fastrock.overturning_spectrum(block, [1.0], [1.0], amplitude_unit="furlong")


def test_the_pulse_shape_is_kind_as_in_pulse():
    block = RigidBlock(0.2, 2.0)
    a = fastrock.overturning_spectrum(block, [2.0, 4.0], [1.0, 3.0], kind="half-sine", progress=False)
    b = fastrock.overturning_spectrum(block, [2.0, 4.0], [1.0, 3.0], pulse="half-sine", progress=False)
    assert list(a.outcome) == list(b.outcome) and a.attrs["pulse"] == "half-sine"
    with pytest.raises(ValueError, match="once"):
        fastrock.overturning_spectrum(block, [2.0], [1.0], kind="half-sine", pulse="one-cosine")

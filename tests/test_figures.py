"""Figures people can publish (issue #16, item 7): each is rendered here and its content checked."""
import math

import numpy as np
import pandas as pd
import pytest

import fastrock as fr
from fastrock.plotting.figures import OUTCOME_LABELS, plot_spectrum


def _labels(ax):
    leg = ax.get_legend()
    return [t.get_text() for t in leg.get_texts()] if leg else []


def test_history_draws_the_excitation_itself_while_the_block_rests(tmp_path):
    """Below uplift the block rests and the integrator stores few rows; the ground panel still
    follows the pulse (a sine, not straight lines between stored rows)."""
    block = fr.RigidBlock(0.2, 2.0)
    pulse = fr.Pulse(0.5, 1.0, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p")
    r = fr.simulate(block, pulse)
    assert r.outcome == "safe" and r.metrics["impacts"] == 0
    fig = r.plot()
    ax = fig.axes[0]
    x, y = ax.lines[0].get_data()
    assert x.size > 10 * len(r.history)
    w = block.p
    a_p = 0.5 * block.g * math.tan(block.alpha)
    expect = np.where(x <= 2 * math.pi / w, a_p * np.sin(w * x), 0.0) / block.g
    np.testing.assert_allclose(y, expect, atol=1e-12)
    assert "rigid block" in ax.get_title() and "one-sine pulse" in ax.get_title()
    fig.savefig(tmp_path / "h.png")


def test_history_adds_slip_and_deflection_panels_and_names_impacts(tmp_path):
    body = fr.FlexibleBody(alpha=0.2, p=2.0, omega_n_over_p=5, base_mass_ratio=0.1)
    r = fr.simulate(body, fr.Pulse(3, 1.5, amplitude_unit="g_tan_alpha", frequency_unit="omega_p/p"),
                    friction=fr.Friction(0.3, lift_off="hold"))
    fig = r.plot()
    assert [a.get_ylabel() for a in fig.axes] == ["ground acc. [g]", r"$\theta/\alpha$ [-]", "slip d [m]",
                                                 "deflection u [m]"]
    fig.savefig(tmp_path / "f.png")
    rec = fr.io.default_records.load_default_record()
    r = fr.simulate(fr.RigidBlock.rectangle(0.2, 1.0), rec, wall=fr.Wall(0.02))
    labels = _labels(r.plot().axes[1])
    n_ground, n_wall = r.metrics["impacts"], r.metrics["wall_impacts"]
    assert n_wall > 0
    assert f"wall impact ({n_wall})" in labels
    assert any(lbl.startswith("ground impact (") for lbl in labels)


def test_spectrum_legend_lists_every_class_with_units_on_the_axes():
    df = fr.overturning_spectrum(fr.RigidBlock(0.2, 2.0), np.linspace(0.5, 8, 6), np.linspace(0.5, 8, 6),
                                 progress=False)
    fig = plot_spectrum(df, title="t")
    ax = fig.axes[0]
    labels = _labels(ax)
    assert len(labels) == len(OUTCOME_LABELS)
    for key, text in OUTCOME_LABELS.items():
        n = int((df.outcome == key).sum())
        assert f"{text} ({n})" in labels
    assert "[-]" in ax.get_xlabel() and "[-]" in ax.get_ylabel()


def test_rocking_spectrum_plot_tells_records_apart_and_names_the_bound():
    from fastrock.plotting.rocking_spectrum import plot_rocking_spectrum
    df = pd.DataFrame({"record": ["A", "A", "B", "B"], "wall": ["two-sided"] * 4,
                       "tp_over_tm": [2.0, 5.0, 3.0, 8.0], "beta": [0.8, 0.5, 0.7, 0.3],
                       "beta_bound": ["exact", "upper", "exact", "lower"]})
    fig = plot_rocking_spectrum(df)
    ax = fig.axes[0]
    labels = _labels(ax)
    assert {"A", "B", "two-sided"} <= set(labels)
    assert any(lbl.startswith("Maiorano et al. upper bound") for lbl in labels)
    assert any(lbl.startswith("censored") for lbl in labels)
    arrows = [c for c in ax.texts if getattr(c, "arrow_patch", None) is not None]
    assert len(arrows) == 2
    # the upper bound points down, the lower bound up
    ends = sorted((a.xy[1] - a.xyann[1]) for a in arrows)
    assert ends[0] < 0 < ends[1]

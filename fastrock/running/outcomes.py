"""Run status codes returned by kernels, and their names.

``outcome`` is the coarse class used in spectra: "safe", "mode1" (overturned
after at least one impact), "mode2" (overturned without impact), "leaning",
"flight", "slide" (friction models) and "failed".  ``status`` refines it.
"""
from fastrock.kernels import layout as L

STATUS = {
    L.SAFE_NO_UPLIFT: "safe:no-uplift",
    L.SAFE_REST: "safe:rest",
    L.SAFE_MOVING: "safe:moving",
    L.SAFE_BOUNDED: "safe:bounded",
    L.OVERTURN_MODE1: "overturn:mode1",
    L.OVERTURN_MODE2: "overturn:mode2",
    L.LEANING: "leaning",
    L.FLIGHT: "flight",
    L.FAIL_STEP_UNDERFLOW: "failed:step-underflow",
    L.FAIL_STEP_BUDGET: "failed:step-budget",
    L.FAIL_EVENT: "failed:event-location",
    L.FAIL_NONFINITE: "failed:non-finite",
    L.FAIL_TRANSITIONS: "failed:transition-loop",
    L.FAIL_OUTPUT_FULL: "failed:output-full",
    L.FAIL_INCONSISTENT: "failed:inconsistent-contact",
    L.FAIL_UNSTABLE: "failed:unstable-step",
    L.FAIL_INTERRUPTED: "failed:interrupted",
    L.FAIL_FACE_CONTACT: "failed:face-contact",
    L.RUNNING: "failed:unfinished",
}

STATUS_DESCRIPTION = {
    "safe:no-uplift": "never left full contact",
    "safe:rest": "uplifted and came back to rest",
    "safe:moving": "upright but still moving when the run ended",
    "safe:bounded": "stopped early: after the excitation the free-rocking energy is below the "
                    "overturning barrier, so it cannot overturn (it decays to rest)",
    "overturn:mode1": "overturned after at least one impact",
    "overturn:mode2": "overturned without any impact",
    "leaning": "came to rest leaning on the wall",
    "flight": "lost contact with the ground (vertical acceleration below -g, or the normal force "
              "reached 0 while rocking)",
    "failed:inconsistent-contact": "friction: no contact mode is consistent even after the Painleve "
                                   "rules (lift-off, tangential impact); left only for rounding exactly "
                                   "at their boundaries, please report the run",
    "failed:unstable-step": "the fixed step dt lies outside the integrator's stability region for this "
                            "body (the solution diverged or would have): a smaller dt, or the adaptive "
                            "solver, gives the answer",
    "failed:interrupted": "stopped by Ctrl-C before the run finished",
    "failed:face-contact": "guard: the block's base went into the wall, which the contact model's face "
                           "modes should have prevented (please report the run)",
}


def _three_digits_down(x):
    """x rounded down to three significant digits (a step printed as it was tried)."""
    import math
    scale = 10.0 ** (math.floor(math.log10(x)) - 2)
    return float(f"{math.floor(x / scale) * scale:.3g}")


#: the stable-step check runs no candidate step that needs more than this many times the run's own
#: step budget (``checked_stable_step``)
CHECK_BUDGET_FACTOR = 8


def checked_stable_step(run, opt, dt, suggested, tries=8):
    """A fixed step at which a run that diverged at ``dt`` ends definite, found by running it again:
    from the kernel's suggestion (the step that brings the diverging step's local error within the
    limit), then halving while the run still diverges, at most ``tries`` runs.  A step that needs
    more fixed steps than the run's budget gets the budget a user would give it (as the front end's
    error for such a step names it), up to ``CHECK_BUDGET_FACTOR`` times the run's budget: the
    smallest step the check runs is span / (CHECK_BUDGET_FACTOR max_steps).  The kernels' suggestion
    assumes the error of a diverging step grows as h^5; far outside the stability region it grows
    much faster and the suggestion can be absurdly small (1.24e-12 s after 9.4e-6 s diverged in fuzz
    flexible_friction:2027:594, whose check then ran with 1e12 steps: the fuzz's "hang"), so it is
    clamped there.  ``run(opt)`` returns (status code, metrics).  Returns (dt, status name, the
    budget or None), or (None, the smallest dt tried, None) if none did."""
    import math

    from fastrock._validate import MAX_STEPS
    step = suggested if math.isfinite(suggested) and 0.0 < suggested < dt else 0.5 * dt
    span = opt[L.O_T_END] - opt[L.O_T0]
    floor = span / (CHECK_BUDGET_FACTOR * opt[L.O_MAX_STEPS])
    for _ in range(tries):
        at_floor = step <= floor
        step = _three_digits_down(max(step, floor))
        o = opt.copy()
        o[L.O_DT_FIXED] = step
        budget = None
        if span / step > opt[L.O_MAX_STEPS]:
            budget = min(int(1.05 * span / step) + 1000, int(MAX_STEPS))
            o[L.O_MAX_STEPS] = float(budget)
        code, met = run(o)
        if code != L.FAIL_UNSTABLE:
            if outcome_of(code) == "failed":
                return None, step, None     # another limit: no step to name
            return step, status_of(code), budget
        if at_floor:
            break                           # the smallest step the check affords diverged too
        nxt = met[L.M_DT_STABLE]
        step = min(nxt if math.isfinite(nxt) and nxt > 0.0 else step, 0.5 * step)
    return None, step, None


def warn_unstable(status, MET, dt, stacklevel=3, checked=None):
    """Warn when fixed-step runs ended as failed:unstable-step.  ``checked``: the result of
    :func:`checked_stable_step` for a single run (``simulate``), named as checked; otherwise
    the smallest step the kernels suggested, named as an estimate."""
    import warnings

    import numpy as np
    status = np.atleast_1d(status)
    bad = status == L.FAIL_UNSTABLE
    if not bad.any():
        return
    if checked is not None:
        step, how, budget = checked
        if step is not None:
            with_budget = "" if budget is None else f" with max_steps = {budget}"
            hint = f"; dt <= {step:.3g} s would be stable (checked{with_budget}: at that step this run ends {how})"
        else:
            hint = (f"; no fixed step down to {how:.3g} s ended this run (checked): the motion is stiffer than "
                    "a fixed step follows, use the adaptive solver")
    else:
        dts = np.atleast_2d(MET)[bad, L.M_DT_STABLE]
        dts = dts[np.isfinite(dts) & (dts > 0)]
        hint = (f"; dt <= {dts.min():.3g} s would be stable by the local-error estimate (simulate() of a "
                "row checks it)") if dts.size else ""
    warnings.warn(f"{int(bad.sum())} of {status.size} run(s) ended as failed:unstable-step: the fixed step "
                  f"dt = {dt:g} s made a local error above 1 % of the motion, where the solution diverges"
                  f"{hint} (or use the adaptive solver)", RuntimeWarning, stacklevel=stacklevel)


def warn_budget(code, met, opt, stacklevel=3):
    """Warn when a run ended as failed:step-budget: it names the budget (``Solver(max_steps=)``,
    the limit the user set or its default), the time the run reached and the steps the whole run
    would take at the rate so far."""
    import warnings
    if int(code) != L.FAIL_STEP_BUDGET:
        return
    taken = met[L.M_NSTEPS] + met[L.M_NREJECT]
    t0, t_end, t = opt[L.O_T0], opt[L.O_T_END], met[L.M_T_FINAL]
    need = taken * (t_end - t0) / (t - t0) if t > t0 else float("inf")
    warnings.warn(f"the run ended as failed:step-budget: its max_steps = {opt[L.O_MAX_STEPS]:.6g} steps "
                  f"(Solver(max_steps=...), the limit of this run) ran out at t = {t:.6g} s of {t_end:.6g} s; "
                  f"at the rate so far the whole run needs about {need:.3g} steps. Give a larger max_steps "
                  f"(up to 1e12), a shorter run, or a looser rtol", RuntimeWarning, stacklevel=stacklevel)


def outcome_of(code):
    code = int(code)
    if code in (L.SAFE_NO_UPLIFT, L.SAFE_REST, L.SAFE_MOVING, L.SAFE_BOUNDED):
        return "safe"
    if code == L.OVERTURN_MODE1:
        return "mode1"
    if code == L.OVERTURN_MODE2:
        return "mode2"
    if code == L.LEANING:
        return "leaning"
    if code == L.FLIGHT:
        return "flight"
    return "failed"


def status_of(code):
    return STATUS.get(int(code), f"failed:code{int(code)}")


EVENT_NAMES = {
    L.EV_UPLIFT: "uplift",
    L.EV_IMPACT: "impact",
    L.EV_WALL_IMPACT: "wall-impact",
    L.EV_OVERTURN: "overturn",
    L.EV_REST: "rest",
    L.EV_PASS_ALPHA: "pass-alpha",
    L.EV_WALL_REST: "wall-rest",
    L.EV_WALL_RELEASE: "wall-release",
    L.EV_LEANING: "leaning",
    L.EV_FLIGHT: "flight",
    L.EV_SLIP: "slip",
    L.EV_STICK: "stick",
    L.EV_PEAK: "peak",
    L.EV_CONTACT: "contact",
    L.EV_LIFT_OFF_HELD: "lift-off-held",
    L.EV_RELOAD: "reload",
}

MODE_NAMES = {
    L.MODE_REST: "rest",
    L.MODE_ROCK: "rock",
    L.MODE_SLIDE: "slide",
    L.MODE_SLIDE_ROCK: "slide-rock",
    L.MODE_FLIGHT: "flight",
    L.MODE_OVERTURNED: "overturned",
    L.MODE_WALL_REST: "wall-rest",
}

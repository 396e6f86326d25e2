"""The ``fastrock`` command: parser, the spectrum/simulate/warmup subcommands, main.
"""
from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from fastrock.cli.output import (EXIT_INTERRUPTED, MAX_GRID_RUNS, add_output_options, grid_option,
    interrupted_exit, write_table, wrote)


def _shape_body(args):
    """A RigidBody from --outline or --mesh, printed so the user can check the reduction."""
    from fastrock.model.rigid_body import RigidBody
    given = [o for o, v in (("--outline", args.outline), ("--mesh", args.mesh)) if v is not None]
    if len(given) == 2:
        raise ValueError("give --outline or --mesh, not both")
    clash = [o for o, v in (("--b", args.b), ("--h", args.h), ("--omega-n-over-p", args.omega_n_over_p))
             if v is not None]
    if clash:
        raise ValueError(f"{given[0]} defines the body; it takes no {', '.join(clash)}")
    mass = {"density": args.density} if args.density is not None else {"mass": 1.0 if args.mass is None else args.mass}
    if args.outline is not None:
        from fastrock.io.outline import read_outline
        if args.density is not None:
            if args.thickness is None:
                raise ValueError("--density with --outline needs --thickness [m] (out of plane)")
            mass["thickness"] = args.thickness
        body = RigidBody.from_polygon(read_outline(args.outline), pose=args.pose, e=args.e, **mass)
    else:
        if args.thickness is not None:
            raise ValueError("--thickness is for --outline; a mesh has its own depth")
        body = RigidBody.from_mesh(args.mesh, axis=_vector("--mesh-axis", args.mesh_axis),
                                   up=_vector("--mesh-up", args.mesh_up), pose=args.pose, e=args.e, **mass)
    print(body.describe())
    return body


def _vector(option, text):
    try:
        v = [float(t) for t in text.split(",")]
    except ValueError:
        v = []
    if len(v) != 3:
        raise ValueError(f"{option} must be three numbers x,y,z, got {text!r}")
    return tuple(v)


def _body(args):
    from fastrock.model.bodies import FlexibleBody, RigidBlock
    if getattr(args, "outline", None) is not None or getattr(args, "mesh", None) is not None:
        return _shape_body(args)
    if getattr(args, "omega_n_over_p", None) is not None:
        if args.b is not None or args.h is not None:
            raise ValueError("--omega-n-over-p (flexible body) takes --alpha and --p, not --b/--h")
        # --mass is the column's mass m (it matters on a foundation, whose stiffnesses are absolute)
        return FlexibleBody(alpha=args.alpha, p=args.p, omega_n_over_p=args.omega_n_over_p, zeta=args.zeta,
                            base_mass_ratio=args.base_mass_ratio,
                            mass=1.0 if getattr(args, "mass", None) is None else args.mass)
    if args.b is not None or args.h is not None:
        if args.b is None or args.h is None:
            raise ValueError("give both --b and --h (half-width and half-height, m)")
        return RigidBlock.rectangle(b=args.b, h=args.h, e=args.e)
    return RigidBlock(alpha=args.alpha, p=args.p, e=args.e)


def _wall(args):
    if getattr(args, "wall_gap", None) is None:
        return None
    from fastrock.model.wall import Wall
    return Wall(gap=args.wall_gap, side=args.wall_side, height=args.wall_height,
                restitution=args.wall_restitution, friction=args.wall_friction)


def _friction(args):
    from fastrock.model.friction import Friction
    if getattr(args, "mu_s", None) is None:
        if getattr(args, "lift_off", None) == "flight":
            return Friction.never_slipping()
        return None
    return Friction(args.mu_s, args.mu_k, lift_off=args.lift_off)


def _ground(args):
    if not getattr(args, "slope", 0.0):
        return None
    from fastrock.model.ground import Ground
    return Ground(slope=args.slope, direction=args.slope_direction)


def _foundation(args, body):
    kind = getattr(args, "foundation", None)
    if kind is None:
        return None
    from fastrock.model import foundation as F
    if args.foundation_omega is None:
        raise ValueError("--foundation needs --foundation-omega (rocking vibration in full contact, rad/s)")
    cls = {"two-spring": F.TwoSpringFoundation, "switching": F.SwitchingFoundation,
           "linear": F.LinearVibration}[kind]
    return cls.from_vibration(body, args.foundation_omega, args.foundation_zeta, mass=args.mass)


def _add_body_options(p):
    g = p.add_argument_group("body (rigid block)")
    g.add_argument("--alpha", type=float, default=0.25, help="slenderness angle alpha [rad] (default 0.25)")
    g.add_argument("--p", type=float, default=2.0, help="frequency parameter p [rad/s] (default 2.0)")
    g.add_argument("--b", type=float, help="half-width [m] (with --h: rectangle, overrides --alpha/--p; default: use --alpha/--p)")
    g.add_argument("--h", type=float, help="half-height [m] (with --b; default: use --alpha/--p)")
    g.add_argument("--e", type=float, help="ground impact restitution e [-] (default: Housner, 1 - 1.5 sin^2 alpha)")
    sb = p.add_argument_group("rigid body from a shape (RigidBody: each side its own alpha and p)")
    sb.add_argument("--outline", metavar="FILE",
                    help="2D outline in the shaking plane: a text/CSV file of x y vertices [m], one per "
                         "row (default: a rectangle from --alpha/--p or --b/--h)")
    sb.add_argument("--mesh", metavar="FILE",
                    help="closed 3D surface (OBJ or STL) [m], cut by the shaking plane (default: none)")
    sb.add_argument("--mesh-axis", default="0,1,0",
                    help="normal of the shaking plane in the mesh's coordinates, x,y,z (default 0,1,0)")
    sb.add_argument("--mesh-up", default="0,0,1",
                    help="the mesh's vertical, x,y,z (default 0,0,1)")
    sb.add_argument("--density", type=float,
                    help="density [kg/m^3] (with --outline also --thickness; default: mass from --mass)")
    sb.add_argument("--thickness", type=float, help="out-of-plane thickness of an --outline [m] (no default)")
    sb.add_argument("--pose", type=float, default=0.0,
                    help="rotation of the shape before it settles on its lowest facet [rad] (default 0)")
    fb = p.add_argument_group("flexible body (elastic column on a rocking base; docs, theory: "
                              "'Flexible rocking body')")
    fb.add_argument("--omega-n-over-p", type=float,
                    help="column frequency ratio omega_n/p [-]: a flexible body instead of a rigid block "
                         "(default: a rigid block)")
    fb.add_argument("--zeta", type=float, default=0.0, help="column damping ratio zeta [-] (default 0)")
    fb.add_argument("--base-mass-ratio", type=float,
                    help="rigid base mass m_b/m [-] (default 0, or 0.1 with --mu-s)")
    w = p.add_argument_group("rear wall (one-sided rocking)")
    w.add_argument("--wall-gap", type=float, help="clear gap d [m] to a rear wall (default: no wall)")
    w.add_argument("--wall-side", type=int, default=-1, choices=(-1, 1),
                   help="-1: wall on the negative-theta side, so a positive pulse throws the block "
                        "toward it (default -1)")
    w.add_argument("--wall-height", type=float, help="wall height [m] (default: taller than the block)")
    w.add_argument("--wall-restitution", type=float, default=1.0, help="wall restitution e_w [-] (default 1)")
    w.add_argument("--wall-friction", type=float, default=0.0,
                   help="Coulomb friction mu_w of the wall contact [-] (default 0, frictionless; > 0 "
                        "needs the contact model: --mu-s, or --lift-off flight)")
    gr = p.add_argument_group("sloping ground (rigid block)")
    gr.add_argument("--slope", type=float, default=0.0,
                    help="ground inclination phi [rad], descending toward +x (default 0, level)")
    gr.add_argument("--slope-direction", default="horizontal", choices=("horizontal", "slope"),
                    help="the excitation acts horizontally (default) or along the slope [-]")
    fd = p.add_argument_group("flexible foundation (rigid block with --b/--h; a flexible body on two-spring)")
    fd.add_argument("--foundation", choices=("two-spring", "switching", "linear"),
                    help="stand the block on a flexible foundation (default: rigid ground)")
    fd.add_argument("--foundation-omega", type=float,
                    help="its small-amplitude rocking vibration in full contact [rad/s] (no default: "
                         "required with --foundation)")
    fd.add_argument("--foundation-zeta", type=float, default=0.0, help="its damping ratio [-] (default 0)")
    fd.add_argument("--mass", type=float, default=None,
                    help="body mass [kg]: a block on a foundation, or a shape without --density (default 1; a shape with --density has its own)")
    f = p.add_argument_group("friction (sliding)")
    f.add_argument("--mu-s", type=float, help="static friction coefficient mu_s [-] (default: no sliding)")
    f.add_argument("--mu-k", type=float, help="kinetic friction coefficient mu_k [-] (default mu_s)")
    f.add_argument("--lift-off", default="stop", choices=("stop", "hold", "flight"),
                   help="the normal force reaching 0: stop with outcome 'flight' (default); 'flight': "
                        "fly and land, without --mu-s never slipping; 'hold' (flexible body): hold "
                        "the pivot down, slipping without friction while N < 0")


def _add_solver_options(p):
    g = p.add_argument_group("integrator")
    g.add_argument("--rtol", type=float, help="relative tolerance of adaptive RK45 [-] (default 1e-8)")
    g.add_argument("--atol", type=float, help="absolute tolerance [rad, rad/s] (default rtol*1e-2)")
    g.add_argument("--dt", type=float, help="fixed integration step [s] instead of adaptive RK45 "
                                            "(default: adaptive)")
    g.add_argument("--method", choices=("auto", "RK45", "Rodas4"),
                   help="integration method (default auto: RK45, turning to the stiff Rodas4 on the foundation "
                        "models where stiff springs call for it)")


def _solver(args):
    from fastrock.running.solver import make_solver
    return make_solver(None, args.rtol, args.atol, args.dt, **({"method": args.method} if args.method else {}))


def cmd_spectrum(args):
    from fastrock.plotting.figures import plot_spectrum
    from fastrock.analyses.spectrum import overturning_spectrum
    body = _body(args)
    wall = _wall(args)
    signs = [1, -1] if args.sign == "both" else [int(args.sign)]
    amps = grid_option("--amp", args.amp_min, args.amp_max, args.n_amp, positive=False)
    freqs = grid_option("--freq", args.freq_min, args.freq_max, args.n_freq)
    if amps.size * freqs.size * len(signs) > MAX_GRID_RUNS:
        raise ValueError(f"--n-amp x --n-freq: {amps.size} x {freqs.size} x {len(signs)} sign(s) = "
                         f"{amps.size * freqs.size * len(signs):,} runs, more than {MAX_GRID_RUNS:,}")
    t0 = time.perf_counter()
    df = overturning_spectrum(body, amps, freqs, sign=signs, pulse=args.pulse, amplitude_unit=args.amplitude_unit,
                              frequency_unit=args.frequency_unit, wall=wall, friction=_friction(args), ground=_ground(args),
                              foundation=_foundation(args, body), mass=args.mass,
                              solver=_solver(args), progress=not args.quiet)
    el = time.perf_counter() - t0
    n_total = len(signs) * amps.size * freqs.size
    tables = write_table(df, args)
    df = df.assign(omega_p=2 * np.pi * df["frequency_hz"])     # for a rad/s axis
    plt = __import__("matplotlib.pyplot").pyplot
    from fastrock.plotting.figures import describe_body
    fig, axes = plt.subplots(1, len(signs), figsize=(6.8 * len(signs), 5.4), squeeze=False,
                             constrained_layout=True)
    for ax, s in zip(axes[0], signs):
        plot_spectrum(df[df["sign"] == s], ax=ax, **_spectrum_axes(args),
                      title=f"{args.pulse} pulse, sign {s:+d}" + ("" if wall is None else f", wall gap {wall.gap:g} m")
                            + f"\n{describe_body(body)}")
        if df.attrs.get("interrupted"):   # the whole grid's axes, the cells not run left blank
            ax.set_xlim(freqs[0], freqs[-1])
            ax.set_ylim(amps[0], amps[-1])
    fig.savefig(args.png, dpi=130)
    counts = {k: v for k, v in df["outcome"].value_counts().to_dict().items() if v}
    print(f"{len(df)} runs in {el:.2f} s ({len(df) / el:,.0f} runs/s), outcomes {counts}")
    if df.attrs.get("interrupted"):
        return interrupted_exit(len(df), n_total, "runs", tables + [args.png])
    wrote(tables + [args.png])
    return 0


def _spectrum_axes(args):
    """Plot the spectrum in the units its grid was given in."""
    axes = {}
    if args.amplitude_unit != "g_tan_alpha":
        axes["y"] = "amplitude_g" if args.amplitude_unit == "g" else "amplitude"
    if args.frequency_unit != "omega_p/p":
        axes["x"] = "frequency_hz" if args.frequency_unit == "Hz" else "omega_p"
    return axes


def cmd_simulate(args):
    from fastrock.model.excitation import Pulse
    from fastrock.running.simulate import simulate
    body = _body(args)
    pulse = Pulse(amplitude=args.amplitude, frequency=args.frequency, sign=args.sign, kind=args.pulse,
                  amplitude_unit=args.amplitude_unit, frequency_unit=args.frequency_unit)
    r = simulate(body, pulse, wall=_wall(args), friction=_friction(args), ground=_ground(args),
                 foundation=_foundation(args, body),
                 mass=args.mass, theta0=args.theta0, solver=_solver(args), duration=args.duration)
    m = r.metrics
    print(f"outcome {r.outcome} ({r.status}); kernel {r.kernel}")
    print(f"max |theta|/alpha = {m['max_rotation_ratio']:.6g}, impacts = {m['impacts']}, "
          f"uplift t = {m['time_uplift']:.6g} s, overturn t = {m['time_overturn']:.6g} s, nfev = {m['nfev']}")
    wrote(write_table(r.history, args))
    if args.events:
        r.events.to_csv(args.events, index=False)
        wrote([args.events])
    if args.png:
        r.plot().savefig(args.png, dpi=130)
        wrote([args.png])
    return 0


def cmd_warmup(args):
    from fastrock.running.warmup import warmup
    for name, seconds in warmup(args.models or None):
        print(f"{name:<16} ready in {seconds:6.2f} s")
    return 0


def build_parser():
    p = argparse.ArgumentParser(prog="fastrock", description="Rocking, sliding and overturning of "
                                "free-standing bodies under ground shaking.")
    from fastrock.constants import VERSION
    p.add_argument("--version", action="version", version=f"fastrock {VERSION}")
    sub = p.add_subparsers(dest="command", required=True)

    s = sub.add_parser("spectrum", help="overturning spectrum under pulses (PNG + CSV)",
                       description="Overturning spectrum a_p/(g tan alpha) against omega_p/p under "
                                   "one-sine pulses, on built-in defaults.")
    _add_body_options(s)
    s.add_argument("--pulse", default="one-sine", choices=("one-sine", "half-sine", "one-cosine"),
                   help="pulse shape (default one-sine)")
    s.add_argument("--sign", default="1", choices=("1", "-1", "both"), help="pulse sign (default +1)")
    s.add_argument("--amp-min", type=float, default=0.5, help="smallest amplitude [--amplitude-unit] (default 0.5)")
    s.add_argument("--amp-max", type=float, default=8.0, help="largest amplitude [--amplitude-unit] (default 8)")
    s.add_argument("--n-amp", type=int, default=120, help="number of amplitudes (default 120)")
    s.add_argument("--freq-min", type=float, default=0.25, help="smallest frequency [--frequency-unit] (default 0.25)")
    s.add_argument("--freq-max", type=float, default=10.0, help="largest frequency [--frequency-unit] (default 10)")
    s.add_argument("--n-freq", type=int, default=120, help="number of frequencies (default 120)")
    s.add_argument("--amplitude-unit", default="g_tan_alpha", choices=("g_tan_alpha", "g", "m/s2"),
                   help="unit of the amplitude axis (default g_tan_alpha, i.e. a_p/(g tan alpha))")
    s.add_argument("--frequency-unit", default="omega_p/p", choices=("omega_p/p", "Hz", "rad/s"),
                   help="unit of the frequency axis (default omega_p/p)")
    _add_solver_options(s)
    add_output_options(s, png="spectrum.png", csv="spectrum.csv", figure="the spectrum figure",
                       table="the table of runs")
    s.set_defaults(func=cmd_spectrum)

    s = sub.add_parser("simulate", help="one run under a pulse: outcome, time history, events")
    _add_body_options(s)
    s.add_argument("--pulse", default="one-sine", choices=("one-sine", "half-sine", "one-cosine"),
                   help="pulse shape (default one-sine)")
    s.add_argument("--amplitude", type=float, default=3.0,
                   help="pulse amplitude [--amplitude-unit] (default 3)")
    s.add_argument("--amplitude-unit", default="g_tan_alpha", choices=("g", "m/s2", "g_tan_alpha"),
                   help="unit of --amplitude (default g_tan_alpha, i.e. a_p/(g tan alpha))")
    s.add_argument("--frequency", type=float, default=2.0,
                   help="pulse frequency [--frequency-unit] (default 2)")
    s.add_argument("--frequency-unit", default="omega_p/p", choices=("Hz", "rad/s", "omega_p/p"),
                   help="unit of --frequency (default omega_p/p)")
    s.add_argument("--sign", type=int, default=1, choices=(1, -1), help="pulse sign (default +1)")
    s.add_argument("--theta0", type=float, default=0.0, help="initial rotation [rad] (default 0)")
    s.add_argument("--duration", type=float, help="end time [s] (default: pulse + 10 s)")
    _add_solver_options(s)
    add_output_options(s, figure="the time-history figure", table="the time history")
    s.add_argument("--events", metavar="FILE", help="write the events table as CSV (default: not written)")
    s.set_defaults(func=cmd_simulate)

    s = sub.add_parser("warmup", help="compile (or load from cache) the kernels ahead of a sweep")
    from fastrock.running.registry import MODELS
    s.add_argument("models", nargs="*", default=None,
                   help=f"models to compile: registry names ({', '.join(MODELS)}) or the families wall, "
                        "friction, foundation (default: every model)")
    s.set_defaults(func=cmd_warmup)

    for register in _extra_commands():
        register(sub)
    for cmd in sub.choices.values():
        if "--quiet" not in cmd._option_string_actions:
            cmd.add_argument("--quiet", "-q", action="store_true",
                             help="print only errors: no progress bar, no summary (default: off)")
    return p


def _extra_commands():
    """Subcommands defined in their own modules."""
    from fastrock.cli import accuracy, fit, rocking_spectrum, scene, study
    return [fit.add_fit_subcommand, rocking_spectrum.add_subcommands, accuracy.add_subcommand,
            scene.add_subcommand, scene.add_batch_subcommand, study.add_subcommand]


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.quiet:
            import contextlib
            import os
            with open(os.devnull, "w") as null, contextlib.redirect_stdout(null):
                return args.func(args)
        return args.func(args)
    except ValueError as exc:
        print(f"fastrock: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:          # a file that cannot be read or written
        where = f": {exc.filename}" if getattr(exc, "filename", None) else ""
        print(f"fastrock: error: {exc.strerror or exc}{where}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        # commands with partial results (sweeps, studies) write them and return 130 themselves
        print(f"fastrock: interrupted: '{args.command}' stopped before it finished; nothing written",
              file=sys.stderr)
        return EXIT_INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())

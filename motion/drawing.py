"""Pictures of a traced configuration space (thesis Figs. 6.6–6.8): the pieces in the plane
of the parameters, one colour per sign vector, the branch points marked; the coupler
curves, the path of a tracer joint along every piece, in the same colours; and the same
paths coloured by circuit, the parts of the motion the linkage cannot pass between
without being taken apart."""

from __future__ import annotations

from baranov.solvers.modes import signs_text

from .configuration_space import OneDofSystem, sign_index
from .tracing import Trace


def render_trace(system: OneDofSystem, traced: Trace, tracers: list[str],
                 eta_triangles: list[tuple[str, str, str]] | None = None,
                 fixed: dict[str, tuple[float, float]] | None = None) -> bytes:
    """A PNG image (bytes) of :func:`trace_figure`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from baranov.solvers.drawing import png_bytes

    figure = trace_figure(system, traced, tracers, eta_triangles, fixed)
    image = png_bytes(figure)
    plt.close(figure)
    return image


def trace_figure(system: OneDofSystem, traced: Trace, tracers: list[str],
                 eta_triangles: list[tuple[str, str, str]] | None = None,
                 fixed: dict[str, tuple[float, float]] | None = None):
    """A matplotlib figure: the configuration space (two parameters: a curve; one: the ranges of each
    sign vector as bars on its row, branch points as ticks) and the paths of ``tracers``
    in the plane (one line style each), both coloured by η over ``eta_triangles``
    (default: the plan's free-sign triangles);
    ``fixed``: the fixed joints' places (default: the scene's ground; another link's in a
    kinematic inversion, :mod:`baranov.motion.inversion`)."""
    import matplotlib.pyplot as plt

    names = system.parameter_names
    triangles = eta_triangles or list(system.plan.free_sign_triangles)
    # one colour per sign vector of the plan (a row of its own with one parameter), the
    # same in both panels, labelled with it and the thesis's η over ``triangles``
    keys = [(sign_index(piece.middle, triangles), signs_text(piece.signs)) for piece in traced.pieces]
    rows = sorted(set(keys))
    colours = plt.get_cmap("tab10" if len(rows) <= 10 else "tab20")
    colour = {key: colours(n % colours.N) for n, key in enumerate(rows)}
    label = {key: f"η = {key[0]} ({key[1]})" for key in rows}
    styles = ["-", "--", ":", "-."]
    figure, (space, paths, by_circuit) = plt.subplots(1, 3, figsize=(17, 5.5))
    for piece, key in zip(traced.pieces, keys, strict=True):
        u = [point.parameters[names[0]] for point in piece.points]
        v = ([point.parameters[names[-1]] for point in piece.points] if len(names) > 1
             else [rows.index(key)] * len(u))
        space.plot(u + u[:1] if piece.closed else u, v + v[:1] if piece.closed else v, color=colour[key],
                   lw=1.5 if len(names) > 1 else 6, solid_capstyle="butt", label=label[key])
        for number, tracer in enumerate(tracers):
            x = [point.joints[tracer][0] for point in piece.points]
            y = [point.joints[tracer][1] for point in piece.points]
            paths.plot(x + x[:1] if piece.closed else x, y + y[:1] if piece.closed else y, color=colour[key],
                       lw=1.2, linestyle=styles[number % len(styles)])
    for branch_point in traced.branch_points:
        values = [branch_point.parameters[name] for name in names]
        if len(names) > 1:
            space.plot(*values, "ko", ms=3)
        else:  # where two pieces meet: a tick across each of their rows
            for index, _ in branch_point.pieces:
                space.plot(values[0], rows.index(keys[index]), "k|", ms=14, mew=1.5)
    if len(names) > 1:
        handles, labels = space.get_legend_handles_labels()
        unique = dict(zip(labels, handles, strict=False))
        order = [label[key] for key in rows]
        space.legend([unique[text] for text in order], order, fontsize=7, ncol=2 if len(order) > 8 else 1,
                     title="sign vector", title_fontsize=7)
    space.set_xlabel(names[0])
    if len(names) > 1:
        space.set_ylabel(names[-1])
    else:  # one parameter: a row per sign vector, its ranges as bars, branch points as ticks
        space.set_yticks(range(len(rows)), [label[key] for key in rows])
        space.set_ylim(-0.7, len(rows) - 0.3)
    space.set_title(f"configuration space: {len(traced.pieces)} pieces, {len(traced.branch_points)} branch points")
    if len(tracers) > 1:
        from matplotlib.lines import Line2D

        paths.legend([Line2D([], [], color="black", linestyle=styles[n % len(styles)]) for n in range(len(tracers))],
                     tracers, fontsize=7, title="tracer", title_fontsize=7)
    fixed = fixed or system.scene.world
    for axes in (paths, by_circuit):
        axes.plot([p[0] for p in fixed.values()], [p[1] for p in fixed.values()], "k^", ms=7)
        axes.set_aspect("equal")
    paths.set_title(f"coupler curves of {', '.join(tracers)} (fixed joints ▲)")
    _draw_circuits(by_circuit, traced, tracers, styles)
    figure.tight_layout()
    return figure


def _draw_circuits(axes, traced: Trace, tracers: list[str], styles: list[str]) -> None:
    """The tracers' paths, one colour per circuit, its branch points as dots and the
    singular configurations as crosses."""
    import matplotlib.pyplot as plt

    colours = plt.get_cmap("tab10" if len(traced.circuits) <= 10 else "tab20")
    for number, circuit in enumerate(traced.circuits):
        colour = colours(number % colours.N)
        for n in circuit.pieces:
            piece = traced.pieces[n]
            points = list(piece.points) + ([piece.points[0]] if piece.closed else [])
            for k, tracer in enumerate(tracers):
                axes.plot([p.joints[tracer][0] for p in points], [p.joints[tracer][1] for p in points], color=colour,
                          lw=1.2, linestyle=styles[k % len(styles)],
                          label=f"circuit {number} ({branches_text(len(circuit.pieces))})"
                          if n == circuit.pieces[0] and k == 0 else None)
        ends = [traced.pieces[traced.branch_points[b].pieces[0][0]].points[-1] for b in circuit.branch_points]
        for tracer in tracers:
            axes.plot([p.joints[tracer][0] for p in ends], [p.joints[tracer][1] for p in ends], "o", color=colour, ms=3)
    for point in traced.singular_points:
        for tracer in tracers:
            axes.plot(*point.point.joints[tracer], "rx", ms=8)
    if traced.circuits:
        axes.legend(fontsize=7, title="circuit (branch points ●)", title_fontsize=7)
    axes.set_title(f"{len(traced.circuits)} circuits: the same paths by circuit")


def branches_text(count: int) -> str:
    """"1 branch", "4 branches": as the picture's legend and ``baranov trace`` say it."""
    return f"{count} branch" + ("es" if count != 1 else "")

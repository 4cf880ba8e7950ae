"""Pictures of a traced configuration space (thesis Figs. 6.6–6.8): the pieces in the plane
of the parameters, one colour per sign vector, the branch points marked; and the coupler
curves, the path of a tracer joint along every piece, in the same colours."""

from __future__ import annotations

from .configuration_space import OneDofSystem, sign_index
from .tracing import Trace


def render_trace(system: OneDofSystem, traced: Trace, tracers: list[str],
                 eta_triangles: list[tuple[str, str, str]] | None = None,
                 fixed: dict[str, tuple[float, float]] | None = None) -> bytes:
    """A PNG: the configuration space (two parameters: a curve; one: ranges per sign
    vector, drawn at the sign vector's index) and the paths of ``tracers`` in the plane;
    pieces labelled by η over ``eta_triangles`` (default: the plan's free-sign triangles);
    ``fixed``: the fixed joints' places (default: the scene's ground; another link's in a
    kinematic inversion, :mod:`baranov.motion.inversion`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from baranov.solvers.drawing import png_bytes

    names = system.parameter_names
    colours = plt.get_cmap("tab20")
    signs = sorted({piece.signs for piece in traced.pieces})
    colour = {s: colours(n % 20) for n, s in enumerate(signs)}
    figure, (space, paths) = plt.subplots(1, 2, figsize=(12, 5.5))
    for piece in traced.pieces:
        u = [point.parameters[names[0]] for point in piece.points]
        v = ([point.parameters[names[-1]] for point in piece.points] if len(names) > 1
             else [signs.index(piece.signs)] * len(u))
        label = f"η = {sign_index(piece.points[0], eta_triangles or list(system.plan.free_sign_triangles))}"
        space.plot(u + u[:1] if piece.closed else u, v + v[:1] if piece.closed else v, color=colour[piece.signs],
                   lw=1.5, label=label)
        for tracer in tracers:
            x = [point.joints[tracer][0] for point in piece.points]
            y = [point.joints[tracer][1] for point in piece.points]
            paths.plot(x + x[:1] if piece.closed else x, y + y[:1] if piece.closed else y, color=colour[piece.signs],
                       lw=1.2)
    for branch_point in traced.branch_points:
        values = [branch_point.parameters[name] for name in names]
        if len(names) > 1:
            space.plot(*values, "ko", ms=3)
    handles, labels = space.get_legend_handles_labels()
    unique = dict(zip(labels, handles, strict=True))
    order = sorted(unique, key=lambda text: int(text.split("= ")[1]))
    space.legend([unique[k] for k in order], order, fontsize=6, ncol=2, title="sign vector", title_fontsize=7)
    space.set_xlabel(names[0])
    space.set_ylabel(names[-1] if len(names) > 1 else "sign vector")
    space.set_title(f"configuration space: {len(traced.pieces)} pieces, {len(traced.branch_points)} branch points")
    fixed = fixed or system.scene.world
    paths.plot([p[0] for p in fixed.values()], [p[1] for p in fixed.values()], "k^", ms=7)
    paths.set_aspect("equal")
    paths.set_title(f"coupler curves of {', '.join(tracers)} (fixed joints ▲)")
    figure.tight_layout()
    image = png_bytes(figure)
    plt.close(figure)
    return image

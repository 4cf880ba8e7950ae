"""An animation of a linkage moving along one branch of its driven motion
(:mod:`.driving`): one frame per input value, the linkage drawn as ``baranov solve --plot``
draws an assembly mode, the tracers' paths so far behind it."""

from __future__ import annotations

import tempfile
from pathlib import Path

from baranov.scene import Scene
from baranov.solvers.drawing import draw_mode

from .driving import DrivenBranch


def render_animation(scene: Scene, branch: DrivenBranch, tracers: list[str], input_name: str,
                     unit: str = "", milliseconds: int = 120) -> bytes:
    """A GIF of ``scene`` at every configuration of ``branch`` in order (``milliseconds``
    per frame, 640 × 640 pixels), the paths of ``tracers`` drawn up to the frame (one colour
    each, named in a legend), each tracer point of a link shaded with the link's first two
    joints, the input's value in the title. The view is fixed: it holds every frame, with
    room for the labels. Cost: one drawing per frame."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    xs = [x for point in branch.points for x, _ in point.joints.values()]
    ys = [y for point in branch.points for _, y in point.joints.values()]
    extent = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    margin = 0.15 * extent  # room for the joints' labels at the edge of the view
    attached = {tracer.name: scene.link_of(tracer.link).joints for tracer in scene.tracers}
    colours = plt.get_cmap("tab10")
    figure, axis = plt.subplots(figsize=(6.4, 6.4), dpi=100)

    def frame(number: int) -> None:
        axis.clear()
        point = branch.points[number]
        for tracer, joints in attached.items():  # a tracer is a point of its link: drawn joined to it
            corners = [point.joints[joint] for joint in joints[:2]] + [point.joints[tracer]]
            axis.fill([x for x, _ in corners], [y for _, y in corners], color="0.85", edgecolor="0.4",
                      linewidth=0.8, zorder=1.5)
        for index, tracer in enumerate(tracers):
            path = [p.joints[tracer] for p in branch.points[:number + 1]]
            axis.plot([x for x, _ in path], [y for _, y in path], color=colours(index % 10), linewidth=1.4,
                      zorder=2.5, label=f"path of {tracer}")
        draw_mode(axis, scene, point, extent)
        axis.set_xlim(min(xs) - margin, max(xs) + margin)
        axis.set_ylim(min(ys) - margin, max(ys) + margin)
        axis.set_aspect("equal")
        if tracers:
            axis.legend(loc="upper right", fontsize=8)
        axis.set_title(f"from piece {branch.piece}, {input_name} = {branch.values[number]:.4g}{unit} "
                       f"({number + 1}/{len(branch.points)})", fontsize=10)

    animation = FuncAnimation(figure, frame, frames=len(branch.points))
    with tempfile.TemporaryDirectory(prefix="baranov-animation-") as folder:
        target = Path(folder) / "motion.gif"
        animation.save(target, writer=PillowWriter(fps=max(1, round(1000 / milliseconds))), dpi=100)
        plt.close(figure)
        return target.read_bytes()
